// problems/3d/hopkinson_multirate.cpp -- the two clock studies of the Hopkinson tension case (Biondani
// 2018 sec. 9.1.3; spec/000c sec. 3.3-3.4, Table 9.3, V14): does conduction matter over the first
// 30 us, on its own clock of N_sync(MK) mechanical steps, and what does releasing the plastic heat only
// every N_sync(MH) steps do. The scene is that of hopkinson_tension_3d (problems/common/hopkinson_scene.hpp).
// Runs, each --t-end (30 us) long with one mechanical step dt for all of them: the largest step <= the
// stable one (0.5 x Silling-Askari) that makes N_sync(MK) dt divide t_end (the source instead changed
// dt in the N_sync(MK) = 94 run only, to which it attributes that run's larger error):
//   adiabatic   conduction off, N_sync(MH) 1            (the reference of both studies)
//   mk1         conduction on, N_sync(MK) 1, N_sync(MH) 1
//   mk<N>       conduction on, N_sync(MK) --nsync-mk (94), N_sync(MH) 1
//   mh<N>       conduction off, N_sync(MH) --nsync-mh (100)
// Errors of a run against adiabatic (temperatures in degrees C, as the source), T_c the centre node's:
//   eps1 = (T_c - T_c,ref) / T_c,ref at t_s;
//   eps2 = int (T - T_ref) dx / int T_ref dx along the surface centreline at t_s (trapezoidal);
//   eps3 = int (T_c - T_c,ref) dt / int T_c,ref dt over 0..t_end (trapezoidal on every step);
// t_s a synchronisation instant of the run: t_end for the conduction runs (a thermal step ends
// there), the last release at or before t_end for mh<N> (the heat of the steps after it is not yet
// in the field; the source's 30 us is such an instant).
// Staircase: the largest rise of T_c in one mechanical step (N_sync(MH) = 100: each release at once).
// Published (Table 9.3 and sec. 9.1.3): eps1..3 of mk1 -2.76e-6, -3.94e-8, -7.48e-7; of mk94 -5.09e-5,
// -2.17e-5, -2.47e-5; of mh100 eps1 5.29e-5, eps2 5.45e-5 and jumps above 1 C.
// Run: hopkinson_multirate_3d [--t-end 30e-6] [--nsync-mk 94] [--nsync-mh 100] [hopkinson options]
//   [--quick] [--check] [--out DIR]. Writes centre.csv (T_c of every run per step), runs.csv, summary.csv,
//   params.csv.
#include "pd/core/timer.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "problems/common/hopkinson_scene.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Outcome {
    std::string name;
    std::vector<double> T_c;   // centre node temperature after each step (and at t = 0) [C]
    std::vector<double> x;     // surface centreline [m]
    std::vector<double> T[2];  // its temperatures after the steps `at` [C]
    double wall = 0;           // [s]
};

Outcome run_one(const std::string& name, pd::HopkinsonParams p, bool conduction, long nsync_mk, long nsync_mh, long steps,
                const long (&at)[2])
{
    p.conduction = conduction, p.nsync_mk = nsync_mk, p.nsync_mh = nsync_mh;
    pd::HopkinsonScene hs(p);
    Outcome o{name, {}, {}, {}, 0};
    for (int i : hs.line) o.x.push_back(hs.d.body.x.c[0][i]);
    const pd::io::Timer timer;
    hs.ex.start();
    o.T_c.push_back(hs.field->theta[hs.centre]);
    for (long n = 1; n <= steps; ++n) {
        hs.ex.step(hs.dt);
        o.T_c.push_back(hs.field->theta[hs.centre]);
        for (int a : {0, 1})
            if (n == at[a]) for (int i : hs.line) o.T[a].push_back(hs.field->theta[i]);
    }
    o.wall = timer.seconds();
    return o;
}

double trapezoid(const std::vector<double>& x, const std::vector<double>& f)
{
    double s = 0;
    for (std::size_t k = 1; k < x.size(); ++k) s += 0.5 * (f[k] + f[k - 1]) * (x[k] - x[k - 1]);
    return s;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options: the case's (hopkinson_scene.hpp) and the studies', echoed and saved.
    pd::io::Case run("hopkinson_multirate_3d", "Hopkinson case: conduction and heat-release clocks over 30 us (spec/000c Table 9.3, V14).",
                     "reports/3d/hopkinson_multirate");
    pd::io::Options& opt = run.opt;
    pd::add_hopkinson_options(opt);
    double& t_end = opt.add("t-end", 30e-6, "duration of each run", "s");
    int &nsync_mk = opt.add_int("nsync-mk", 94, "N_sync(MK) of the multirate conduction run"),
        &nsync_mh = opt.add_int("nsync-mh", 100, "N_sync(MH) of the delayed-release run");
    opt.require_positive("t-end");
    for (const char* o : {"nsync-mk", "nsync-mh"}) opt.require_at_least(o, 2);
    run.parse(argc, argv);
    run.quick_default("delta", 2e-3);
    pd::HopkinsonParams p = pd::hopkinson_params(opt);
    run.start();

    // 2. The common step: N_sync(MK) dt divides t_end, dt <= the stable step.
    double dt = 0;
    {
        pd::HopkinsonScene probe(p);
        probe.print();
        const long thermal_steps = static_cast<long>(std::ceil(t_end / (nsync_mk * probe.dt) * (1 - 1e-12)));
        dt = t_end / double(thermal_steps * nsync_mk);
        std::printf("stable step %.5g us; common step %.5g us (%ld thermal steps of N_sync(MK) = %d)\n", probe.dt * 1e6, dt * 1e6,
                    thermal_steps, nsync_mk);
    }
    p.dt = dt;
    const long steps = std::lround(t_end / dt), at[2] = {steps, steps / nsync_mh * nsync_mh};  // t_s (header)

    // 3. The four runs.
    const std::string mk = "mk" + std::to_string(nsync_mk), mh = "mh" + std::to_string(nsync_mh);
    std::vector<Outcome> runs;
    runs.push_back(run_one("adiabatic", p, false, 1, 1, steps, at));
    runs.push_back(run_one("mk1", p, true, 1, 1, steps, at));
    runs.push_back(run_one(mk, p, true, nsync_mk, 1, steps, at));
    runs.push_back(run_one(mh, p, false, 1, nsync_mh, steps, at));

    // 4. Errors against the adiabatic run, the staircase, CSVs, summary and checks.
    const Outcome& ref = runs[0];
    std::vector<double> t(steps + 1);
    for (long n = 0; n <= steps; ++n) t[n] = n * dt;
    pd::io::CsvWriter centre(run.file("centre.csv"), {"t_s", "T_c_adiabatic_C", "T_c_mk1_C", "T_c_" + mk + "_C", "T_c_" + mh + "_C"});
    for (long n = 0; n <= steps; ++n) centre.row({t[n], runs[0].T_c[n], runs[1].T_c[n], runs[2].T_c[n], runs[3].T_c[n]});
    pd::io::CsvWriter csv(run.file("runs.csv"), {"run", "eps1", "eps2", "eps3", "max_step_rise_C", "T_c_end_C", "wall_s"});
    struct Published { const char* run; double e1, e2, e3; };
    const Published pub[] = {{"mk1", -2.76e-6, -3.94e-8, -7.48e-7}, {"mk94", -5.09e-5, -2.17e-5, -2.47e-5}, {"mh100", 5.29e-5, 5.45e-5, NAN}};
    std::printf("\n%-10s %12s %12s %12s %10s %10s %8s\n", "run", "eps1", "eps2", "eps3", "jump_C", "T_c_C", "wall_s");
    double jump_ref = 0;
    for (const Outcome& o : runs) {
        const int a = o.name == mh ? 1 : 0;  // t_s (header)
        std::vector<double> dT(o.T_c.size()), dTx(o.x.size());
        double jump = 0;
        for (std::size_t n = 0; n < o.T_c.size(); ++n) dT[n] = o.T_c[n] - ref.T_c[n];
        for (std::size_t n = 1; n < o.T_c.size(); ++n) jump = std::max(jump, o.T_c[n] - o.T_c[n - 1]);
        for (std::size_t q = 0; q < o.x.size(); ++q) dTx[q] = o.T[a][q] - ref.T[a][q];
        const double e1 = dT[at[a]] / ref.T_c[at[a]], e2 = trapezoid(o.x, dTx) / trapezoid(ref.x, ref.T[a]), e3 = trapezoid(t, dT) / trapezoid(t, ref.T_c);
        if (&o == &ref) jump_ref = jump;
        csv.row({o.name, e1, e2, e3, jump, o.T_c.back(), o.wall});
        std::printf("%-10s %12.4e %12.4e %12.4e %10.4f %10.4f %8.1f\n", o.name.c_str(), e1, e2, e3, jump, o.T_c.back(), o.wall);
        std::fflush(stdout);
        if (&o == &ref) continue;
        const std::string key = o.name;  // published values exist for mk1, mk94 and mh100 only
        for (const Published& q : pub)
            if (key == q.run)
                run.summary({{o.name + "_eps1", e1, q.e1, NAN, "-"}, {o.name + "_eps2", e2, q.e2, NAN, "-"},
                             std::isnan(q.e3) ? pd::io::SummaryRow{o.name + "_eps3", e3, NAN, NAN, "-"} : pd::io::SummaryRow{o.name + "_eps3", e3, q.e3, NAN, "-"}});
        run.summary({{o.name + "_max_step_rise", jump, NAN, NAN, "K"}, {o.name + "_wall", o.wall, NAN, NAN, "s"}});
        if (o.name == mh) {
            run.property(jump > 10 * jump_ref, mh + ": the centre temperature rises in steps (largest step rise > 10x the adiabatic run's)");
            run.property(std::abs(e1) < 1e-2 && std::abs(e2) < 1e-2, mh + ": the delayed release changes T at its last release by < 1 % (eps1, eps2)");
        } else {
            run.property(e1 < 0 && e3 < 0, o.name + ": conduction cools the hot centre (eps1, eps3 < 0)");
            run.property(std::abs(e1) < 1e-3, o.name + ": conduction changes the centre temperature by < 0.1 % over the run (eps1)");
        }
    }
    run.summary({{"dt", dt, NAN, NAN, "s"}, {"steps", double(steps), NAN, NAN, "-"}, {"T_c_end_adiabatic", ref.T_c.back(), NAN, NAN, "C"}});
    run.property(ref.T_c.back() > ref.T_c.front(), "the centre heats in the adiabatic run");
    return run.finish("eps of Table 9.3 and the N_sync(MH) staircase over %.3g us", t_end * 1e6);
}

int main(int argc, char** argv) { return pd::io::guarded_main("hopkinson_multirate_3d", [&] { return run_case(argc, argv); }); }
