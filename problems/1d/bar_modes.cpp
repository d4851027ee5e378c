// problems/1d/bar_modes.cpp -- fixed-free bar released from uniform strain: LPS/PMB vs classical.
// Case: bar [0, l], section A, clamped at x = 0, free at x = l, u(x,0) = eps0 x, v = 0; free axial
//   vibration for t_end (default 16 T1). Cell-centred nodes x_i = (i + 1/2) dx, dx = l/N, delta = m dx.
//   Clamp: a fixed layer of m cells OUTSIDE the bar, x in [-delta, 0), so the vibrating bar keeps its
//   length l (the source fixes the first m of its N nodes, x = 0..(m-1) dx, shortening the bar).
// Source: seed 000b sec. 4.5, Table 4.1 (spec/000b sec. 5.1 T1 and V1: 1D LPS t = omega E theta |xi|/m).
// Reference: reference/bar_1d.hpp: f1 = c/(4l) (Eq. 4.36); modal series u(x,t) at the tip node
//   x = l - dx/2; lumped linear FE bar with the same dx (N+1 nodes, tip at x = l) by SUNDIALS CVODE for
//   N <= 200, above that the exact discrete-mode solution of the same FE system (CVODE cost ~ N^2).
// Compared: f1 of the tip record (dominant_frequency); E1 = int|u - u_ref| dt / int|u_ref| dt of the
//   tip over the first T1 and the whole window (spec 5.1 reconstruction), and against the FE bar;
//   delta-convergence (m fixed, N = 10..1000) and m-convergence (delta fixed) for LPS and PMB with wall
//   time; stability: dt = factor * dt_SA (safety not applied), factor 0.5..1.3, then the threshold by
//   bisection, beside the PMB von Neumann limit of the lattice.
// Time step: dt = dt_factor * safety * dt_SA, dt_SA = Silling-Askari (3.14) with the 1D PMB
//   micromodulus of --calibration (exact bound for PMB, the source's stand-in for LPS), rounded down
//   so that t_end is a whole number of samples and steps.
// Integrators: velocity Verlet (default) or --integrator newmark (beta 1/4, gamma 1/2, time/newmark.hpp)
//   at dt = --newmark-dt x dt_SA; the study mode also compares both at N (the run and the comparison:
//   problems/common/fixed_free_bar.hpp).
// Run: bar_modes_1d [--N 200 --model lps|pmb] [--m 3] [--integrator verlet|newmark] [--quick] [--check]
//   default: both studies, the stability sweep and the integrator comparison; --N n: one run of --model.
// Writes: convergence.csv, stability.csv, integrators.csv, summary.csv, history.csv (tip: PD, exact,
//   FE), params.csv.
// Exit: 2 invalid option, 3 a run became unstable (outside the stability study), 1 a check failed.
#include "pd/io/case.hpp"
#include "pd/io/convergence.hpp"
#include "pd/io/guarded_main.hpp"
#include "problems/common/fixed_free_bar.hpp"
#include "problems/common/stability_sweep.hpp"
#include "reference/bar_1d_scores.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <map>
#include <numbers>
#include <tuple>

namespace {

constexpr int n_modes = 2000;         // modal-series terms: tail < 0.2 eps0 l / n_modes = 1e-4 eps0 l
constexpr int fe_cvode_max_N = 200;   // CVODE (Adams, rtol 1e-10) costs ~ N^2: 16 s at N = 200
constexpr double guard_periods = 4;   // stability runs: 4 T1 = 884/factor steps at N = 100; a mode 0.5 %
                                      // above the limit grows 20 %/step and passes the guard from round-off in ~210
constexpr double search_tol = 0.005;  // threshold bisection to 0.5 %
constexpr double search_max = 8;      // search up to 8 dt_SA (LPS interior von Neumann limit: 2.9)

using Bar = pd::FixedFreeBar;
using Run = pd::FixedFreeBarRun;

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI; defaults = the source's case, spec/000b V1), validated, echoed and saved.
    pd::io::Case run("bar_modes_1d", "Fixed-free bar released from uniform strain: PD (LPS, PMB) vs classical.", "reports/1d/bar_modes");
    pd::io::Options& opt = run.opt;
    const double& E = opt.add("E", 200e9, "Young's modulus", "Pa");
    const double& rho = opt.add("rho", 7800, "density", "kg/m^3");
    const double& l = opt.add("length", 1.0, "bar length l", "m");
    const double& A = opt.add("area", 0.01, "cross-section A", "m^2");
    const double& eps0 = opt.add("eps0", 1e-3, "initial uniform strain (not given by the source)");
    const int& N = opt.add_int("N", 100, "cells in the bar: given = one run at N; else N of the stability sweep");
    const int& m = opt.add_int("m", 3, "horizon ratio delta/dx");
    const std::string& model = opt.add_string("model", "lps", "model of the single run (the studies run both)", {"lps", "pmb"});
    const std::string& infl = opt.add_string("influence", "one", "influence function", {"one", "inv_xi", "triangular"});
    const std::string& cal = opt.add_string("calibration", "lattice", "PMB micromodulus: exact on the lattice, or 2E/(A delta^2)",
                                            {"lattice", "continuum"});
    const double& dt_factor = opt.add("dt-factor", 1.0, "dt = dt-factor * safety * dt_SA");
    const double& safety = opt.add("safety", 0.5, "safety factor on dt_SA (the source's normal 0.5)");
    double& t_end = opt.add("t-end", NAN, "duration (nan = 16 T1, --quick 4 T1)", "s");
    const int& samples = opt.add_int("samples", 100, "tip samples per T1");
    const double& delta_fixed = opt.add("delta-fixed", 0.05, "horizon of the m-convergence study", "m");
    const std::string& integrator = opt.add_string("integrator", "verlet", "time integrator of the runs", {"verlet", "newmark"});
    const double& newmark_dt = opt.add("newmark-dt", 4, "Newmark dt / dt_SA (no safety factor; unconditionally stable)");
    for (const char* p : {"E", "rho", "length", "area", "eps0", "dt-factor", "safety", "t-end", "delta-fixed", "newmark-dt"})
        opt.require_positive(p);
    opt.require_at_least("m", 1);
    opt.require_at_least("N", 5);         // the source's coarsest bar has 10 cells; below 5 no mode shape is left
    opt.require_at_least("samples", 10);  // the frequency fit and E1 need >= 10 samples per period
    run.parse(argc, argv);
    const bool quick = run.quick(), single = opt.given("N");
    const Bar bar{E, rho, l, A, eps0, pd::ref::bar_frequency(1, E, rho, l), samples, pd::Influence::parse(infl),
                  cal == "lattice" ? pd::PMB::Params::Calibration::lattice : pd::PMB::Params::Calibration::continuum,
                  integrator == "newmark"};
    const double dt_scale = bar.newmark ? newmark_dt : dt_factor * safety;  // dt / dt_SA of the runs
    const int m_min = infl == "triangular" ? 2 : 1;  // triangular omega(delta) = 0: with m = 1 no bond carries force
    if (m < m_min) opt.fail("option --m must be >= 2 with --influence triangular (m = 1 leaves no bond), got 1");
    if (std::isnan(t_end)) t_end = (quick ? 4 : 16) / bar.f1;
    // The frequency meter needs two periods after the first upward crossing (at 3/4 T1): t_end >= 3 T1.
    if (t_end < 3 / bar.f1) opt.fail("option --t-end must be >= 3 T1 = " + std::to_string(3 / bar.f1) + " s (frequency fit)");
    std::printf("bar_modes_1d: f1 = c/(4l) = %.3f Hz, T1 = %.5g s, t_end = %.5g s\n", bar.f1, 1 / bar.f1, t_end);
    run.start();
    // 2.-5. The runs (problems/common/fixed_free_bar.hpp): 2. lattice of the bar and its clamp layer,
    // families; 3. model, dt from dt_SA; 4. clamp held, u0 = eps0 x; 5. integration, tip sampled.
    std::vector<std::tuple<std::string, std::string, int, int>> runs;  // study, model, N, m
    const std::vector<int> N_list = quick ? std::vector{20, 40, 80} : std::vector{10, 50, 100, 200, 500, 1000};
    for (const char* mod : {"lps", "pmb"})
        for (int n : N_list) runs.push_back({"delta", mod, n, m});
    for (const char* mod : {"lps", "pmb"})
        for (int mm : quick ? std::vector{1, 2, 4} : std::vector{1, 2, 3, 4, 6, 8})
            if (mm >= m_min) runs.push_back({"m", mod, static_cast<int>(std::lround(mm * l / delta_fixed)), mm});
    if (single) runs = {{"single", model, N, m}};
    const std::map<int, double> thesis{{10, .592}, {50, .142}, {100, .076}, {200, .038}, {500, .015}, {1000, .007}};  // Table 4.1
    auto thesis_E1 = [&](const std::string& mod, int n, int mm) {  // the source's E1 for this run, if any
        return mod == "lps" && mm == 3 && infl == "one" && thesis.count(n) ? thesis.at(n) : NAN; };
    pd::io::ConvergenceTable table({"study", "model"}, {"f1_Hz", "f1_rel_error", "E1_T1", "E1_fe", "thesis_E1", "dt_s", "steps"});
    pd::ref::BarScorer scorer(E, rho, l, eps0, fe_cvode_max_N, n_modes);
    std::map<std::string, std::pair<Run, pd::ref::BarScores>> finest;  // per model: the finest delta-study (or single) run
    double f1_cvode = NAN, dx_cvode = NAN;                              // the finest CVODE FE record
    char verdict[200] = "";
    for (const auto& [study, mod, n, mm] : runs) {
        const Run r = pd::release_fixed_free_bar(bar, mod, n, mm, dt_scale, t_end, false);
        const pd::ref::BarScores s = scorer.score(r.t_s, r.tip_m, r.x_tip, n, study != "m");
        table.add({.dx_m = r.dx, .delta_m = r.delta, .m = double(mm), .nodes = r.nodes, .bonds = r.bonds, .error = s.E1,
                   .wall_s = r.wall_s, .labels = {study, mod},
                   .extras = {s.f1, s.f1 / bar.f1 - 1, s.E1_T1, s.E1_fe, thesis_E1(mod, n, mm), r.dt, double(r.steps)}});
        table.write_csv(run.file("convergence.csv"));  // rewritten per row: the rows done survive an abort
        if (study == "m") continue;
        finest[mod] = {r, s};
        if (n <= fe_cvode_max_N) f1_cvode = s.f1_fe, dx_cvode = r.dx;
        if (study == "single" || (mod == "lps" && n == N)) {  // tip histories of the run at N
            pd::io::CsvWriter csv(run.file("history.csv"), {"t_s", "u_tip_m", "u_exact_m", "u_fe_m"}, false);
            for (std::size_t j = 0; j < r.t_s.size(); ++j) csv.row({r.t_s[j], r.tip_m[j], s.exact[j], s.fe[j]});
        }
    }
    // 6. Compare with the references, write, print; the study mode adds 7. and 8.
    table.print(std::cout);
    const auto& [rf, sf] = finest.begin()->second;  // "lps" sorts first
    run.summary({
        {"f1", sf.f1, bar.f1, pd::io::relative_error(sf.f1, bar.f1), "Hz"},
        {"E1_first_T1", sf.E1_T1, thesis_E1(finest.begin()->first, rf.N, rf.m), NAN, "-"},
        {"E1_window", sf.E1, NAN, NAN, "-"}, {"E1_vs_fe", sf.E1_fe, NAN, NAN, "-"},
        {"f1_fe_cvode", f1_cvode, bar.f1, pd::io::relative_error(f1_cvode, bar.f1), "Hz"}, {"dt", rf.dt, NAN, NAN, "s"},
        {"dt_crit_SA", rf.dt_crit, NAN, NAN, "s"}, {"energy_growth", rf.growth, 1, NAN, "-"}});
    // f1 is first order in dx: the clamp layer and the free surface move the effective ends by O(dx)
    // (measured f1 error -1.0 dx/l for N = 50..1000, LPS and PMB); the bound allows 2 dx/l: only the
    // order is argued, the coefficient is twice our measured one (a regression bound).
    run.regression_bound(std::abs(sf.f1 / bar.f1 - 1) <= 2 * rf.dx / l,
                         "f1 within 2 dx/l of c/(4l) (finest N of the study; 2x the measured -1.0 dx/l)");
    std::snprintf(verdict, sizeof verdict, "%s f1 = %.3f Hz (%+.3f %%, E1 first T1 %.4f) at N = %d",
                  finest.begin()->first.c_str(), sf.f1, 100 * (sf.f1 / bar.f1 - 1), sf.E1_T1, rf.N);
    // Lumped linear FE: f1_h/f1 = sin(k1 dx/2)/(k1 dx/2), error (k1 dx)^2/24 (second order); 2x for the meter.
    const double kdx = std::numbers::pi / 2 * dx_cvode / l;  // k1 dx of the finest CVODE record
    if (!std::isnan(f1_cvode))
        run.check(std::abs(f1_cvode / bar.f1 - 1) <= 2 * kdx * kdx / 24, "CVODE FE f1 within 2 (k1 dx)^2/24 of c/(4l)");
    if (!single) {
        // 7. Stability: dt = factor * dt_SA exactly (no safety), N cells, 4 T1; threshold by bisection.
        std::vector<std::pair<std::string, pd::io::StabilityResult>> stab;
        for (const char* mod : {"pmb", "lps"}) {
            auto at_factor = [&](double f) {
                Bar explicit_bar = bar;  // the stability limit is the explicit one
                explicit_bar.newmark = false;
                const Run r = pd::release_fixed_free_bar(explicit_bar, mod, N, m, f, guard_periods / bar.f1, true);
                return pd::io::StabilityPoint{f, r.dt, r.dt_crit, r.growth, r.unstable_step < 0, r.unstable_step};
            };
            const std::vector<double> factors = {0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3};
            stab.push_back({mod, pd::io::stability_sweep(factors, at_factor, search_max, search_tol)});
            pd::io::print_stability(std::cout, mod, stab.back().second.points);
        }
        pd::io::write_stability_csv(run.file("stability.csv"), stab);
        const double vn = pd::ref::lattice_von_neumann_ratio([&](int q) { return bar.w(q, m) / q; }, m);  // PMB springs
        const double thr_pmb = stab[0].second.threshold, thr_lps = stab[1].second.threshold;
        const std::size_t n_lps = N_list.size();  // rows: delta lps, delta pmb, m lps, m pmb
        const double rate_lps = table.rate(n_lps - 1), rate_pmb = table.rate(2 * n_lps - 1);  // finest pairs
        const double f1_pmb = finest["pmb"].second.f1;
        run.summary({{"f1_pmb", f1_pmb, bar.f1, pd::io::relative_error(f1_pmb, bar.f1), "Hz"},
                     {"rate_E1_lps", rate_lps, 1, std::abs(rate_lps - 1), "-"},
                     {"rate_E1_pmb", rate_pmb, 1, std::abs(rate_pmb - 1), "-"},
                     {"dt_limit_pmb_over_SA", thr_pmb, vn, pd::io::relative_error(thr_pmb, vn), "-"},
                     {"dt_limit_lps_over_SA", thr_lps, NAN, NAN, "-"}});
        std::printf("stability limit / dt_SA at N = %d: PMB %.4f (von Neumann %.4f), LPS %.4f\n", N, thr_pmb, vn, thr_lps);
        // E1 ~ C dx once the phase drift over the window is small (spec 5.1: error x N ~ const).
        run.check(rate_lps >= 0.7 && rate_lps <= 1.5, "LPS observed rate of E1 in [0.7, 1.5] (finest pair)");
        run.property(stab[0].second.points[0].stable && stab[1].second.points[0].stable, "stable at dt-factor 0.5 (PMB, LPS)");
        // Von Neumann is exact for the interior of the PMB lattice; the bisection resolves 0.5 %.
        run.check(std::abs(thr_pmb / vn - 1) <= 0.02, "PMB stability limit within 2 % of von Neumann");
        std::snprintf(verdict + std::strlen(verdict), 120, "; E1 rate %.2f/%.2f, dt limit %.3f/%.3f dt_SA (LPS/PMB)",
                      rate_lps, rate_pmb, thr_lps, thr_pmb);
    }
    if (!single) {
        // 8. Integrators side by side (LPS, N, same window): Verlet at its standard step, Newmark at the same
        // step and beyond the explicit limit (LPS, N = 100: 1.99 dt_SA); records of >= 24 samples per T1.
        const auto rows = pd::compare_bar_integrators({{false, dt_factor * safety}, {true, dt_factor * safety}, {true, 4}, {true, 12}},
            bar.f1, [&](bool newmark, double f) {
                Bar b = bar;
                b.newmark = newmark;
                b.samples = std::min(samples, static_cast<int>(1 / (bar.f1 * f * rf.dt_crit)));
                return pd::release_fixed_free_bar(b, "lps", N, m, f, t_end, false);
            }, [&](const Run& r) { return scorer.score(r.t_s, r.tip_m, r.x_tip, N, false); });
        pd::print_bar_integrators(rows, N);
        pd::write_bar_integrators(run.file("integrators.csv"), rows);
        // At Verlet's step, Newmark's period error ~ (omega dt)^2/12 is negligible for mode 1: same f1 bound.
        run.regression_bound(std::abs(rows[1].f1_rel_error) <= 2.0 / N, "Newmark f1 within 2 dx/l of c/(4l) at Verlet's step (the Verlet bound)");
        run.summary({"f1_newmark_4dt_SA", (1 + rows[2].f1_rel_error) * bar.f1, bar.f1, std::abs(rows[2].f1_rel_error), "Hz"});
    }
    return run.finish("%s", verdict);
}

int main(int argc, char** argv) { return pd::io::guarded_main("bar_modes_1d", [&] { return run_case(argc, argv); }); }
