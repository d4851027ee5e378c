// problems/3d/viscoelastic_relaxation.cpp -- relaxation of Mitchell's ordinary viscoelastic model
// (models/viscoelastic_lps.hpp) and of the correspondence viscoelastic model
// (models/viscoelastic_correspondence.hpp) under a step pure shear and under a ramp-and-hold.
// Case: a cube of n^3 nodes, every node moved with the uniform deformation y = F(t) x, F = I +
//   (gamma0/2)(e_x e_y + e_y e_x) (engineering shear gamma0), applied at t = 0 in one step of dt = 0
//   and held (step), or ramped linearly over --ramp-tau tau_b and held (ramp). A polymer-like
//   E = 3 GPa, nu = 0.35, gamma_b = 1, tau_b = 1 ms (the source gives no numbers: spec/000c V4-V5).
// Source: Biondani 2018 sec. 7.2-7.3, eqs. 7.18-7.29 (spec/000c sec. 1.4-1.5, V4-V5, errata 1-5).
// References (closed forms, evaluated here from the geometry, not by the models):
//   V4 centre node, bond of largest |e_d|: t_d(t) = alpha omega e_d0 (1 + gamma_b e^{-t/tau_b}),
//      alpha = 15 G/m, e_d0 = |F xi| - |xi| - theta |xi|/3 by hand sums; theta = O(gamma0^2) at full families.
//   V5 centre node: sigma_xy(t) = G gamma0 (1 + gamma_b e^{-t/tau_b}); the mean stress does not relax.
//   Ramp (7.18): x(t) = rate min(t, t1): viscous part gamma_b (x - h), h = rate (r(t) - r(t - t1)),
//      r(s) = s - tau_b (1 - e^{-s/tau_b}) for s > 0 (x = e_d for V4, 2 G eps_xy for V5).
// Run: viscoelastic_relaxation_3d [--E 3e9] [--nu 0.35] [--gamma-b 1] [--tau 1e-3] [--gamma0 1e-3]
//   [--n 8] [--dx 1e-3] [--m 3.05] [--steps-per-tau 10] [--hold-tau 5] [--ramp-tau 2] [--quick] [--check] [--out DIR]
// Writes: step.csv, ramp.csv (histories), summary.csv, params.csv.
#include "pd/bond_loop.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "problems/common/measure/shear_cube.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/models/viscoelastic_lps.hpp"
#include "reference/lps_shear.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace {

// alpha, theta and e_d of bond k of node i under the shear gamma, from the hand-written family sums
// of reference/lps_shear.hpp (its own neighbour search, not pd::Bonds).
struct HandLPS {
    double alpha = 0, theta = 0, ed = 0;
};
using Points = std::vector<std::array<double, 3>>;
HandLPS hand_lps(const Points& pts, const pd::Body<3>& body, const pd::Bonds& b, std::size_t i, std::int64_t k, double gamma, double G)
{
    const auto f = pd::ref::lps_shear_family(pts, body.volume, static_cast<int>(i), b.delta, G, gamma);
    const auto at = std::find(f.partner.begin(), f.partner.end(), b.partner[k]) - f.partner.begin();
    return {f.alpha, f.theta, f.ed.at(at)};
}

struct Histories {
    double lps_err = 0, corr_err = 0, lps_ratio0 = 0, corr_sxy0 = 0, mean_drift = 0, theta_max = 0;  // see summary
};

int run_case(int argc, char** argv)
{
    // 1. Options (no published numbers: a polymer-like default), echoed and saved.
    pd::io::Case run("viscoelastic_relaxation_3d", "Relaxation of the ordinary and correspondence viscoelastic models (spec/000c V4-V5).",
                     "reports/3d/viscoelastic_relaxation");
    pd::io::Options& opt = run.opt;
    opt.add("E", 3e9, "Young's modulus of the equilibrium (elastic) branch", "Pa");
    opt.add("nu", 0.35, "Poisson's ratio", "-");
    opt.add("gamma-b", 1, "Maxwell branch stiffness ratio G_b/G", "-");
    opt.add("tau", 1e-3, "relaxation time tau_b", "s");
    opt.add("gamma0", 1e-3, "engineering shear strain of the step / ramp", "-");
    opt.add_int("n", 8, "nodes per cube side (--quick: 6)");
    opt.add("dx", 1e-3, "lattice spacing", "m");
    opt.add("m", 3.05, "horizon ratio delta/dx", "-");
    opt.add_int("steps-per-tau", 10, "time steps per relaxation time");
    opt.add("hold-tau", 5, "hold duration in relaxation times", "-");
    opt.add("ramp-tau", 2, "ramp duration in relaxation times", "-");
    for (const char* p : {"E", "tau", "gamma0", "dx", "hold-tau", "ramp-tau"}) opt.require_positive(p);
    opt.require_range("nu", -1, 0.5, false, false);
    opt.require_at_least("gamma-b", 0);
    opt.require_at_least("n", 5);
    opt.require_at_least("m", 1);
    opt.require_at_least("steps-per-tau", 1);
    opt.require_range("gamma0", 0, 0.5, false, true);
    run.parse(argc, argv);
    run.quick_default("n", 6);
    run.start();
    const pd::Elastic mat = pd::Elastic::from_E_nu(opt.get("E"), opt.get("nu"));
    const double G = mat.G, gb = opt.get("gamma-b"), tau = opt.get("tau"), g0 = opt.get("gamma0");
    const int n = opt.get_int("n"), spt = opt.get_int("steps-per-tau");
    const double dx = opt.get("dx"), dt = tau / spt;
    pd::require_steps(2 * (opt.get("hold-tau") + opt.get("ramp-tau")) * spt, "(--hold-tau + --ramp-tau) x --steps-per-tau, two runs");
    const long hold = std::lround(opt.get("hold-tau") * spt), ramp = std::max(1L, std::lround(opt.get("ramp-tau") * spt));
    const pd::io::Timer timer;

    // 2. Discretisation: cube, families; centre node and its bond of largest |e_d| under the shear.
    const pd::Body<3> body = pd::box<3>({{0, 0, 0}}, {{n * dx, n * dx, n * dx}}, dx);
    const pd::Bonds bonds = pd::build_bonds(body, opt.get("m") * dx);
    const std::size_t c = pd::node_nearest_diagonal_point(body, 0.5 * n * dx);
    const Points pts = pd::point_list(body);
    std::int64_t kc = bonds.begin(c);
    for (std::int64_t k = bonds.begin(c); k < bonds.end(c); ++k)
        if (std::abs(hand_lps(pts, body, bonds, c, k, g0, G).ed) > std::abs(hand_lps(pts, body, bonds, c, kc, g0, G).ed)) kc = k;
    const HandLPS hl = hand_lps(pts, body, bonds, c, kc, g0, G);
    std::printf("cube %d^3 nodes, %zu bonds; centre node %zu (%zu bonds), measured bond |xi| = %.3g m\n", n, bonds.size(), c,
                static_cast<std::size_t>(bonds.end(c) - bonds.begin(c)), bonds.length[kc]);

    // 3-5. Step (ramp = 0 steps) and ramp-and-hold histories of both models.
    auto r = [&](double s) { return s > 0 ? s - tau * (1 - std::exp(-s / tau)) : 0.0; };
    // LPS ramp reference: e_db from d e_db/dt = (e_d(t) - e_db)/tau_b (7.24) by classical RK4, 20
    // substeps per step, with e_d(t) from the exact kinematics (hand_lps): an independent integration.
    const int substeps = 20;
    auto history = [&](bool is_ramp, const std::string& file) {
        Histories h;
        pd::ViscoelasticLPS lps({{mat}, gb, tau}, bonds);
        pd::Correspondence<3> cm({mat, pd::Correspondence<3>::Law::flanagan_taylor}, body, bonds);
        pd::ViscoelasticCorrespondence corr(cm, {gb, tau}, body.x);
        pd::Field<3> f;
        pd::io::CsvWriter csv(run.file(file), {"t_s", "gamma", "lps_td_N_per_m6", "lps_td_ref_N_per_m6", "lps_theta_centre",
                                               "corr_sigma_xy_Pa", "corr_sigma_xy_ref_Pa", "corr_mean_stress_Pa"});
        const long steps = (is_ramp ? ramp : 0) + hold;
        const double t1 = is_ramp ? ramp * dt : 0;
        double p0 = 0, edb_ref = 0;  // edb_ref: reference back extension of the ramp [m]
        for (long s = 0; s <= steps; ++s) {
            const double t = s * dt, step_dt = s == 0 ? 0.0 : dt;
            const double g = is_ramp ? g0 * std::min(t / t1, 1.0) : g0;  // engineering shear at t [-]
            const pd::Field<3> y = pd::sheared(body, g);
            pd::internal_force(lps, bonds, y, step_dt, f);
            pd::internal_force(corr, bonds, y, step_dt, f);
            lps.commit(), corr.commit();
            // References: the elastic value x(t) plus the branch gamma_b (x - h).
            const double omega = bonds.omega[kc], ed_full = hl.ed;
            auto ed_at = [&](double tt) { return hand_lps(pts, body, bonds, c, kc, is_ramp ? g0 * std::min(tt / t1, 1.0) : g0, G).ed; };
            if (is_ramp && s > 0)
                for (int q = 0; q < substeps; ++q) {  // RK4 on (7.24) over [t - dt, t]
                    const double ta = t - dt + q * dt / substeps, hs = dt / substeps;
                    const double k1 = (ed_at(ta) - edb_ref) / tau, k2 = (ed_at(ta + hs / 2) - edb_ref - hs / 2 * k1) / tau;
                    const double k3 = (ed_at(ta + hs / 2) - edb_ref - hs / 2 * k2) / tau, k4 = (ed_at(ta + hs) - edb_ref - hs * k3) / tau;
                    edb_ref += hs / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
                }
            const double ed = ed_at(t);
            const double td_ref = hl.alpha * omega * (ed + gb * (is_ramp ? ed - edb_ref : ed * std::exp(-t / tau)));
            const double visc = is_ramp ? (std::min(t, t1) - (r(t) - r(t - t1))) / t1 : std::exp(-t / tau);  // (x - h)/x_full, (7.18)
            const double sxy_ref = G * g0 * ((is_ramp ? std::min(t / t1, 1.0) : 1.0) + gb * visc);
            const double td = lps.deviatoric_force_state(c, kc), sxy = cm.sigma[c](0, 1), p = cm.sigma[c].trace() / 3;
            if (s == 0) h.lps_ratio0 = td / (hl.alpha * omega * ed_full), h.corr_sxy0 = sxy, p0 = p;
            h.lps_err = std::max(h.lps_err, std::abs(td - td_ref) / (hl.alpha * omega * std::abs(ed_full) * (1 + gb)));
            h.corr_err = std::max(h.corr_err, std::abs(sxy - sxy_ref) / (G * g0 * (1 + gb)));
            if (!is_ramp) h.mean_drift = std::max(h.mean_drift, std::abs(p - p0) / (G * g0));
            h.theta_max = std::max(h.theta_max, std::abs(lps.lps.theta[c]));
            csv.row({t, g, td, td_ref, lps.lps.theta[c], sxy, sxy_ref, p});
            if (s % (steps / 10 > 0 ? steps / 10 : 1) == 0)
                std::printf("  %-4s t/tau %6.2f  t_d %12.6g (ref %12.6g)  sigma_xy %12.6g Pa (ref %12.6g)\n", is_ramp ? "ramp" : "step",
                            t / tau, td, td_ref, sxy, sxy_ref);
        }
        return h;
    };
    const Histories step = history(false, "step.csv"), rmp = history(true, "ramp.csv");
    const double wall = timer.seconds();

    // 6. Summary, checks, verdict.
    const double sxy0_ref = G * g0 * (1 + gb);
    run.summary({
        {"lps_td0_over_elastic", step.lps_ratio0, 1 + gb, pd::io::relative_error(step.lps_ratio0, 1 + gb), "-"},
        {"lps_step_max_rel_error", step.lps_err, 0, NAN, "-"},
        {"lps_ramp_max_rel_error", rmp.lps_err, 0, NAN, "-"},
        {"lps_theta_centre_max", step.theta_max, 0, NAN, "-"},
        {"corr_sigma_xy0", step.corr_sxy0, sxy0_ref, pd::io::relative_error(step.corr_sxy0, sxy0_ref), "Pa"},
        {"corr_step_max_rel_error", step.corr_err, 0, NAN, "-"},
        {"corr_ramp_max_rel_error", rmp.corr_err, 0, NAN, "-"},
        {"corr_mean_stress_drift_over_G_gamma0", step.mean_drift, 0, NAN, "-"},
        {"wall_s", wall, NAN, NAN, "s"}});
    std::printf("LPS: t_d(0+)/elastic %.9f (1 + gamma_b = %g), max error step %.2e ramp %.2e, |theta| %.2e\n", step.lps_ratio0, 1 + gb,
                step.lps_err, rmp.lps_err, step.theta_max);
    std::printf("correspondence: sigma_xy(0+) %.6g Pa (ref %.6g), max error step %.2e ramp %.2e, mean-stress drift %.2e; %.2f s\n",
                step.corr_sxy0, sxy0_ref, step.corr_err, rmp.corr_err, step.mean_drift, wall);
    // Tolerances: correspondence: the reference is linear in gamma, the Flanagan-Taylor strain of the
    // step is eps/(1 - eps^2/4), eps = gamma0/2: relative error gamma0^2/16 (6.25e-8 at 1e-3). LPS ramp:
    // the model takes e_d linear in each step, the exact e_d(t) has a curvature O(gamma0) relative,
    // error O(gamma0 (dt/tau)^2) (1.7e-8 measured). Both bounded by 10 gamma0^2.
    const double geo = 10 * g0 * g0;  // 1e-5 at gamma0 = 1e-3: ten times the second-order term
    run.check(std::abs(step.lps_ratio0 - (1 + gb)) < 1e-12 * (1 + gb), "LPS: t_d(0+) = (1 + gamma_b) alpha omega e_d0 to round-off");
    run.check(step.lps_err < 1e-12, "LPS: step relaxation = alpha omega e_d0 (1 + gamma_b e^{-t/tau_b}) to 1e-12");
    run.check(rmp.lps_err < geo, "LPS: ramp-and-hold = convolution (7.18) to 10 gamma0^2");
    run.check(step.theta_max < g0 * g0, "LPS: dilatation at the centre node below gamma0^2 (zero to first order)");
    run.check(step.corr_err < geo, "correspondence: step relaxation = G gamma0 (1 + gamma_b e^{-t/tau_b}) to 10 gamma0^2");
    run.check(rmp.corr_err < geo, "correspondence: ramp-and-hold = convolution (7.18) to 10 gamma0^2");
    run.property(step.mean_drift < 1e-12, "correspondence: mean stress unchanged by the relaxation (round-off)");
    return run.finish("both models relax as the SLS closed forms (worst error %.2e)",
                      std::max({step.lps_err, rmp.lps_err, step.corr_err, rmp.corr_err}));
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("viscoelastic_relaxation_3d", [&] { return run_case(argc, argv); }); }
