// problems/3d/pmma_disk_impact.cpp -- falling-weight impact of a steel tip on a clamped PMMA disc
// with random critical stretch (Soares 2018; spec/001_004 B.5, V7).
// Case: disc 76 mm x 3 mm, E 3.3 GPa, nu 0.35, rho 1190 kg/m^3, delta 3.1 mm; points with r >=
// --r-clamp (32 mm: the ring size is not given, our assumption) are fixed (the source clamps
// the points touching the ring). Rigid sphere (bc/contact.hpp) of diameter 12.7 mm and mass 18.49 kg
// (the source lumped the mass into the tip) at 1.065 m/s along -z, touching the top layer of
// points at t = 0, penalty contact, no gravity.
// s_c ~ N(1.328e-2, 3.32e-3) per node (CoV 25 %), bond rule min, floor 0; clamped points never fail.
// Model: LPS (nu = 0.35 needs a state-based model, spec B.3) or PMB (nu = 1/4).
// Reference: qualitative only [src]: the support reaction has a first peak, a dip and a second
// peak at final failure (read on 0.25 ms window means of the support reaction: the disc rings, the
// raw samples are noise); the tip decelerates; radial plus circumferential cracks. Initial kinetic
// energy 10.49 J [DERIVED] must be accounted for: E_kin + E_el + E_contact + E_damage (damage by
// difference, as the source), checked to close before the first bond breaks.
// Discretisation: the source used dx = 1 mm (25,946 points with its tip); the default here is
// dx = 1.5 mm (m = 2.07) to run in minutes; problems/cases.txt runs dx = 1 mm.
// Run: pmma_disk_impact_3d [--model lps|pmb] [--dx 1.5e-3] [--seed 1] [--t-end 8e-3] [--quick] [--check]
// Writes: history.csv (impactor z, v, contact force, support reaction, energies, broken bonds),
// force_window.csv (window means of support and tip forces), damage.csv and damage.vtu (final
// point damage), summary.csv, params.csv.
#include "problems/common/analysis/force_history.hpp"
#include "pd/bc/contact.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/io/vtu.hpp"
#include "pd/models/registry.hpp"
#include "pd/core/random_field.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace {

struct Outcome {
    pd::TwoPeaks peaks;  // of the window-mean support force, times from first contact
    double F_mean_max = 0;  // largest window mean of the support force [N]
    double v_end = NAN, w_max = 0, E_gap_pre = 0, E_damage = NAN;
    double t_first_break = NAN, wall = 0;
    long broken = 0, steps = 0;
    std::vector<double> phi;
};

struct Setup {
    const pd::Body<3>& body;
    pd::NodeSet clamp;
    double rho, dt, t_end, v0, mass, radius, z_top, k_pen, window;
    pd::CriticalStretch* cs;
};

template <class Model>
Outcome simulate(Model& model, pd::Bonds& bonds, const Setup& s, const std::filesystem::path& out, pd::io::Checkpoints& cp)
{
    pd::io::Timer timer;
    pd::Explicit<3, Model> sim(s.body, bonds, model, s.rho);
    if (s.cs) sim.scene.set_damage(*s.cs);
    sim.boundary.fix(s.clamp);
    // The tip starts touching the top layer of points: t = 0 is the first contact.
    pd::Impactor<3> tip{.mass = s.mass, .radius = s.radius, .c = {0, 0, s.z_top + s.radius}, .V = {0, 0, -s.v0}, .k = s.k_pen};
    tip.validate();
    sim.scene.extra_force = [&](double t, const pd::Field<3>& y, const pd::Field<3>&, pd::Field<3>& b) { tip(t, y, b, s.body.volume); };
    const double E0 = tip.kinetic_energy();  // [J]
    pd::io::CsvWriter h(out / "history.csv", {"t_s", "z_tip_m", "v_tip_m_s", "F_contact_N", "F_support_N", "E_tip_kinetic_J",
                                              "E_body_kinetic_J", "E_elastic_J", "E_contact_J", "E_damage_J", "broken_bonds"});
    Outcome o;
    pd::require_steps(std::ceil(s.t_end / s.dt), "--t-end / dt");
    const long steps = static_cast<long>(std::ceil(s.t_end / s.dt));
    const long every = std::max(1L, steps / 500);  // ~500 samples
    pd::WindowMean F_support(s.window), F_tip(s.window);  // window means of the support and tip forces [N]
    long broken_at_contact = -1;
    double Fc_max = 0, t_Fc_max = 0;  // maximum contact force on the tip [N] and its time [s]
    auto state = [&](pd::StateArchive& ar) {  // what a checkpoint holds (io/checkpoints.hpp)
        sim.state(ar), tip.state(ar), h.state(ar), F_support.state(ar, "F_support"), F_tip.state(ar, "F_tip"), timer.state(ar, "wall");
        ar("t_first_break", o.t_first_break), ar("E_gap_pre", o.E_gap_pre), ar("E_damage", o.E_damage), ar("w_max", o.w_max);
        ar("steps", o.steps), ar("broken_at_contact", broken_at_contact), ar("Fc_max", Fc_max), ar("t_Fc_max", t_Fc_max);
    };
    cp.loop(steps, state, [&] { sim.start(); }, [&](long n) {
        sim.step(s.dt);
        if (std::isnan(o.t_first_break) && sim.broken_bonds > 0) o.t_first_break = sim.t;
        double F_sup = 0;  // support reaction along z [N]: -sum f_z V over the clamped points
        for (int i : s.clamp) F_sup -= sim.internal_force_density().c[2][i] * s.body.volume[i];
        F_support.add(sim.t, s.dt, std::abs(F_sup)), F_tip.add(sim.t, s.dt, std::abs(tip.F[2]));
        if (n % every && n != steps) return true;
        const pd::Energies e = sim.check_energy();
        const double Uc = tip.contact_energy(sim.positions(), s.body.volume);
        const double Ed = E0 - tip.kinetic_energy() - e.kinetic - e.strain - Uc;  // by difference
        h.row({sim.t, tip.c[2], tip.V[2], tip.F[2], F_sup, tip.kinetic_energy(), e.kinetic, e.strain, Uc, Ed, sim.broken_bonds});
        // Energy closure while no bond has broken since the tip touched (bonds floored at s0 = 0
        // may break at round-off stretch before contact; they store no energy).
        if (broken_at_contact < 0 && tip.in_contact > 0) broken_at_contact = sim.broken_bonds;
        if (broken_at_contact < 0 || sim.broken_bonds == broken_at_contact) o.E_gap_pre = std::max(o.E_gap_pre, std::abs(Ed) / E0);
        o.E_damage = Ed;
        o.w_max = std::max(o.w_max, s.z_top + s.radius - tip.c[2]);
        o.steps = n;
        if (std::abs(tip.F[2]) > Fc_max) Fc_max = std::abs(tip.F[2]), t_Fc_max = sim.t;
        // Stop: rebounding, or perforated (tip contact force below 2 % of its maximum 0.3 ms
        // after that maximum).
        return !(tip.V[2] > 0 || (sim.t > t_Fc_max + 3e-4 && std::abs(tip.F[2]) < 0.02 * Fc_max));
    });
    // The source's first peak, dip and second peak, read on the window means (a drop of 10 %).
    o.peaks = pd::two_peaks(F_support.t_mid_s, F_support.mean);
    for (double F : F_support.mean) o.F_mean_max = std::max(o.F_mean_max, F);
    pd::io::CsvWriter fw(out / "force_window.csv", {"t_s", "F_support_mean_N", "F_tip_mean_N"});
    for (std::size_t k = 0; k < F_support.mean.size(); ++k) fw.row({F_support.t_mid_s[k], F_support.mean[k], F_tip.mean[k]});
    o.v_end = tip.V[2];
    o.broken = sim.broken_bonds;
    o.phi = pd::point_damage(bonds);
    o.wall = timer.seconds();
    return o;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI, defaults = the source's case except dx; see header), echoed and saved.
    pd::io::Case run("pmma_disk_impact_3d", "Steel tip on a clamped PMMA disc with random critical stretch (spec/001_004 V7).",
                     "reports/3d/pmma_disk_impact", "output folder (CSV files, params.csv, damage.vtu)");
    pd::io::Options& opt = run.opt;
    std::string& model_name = opt.add_string("model", "lps", "material model", {"lps", "pmb"});
    double& E = opt.add("E", 3.3e9, "Young's modulus", "Pa");
    double& nu = opt.add("nu", 0.35, "Poisson's ratio (pmb: 1/4 implied)");
    double& rho = opt.add("rho", 1190, "density", "kg/m^3");
    double& D = opt.add("diameter", 0.076, "disc diameter", "m");
    double& thick = opt.add("thickness", 0.003, "disc thickness", "m");
    double& r_clamp = opt.add("r-clamp", 0.032, "points at radius >= r-clamp are clamped", "m");
    double& delta = opt.add("delta", 3.1e-3, "horizon", "m");
    double& dx = opt.add("dx", 1.5e-3, "lattice spacing (source 1e-3; quick 2e-3)", "m");
    double& mass = opt.add("mass", 18.49, "impactor mass", "kg");
    double& tip_d = opt.add("tip-diameter", 0.0127, "impactor tip diameter", "m");
    double& v0 = opt.add("v0", 1.065, "impact velocity", "m/s");
    double& penalty = opt.add("penalty", 1, "contact penalty factor k = factor E/dx^2");
    double& s_mean = opt.add("s-mean", 1.328e-2, "critical stretch mean");
    double& s_sd = opt.add("s-sd", 3.32e-3, "critical stretch standard deviation");
    std::string& rule = opt.add_string("bond-rule", "min", "bond value from the two nodes", {"min", "max", "mean", "bond"});
    int& seed = opt.add_int("seed", 1, "random field seed");
    double& t_end = opt.add("t-end", 8e-3, "end time from first contact (quick 1.2e-3)", "s");
    double& window = opt.add("force-window", 0.25e-3, "window of the force means (the disc rings: raw samples are noise)", "s");
    double& dt_factor = opt.add("dt-factor", 0.5, "time step / Silling-Askari critical step (PMB bound; LPS at nu 0.35 is unstable at 0.8)");
    for (const char* o : {"E", "rho", "diameter", "thickness", "r-clamp", "delta", "dx", "mass", "tip-diameter", "v0", "penalty",
                          "s-mean", "t-end", "force-window", "dt-factor"})
        opt.require_positive(o);
    opt.require_at_least("seed", 0);
    run.allow_checkpoints();
    run.parse(argc, argv);
    if (!(s_sd >= 0)) opt.fail("option --s-sd must be >= 0");
    if (!(r_clamp < 0.5 * D)) opt.fail("option --r-clamp must be below the disc radius");
    if (const std::string msg = pd::validate_elastic(E, nu, 3, pd::Plane::strain); !msg.empty()) opt.fail(msg);
    const bool quick = run.quick();
    run.quick_default("dx", 2e-3);
    run.quick_default("t-end", 1.2e-3);
    run.start();
    const std::filesystem::path& out = run.out();

    // 2. Discretisation: disc of cells dx centred on the z axis, bottom face z = 0.
    const double R = 0.5 * D;
    const pd::Body<3> body = pd::fill<3>({-R, -R, 0}, {R, R, thick}, dx, pd::in_cylinder({0, 0, 0}, 2, R, -1, 1));
    const pd::NodeSet clamp = pd::select<3>(body, [&](const pd::Vec<3>& p) { return std::hypot(p[0], p[1]) >= r_clamp; }, "clamped ring");
    pd::Bonds bonds = pd::build_bonds(body, delta);
    bonds.enable_damage();
    std::printf("nodes %zu (clamped %zu), bonds %zu, layers %ld, m = %.3g\n", body.size(), clamp.size(), bonds.size(),
                std::lround(thick / dx), delta / dx);

    // 3. Damage: random critical stretch per bond; clamped points never fail.
    pd::CriticalStretch cs;
    cs.s0_bond = pd::bond_field(pd::RandomSpec::normal(s_mean, s_sd, static_cast<std::uint64_t>(seed)), bonds, pd::parse_bond_rule(rule));
    cs.protect(clamp, body.size());
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const pd::PMB::Params pmb{.material = mat, .dim = 3};
    const double c = pd::PMB::micromodulus(pmb, pd::Influence{}, delta);  // also the LPS stand-in (critical_step.hpp)
    const double dt = dt_factor * pd::critical_step_silling_askari(bonds, rho, c).dt;
    std::printf("dt %.4g s, up to %ld steps\n", dt, static_cast<long>(std::ceil(t_end / dt)));

    // 4.-5. Impactor and integration.
    const double z_top = *std::max_element(body.x.c[2].begin(), body.x.c[2].end());  // top layer of points [m]
    const Setup setup{body, clamp, rho, dt, t_end, v0, mass, 0.5 * tip_d, z_top, pd::Impactor<3>::default_penalty(E, dx, penalty), window, &cs};
    const Outcome o = pd::with_model<pd::PMB, pd::LPS>(pd::ModelChoice{.name = model_name, .material = mat}, body, bonds,
                                     [&](auto& model) { return simulate(model, bonds, setup, out, run.checkpoints()); });

    // 6. Crack pattern, summary, verdict.
    pd::io::CsvWriter dmg(out / "damage.csv", {"x_m", "y_m", "z_m", "phi"});
    for (std::size_t i = 0; i < body.size(); ++i) dmg.row({body.x.c[0][i], body.x.c[1][i], body.x.c[2][i], o.phi[i]});
    pd::io::VtuWriter vtu(out / "damage.vtu");
    vtu.points(body.x.c[0], body.x.c[1], body.x.c[2]);
    vtu.scalar("damage", o.phi);
    vtu.write();
    const double E0 = 0.5 * mass * v0 * v0, nan = NAN;
    using pd::io::relative_error;
    // A force-history feature the run did not show (TwoPeaks: NaN, e.g. no second peak, or no peak
    // yet in the short --quick run) is not observed.
    run.summary_observed({
        {"initial_kinetic_energy", E0, 10.49, relative_error(E0, 10.49), "J"},  // [DERIVED] spec B.5
        {"first_peak_support_force", o.peaks.F1, nan, nan, "N"},  // window means, times from first contact
        {"first_peak_time", o.peaks.t1, nan, nan, "s"},
        {"dip_support_force", o.peaks.F_dip, nan, nan, "N"},
        {"dip_time", o.peaks.t_dip, nan, nan, "s"},
        {"second_peak_support_force", o.peaks.F2, nan, nan, "N"},
        {"second_peak_time", o.peaks.t2, nan, nan, "s"},
        {"first_bond_break_time", o.t_first_break, nan, nan, "s"},  // incl. floored bonds at rest
        {"tip_velocity_end", -o.v_end, v0, relative_error(-o.v_end, v0), "m/s"},  // reference: no deceleration
        {"tip_travel_max", o.w_max, nan, nan, "m"},
        {"energy_gap_until_breakage_under_tip", o.E_gap_pre, 0, nan, "-"},
        {"damage_energy_end", o.E_damage, nan, nan, "J"},
        {"broken_bonds", static_cast<double>(o.broken), nan, nan, "-"},
        {"wall_time", o.wall, nan, nan, "s"}});
    run.print_summary(28);

    // Checks: the energy balance closes within 2 % of E0 while no bond breaks under the tip
    // (Verlet O(dt^2) with the stiff penalty; the measured gap is the summary row
    // energy_gap_until_breakage_under_tip); the tip decelerates; the support carries a force; bonds
    // break; and, on a run long enough to reach final failure
    // (not --quick), the source's shape: a first peak, a dip of at least 10 %, a second peak above
    // the first.
    run.property(o.E_gap_pre < 0.02, "energy balance closes within 2 % until bonds break under the tip");
    run.property(-o.v_end < v0, "the tip decelerates");
    run.property(o.F_mean_max > 0, "the support carries a reaction force");
    run.property(o.broken > 0, "bonds break under the tip");
    if (!quick) run.property(!std::isnan(o.peaks.F2), "support force: first peak, dip, second peak");
    return run.finish("support force (%.3g ms means) first peak %.4g N at %.4g ms, dip %.4g N at %.4g ms, second peak %.4g N at %.4g ms;"
                      " tip %.4g -> %.4g m/s, %ld broken bonds, %.1f s", window * 1e3, o.peaks.F1, o.peaks.t1 * 1e3, o.peaks.F_dip, o.peaks.t_dip * 1e3,
                      o.peaks.F2, o.peaks.t2 * 1e3, v0, -o.v_end, o.broken, o.wall);
}

int main(int argc, char** argv) { return pd::io::guarded_main("pmma_disk_impact_3d", [&] { return run_case(argc, argv); }); }
