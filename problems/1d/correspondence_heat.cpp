// problems/1d/correspondence_heat.cpp -- hourglass modes of the correspondence heat model and their
// suppression, 1D bar with both ends suddenly held at 100 C.
// Case: the agwai_bar case (l = 0.1 m, A = 1e-4 m^2, rho = 7800, c = 502.08, k = 50, 0 C inside, 100 C
//   held in 3 cells outside each end) with N = 500 cells, delta = 3 dx, full volumes; implicit Euler
//   dt = 10 s to t = 500 s. Correspondence heat (gradient through the shape tensor, h = omega (K^-1 q).xi)
//   plus the suppression C_hg kappa_1 (theta_j - theta_i - g.xi)/|xi| with the stabilising sign.
// Source: seed 000b sec. 6.7, Figs. 6.7-6.8 (spec/000b sec. 5.11 T11, V11): qualitative only: C_hg = 0
//   oscillates, 0.01 strongly, 0.1 everywhere but less, 1 only near the ends, 100 none, 10000 smooth but
//   biased. Here those statements become numbers.
// Reference: reference/heat_1d.hpp: the classical 3-point finite-difference bar (implicit Euler, the same
//   dt) on a 4x finer grid, interpolated linearly to the PD nodes.
// Measured per C_hg: oscillation = max over free nodes of |theta_{i-1} - 2 theta_i + theta_{i+1}|/4 (the
//   amplitude of an odd-even pattern; a smooth profile gives dx^2 |theta''|/4), the RMS and max distance
//   from the classical profile, wall time.
// Run: correspondence_heat_1d [--N 500] [--chg 0,0.01,0.1,1,100,10000] [--dt 10] [--t-end 500] [--quick]
//   [--check] [--out DIR]. Writes: oscillation.csv, profiles.csv, summary.csv, params.csv.
#include "pd/heat/conduction.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/lattice.hpp"
#include "reference/heat_1d.hpp"

#include <cmath>
#include <cstdio>

namespace {

constexpr double T_start = 0, T_held = 100;  // [C] (spec T7/T11)
constexpr int fd_refine = 4;                 // classical grid 4x finer than the PD cells

int run_case(int argc, char** argv)
{
    // 1. Options (defaults: spec/000b T11).
    pd::io::Case run("correspondence_heat_1d", "Hourglass suppression in 1D correspondence heat conduction (spec/000b T11).",
                     "reports/1d/correspondence_heat");
    pd::io::Options& opt = run.opt;
    opt.add("k", 50, "thermal conductivity", "W/(m K)");
    opt.add("rho", 7800, "density", "kg/m^3");
    opt.add("c", 502.08, "specific heat", "J/(kg K)");
    opt.add("length", 0.1, "bar length", "m");
    opt.add("area", 1e-4, "cross-section", "m^2");
    opt.add("dt", 10, "implicit Euler step", "s");
    opt.add("t-end", 500, "final time", "s");
    opt.add_int("N", 500, "cells along the bar (--quick: 100)");
    opt.add_int("m", 3, "horizon ratio delta/dx");
    opt.add_string("chg", "0,0.01,0.1,1,100,10000", "hourglass coefficients C_hg (comma list)");
    opt.add_string("bc", "outside", "held cells outside the bar, or its first/last m cells", {"outside", "inside"});
    for (const char* o : {"k", "rho", "c", "length", "area", "dt", "t-end"}) opt.require_positive(o);
    opt.require_at_least("N", 8);
    opt.require_at_least("m", 1);
    run.parse(argc, argv);
    run.quick_default("N", 100);
    run.time_scale_set_by("--k, --rho, --c, --length, --N, --m");
    run.start();
    const std::vector<double> chg = pd::io::list_option(opt, "chg", pd::io::ListValues::non_negative);
    const int N = opt.get_int("N"), m = opt.get_int("m");
    const double l = opt.get("length"), A = opt.get("area"), dx = l / N, dt = opt.get("dt");
    pd::require_steps(std::round(opt.get("t-end") / dt), "--t-end / --dt");
    const int steps = int(std::lround(opt.get("t-end") / dt));

    // 2. Discretisation: N cells; held: m cells outside each end, or the first/last m cells.
    const bool outside = opt.get_string("bc") == "outside";
    const double ext = outside ? m * dx : 0, lo = outside ? 0 : m * dx, hi = outside ? l : l - m * dx;
    const auto body = pd::box<1>(pd::Vec<1>{-ext}, pd::Vec<1>{l + ext}, dx, A);
    const auto bonds = pd::build_bonds(body, m * dx);
    pd::HeatLoads loads;
    for (int i : pd::select<1>(body, [&](const pd::Vec<1>& p) { return p[0] < lo || p[0] > hi; }, "held ends"))
        loads.fixed.push_back(i), loads.fixed_value.push_back(T_held);
    const int first = outside ? m : 0, last = outside ? m + N : N;  // the cells of the bar

    // 3. Classical reference profile at the PD nodes.
    const pd::ref::HeatBar1D bar{l, opt.get("k") / (opt.get("rho") * opt.get("c")), T_start, T_held};
    const std::vector<double> fd = pd::ref::heat_bar_fd_profile(bar, fd_refine * N, dt, steps);
    auto classical = [&](double x) {
        const double s = x / (l / (fd_refine * N));
        const int i = std::min(int(s), fd_refine * N - 1);
        return fd[i] + (s - i) * (fd[i + 1] - fd[i]);
    };

    // 4. One run per C_hg.
    pd::io::CsvWriter osc_csv(run.file("oscillation.csv"), {"C_hg", "oscillation_K", "rms_distance_K", "max_distance_K", "wall_s"});
    std::vector<std::vector<double>> profiles;
    std::vector<double> osc, rms;
    for (double C : chg) {
        pd::io::Timer timer;
        pd::CorrespondenceHeat<1> model({opt.get("k"), C, A}, body, bonds);
        pd::Conduction<pd::CorrespondenceHeat<1>> heat(model, bonds, std::vector<double>(body.size(), opt.get("rho") * opt.get("c")), loads);
        std::vector<double> theta(body.size(), T_start);
        heat.apply_fixed(theta);
        for (int n = 0; n < steps; ++n) heat.implicit_euler(theta, dt);
        double o = 0, r2 = 0, dmax = 0;
        for (int i = first; i < last; ++i) {
            if (i == 0 || i + 1 == int(body.size())) continue;
            o = std::max(o, std::abs(theta[i - 1] - 2 * theta[i] + theta[i + 1]) / 4);
            const double d = theta[i] - classical(body.x.c[0][i]);
            r2 += d * d / N, dmax = std::max(dmax, std::abs(d));
        }
        osc.push_back(o), rms.push_back(std::sqrt(r2)), profiles.push_back(theta);
        osc_csv.row({C, o, std::sqrt(r2), dmax, timer.seconds()});
        std::printf("C_hg = %-8g oscillation %10.4e K   distance from classical: rms %9.4e K, max %9.4e K   (%.3f s)\n", C, o,
                    std::sqrt(r2), dmax, timer.seconds());
    }
    std::vector<std::string> cols = {"x_m", "T_classical_C"};
    for (double C : chg) cols.push_back("T_chg_" + pd::io::CsvCell(C).text() + "_C");
    pd::io::CsvWriter prof(run.file("profiles.csv"), cols, false);
    for (int i = first; i < last; ++i) {
        std::vector<double> row = {body.x.c[0][i], classical(body.x.c[0][i])};
        for (const auto& p : profiles) row.push_back(p[i]);
        prof.row(row);
    }

    // 5. Work-precision at C_hg = 1: final profile error (max over the bar, K) of each integrator
    //    against CVODE at rtol 1e-10 on the same PD model.
    {
        pd::CorrespondenceHeat<1> model({opt.get("k"), 1.0, A}, body, bonds);
        pd::Conduction<pd::CorrespondenceHeat<1>> heat(model, bonds, std::vector<double>(body.size(), opt.get("rho") * opt.get("c")), loads);
        const double t_end = steps * dt;
        auto final_profile = [&](const std::string& scheme, double step, long& n_steps) {
            std::vector<double> theta(body.size(), T_start);
            heat.apply_fixed(theta);
            if (scheme == "cvode") {
                pd::CvodeOptions co;
                co.rtol = step, co.atol = step * T_held;
                pd::HeatCvode<pd::CorrespondenceHeat<1>> cv(heat, model, bonds, theta, 0.0, co);
                theta = cv.advance(t_end);
                n_steps = cv.stats().steps;
                return theta;
            }
            n_steps = std::lround(t_end / step);
            for (long n = 0; n < n_steps; ++n) scheme == "implicit" ? heat.implicit_euler(theta, t_end / n_steps) : heat.explicit_euler(theta, t_end / n_steps);
            return theta;
        };
        long n_ref = 0;
        const std::vector<double> ref = final_profile("cvode", 1e-10, n_ref);
        const double dt_crit = pd::thermal_critical_step(model, bonds, heat, std::vector<double>(body.size(), T_start));
        pd::io::CsvWriter wp(run.file("work_precision.csv"), {"integrator", "dt_s", "rtol", "error", "wall_s", "steps"});
        std::printf("work-precision at C_hg = 1 (error: max |T - T_cvode(rtol 1e-10)| at t = %g s; dt_crit %.4g s):\n", t_end, dt_crit);
        auto record = [&](const std::string& scheme, double step) {
            pd::io::Timer timer;
            long n = 0;
            const auto th = final_profile(scheme, step, n);
            double e = 0;
            for (int i = first; i < last; ++i) e = std::max(e, std::abs(th[i] - ref[i]));
            const bool cv = scheme == "cvode";
            wp.row({scheme, cv ? t_end / n : t_end / n, cv ? step : NAN, e, timer.seconds(), n});
            std::printf("  %-8s dt %-9.4g error %-9.3e K  wall %.3f s, %ld steps\n", scheme.c_str(), t_end / n, e, timer.seconds(), n);
        };
        for (double f : {0.9, 0.45}) record("explicit", f * dt_crit);
        for (double h : {10.0, 2.5, 0.625}) record("implicit", h);
        for (double tol : {1e-4, 1e-7}) record("cvode", tol);
    }

    // 6. Checks: the source's qualitative statements, as numbers (only for the default C_hg list).
    for (std::size_t q = 0; q < chg.size(); ++q)
        run.summary({"oscillation_chg_" + pd::io::CsvCell(chg[q]).text(), osc[q], NAN, NAN, "K"});
    if (!opt.given("chg")) {
        run.property(osc[0] > 10 * osc[3], "C_hg = 0 oscillates: odd-even amplitude > 10x that at C_hg = 1");
        bool falling = true;
        for (std::size_t q = 1; q < 5; ++q) falling = falling && osc[q] < osc[q - 1];
        run.property(falling, "oscillation falls with C_hg from 0 to 100");
        run.property(osc[4] < 0.05 * osc[0], "C_hg = 100: oscillation below 5 % of C_hg = 0");
        run.property(rms[5] > rms[4], "C_hg = 10000 departs further from classical than C_hg = 100");
    }
    return run.finish("odd-even oscillation %.3e K at C_hg = %g, %.3e K at C_hg = %g", osc.front(), chg.front(), osc.back(),
                      chg.back());
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("correspondence_heat_1d", [&] { return run_case(argc, argv); }); }
