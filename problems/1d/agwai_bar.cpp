// problems/1d/agwai_bar.cpp -- transient heat conduction in a 1D bar: Agwai bond-based PD vs classical.
// Case: bar [0, l], section A, initially at T0 = 0 C, both ends held at 100 C from t = 0; the time t50
//   at which the centre reaches 50 C. Cell-centred nodes x_i = (i + 1/2) dx, dx = l/N, delta = m dx;
//   the held ends are m cells OUTSIDE the bar (spec [RECON]: the convention closest to the source), and
//   the bond to a neighbour at |xi| = delta gets half its volume (--volume half: PA-PDLAMMPS partial volume).
// Source: seed 000b sec. 6.3, Table 6.1 (spec/000b sec. 5.7 T7, V8): Agwai kappa_1 = 2k/(A delta^2),
//   implicit Euler dt = 10 s, t50 by linear interpolation in time.
// Reference: reference/heat_1d.hpp: the source's classical column (3-point finite differences on N+1
//   nodes, implicit Euler with the same dt), and the exact continuum t50 (Fourier series, 74.163 s).
// Compared: PD t50 per N = 10 ... 1000 beside the source's PD and classical columns and the spec's
//   reconstruction of the source's PD convention; observed order; work-precision of the three
//   integrators (explicit Euler at fractions of the thermal critical step, implicit Euler, CVODE) at one
//   N, error against the time-converged PD value (CVODE at rtol 1e-11).
// Run: agwai_bar_1d [--N 100] [--integrator implicit|explicit|cvode] [--dt 10] [--m 3] [--k --rho --c
//   --length --area] [--volume half|full] [--quick] [--check] [--out DIR]; default: the N study.
// Writes: convergence.csv, work_precision.csv, summary.csv, params.csv.
#include "pd/heat/agwai.hpp"
#include "pd/time/heat_time_to_reach.hpp"
#include "pd/io/convergence.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/case.hpp"
#include "pd/core/lattice.hpp"
#include "reference/heat_1d.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>

namespace {

constexpr double T_start = 0, T_held = 100, T_target = 50;  // [C] (spec T7)

struct Bar {
    double k, rho, c, l, A, dt, t_max;  // [W/(m K)], [kg/m^3], [J/(kg K)], [m], [m^2], [s], [s]
    int m;
    bool half_volume;
};

struct Outcome {
    pd::ReachResult reach;
    long long nodes = 0, bonds = 0;
    double dt_crit = 0;  // thermal critical step of explicit Euler [s]
};

// One PD bar of N cells: t50 with the given integrator (dt for Euler, step = rtol for CVODE).
Outcome run_bar(const Bar& cs, int N, pd::HeatIntegrator scheme, double step)
{
    const double dx = cs.l / N, delta = cs.m * dx;
    auto body = pd::box<1>(pd::Vec<1>{-cs.m * dx}, pd::Vec<1>{cs.l + cs.m * dx}, dx, cs.A);  // bar + held cells
    pd::BondOptions bo;
    bo.partial_volume = cs.half_volume ? pd::PartialVolume::pa_pdlammps : pd::PartialVolume::none;
    const auto bonds = pd::build_bonds(body, delta, bo);
    pd::Agwai model({cs.k, cs.A}, body, bonds);
    pd::HeatLoads loads;
    for (int i : pd::select<1>(body, [&](const pd::Vec<1>& p) { return p[0] < 0 || p[0] > cs.l; }, "held ends"))
        loads.fixed.push_back(i), loads.fixed_value.push_back(T_held);
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), cs.rho * cs.c), loads);
    // Centre: mean of the two nodes around x = l/2 (N even; equal by symmetry) or the middle node.
    const int a = cs.m + (N - 1) / 2, b = cs.m + N / 2;
    const pd::Probe centre = [a, b](const std::vector<double>& T) { return 0.5 * (T[a] + T[b]); };
    pd::CvodeOptions opt;
    opt.rtol = step, opt.atol = step * T_held;
    Outcome o;
    o.nodes = body.size(), o.bonds = bonds.size();
    o.dt_crit = pd::thermal_critical_step(model, bonds, heat, std::vector<double>(body.size(), T_start));
    o.reach = pd::time_to_reach(heat, model, bonds, std::vector<double>(body.size(), T_start), scheme, step, opt,
                                cs.t_max, centre, T_target);
    if (!o.reach.reached) throw std::invalid_argument("the centre did not reach 50 C within --t-max (raise --t-max, or check --k, --rho, --c, --length)");
    return o;
}

int run_case(int argc, char** argv)
{
    // 1. Options (defaults: spec/000b T7).
    pd::io::Case run("agwai_bar_1d", "1D transient conduction, Agwai PD vs classical (spec/000b T7).", "reports/1d/agwai_bar");
    pd::io::Options& opt = run.opt;
    opt.add("k", 50, "thermal conductivity", "W/(m K)");
    opt.add("rho", 7800, "density", "kg/m^3");
    opt.add("c", 502.08, "specific heat", "J/(kg K)");
    opt.add("length", 0.1, "bar length", "m");
    opt.add("area", 1e-4, "cross-section", "m^2");
    opt.add("dt", 10, "implicit Euler step (the source's)", "s");
    opt.add("t-max", 2000, "give up when the centre has not reached 50 C by then", "s");
    opt.add_int("m", 3, "horizon ratio delta/dx");
    opt.add_int("N", 0, "cells along the bar; 0 = the study N = 10 ... 1000");
    opt.add_string("integrator", "implicit", "integrator of a single run (--N)", {"implicit", "explicit", "cvode"});
    opt.add_string("volume", "half", "volume of the neighbour at |xi| = delta", {"half", "full"});
    for (const char* p : {"k", "rho", "c", "length", "area", "dt", "t-max"}) opt.require_positive(p);
    opt.require_at_least("m", 1);
    opt.require_at_least("N", 0);
    run.time_scale_set_by("--k, --rho, --c, --length, --N, --m");
    run.start(argc, argv);
    const Bar cs{opt.get("k"), opt.get("rho"), opt.get("c"), opt.get("length"), opt.get("area"), opt.get("dt"),
          opt.get("t-max"), opt.get_int("m"), opt.get_string("volume") == "half"};
    const bool quick = run.quick();
    pd::ref::HeatBar1D ref_bar{cs.l, cs.k / (cs.rho * cs.c), T_start, T_held};
    const double t50_exact = pd::ref::heat_bar_exact_time_to(ref_bar, 0.5 * cs.l, T_target);

    // 2. A single resolution (--N): t50 against the classical value of the same N and dt.
    if (opt.get_int("N") > 0) {
        const int N = opt.get_int("N");
        const auto scheme = pd::parse_heat_integrator(opt.get_string("integrator"));
        const double step = scheme == pd::HeatIntegrator::cvode ? 1e-8 : cs.dt;
        const Outcome o = run_bar(cs, N, scheme, step);
        const double t50_fd = pd::ref::heat_bar_fd_time_to(ref_bar, N, cs.dt, 0.5 * cs.l, T_target);
        std::printf("N = %d (%s): t50 PD %.4f s, classical %.4f s, exact %.4f s, %.3f s wall\n", N,
                    pd::name(scheme), o.reach.t, t50_fd, t50_exact, o.reach.wall_s);
        run.summary({{"t50", o.reach.t, t50_fd, pd::io::relative_error(o.reach.t, t50_fd), "s"},
                     {"t50_exact_continuum", t50_exact, 74.163, pd::io::relative_error(t50_exact, 74.163), "s"}});
        run.property(o.reach.t > t50_fd, "PD diffuses more slowly than classical (source, Fig. 6.1)");
        return run.finish("N = %d: t50 PD %.4f s (classical %.4f s)", N, o.reach.t, t50_fd);
    }

    // 3. The N study (implicit Euler, dt = 10 s): ours, source PD, spec reconstruction, classical.
    const std::map<int, double> source_pd = {{10, 101.517}, {50, 83.665}, {100, 81.136}, {200, 79.843}, {500, 79.124}, {1000, 78.883}};
    const std::map<int, double> recon_pd = {{10, 105.72}, {50, 83.83}, {100, 81.18}, {200, 79.853}};
    const std::map<int, int> recon_decimals = {{10, 2}, {50, 2}, {100, 2}, {200, 3}};  // as printed in the spec
    const std::vector<int> Ns = quick ? std::vector<int>{10, 50, 100} : std::vector<int>{10, 50, 100, 200, 500, 1000};
    pd::io::ConvergenceTable table({}, {"t50_pd_s", "t50_classical_s", "t50_source_pd_s", "t50_recon_pd_s"});
    std::map<int, double> ours;
    for (int N : Ns) {
        const Outcome o = run_bar(cs, N, pd::HeatIntegrator::implicit_euler, cs.dt);
        const double fd = pd::ref::heat_bar_fd_time_to(ref_bar, N, cs.dt, 0.5 * cs.l, T_target);
        ours[N] = o.reach.t;
        const double src = source_pd.count(N) ? source_pd.at(N) : NAN, rec = recon_pd.count(N) ? recon_pd.at(N) : NAN;
        table.add({.dx_m = cs.l / N, .delta_m = cs.m * cs.l / N, .m = double(cs.m), .nodes = o.nodes, .bonds = o.bonds,
                   .error = (o.reach.t - fd) / fd, .wall_s = o.reach.wall_s, .extras = {o.reach.t, fd, src, rec}});
    }
    table.print(std::cout);
    table.write_csv(run.file("convergence.csv"));
    const double rate = table.rate(Ns.size() - 1);
    run.check(rate > 0.9 && rate < 1.1, "first-order convergence to classical (finest pair rate in 0.9..1.1)");
    // The spec's reconstruction of the same convention, printed to 2-3 decimals: ours within half a unit
    // of its last printed digit.
    for (const auto& [N, rec] : recon_pd)
        if (ours.count(N))
            run.check(std::abs(ours[N] - rec) <= 0.5 * std::pow(10.0, -recon_decimals.at(N)),
                      "t50 = spec reconstruction within half a unit of its last printed digit, N = " + std::to_string(N));
    for (const auto& [N, t] : ours) run.summary({"t50_N" + std::to_string(N), t, source_pd.at(N), pd::io::relative_error(t, source_pd.at(N)), "s"});
    run.summary({"rate_t50", rate, 1, std::abs(rate - 1), "-"});
    run.summary({"t50_exact_continuum", t50_exact, 74.163, pd::io::relative_error(t50_exact, 74.163), "s"});

    // 4. Work-precision at one N: error of t50 against the time-converged PD value, and wall time.
    const int Nw = quick ? 50 : 200;
    const double t_ref = run_bar(cs, Nw, pd::HeatIntegrator::cvode, 1e-11).reach.t;
    pd::io::CsvWriter wp(run.file("work_precision.csv"), {"integrator", "dt_s", "rtol", "error", "wall_s", "steps", "t50_s"});
    const double dt_crit = run_bar(cs, Nw, pd::HeatIntegrator::cvode, 1e-6).dt_crit;
    std::printf("work-precision, N = %d (thermal critical step %.4g s, reference t50 %.9f s):\n", Nw, dt_crit, t_ref);
    // dt_s: the fixed step, for CVODE the mean internal step t50/steps; rtol: CVODE's tolerance.
    auto record = [&](pd::HeatIntegrator s, double step) {
        const Outcome o = run_bar(cs, Nw, s, step);
        const double err = std::abs(o.reach.t - t_ref) / t_ref;
        const bool cv = s == pd::HeatIntegrator::cvode;
        const double dt = cv ? o.reach.t / o.reach.steps : step;
        wp.row({pd::name(s), dt, cv ? step : NAN, err, o.reach.wall_s, o.reach.steps, o.reach.t});
        std::printf("  %-8s dt %-10.4g rtol %-8.1e error %-10.3e wall %.4f s, %ld steps\n", pd::name(s), dt,
                    cv ? step : NAN, err, o.reach.wall_s, o.reach.steps);
        return err;
    };
    for (double f : {0.9, 0.5, 0.25}) record(pd::HeatIntegrator::explicit_euler, f * dt_crit);
    std::vector<double> e_imp;
    for (double dt : {10.0, 5.0, 2.5, 1.25}) e_imp.push_back(record(pd::HeatIntegrator::implicit_euler, dt));
    for (double tol : {1e-4, 1e-6, 1e-8}) record(pd::HeatIntegrator::cvode, tol);
    run.check(std::abs(e_imp[2] / e_imp[3] - 2) < 0.2, "implicit Euler first order in dt (error ratio 2 +- 0.2)");
    return run.finish("PD t50 at N = %d: %.3f s (classical %.3f s, source %.3f s); rate %.2f", Ns.back(), ours[Ns.back()],
                      pd::ref::heat_bar_fd_time_to(ref_bar, Ns.back(), cs.dt, 0.5 * cs.l, T_target), source_pd.at(Ns.back()), rate);
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("agwai_bar_1d", [&] { return run_case(argc, argv); }); }
