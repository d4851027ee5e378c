// problems/3d/numerical_viscosity.cpp -- numerical viscosity (a Maxwell branch tuned to the
// node-to-node shear-wave transit frequency) in the ordinary (Mitchell) and correspondence
// viscoelastic models: low-frequency stiffness unchanged, high-frequency stiffness times eta^2.
// Case: Si3N4 of the notched plate, E = 310 GPa, nu = 0.29, rho = 3200 kg/m^3 (assumed by the spec),
//   delta = 0.75 mm, m = 3.05 (Biondani 2018 sec. 8.4.1-8.4.2; spec/000c sec. 2.7, V6, errata 7-8).
// Parameters (models/viscoelastic_numerical.hpp, 8.27-8.29): gamma_b = eta^2 - 1, tau_b = 1/(2 pi eta f_cS).
// Measurement: a cube of n^3 nodes, every node moved with the homogeneous shear gamma(t) = gamma0
//   sin(w t) (engineering), N steps per period, the deviatoric response projected on sin/cos over whole
//   periods after a transient of 10 tau_b (e^-10 = 4.5e-5; and 2 periods): the stiffness |sigma_xy|/(G gamma0)
//   (correspondence, centre node) and |t_d|/(alpha omega e_d) (ordinary, the centre node's bond of
//   largest |e_d|), and the phase lead, at w_0/100, sqrt(w_0 w_P) and 30 w_P.
// Reference: the SLS transfer function G*(w)/G = (1 + i w/w_0)/(1 + i w/w_P), w_P = 1/tau_b,
//   w_0 = w_P/eta^2 (7.32-7.33): -> 1 at low, -> eta^2 at high frequency, phase asin(gamma_b/(2 + gamma_b)).
// Wave test: first torsional mode of a free bar (20 x 6 x 6 nodes, ordinary model), frequency from the
//   zero crossings of the end twist; elastic, with the V6 tau_b, and with tau_b = 100/w_e (pole far below
//   the mode: stiffness eta^2 G); reference: the root of m lambda^2 + k G*(lambda)/G = 0.
// Run: numerical_viscosity_3d [--eta 3] [--E --nu --rho --delta --m] [--gamma0 1e-4] [--n 5]
//   [--steps-per-period 200] [--periods 4] [--quick] [--check] [--out DIR]
// Writes: response.csv, summary.csv (with the wave-test ratios), params.csv.
#include "pd/bond_loop.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "problems/common/measure/shear_cube.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/models/viscoelastic_lps.hpp"
#include "pd/models/viscoelastic_numerical.hpp"
#include "pd/time/verlet.hpp"
#include "reference/lps_shear.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <utility>

namespace {

constexpr double pi = std::numbers::pi;

struct Response { std::complex<double> lps, corr; };  // complex stiffness over the elastic one [-]

// Wave test: free-free torsion of a square bar (Lx = 20 dx, 6 x 6 nodes), started with the velocity
// of the first torsional mode, v = v0 cos(pi x/L) e_x x r; the twist difference of the two end layers
// phi(t) ~ e^{-a t} sin(w_d t) has its zero crossings at k pi/w_d exactly. Returns w_d [rad/s] from the
// last of the first `crossings` zero crossings (linear interpolation between steps).
template <class Model>
double torsion_frequency(const pd::Body<3>& bar, pd::Bonds& bonds, Model& model, double rho, double L, double dt, int crossings)
{
    pd::Explicit<3, Model> sim(bar, bonds, model, rho);
    std::vector<int> left, right;
    double yc = 0, zc = 0;
    for (std::size_t i = 0; i < bar.size(); ++i) yc += bar.x.c[1][i] / bar.size(), zc += bar.x.c[2][i] / bar.size();
    const auto [x_min, x_max] = std::minmax_element(bar.x.c[0].begin(), bar.x.c[0].end());
    for (std::size_t i = 0; i < bar.size(); ++i) {
        const double a = 1e-3 * std::cos(pi * bar.x.c[0][i] / L);  // angular velocity [rad/s]: strains ~1e-12, linear
        sim.v.c[1][i] = -a * (bar.x.c[2][i] - zc), sim.v.c[2][i] = a * (bar.x.c[1][i] - yc);
        if (bar.x.c[0][i] < *x_min + 1e-9 * L) left.push_back(static_cast<int>(i));
        if (bar.x.c[0][i] > *x_max - 1e-9 * L) right.push_back(static_cast<int>(i));
    }
    auto twist = [&](const std::vector<int>& set) {  // mean rotation of a layer about the axis [rad]
        double num = 0, den = 0;
        for (int i : set) {
            const double ry = bar.x.c[1][i] - yc, rz = bar.x.c[2][i] - zc;
            num += ry * sim.u.c[2][i] - rz * sim.u.c[1][i], den += ry * ry + rz * rz;
        }
        return num / den;
    };
    sim.start();
    double prev = 0, t_cross = 0;
    for (int found = 0; found < crossings;) {
        sim.step(dt);
        const double phi = twist(left) - twist(right);
        if (sim.step_count > 1 && (phi > 0) != (prev > 0)) t_cross = sim.t - dt * phi / (phi - prev), ++found;
        prev = phi;
    }
    return crossings * pi / t_cross;
}

int run_case(int argc, char** argv)
{
    // 1. Options (defaults: the thesis' Si3N4 plate), echoed and saved.
    pd::io::Case run("numerical_viscosity_3d", "Numerical viscosity: low/high-frequency stiffness (spec/000c V6).",
                     "reports/3d/numerical_viscosity");
    pd::io::Options& opt = run.opt;
    opt.add("eta", 3.0, "damping coefficient eta (> 1)", "-");
    opt.add("E", 310e9, "Young's modulus", "Pa");
    opt.add("nu", 0.29, "Poisson's ratio", "-");
    opt.add("rho", 3200, "density", "kg/m^3");
    opt.add("delta", 0.75e-3, "horizon", "m");
    opt.add("m", 3.05, "horizon ratio delta/dx", "-");
    opt.add("gamma0", 1e-4, "engineering shear strain amplitude", "-");
    opt.add_int("n", 5, "nodes per cube side");
    opt.add_int("steps-per-period", 200, "time steps per period (--quick: 50)");
    opt.add_int("periods", 4, "periods measured after the transient");
    for (const char* p : {"E", "rho", "delta", "gamma0"}) opt.require_positive(p);
    opt.require_range("nu", -1, 0.5, false, false);
    for (auto [name, lo] : {std::pair{"m", 1}, std::pair{"n", 5}, std::pair{"steps-per-period", 8}, std::pair{"periods", 1}})
        opt.require_at_least(name, lo);
    run.parse(argc, argv);
    if (!(opt.get("eta") > 1)) opt.fail("--eta must be > 1");
    run.quick_default("steps-per-period", 50);
    run.start();
    const bool quick = run.quick();
    const pd::Elastic mat = pd::Elastic::from_E_nu(opt.get("E"), opt.get("nu"));
    const double rho = opt.get("rho"), dx = opt.get("delta") / opt.get("m"), eta = opt.get("eta"), g0 = opt.get("gamma0");
    const int n = opt.get_int("n"), N = opt.get_int("steps-per-period"), periods = opt.get_int("periods");
    const pd::io::Timer timer;

    // 2. Parameters (8.27-8.29) for the thesis' three eta and the chosen one.
    std::printf("c_S = %.1f m/s, f_cS = %.4g Hz (dx = %.4g m)\n", std::sqrt(mat.G / rho), std::sqrt(mat.G / rho) / dx, dx);
    for (double e : {1.01, 1.1, 3.0}) {
        const pd::MaxwellShear p = pd::numerical_viscosity(mat.G, rho, dx, e);
        std::printf("  eta %5.2f: gamma_b %.4f, tau_b %.3f ns, max phase %.2f deg\n", e, p.gamma_b, p.tau_b * 1e9,
                    std::asin(p.gamma_b / (2 + p.gamma_b)) * 180 / pi);
    }
    const pd::MaxwellShear vp = pd::numerical_viscosity(mat.G, rho, dx, eta);
    const double wP = 1 / vp.tau_b, w0 = wP / (eta * eta);
    auto Gstar = [&](double w) { return (1.0 + std::complex<double>(0, w / w0)) / (1.0 + std::complex<double>(0, w / wP)); };

    // 3. Discretisation and models: cube, centre node c and its bond kc of largest |e_d|.
    const pd::Body<3> body = pd::box<3>({{0, 0, 0}}, {{n * dx, n * dx, n * dx}}, dx);
    const pd::Bonds bonds = pd::build_bonds(body, opt.get("delta"));
    const std::size_t c = pd::node_nearest_diagonal_point(body, 0.5 * n * dx);
    // alpha, e_d by hand (reference/lps_shear.hpp); the elastic t_d amplitude alpha omega e_d of the bond
    // of largest |e_d|, odd part in gamma0 (the projection keeps it; omega = 1).
    const auto pts = pd::point_list(body);
    const auto fp = pd::ref::lps_shear_family(pts, body.volume, static_cast<int>(c), bonds.delta, mat.G, g0);
    const auto fm = pd::ref::lps_shear_family(pts, body.volume, static_cast<int>(c), bonds.delta, mat.G, -g0);
    std::size_t q_max = 0;
    for (std::size_t q = 0; q < fp.ed.size(); ++q)
        if (std::abs(fp.ed[q]) > std::abs(fp.ed[q_max])) q_max = q;
    std::int64_t kc = bonds.begin(c);
    while (bonds.partner[kc] != fp.partner[q_max]) ++kc;
    const double td_el = fp.alpha * bonds.omega[kc] * 0.5 * (fp.ed[q_max] - fm.ed[q_max]);

    // 4. Harmonic forcing at one frequency: both models, projection after the transient.
    auto respond = [&](double w) {
        pd::ViscoelasticLPS lps({{mat}, vp.gamma_b, vp.tau_b}, bonds);
        pd::Correspondence<3> cm({mat, pd::Correspondence<3>::Law::flanagan_taylor}, body, bonds);
        pd::ViscoelasticCorrespondence corr(cm, {vp.gamma_b, vp.tau_b}, body.x);
        const double T = 2 * pi / w, dt = T / N;
        const int transient = std::max(2, static_cast<int>(std::ceil(10 * vp.tau_b / T)));
        pd::require_steps((double(transient) + periods) * N, "--periods (+ the transient) x --steps-per-period");
        std::complex<double> pl = 0, pc = 0;
        pd::Field<3> y, f;
        for (long s = 1; s <= static_cast<long>(transient + periods) * N; ++s) {
            const double ph = 2 * pi * static_cast<double>(s % N) / N;
            y = pd::sheared(body, g0 * std::sin(ph));
            pd::internal_force(lps, bonds, y, dt, f);
            pd::internal_force(corr, bonds, y, dt, f);
            lps.commit(), corr.commit();
            if (s <= static_cast<long>(transient) * N) continue;
            const std::complex<double> basis(std::sin(ph), std::cos(ph));  // sin -> real part, cos -> imaginary (lead)
            pl += lps.deviatoric_force_state(c, kc) * basis, pc += cm.sigma[c](0, 1) * basis;
        }
        const double norm = 2.0 / (static_cast<double>(periods) * N);
        return Response{pl * norm / td_el, pc * norm / (mat.G * g0)};
    };

    // 5. Low, peak-phase and high frequency; compare with G*/G.
    pd::io::CsvWriter csv(run.file("response.csv"), {"omega_rad_s", "omega_over_w0", "lps_stiffness", "corr_stiffness", "ref_stiffness",
                                                  "lps_phase_deg", "corr_phase_deg", "ref_phase_deg"});
    const double disc = std::pow(2 * pi / N, 2) / 12;  // O((w dt)^2) of the integrator (problems/1d/sls_frequency.cpp)
    const double tol = 3 * disc + 10 * g0 * g0;        // plus O(gamma0^2) of the kinematics
    run.summary({{"gamma_b", vp.gamma_b, eta * eta - 1, pd::io::relative_error(vp.gamma_b, eta * eta - 1), "-"},
                 {"tau_b", vp.tau_b, NAN, NAN, "s"}});
    const char* names[] = {"low", "mid", "high"};
    const double freqs[] = {w0 / 100, std::sqrt(w0 * wP), 30 * wP};
    for (int q = 0; q < 3; ++q) {
        const Response r = respond(freqs[q]);
        const std::complex<double> ref = Gstar(freqs[q]);
        csv.row({freqs[q], freqs[q] / w0, std::abs(r.lps), std::abs(r.corr), std::abs(ref), std::arg(r.lps) * 180 / pi,
                 std::arg(r.corr) * 180 / pi, std::arg(ref) * 180 / pi});
        std::printf("  %-4s w = %10.4g rad/s: stiffness LPS %.6f, corr %.6f, ref %.6f; phase LPS %.4f, corr %.4f, ref %.4f deg\n",
                    names[q], freqs[q], std::abs(r.lps), std::abs(r.corr), std::abs(ref), std::arg(r.lps) * 180 / pi,
                    std::arg(r.corr) * 180 / pi, std::arg(ref) * 180 / pi);
        for (auto [model, z] : {std::pair{"lps", r.lps}, std::pair{"corr", r.corr}}) {
            const std::string key = std::string(model) + "_stiffness_" + names[q];
            run.summary({key, std::abs(z), std::abs(ref), pd::io::relative_error(std::abs(z), std::abs(ref)), "-"});
            // The orders are argued; the coefficients 3 and 10 are chosen, not derived (a regression bound).
            run.regression_bound(std::abs(z - ref) < tol * std::abs(ref),
                                 key + ": complex stiffness = G*/G within 3 (w dt)^2/12 + 10 gamma0^2 (coefficients chosen)");
            if (q == 1) run.summary({std::string(model) + "_phase_max_deg", std::arg(z) * 180 / pi, std::arg(ref) * 180 / pi,
                                     pd::io::relative_error(std::arg(z), std::arg(ref)), "deg"});
        }
    }

    // 6. Wave test: torsional mode of a bar, elastic vs numerical viscosity (V6 tau_b), and with the pole
    //    moved far below the mode (tau_b = 100/w_e): the SLS predicts the root of
    //    lambda^3/wP + lambda^2 + (w_e^2/w0) lambda + w_e^2 = 0 (m lambda^2 + k G*(lambda)/G = 0), w_d = Im lambda.
    const int nb = 6, lb = 20;
    const pd::Body<3> bar = pd::box<3>({{0, 0, 0}}, {{lb * dx, nb * dx, nb * dx}}, dx);
    pd::Bonds bar_bonds = pd::build_bonds(bar, opt.get("delta"));
    const double c_P = std::sqrt((mat.K + 4 * mat.G / 3) / rho), dt_w = 0.25 * dx / c_P;  // a quarter of the CFL step [s]
    const int crossings = quick ? 2 : 4;
    pd::ViscoelasticLPS elastic({{mat}, 0.0, 1.0}, bar_bonds);
    const double w_e = torsion_frequency(bar, bar_bonds, elastic, rho, lb * dx, dt_w, crossings);
    auto predicted = [&](double gamma_b, double tau) {  // Im of the oscillating root, Newton from i w_e sqrt(G*(w_e)/G)
        const double p = 1 / tau, z = p / (1 + gamma_b);
        const std::complex<double> iw(0, w_e);
        std::complex<double> lam = iw * std::sqrt((1.0 + iw / z) / (1.0 + iw / p));
        for (int it = 0; it < 60; ++it)
            lam -= (lam * lam * lam / p + lam * lam + w_e * w_e / z * lam + w_e * w_e) / (3.0 * lam * lam / p + 2.0 * lam + w_e * w_e / z);
        return lam.imag();
    };
    std::printf("wave test (torsion, %zu nodes): elastic w_e = %.6g rad/s, w_e/w0 = %.4f\n", bar.size(), w_e, w_e / w0);
    for (int q = 0; q < 2; ++q) {
        const double tau = q == 0 ? vp.tau_b : 100 / w_e;
        pd::ViscoelasticLPS visco({{mat}, vp.gamma_b, tau}, bar_bonds);
        // q = 1: the stiffness eta^2 G needs a step eta times smaller.
        const double w_d = torsion_frequency(bar, bar_bonds, visco, rho, lb * dx, q == 0 ? dt_w : dt_w / eta, crossings);
        const double ref = predicted(vp.gamma_b, tau);
        const std::string key = q == 0 ? "wave_low_frequency_ratio" : "wave_high_frequency_ratio";
        std::printf("  %s (tau_b = %.4g s): w_d/w_e = %.6f, SLS root %.6f\n", key.c_str(), tau, w_d / w_e, ref / w_e);
        run.summary({key, w_d / w_e, ref / w_e, pd::io::relative_error(w_d, ref), "-"});
        // 1e-3: the bar's surface layers have theta != 0 (K untouched by the branch) and the start excites
        // higher modes; the bound rests on the errors measured at 4 crossings (reports/3d/numerical_viscosity.md).
        run.regression_bound(std::abs(w_d / ref - 1) < 1e-3, key + ": torsion frequency = SLS root to 0.1 % (margin over measured)");
    }
    const double wall = timer.seconds();
    run.summary({{"high_over_low_expected_eta2", std::abs(Gstar(freqs[2])) / std::abs(Gstar(freqs[0])), eta * eta, NAN, "-"},
                 {"wall_s", wall, NAN, NAN, "s"}});
    return run.finish("eta = %g, low-frequency stiffness ~ G, high-frequency ~ eta^2 G = %.4g G (%.1f s)", eta, eta * eta, wall);
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("numerical_viscosity_3d", [&] { return run_case(argc, argv); }); }
