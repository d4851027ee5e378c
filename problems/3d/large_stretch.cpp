// problems/3d/large_stretch.cpp -- the V2 bar stretched quasi-statically to 100 % nominal strain:
// engineering stress-strain and von Mises vs equivalent strain for LPS, PALS, correspondence
// (Flanagan-Taylor, and Saint Venant-Kirchhoff for comparison) and PMB (reference line).
// Case: bar 10 x 2 x 1 mm, E = 100 GPa, nu = 0.33, dx = l3/n, delta = 3.05 dx, grips of 2 delta
// outside the bar (pd::gripped_bar, as bar_stiffness_3d), left u_x = 0, right u_x = U; lateral
// components free. --steps equal end-displacement steps to U = strain l2, each solved by ADR
// warm-started from the previous step (secant predictor 2 u_(s-1) - u_(s-2)); Flanagan-Taylor
// through pd::LoadStep (stress from the state committed at the previous step, every iteration).
// Source: seed 000b sec. 4.8, Figs. 4.6-4.7 (spec/000b sec. 5.5 T5, V5): LPS, PALS linear,
// correspondence with decreasing slope. Reference: reference/uniaxial_stretch (closed-form
// uniaxial-stress curves: hypoelastic E ln(lambda) lambda^(-2 nu), SVK, and the PD continuum of
// LPS/PALS and PMB by quadrature), evaluated at the measured gauge stretch.
// Measured (interior, no grip effect): P = F/(l1 l3) (F: right-grip reaction); gauge stretch
// lambda = 1 + du/dist (mean u_x of the layers nearest 0.5 l2 -+ delta, as bar_stiffness);
// lateral stretches mu_y, mu_z = least-squares slope of deformed vs reference y (z) over the two
// mid-length layers; true stress sigma = F/(l1 l3 mu_y mu_z); von Mises = |sigma| (uniaxial
// stress); equivalent strain eps_eq = sqrt(2/3 h':h'), h' = dev diag(ln lambda, ln mu_y, ln mu_z).
// Run: large_stretch_3d [--model all|pmb|lps|pals|correspondence|correspondence-svk] [--n 4]
//      [--steps 50] [--strain 1] [--tol 1e-9] [--safety 1.2] [--quick] [--check] [--out DIR]
// Load stepping: problems/common/stepped_bar_stretch.hpp; measurement: problems/common/measure/bar_stretch.hpp.
// Writes: curves.csv (one row per model and step), summary.csv, params.csv.
#include "problems/common/bar_options.hpp"
#include "problems/common/grips.hpp"
#include "problems/common/stepped_bar_stretch.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/load_step.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/time/dynamic_relaxation.hpp"

#include <cmath>
#include <cstdio>
#include <map>

using Point = pd::StretchPoint;
using Run = pd::StretchCurve;
using pd::ref::UniaxialLaw;

static int run_case(int argc, char** argv)
{
    // 1. Options (SI, defaults = the source's case), echoed and saved.
    pd::io::Case run("large_stretch_3d", "V2 bar to 100 % nominal strain (spec/000b V5): stress-strain per PD model.",
                     "reports/3d/large_stretch");
    pd::io::Options& opt = run.opt;
    const pd::io::BarOptions bar_opt = pd::io::add_bar_options(opt, 1.0, "final end displacement / length (source: 1)");
    auto& [E, nu, L, W, T, strain, m, grip] = bar_opt;
    int& n = opt.add_int("n", 4, "nodes through the thickness (source: 5; standard 4 for run time; quick: 3)");
    int& steps = opt.add_int("steps", 50, "equal load steps (source: 50; quick: 10)");
    std::string& which = opt.add_string("model", "all", "material model",
                                        {"all", "pmb", "lps", "pals", "correspondence", "correspondence-svk"});
    double& C_hg = opt.add("C-hg", 0.02, "correspondence hourglass coefficient (source: 0.02)");
    double& tol = opt.add("tol", 1e-9, "ADR relative residual tolerance per load step");
    double& safety = opt.add("safety", 1.2, "ADR density safety factor over the reference-tangent bound");
    int& max_iter = opt.add_int("max-iter", 5000, "ADR iteration limit per load step (converged steps need < 600)");
    for (const char* o : {"tol", "safety"}) opt.require_positive(o);
    opt.require_at_least("n", 2);
    opt.require_at_least("steps", 1);
    opt.require_at_least("C-hg", 0);
    opt.require_at_least("max-iter", 1);
    run.allow_checkpoints();
    run.parse(argc, argv);
    bar_opt.validate(opt);
    run.quick_default("n", 2);
    run.quick_default("steps", 10);
    run.quick_default("strain", 0.5);  // n = 2: PALS turns its two-layer section inside out at 0.7
    run.start();

    // 2. Discretisation: bar plus grips; gauge layers at 0.5 l2 -+ delta, the mid-length layers.
    const pd::GaugedBar s = pd::gauged_bar(L, W, T, T / n, m * T / n, grip * m * T / n);
    pd::Bonds bonds = pd::build_bonds(s.bar.body, s.delta);
    std::printf("\nnodes %zu, bonds %zu, dx %.3e m, delta %.3e m, gauge %.3e m\n", s.bar.body.size(), bonds.size(), s.dx, s.delta, s.gauge.dist);

    // 3.-5. Per model: 3. the model; 4. the grips, left u_x = 0, right u_x = U, lateral components free;
    // 5. U in equal steps, each solved by ADR (problems/common/stepped_bar_stretch.hpp) and measured.
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    std::vector<std::string> models{"pmb", "lps", "pals", "correspondence", "correspondence-svk"};
    if (which != "all") models = {which};
    const pd::StretchLoading load{strain, steps, tol, max_iter, safety};
    auto none = [](const pd::Bonds&, const pd::Field<3>&) {};
    std::map<std::string, Run> runs;
    for (const std::string& name : models) {
        using Corr = pd::Correspondence<3>;
        const pd::Body<3>& body = s.bar.body;
        auto load_steps = [&](auto& model, UniaxialLaw law, auto commit) {  // density: the model's reference-tangent bound
            return pd::stretch_bar_in_steps(model, pd::stiffness_bound(model, bonds, body.x), s, bonds, load, nu, law, mat, commit,
                                            run.checkpoints());
        };
        Run r;
        if (name == "pmb") {  // nu = 1/4, energy surface correction (classical W_inf), as bar_stiffness_3d
            pd::PMB model({.material = mat, .dim = 3}, bonds);
            pd::apply_surface_correction(model, body, bonds, pd::SurfaceCorrectionMethod::energy,
                                         {.reference = pd::SurfaceCorrectionOptions::Reference::classical, .kappa = mat.K});
            const pd::Elastic pmb_mat = pd::Elastic::from_E_nu(3 * mat.K * 0.5, 0.25);  // E = 1.5 K
            r = pd::stretch_bar_in_steps(model, pd::stiffness_bound(model, bonds, body.x), s, bonds, load, 0.25, UniaxialLaw::pmb_continuum,
                                         pmb_mat, none, run.checkpoints());
        } else if (name == "lps") {
            pd::LPS model({.material = mat, .dim = 3}, bonds);
            r = load_steps(model, UniaxialLaw::lps_continuum, none);
        } else if (name == "pals") {
            pd::PALS model({.material = mat}, body, bonds);
            r = load_steps(model, UniaxialLaw::lps_continuum, none);
        } else if (name == "correspondence-svk") {
            Corr model({.material = mat, .law = Corr::Law::saint_venant_kirchhoff, .C_hg = C_hg}, body, bonds);
            r = load_steps(model, UniaxialLaw::saint_venant_kirchhoff, none);
        } else {
            Corr model({.material = mat, .law = Corr::Law::flanagan_taylor, .C_hg = C_hg}, body, bonds);
            pd::LoadStep<Corr> ls(model, body.x);
            r = load_steps(ls, UniaxialLaw::hypoelastic, [&](const pd::Bonds& bb, const pd::Field<3>& y) { ls.commit(bb, y); });
        }
        std::printf("%-19s %s, %zu steps, %.1f s%s%s\n", name.c_str(), r.converged ? "converged" : "NOT converged", r.curve.size(),
                    r.wall_s, r.converged ? "" : ": ", r.message.c_str());
        std::fflush(stdout);
        runs[name] = r;
    }

    // 6. CSVs, table at selected strains, checks, verdict.
    pd::io::CsvWriter csv(run.file("curves.csv"), {"model", "step", "strain_nominal", "P_Pa", "lambda_gauge", "mu_y", "mu_z",
                                               "sigma_true_Pa", "eps_eq", "sigma_vm_Pa", "P_closed_Pa", "sigma_closed_Pa",
                                               "eps_eq_closed", "rel_dev_P", "iterations", "residual"});
    std::printf("\n%-19s %7s %8s %12s %12s %9s %9s %8s %12s %12s %6s\n", "model", "strain", "lambda", "P_Pa", "P_closed_Pa",
                "rel_dev", "shape_dev", "eps_eq", "sigma_vm_Pa", "sig_closed", "iters");
    for (const auto& [name, r] : runs) {
        if (r.curve.empty()) continue;
        const Point& p1 = r.curve.front();
        const double bias = p1.P / p1.P_ref;  // small-strain ratio (surface effect of the thin bar)
        long iters = 0;
        for (std::size_t k = 0; k < r.curve.size(); ++k) {
            const Point& p = r.curve[k];
            iters += p.iterations;
            const double dev = p.P / p.P_ref - 1, shape = p.P / p.P_ref / bias - 1;
            csv.row({name, k + 1, p.strain, p.P, p.lambda, p.mu_y, p.mu_z, p.sigma, p.eps_eq, std::abs(p.sigma), p.P_ref,
                     p.sigma_ref, p.eps_eq_ref, dev, p.iterations, p.residual});
            const std::size_t N = r.curve.size();
            if (k == 0 || k + 1 == N || k + 1 == N / 10 || k + 1 == N / 4 || k + 1 == N / 2 || k + 1 == 3 * N / 4)
                std::printf("%-19s %7.3f %8.4f %12.5e %12.5e %9.2e %9.2e %8.4f %12.5e %12.5e %6ld\n", name.c_str(), p.strain, p.lambda,
                            p.P, p.P_ref, dev, shape, p.eps_eq, std::abs(p.sigma), p.sigma_ref, p.iterations);
        }
        const Point& pe = r.curve.back();
        run.summary({{"P_end_" + name, pe.P, pe.P_ref, pd::io::relative_error(pe.P, pe.P_ref), "Pa"},
                     {"shape_end_" + name, pe.P / pe.P_ref / bias, 1.0, std::abs(pe.P / pe.P_ref / bias - 1), "-"},
                     {"wall_" + name, r.wall_s, NAN, NAN, "s"},
                     {"iterations_" + name, static_cast<double>(iters), NAN, NAN, "-"}});
    }
    // --check (reasons in reports/3d/large_stretch.md): every step converged (SVK: the steps up to
    // its first failure); the secant slope of the Flanagan-Taylor curve decreases; correspondence (FT, SVK) within 1 % of its closed form at
    // every step; PMB, LPS, PALS follow the shape of their continuum curve within 15 %.
    for (const auto& [name, r] : runs) {
        const bool required = name != "correspondence-svk";  // SVK stalls beyond ~50 % (report): curve up to there
        run.property((r.converged || !required) && !r.curve.empty(),
                  name + (required ? ": every load step converged" : ": load steps converged up to its first failure (at least one)"));
    }
    if (runs.count("correspondence") && runs["correspondence"].curve.size() >= 3) {
        const auto& c = runs["correspondence"].curve;
        const std::size_t h = c.size() / 2;
        const double s1 = c[h - 1].P / c[h - 1].strain, s2 = (c.back().P - c[h - 1].P) / (c.back().strain - c[h - 1].strain);
        run.property(s2 < s1, "correspondence: Flanagan-Taylor secant slope decreasing");
    }
    for (const auto& [name, r] : runs) {
        const bool corr = name.rfind("correspondence", 0) == 0;
        bool follows = true;
        for (const Point& p : r.curve) {
            const double dev = corr ? p.P / p.P_ref - 1 : p.P / p.P_ref / (r.curve.front().P / r.curve.front().P_ref) - 1;
            follows = follows && std::abs(dev) <= (corr ? 0.01 : 0.15);
        }
        // Correspondence: its closed form is exact for the uniform interior F (1 %: margin on zero). The
        // others: 15 % is about twice the 8 % measured (a regression bound).
        if (corr) run.check(follows, name + ": within 1 % of its closed form at every step");
        else run.regression_bound(follows, name + ": within 15 % of the shape of its closed form at every step (2x measured)");
    }
    const std::string svk = runs.count("correspondence-svk") && !runs["correspondence-svk"].converged
                                ? "; SVK stopped at " + runs["correspondence-svk"].message : "";
    return run.finish("%zu models to nominal strain %.3g in %d steps%s", runs.size(), strain, steps, svk.c_str());
}

int main(int argc, char** argv) { return pd::io::guarded_main("large_stretch_3d", [&] { return run_case(argc, argv); }); }
