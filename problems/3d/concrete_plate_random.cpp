// problems/3d/concrete_plate_random.cpp -- concrete plate pulled at constant speed, with a random
// critical stretch (Soares 2018; spec/001_004 B.4, V6, V8): fracture time and force-displacement
// curve for an ensemble of seeds.
// Case: plate 0.5 x 0.5 x 0.004 m, E 32 GPa, nu 0.25, rho 2400 kg/m^3, delta 11 mm; grip A (x < delta)
// fixed in x and y, grip B (x > L - delta) moved in x at 8 mm/s; u_z = 0 everywhere (the source's
// "plane stress", which is plane strain: spec B.4). The 4 mm thickness is below one spacing, so the
// plate is one layer of points: a 2D plane-strain PMB (nu = 1/4 exact) with thickness 4 mm, dx =
// delta/m. Critical stretch per bond from s_c ~ N(4e-4, 1.5e-4) per node (random_field.hpp),
// bond rule min (the pair fails with its weaker half, spec B.2; --bond-rule max|mean|bond), floored at 0; grips never fail.
// Reference: failure at about 14 ms [src]; apparent modulus about 10 % above E in Peridigm [src],
// of which 6.7 % is the plane-strain modulus E/(1 - nu^2) = 34.13 GPa [DERIVED]; no peak stress
// is printed. Compared: modulus vs E/(1 - nu^2); fracture time (peak force) mean and spread over
// seeds vs 14 ms; energy balance W = E_el + E_kin + E_damage (E_damage by difference, as the source).
// Run: concrete_plate_random_3d [--seeds 3] [--seed 1] [--m 3] [--speed 40e-3] [--quick] [--check]
//      The default speed is 5x the source's 8 mm/s (still ~20 wave transits before failure, so
//      quasi-static) to stay within minutes; problems/cases.txt runs 8 mm/s with 5 seeds. Times
//      are compared with 14 ms x (8 mm/s / speed) x (size / 0.5 m).
// Writes: curve_seed<k>.csv (t, U, F, stress, strain, energies), summary.csv, seeds.csv, params.csv.
#include "pd/damage/critical_stretch.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/pmb.hpp"
#include "pd/core/random_field.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <cmath>
#include <cstdio>

namespace {

struct SeedResult { double t_peak = NAN, F_peak = NAN, strain_peak = NAN, modulus = NAN, E_damage = NAN; bool failed = false; long broken = 0; };

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI, defaults = the source's case), echoed and saved.
    pd::io::Case run("concrete_plate_random_3d", "Concrete plate in tension with random critical stretch (spec/001_004 V6).",
                     "reports/3d/concrete_plate_random");
    pd::io::Options& opt = run.opt;
    double& E = opt.add("E", 32e9, "Young's modulus", "Pa");
    double& rho = opt.add("rho", 2400, "density", "kg/m^3");
    double& L = opt.add("size", 0.5, "plate side (quick: 0.15)", "m");
    double& thick = opt.add("thickness", 0.004, "plate thickness", "m");
    double& delta = opt.add("delta", 0.011, "horizon", "m");
    double& m = opt.add("m", 3, "horizon ratio delta/dx");
    double& speed = opt.add("speed", 40e-3, "grip B speed (source 8e-3; see header)", "m/s");
    double& s_mean = opt.add("s-mean", 4e-4, "critical stretch mean");
    double& s_sd = opt.add("s-sd", 1.5e-4, "critical stretch standard deviation");
    std::string& calib = opt.add_string("calibration", "continuum", "PMB micromodulus: continuum or lattice sum", {"continuum", "lattice"});
    std::string& rule = opt.add_string("bond-rule", "min", "bond value from the two nodes", {"min", "max", "mean", "bond"});
    int& seeds = opt.add_int("seeds", 3, "number of seeds in the ensemble (quick: 2; full-size case: 5)");
    int& seed0 = opt.add_int("seed", 1, "first seed");
    double& t_end = opt.add("t-end", 0.025, "end time (default scaled by (8e-3/speed) (size/0.5))", "s");
    double& dt_factor = opt.add("dt-factor", 0.7, "time step / Silling-Askari critical step");
    for (const char* o : {"E", "rho", "size", "thickness", "delta", "speed", "s-mean", "t-end", "dt-factor"}) opt.require_positive(o);
    opt.require_at_least("m", 1);
    opt.require_at_least("seeds", 1);
    run.allow_checkpoints();
    run.parse(argc, argv);
    if (!(s_sd >= 0)) opt.fail("option --s-sd must be >= 0");
    run.quick_default("size", 0.15);
    run.quick_default("seeds", 2);
    if (!opt.given("t-end")) t_end *= (8e-3 / speed) * (L / 0.5);
    run.start();
    const std::filesystem::path& out = run.out();
    pd::io::Checkpoints& cp = run.checkpoints();
    pd::io::Timer timer;

    // 2. Discretisation: one layer of points, grips delta wide at both ends.
    const double dx = delta / m, nu = 0.25;
    const pd::Body<2> body = pd::box<2>({0, 0}, {L, L}, dx, thick);
    pd::Bonds bonds = pd::build_bonds(body, delta);
    const pd::NodeSet A = pd::select<2>(body, pd::in_box<2>({-1, -1}, {delta, 2 * L}), "grip A");
    const pd::NodeSet B = pd::select<2>(body, pd::in_box<2>({L - delta, -1}, {2 * L, 2 * L}), "grip B");
    double xA = 0, xB = L;  // inner grip edges [m]
    for (int i : A) xA = std::max(xA, body.x.c[0][i]);
    for (int i : B) xB = std::min(xB, body.x.c[0][i]);
    const double gauge = xB - xA;  // [m]
    std::printf("nodes %zu, bonds %zu, dx %.4g m, gauge %.4g m\n", body.size(), bonds.size(), dx, gauge);

    // 3. Model: 2D plane-strain PMB; random critical stretch.
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const pd::PMB::Params params{.material = mat, .dim = 2, .plane = pd::Plane::strain, .measure = thick,
                                 .calibration = calib == "lattice" ? pd::PMB::Params::Calibration::lattice : pd::PMB::Params::Calibration::continuum,
                                 .dx = dx};
    const double c = pd::PMB::micromodulus(params, pd::Influence{}, delta);
    const double E_ps = E / (1 - nu * nu);  // plane-strain uniaxial modulus [Pa]
    const double dt = dt_factor * pd::critical_step_silling_askari(bonds, rho, c).dt;
    pd::require_steps(seeds * std::ceil(t_end / dt), "--t-end / dt x --seeds");
    const long steps = static_cast<long>(std::ceil(t_end / dt));
    const long every = std::max(1L, steps / 400);  // ~400 curve samples
    std::printf("dt %.4g s, %ld steps per seed, %d seeds\n", dt, steps, seeds);

    // 4.-5. Per seed: grips, integrate, record the force-displacement curve and energies.
    std::vector<SeedResult> res;
    pd::io::CsvWriter seeds_csv(out / "seeds.csv", {"seed", "t_peak_s", "F_peak_N", "stress_peak_Pa", "strain_peak", "modulus_Pa",
                                                    "E_damage_J", "broken_bonds", "fractured"});
    for (int s = seed0; s < seed0 + seeds; ++s) {
        pd::Bonds b = bonds;
        b.enable_damage();
        pd::PMB model(params, b);
        pd::CriticalStretch cs;
        cs.s0_bond = pd::bond_field(pd::RandomSpec::normal(s_mean, s_sd, static_cast<std::uint64_t>(s)), b, pd::parse_bond_rule(rule));
        cs.protect(A, body.size());
        cs.protect(B, body.size());
        pd::Explicit<2, pd::PMB> sim(body, b, model, rho);
        sim.scene.set_damage(cs);
        sim.boundary.fix(A);
        sim.boundary.prescribe({pd::Prescribed::Kind::velocity, B, 0, pd::TimeFunction::constant(speed)});
        pd::io::CsvWriter curve(out / ("curve_seed" + std::to_string(s) + ".csv"),
                                {"t_s", "U_m", "F_N", "stress_Pa", "strain", "E_elastic_J", "E_kinetic_J", "W_ext_J", "E_damage_J"});
        SeedResult r{};
        std::vector<double> strains, stresses;  // the samples
        double F_max = 0;
        auto sample = [&](const pd::Energies& e) {
            double F = 0;  // reaction at grip B [N]: -sum f_x V
            for (int i : B) F -= sim.internal_force_density().c[0][i] * body.volume[i];
            const double U = speed * sim.t, strain = U / gauge, stress = F / (L * thick);
            const double Ed = e.external_work - e.strain - e.kinetic;
            curve.row({sim.t, U, F, stress, strain, e.strain, e.kinetic, e.external_work, Ed});
            if (F > F_max) F_max = F, r.t_peak = sim.t, r.F_peak = F, r.strain_peak = strain;
            strains.push_back(strain), stresses.push_back(stress);
            r.E_damage = Ed;
            if (F_max > 0 && F < 0.05 * F_max && sim.t > r.t_peak) r.failed = true;
        };
        auto state = [&](pd::StateArchive& ar) {  // what a checkpoint holds (io/checkpoints.hpp)
            sim.state(ar), curve.state(ar), timer.state(ar, "wall"), ar("strains", strains), ar("stresses", stresses), ar("F_max", F_max);
            ar("t_peak", r.t_peak), ar("F_peak", r.F_peak), ar("strain_peak", r.strain_peak), ar("E_damage", r.E_damage), ar("failed", r.failed);
        };
        cp.loop(steps, state, [&] { sim.start(); }, [&](long n) {
            sim.step(dt);
            if (n % every == 0 || n == steps) sample(sim.check_energy());
            return !r.failed;
        });
        // Apparent modulus: least-squares slope through the origin of the samples with strain in
        // [0.2, 0.6] x the peak strain (past the first wave transits, before the damage spreads).
        double sxy = 0, sxx = 0;
        for (std::size_t k = 0; k < strains.size(); ++k)
            if (const double x = strains[k], y = stresses[k]; x >= 0.2 * r.strain_peak && x <= 0.6 * r.strain_peak) sxy += x * y, sxx += x * x;
        r.modulus = sxx > 0 ? sxy / sxx : NAN;
        r.broken = sim.broken_bonds;
        res.push_back(r);
        seeds_csv.row({s, r.t_peak, r.F_peak, r.F_peak / (L * thick), r.strain_peak, r.modulus, r.E_damage, r.broken, r.failed ? 1 : 0});
        std::printf("seed %d: peak %.4g N at t = %.4g s (strain %.3e), modulus %.4g GPa, fractured %s, broken bonds %ld\n", s, r.F_peak,
                    r.t_peak, r.strain_peak, r.modulus / 1e9, r.failed ? "yes" : "no", r.broken);
    }
    const double wall = timer.seconds();

    // 6. Ensemble statistics, summary, verdict.
    auto stats = [&](auto get) {
        double mu = 0, v = 0;
        for (const auto& r : res) mu += get(r) / res.size();
        for (const auto& r : res) v += (get(r) - mu) * (get(r) - mu) / std::max<std::size_t>(1, res.size() - 1);
        return std::pair{mu, std::sqrt(v)};
    };
    const auto [t_mu, t_sd] = stats([](const SeedResult& r) { return r.t_peak; });
    const auto [e_mu, e_sd] = stats([](const SeedResult& r) { return r.strain_peak; });
    const auto [S_mu, S_sd] = stats([&](const SeedResult& r) { return r.F_peak / (L * thick); });
    const auto [M_mu, M_sd] = stats([](const SeedResult& r) { return r.modulus; });
    int fractured = 0;
    for (const auto& r : res) fractured += r.failed;
    const double t_ref = 14e-3 * (8e-3 / speed) * (L / 0.5), nan = NAN;  // source's time, scaled with --speed, --size
    using pd::io::relative_error;
    run.summary({
        {"fracture_time_mean", t_mu, t_ref, relative_error(t_mu, t_ref), "s"},
        {"fracture_time_sd", t_sd, nan, nan, "s"},
        {"peak_strain_mean", e_mu, 14e-3 * 8e-3 / 0.5, relative_error(e_mu, 14e-3 * 8e-3 / 0.5), "-"},  // [DERIVED] 2.24e-4
        {"peak_strain_sd", e_sd, nan, nan, "-"},
        {"peak_stress_mean", S_mu, nan, nan, "Pa"},
        {"peak_stress_sd", S_sd, nan, nan, "Pa"},
        {"apparent_modulus_mean", M_mu, E_ps, relative_error(M_mu, E_ps), "Pa"},
        {"apparent_modulus_over_E", M_mu / E, 1.10, relative_error(M_mu / E, 1.10), "-"},  // Peridigm: about +10 %
        {"seeds_fractured", static_cast<double>(fractured), static_cast<double>(seeds), nan, "-"},
        {"wall_time", wall, nan, nan, "s"}});
    run.print_summary(28);

    // Checks: every seed fractures; modulus within 10 % of E/(1 - nu^2) (PD surface softening of
    // the free edges and the grip transition; neither published nor derived: a regression bound); the weakest link fails
    // below the mean critical stretch (peak strain < s_mean); seeds differ (spread > 0).
    // The fracture time is NOT checked: the source gives only "about 14 ms" (spec B.4, stated
    // without a tolerance or peak stress), and this model fails about 37 % earlier at 8 mm/s
    // (reports/3d/concrete_plate_random.md). The verdict line says so instead of letting PASS
    // suggest the time is reproduced (10 %: the modulus band above).
    run.property(fractured == seeds, "every seed fractures before t_end");
    run.regression_bound(std::abs(M_mu / E_ps - 1) < 0.10, "apparent modulus within 10 % of E/(1 - nu^2) (band not derived)");
    run.property(e_mu < s_mean, "mean peak strain below the mean critical stretch (weakest link)");
    run.property(seeds == 1 || t_sd > 0, "fracture time varies with the seed");
    const double t_err = relative_error(t_mu, t_ref);
    return run.finish("(checked: modulus, every seed fractures, weakest link, spread) fracture at %.3g +- %.2g ms, source about %.3g ms: "
                      "%s (%+.0f %%); modulus %.4g GPa (E/(1-nu^2) %.4g), %.1f s", t_mu * 1e3, t_sd * 1e3, t_ref * 1e3,
                      std::abs(t_err) < 0.10 ? "fracture time reproduced within 10 %" : "fracture time NOT reproduced",
                      100 * (t_mu / t_ref - 1), M_mu / 1e9, E_ps / 1e9, wall);
}

int main(int argc, char** argv) { return pd::io::guarded_main("concrete_plate_random_3d", [&] { return run_case(argc, argv); }); }
