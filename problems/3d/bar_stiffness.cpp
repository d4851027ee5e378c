// problems/3d/bar_stiffness.cpp -- quasi-static stiffness E of a 3D bar: PMB and LPS (each with and
// without the energy surface correction), LPS+SCF, PALS, correspondence.
// Case: bar l2 x l1 x l3 = 10 x 2 x 1 mm (x axial), E = 100 GPa, nu = 0.33, cubic lattice
// dx = l3/n, delta = 3.05 dx. Grips of --grip x delta (source: 2 delta) are ADDED OUTSIDE the
// 10 mm (spec V2 [RECON]: inside zones would overlap at n = 1): left grip u_x = 0, right grip
// u_x = 1 % of l2, lateral components free. Equilibrium by adaptive dynamic relaxation (ADR,
// default) or Newton-Raphson (--solver newton; solve/newton.hpp, with three statically determinate
// supports removing the lateral rigid modes), warm-started from the uniform uniaxial field.
// Source: seed 000b sec. 4.6, Figs. 4.2-4.3 (spec/000b sec. 5.2 T2, V2). Measurement (4.37):
// E = (F/(l1 l3)) / (du/dist), F the axial reaction of the loaded grip, du the difference of the
// cross-section mean u_x of the two lattice layers nearest 0.5 l2 -+ delta, dist their distance
// (interior sections: no grip effect). E_end = (F/A)/(U/l2) is written alongside.
// Reference: E for all models but PMB; PMB (nu = 1/4 fixed, only K = E/(3(1-2nu)) enters) expects
// E_pmb = 3K(1 - 2/4) = 1.5 K. The source (Fig. 4.3) gives no numbers, only trends.
// Run: bar_stiffness_3d [--model all|pmb|lps|lps-scf|pals|correspondence] [--n 5] [--n-max 10]
//      [--surface-correction both|none|energy] [--bound-factor 1] [--start uniform|zero] [--quick]
//      [--solver adr|newton] [--linear auto|cholesky|cg|lu] [--reuse-tangent] [--check] [--out DIR].
//      ADR density: Gershgorin bounds of each model's reference tangent (exact for PMB; else x --bound-factor).
// Writes: convergence.csv (one row per n, model, correction), summary.csv (finest n), params.csv.
#include "problems/common/bar_supports.hpp"
#include "problems/common/grips.hpp"
#include "problems/common/bar_options.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "problems/common/measure/bar_sections.hpp"
#include "pd/models/registry.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/solve/newton.hpp"
#include "pd/time/dynamic_relaxation.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <type_traits>

namespace {

struct Specimen : pd::GaugedBar {  // length l2 = L, width l1 = W, thickness l3 = T; gauge layers nearest L/2 -+ delta
    double U;                      // end displacement [m]
};

struct Outcome {
    bool converged = false;
    long iterations = 0, tangents = 0;
    double residual = 0, E_meas = NAN, E_end = NAN, wall_s = 0;  // [-], [Pa], [Pa], [s]
    std::string message;
    double support = 0;  // Newton: largest support reaction / force scale [-] (0 at equilibrium)
    double tangent_s = 0, linear_s = 0;  // Newton: assembly and linear-solve time [s]
    int colours = 0;                     // Newton: colours of the finite-difference tangent
};

struct SolverChoice {
    bool newton = false;
    double tol = 0;
    long max_iter = 0;          // ADR
    pd::NewtonOptions options;  // Newton
    std::string linear;         // Newton linear solver, or auto
};

// ADR from the uniform uniaxial field (u_x = U x/L, lateral contraction nu_w), then E from the
// reaction of the right grip and the interior cross-sections.
template <class Model>
Outcome relax(Model& model, const pd::Field<3>& bound, const Specimen& s, pd::Bonds& bonds, double nu_w,
              const SolverChoice& sc, bool warm)
{
    pd::Boundary<3> bc;
    pd::grip_bar_ends(bc, s.bar.left, s.bar.right, pd::TimeFunction::constant(s.U), pd::Grips::axial);
    pd::Field<3> u(s.bar.body.size());
    const double eps = s.U / s.L;
    if (warm) pd::uniaxial_bar_field(s.bar.body, s.L, s.W, s.T, s.U, eps, nu_w, pd::Grips::axial, u);
    Outcome o;
    pd::Field<3> f;  // internal force density at the solution [N/m^3]
    if (sc.newton) {
        const auto supports = pd::lateral_supports(s.bar.body, s.L, s.W, s.T, s.dx);
        for (auto [i, d] : supports)
            bc.prescribe({pd::Prescribed::Kind::displacement, {i}, d, pd::TimeFunction::constant(u.c[d][i])});
        pd::Newton<3, Model> newton(s.bar.body, bonds, model);
        pd::NewtonOptions nopt = sc.options;
        nopt.tol = sc.tol;
        // auto: LU for the non-symmetric correspondence tangent; else Cholesky, CG above 3000 dofs
        // (the simplicial Cholesky of the state-based pattern costs ~90 s at 5000 dofs, reports/3d/bar_stiffness.md).
        const char* automatic = !pd::detail::is_ordinary<Model>() ? "lu" : 3 * s.bar.body.size() > 3000 ? "cg" : "cholesky";
        nopt.linear = pd::parse_linear_solver(sc.linear != "auto" ? sc.linear : automatic);
        const pd::NewtonResult r = newton.solve(u, bc, 0, nopt);
        o = {r.converged, r.iterations, r.tangents, r.residual, NAN, NAN, r.wall_s, r.message};
        f = newton.internal_force_density();
        o.tangent_s = r.tangent_s, o.linear_s = r.linear_s, o.colours = newton.colouring().count;
        for (auto [i, d] : supports) o.support = std::max(o.support, std::abs(f.c[d][i] * s.bar.body.volume[i]) / r.force_scale);
    } else {
        pd::DynamicRelaxation<3, Model> adr(s.bar.body, bonds, model, bound);
        const pd::RelaxationResult r = adr.solve(u, bc, 0, sc.tol, sc.max_iter);
        o = {r.converged, r.iterations, 0, r.residual, NAN, NAN, r.wall_s, r.message};
        f = adr.internal_force_density();
    }
    if (!o.converged) return o;
    const double sigma = pd::grip_stress(f, s);  // engineering stress [Pa]
    const double du = pd::mean_axial_displacement(u, s.gauge.sec_b) - pd::mean_axial_displacement(u, s.gauge.sec_a);
    o.E_meas = sigma / (du / s.gauge.dist);                   // (4.37)
    o.E_end = sigma / eps;
    return o;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI, defaults = the source's case), echoed and saved.
    pd::io::Case run("bar_stiffness_3d", "Quasi-static 3D bar stiffness (spec/000b V2): measured E per PD model vs n.",
                     "reports/3d/bar_stiffness");
    pd::io::Options& opt = run.opt;
    const pd::io::BarOptions bar_opt = pd::io::add_bar_options(opt, 0.01, "end displacement / length");
    const auto& [E, nu, L, W, T, strain, m, grip] = bar_opt;
    int& n_one = opt.add_int("n", 0, "nodes through the thickness (0: sweep 1 2 4 5 8 10 up to --n-max)");
    int& n_max = opt.add_int("n-max", 10, "largest n of the sweep (quick: 2)");
    std::string& which = opt.add_string("model", "all", "material model",
                                        {"all", "pmb", "lps", "lps-scf", "pals", "correspondence"});
    std::string& sc = opt.add_string("surface-correction", "both", "PMB and LPS surface correction", {"both", "none", "energy"});
    double& C_hg = opt.add("C-hg", 0.02, "correspondence hourglass coefficient (source: 0.02)");
    double& tol = opt.add("tol", 1e-9, "relative residual tolerance (ADR and Newton)");
    int& max_iter = opt.add_int("max-iter", 100000, "ADR iteration limit");
    std::string& solver = opt.add_string("solver", "adr", "quasi-static solver", {"adr", "newton"});
    std::string& linear = opt.add_string("linear", "auto", "Newton linear solver (auto: lu for correspondence, cg above 3000 dofs, else cholesky)",
                                         {"auto", "cholesky", "cg", "lu"});
    int& newton_iter = opt.add_int("newton-max-iter", 30, "Newton iteration limit");
    bool& reuse = opt.add_flag("reuse-tangent", "Newton: keep the tangent while the residual falls 10x per iteration");
    double& bound_factor = opt.add("bound-factor", 1, "PALS/correspondence ADR density: model bound x this");
    std::string& start = opt.add_string("start", "uniform", "ADR initial guess (uniform uniaxial field, or zero)", {"uniform", "zero"});
    for (const char* o : {"tol", "bound-factor"}) opt.require_positive(o);
    for (const char* o : {"n", "C-hg"}) opt.require_at_least(o, 0);
    for (const char* o : {"n-max", "max-iter", "newton-max-iter"}) opt.require_at_least(o, 1);
    run.parse(argc, argv);
    bar_opt.validate(opt);
    run.quick_default("n-max", 2);
    run.start();
    std::vector<int> ns;
    for (int n : {1, 2, 4, 5, 8, 10}) if (n <= n_max) ns.push_back(n);
    if (n_one > 0) ns = {n_one};
    if (ns.empty()) opt.fail("option --n-max leaves no n of the sweep");
    const auto models = which == "all" ? std::vector<std::string>{"pmb", "lps", "lps-scf", "pals", "correspondence"} : std::vector{which};
    std::vector<std::string> pmb_sc = sc == "both" ? std::vector<std::string>{"none", "energy"} : std::vector<std::string>{sc};

    const SolverChoice solve_by{solver == "newton", tol, max_iter, {.max_iter = newton_iter, .reuse_tangent = reuse}, linear};
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const double E_pmb = 3 * mat.K * (1 - 2 * 0.25);  // PMB: nu = 1/4, E = 3K(1 - 2 nu) [Pa]
    pd::io::CsvWriter conv(run.file("convergence.csv"),
                           {"n", "dx_m", "delta_m", "m", "nodes", "bonds", "model", "surface_correction", "converged",
                            "iterations", "tangents", "residual", "support_reaction", "E_meas_Pa", "E_end_Pa", "E_expected_Pa", "error", "rate", "wall_s"});
    std::map<std::string, std::pair<double, double>> last;  // case -> (dx, error) for the rate
    std::map<std::string, Outcome> finest;
    bool all_converged = true;
    std::printf("\n%3s %9s %7s %9s %-15s %-7s %6s %9s %12s %12s %10s %8s\n", "n", "dx_m", "nodes", "bonds", "model", "surf",
                "conv", "iters", "E_meas_Pa", "E_end_Pa", "rel_error", "wall_s");
    for (int n : ns) {
        // 2. Discretisation: bar plus ceil(grip delta/dx) grip layers outside each end.
        Specimen s{pd::gauged_bar(L, W, T, T / n, m * T / n, grip * (m * T / n)), strain * L};
        pd::Bonds bonds = pd::build_bonds(s.bar.body, s.delta);
        // 3. Models; ADR density from each model's stiffness bound (dynamic_relaxation.hpp).
        // Classical reference W_inf (the full lattice family does not fit in a bar 1-2 cells thick); kappa: PMB's.
        const pd::SurfaceCorrectionOptions classical{.reference = pd::SurfaceCorrectionOptions::Reference::classical, .kappa = mat.K};
        auto scaled = [&](pd::Field<3> G) { for (auto& c : G.c) for (double& g : c) g *= bound_factor; return G; };
        for (const std::string& name : models)
            for (const std::string& corr : name == "pmb" || name == "lps" ? pmb_sc : std::vector<std::string>{"n/a"}) {
                // 4.-5. Surface correction (PMB, LPS), grips, warm start, ADR.
                const double nu_w = name == "pmb" ? 0.25 : nu;
                const Outcome o = pd::with_model(pd::ModelChoice{.name = name, .material = mat, .C_hg = C_hg}, s.bar.body, bonds, [&](auto& model) {
                    using Model = std::decay_t<decltype(model)>;
                    constexpr bool ordinary = std::is_same_v<Model, pd::PMB> || std::is_same_v<Model, pd::LPS>;
                    if constexpr (ordinary)
                        if (corr != "n/a") pd::apply_surface_correction(model, s.bar.body, bonds, pd::parse_surface_correction(corr), classical);
                    const pd::Field<3> bound = pd::stiffness_bound(model, bonds, s.bar.body.x);
                    return relax(model, ordinary ? bound : scaled(bound), s, bonds, nu_w, solve_by, start == "uniform");
                });
                // 6. Compare with the expected modulus, write the row, print.
                const double E_exp = name == "pmb" ? E_pmb : E;
                const std::string key = name + (corr == "energy" ? "_sc" : "");
                const double err = pd::io::relative_error(o.E_meas, E_exp);
                double rate = NAN;
                if (auto it = last.find(key); it != last.end() && o.converged)
                    rate = std::log(it->second.second / err) / std::log(it->second.first / s.dx);
                if (o.converged) last[key] = {s.dx, err};
                finest[key] = o;
                all_converged = all_converged && o.converged;
                conv.row({n, s.dx, s.delta, m, s.bar.body.size(), bonds.size(), name, corr, o.converged ? 1 : 0, o.iterations,
                          o.tangents, o.residual, o.support, o.E_meas, o.E_end, E_exp, err, rate, o.wall_s});
                std::printf("%3d %9.3e %7zu %9zu %-15s %-7s %6s %9ld %12.5e %12.5e %10.3e %8.2f\n", n, s.dx, s.bar.body.size(),
                            bonds.size(), name.c_str(), corr.c_str(), o.converged ? "yes" : "NO", o.iterations, o.E_meas,
                            o.E_end, err, o.wall_s);
                if (!o.converged) std::printf("    %s: %s\n", key.c_str(), o.message.c_str());
                if (solve_by.newton && o.converged)
                    std::printf("    newton: %ld tangents (%d colours) %.2f s, linear solves %.2f s, support reaction %.1e of the force scale\n",
                                o.tangents, o.colours, o.tangent_s, o.linear_s, o.support);
                std::fflush(stdout);
            }
    }

    // --check (reasons in reports/3d/bar_stiffness.md): every solve converged; at the finest n the energy surface
    // correction brings PMB closer to 1.5 K; in the default case each model's rel_error at the finest n is below
    // its error in the report's table (ADR) plus 10 %: a regression bound (the reference is the classical E, but
    // the bound is our own recorded error, not a tolerance the model was shown to meet); the runs are
    // deterministic, solver tolerance and Newton vs ADR move E by < 1e-5. Tiers n = 2 (quick) and n = 4..10 (largest of 4, 5, 8, 10); n = 1 is degenerate.
    run.property(all_converged, "every " + solver + " solve converged");
    const std::map<std::string, std::array<double, 2>> error_bound{{"pmb", {0.541, 0.320}}, {"pmb_sc", {0.164, 0.0585}},
        {"lps", {1.095, 0.184}}, {"lps_sc", {0.085, 0.052}}, {"lps-scf", {0.430, 0.180}}, {"pals", {0.0137, 0.0068}}, {"correspondence", {2.06e-3, 5.53e-5}}};
    const int nf = ns.back(), tier = nf == 2 ? 0 : nf == 4 || nf == 5 || nf == 8 || nf == 10 ? 1 : -1;
    bool documented = tier >= 0;  // and no physical option changed
    for (const char* o : {"E", "nu", "length", "width", "thickness", "strain", "m", "grip", "C-hg"}) documented &= !opt.given(o);
    for (const auto& [key, o] : finest) {
        const double ref = key.rfind("pmb", 0) == 0 ? E_pmb : E, err = pd::io::relative_error(o.E_meas, ref);
        run.summary({"E_" + key, o.E_meas, ref, err, "Pa"});
        if (ref != E) run.summary({"E_" + key + "_vs_input_E", o.E_meas, E, pd::io::relative_error(o.E_meas, E), "Pa"});
        if (documented)
            run.regression_bound(err < error_bound.at(key)[tier],
                                 "E_" + key + " rel_error < " + pd::io::format_shortest(error_bound.at(key)[tier]) + " (the recorded error + 10 %)");
    }
    std::printf("\nfinest n = %d (summary.csv); PMB expected E = 1.5 K = %.5e Pa (input E = %.5e Pa)\n", ns.back(), E_pmb, E);
    if (finest.count("pmb") && finest.count("pmb_sc")) {
        const double e0 = pd::io::relative_error(finest["pmb"].E_meas, E_pmb), e1 = pd::io::relative_error(finest["pmb_sc"].E_meas, E_pmb);
        std::printf("PMB error %.3e without, %.3e with surface correction\n", e0, e1);
        run.property(e1 < e0, "the energy surface correction brings PMB closer to 1.5 K (finest n)");
    }
    return run.finish("E of %zu cases (model, correction) at finest n = %d; %s solves %s", finest.size(), ns.back(), solver.c_str(),
                      all_converged ? "all converged" : "NOT all converged");
}

int main(int argc, char** argv) { return pd::io::guarded_main("bar_stiffness_3d", [&] { return run_case(argc, argv); }); }
