// problems/3d/model_cost.cpp -- run time of the elastic models relative to PMB on the explicit T2 bar.
// Case: bar 10 x 2 x 1 mm (E = 100 GPa, nu = 0.33; rho not given by the source: 7800 kg/m^3), cubic
// lattice dx = thickness/n, delta = 3.05 dx, clamp zones 2 delta long added outside both ends; one
// zone fixed, the other pulled axially by a linear displacement ramp to 1 % of the length over the
// run. S steps of velocity Verlet at one common dt (dt-factor x Silling-Askari step of PMB; 0.2 is
// the source's PALS safety factor), for PMB, LPS, LPS+SCF, PALS and correspondence (linear law,
// C_hg = 0.02; per-node F, sigma, P on demand, as a run that reads only forces and energies needs
// them, unless --node-matrices), on the same lattice and bonds.
// Source: spec/000b sec. 5.2 (T2 specimen), 5.3 and V3 (T3: run time over PMB's; the source saw
// LPS ~2x, correspondence ~3x, PALS > 8x). Issue 3 asks LPS <= 2x, correspondence <= 3x, PALS <= 3x.
// Measurement (the machine is shared): the five runs advance side by side in blocks of 10 steps,
// order rotated; ratio = median over blocks and R repeats of t_model/t_PMB (best-of-R totals too).
// Only the stepping loop is timed; model set-up is timed apart. Report: --threads 1 (see .md).
// Compared: cost_ratio_<model> vs the source's ratio. --check asserts only what is robust: every
// run stays finite and passes the energy guard, and every ratio is finite and positive (wall-clock
// limits are not asserted; the report states pass/fail against the targets).
// Run: model_cost_3d [--n 8] [--steps 200] [--repeats 3] [--threads 1] [--node-matrices] [--quick] [--check] [--out DIR]
// Writes: summary.csv, runs.csv (per run), timings.csv (per block), params.csv.
#include "problems/common/grips.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>

namespace {

struct Scene {
    const pd::Body<3>& body;
    pd::Bonds& bonds;
    pd::NodeSet fixed, pulled;
    double rho, dt, u_end;  // [kg/m^3], [s], end displacement [m]
    long steps;
};

// One model's simulation, stepped in blocks: advance(k) runs k Verlet steps and returns their wall
// time [s]; finish() runs the energy guard and returns the pulled end's u_x [m]. Both throw
// pd::Unstable on a non-finite state or runaway energy.
struct Runner {
    double setup_s = 0;  // model construction (SCF probe, PALS 6x6 solves, K^-1) [s]
    std::function<double(long)> advance;
    std::function<double()> finish;
};

template <class Make>
Runner make_runner(const Scene& sc, Make&& make)
{
    using Model = decltype(make());
    using Sim = pd::Explicit<3, Model>;
    pd::io::Timer setup;
    auto model = std::make_shared<Model>(make());
    Runner r;
    r.setup_s = setup.seconds();
    auto sim = std::make_shared<Sim>(sc.body, sc.bonds, *model, sc.rho);
    const double t_end = sc.steps * sc.dt;
    pd::grip_bar_ends(sim->boundary, sc.fixed, sc.pulled, pd::TimeFunction::ramp(sc.u_end, t_end), pd::Grips::clamped);
    sim->start();
    const double dt = sc.dt;
    const int tip = sc.pulled.front();
    r.advance = [sim, model, dt](long k) {
        pd::io::Timer loop;
        for (long n = 0; n < k; ++n) sim->step(dt);
        return loop.seconds();
    };
    r.finish = [sim, tip] { sim->check_energy(); return sim->u.c[0][tip]; };
    return r;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI), echoed and saved.
    pd::io::Case run("model_cost_3d", "Explicit T2 bar: run time of LPS, LPS+SCF, PALS, correspondence over PMB's.", "reports/3d/model_cost");
    pd::io::Options& opt = run.opt;
    double& E = opt.add("E", 100e9, "Young's modulus", "Pa");
    double& nu = opt.add("nu", 0.33, "Poisson's ratio");
    double& rho = opt.add("rho", 7800, "density (not given by the source: steel)", "kg/m^3");
    double& L = opt.add("length", 10e-3, "bar length l2 (axial)", "m");
    double& W = opt.add("width", 2e-3, "section width l1", "m");
    double& H = opt.add("thickness", 1e-3, "section thickness l3", "m");
    int& n = opt.add_int("n", 8, "cells through the thickness, dx = thickness/n (quick: 2)");
    double& m = opt.add("m", 3.05, "horizon ratio delta/dx");
    double& strain = opt.add("strain", 0.01, "end displacement / length, ramped linearly over the run");
    double& C_hg = opt.add("C-hg", 0.02, "correspondence hourglass coefficient");
    bool& node_matrices = opt.add_flag("node-matrices", "correspondence stores F, sigma, P per node every step (library default; off here: on demand)");
    double& dt_factor = opt.add("dt-factor", 0.2, "time step / Silling-Askari critical step (PMB stand-in)");
    int& steps = opt.add_int("steps", 200, "velocity Verlet steps per run (quick: 20)");
    int& repeats = opt.add_int("repeats", 3, "repetitions of the whole interleaved set (quick: 2)");
    int& block = opt.add_int("block", 10, "steps per model before the next model's turn (quick: 5)");
    for (const char* o : {"E", "rho", "length", "width", "thickness", "strain", "dt-factor"}) opt.require_positive(o);
    for (const char* o : {"n", "m", "steps", "repeats", "block"}) opt.require_at_least(o, 1);
    opt.require_at_least("C-hg", 0);
    run.parse(argc, argv);
    if (const std::string msg = pd::validate_elastic(E, nu, 3, pd::Plane::strain); !msg.empty()) opt.fail(msg);
    run.quick_default("n", 2);
    run.quick_default("steps", 20);
    run.quick_default("repeats", 2);
    run.quick_default("block", 5);
    run.start();
    pd::require_steps(5.0 * steps * repeats, "--steps x --repeats x 5 models");

    // 2. Discretisation: bar plus clamp zones ceil(2 delta/dx) cells long at both ends (outside).
    const double dx = H / n, delta = m * dx;
    const pd::GrippedBar bar = pd::gripped_bar(L, W, H, dx, 2 * delta);
    const pd::Body<3>& body = bar.body;
    pd::Bonds bonds = pd::build_bonds(body, delta);
    const pd::NodeSet& fixed = bar.left;
    const pd::NodeSet& pulled = bar.right;

    // 3. Models (all on the same bonds) and the common time step.
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const pd::PMB::Params pmb_params{.material = mat, .dim = 3};
    const double c_pmb = pd::PMB::micromodulus(pmb_params, pd::Influence{}, delta);
    const double dt = dt_factor * pd::critical_step_silling_askari(bonds, rho, c_pmb).dt;
    const Scene sc{body, bonds, fixed, pulled, rho, dt, strain * L, steps};
    const std::vector<std::string> names{"pmb", "lps", "lps_scf", "pals", "correspondence"};
    auto make = [&](std::size_t k) -> Runner {
        switch (k) {
        case 0: return make_runner(sc, [&] { return pd::PMB(pmb_params, bonds); });
        case 1: return make_runner(sc, [&] { return pd::LPS({.material = mat, .dim = 3}, bonds); });
        case 2: return make_runner(sc, [&] { pd::LPS lps({.material = mat, .dim = 3}, bonds); lps.apply_shear_correction(body.x); return lps; });
        case 3: return make_runner(sc, [&] { return pd::PALS({.material = mat}, body, bonds); });
        default: return make_runner(sc, [&] {
            using C = pd::Correspondence<3>;
            return C({.material = mat, .law = C::Law::linear, .C_hg = C_hg, .node_matrices = node_matrices}, body, bonds);
        });
        }
    };
    const std::size_t M = names.size();
    std::printf("nodes %zu, bonds %zu (%.1f per node), dx %.4g m, delta %.4g m, dt %.4g s, %d steps in blocks of %d x %zu models "
                "x %d repeats, %d threads\n", body.size(), bonds.size(), double(bonds.size()) / body.size(), dx, delta, dt, steps,
                block, M, repeats, pd::max_threads());

    // 4.-5. All five runs advance side by side, `block` steps each in turn (order rotated every
    // block), so the machine's load changes hit every model alike; whole runs are repeated R times.
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<double> best_setup(M, inf), best_step(M, inf);
    std::vector<std::vector<double>> block_ratio(M);  // t_model / t_pmb per block [-]
    bool tips_ok = true;
    pd::io::CsvWriter blocks(run.file("timings.csv"), {"repeat", "block", "model", "steps", "wall_s"});
    pd::io::CsvWriter runs(run.file("runs.csv"), {"repeat", "model", "setup_s", "step_s", "bond_updates_per_s", "tip_u_m"});
    for (int r = 0; r < repeats; ++r) {
        std::vector<Runner> runner;
        for (std::size_t k = 0; k < M; ++k) runner.push_back(make(k));
        std::vector<double> total(M, 0.0), t(M, 0.0);
        for (long s0 = 0, b = 0; s0 < steps; s0 += block, ++b) {
            const long k_steps = std::min<long>(block, steps - s0);
            for (std::size_t q = 0; q < M; ++q) {
                const std::size_t k = (q + b + r) % M;
                t[k] = runner[k].advance(k_steps);
                total[k] += t[k];
                blocks.row({r, b, names[k], k_steps, t[k]});
            }
            for (std::size_t k = 0; k < M; ++k) block_ratio[k].push_back(t[k] / t[0]);
        }
        for (std::size_t k = 0; k < M; ++k) {
            const double tip = runner[k].finish();
            runs.row({r, names[k], runner[k].setup_s, total[k], double(bonds.size()) * steps / total[k], tip});
            best_setup[k] = std::min(best_setup[k], runner[k].setup_s);
            best_step[k] = std::min(best_step[k], total[k]);
            tips_ok = tips_ok && std::abs(tip - strain * L) <= 1e-9 * strain * L;  // the ramp ends exactly at u_end
        }
    }

    // 6. Ratios against PMB (median of the block ratios; best-of-R totals beside), summary, table, verdict.
    const std::vector<double> source{1, 2, std::nan(""), 8, 3};   // spec/000b sec. 5.3 (LPS+SCF not given)
    const std::vector<double> target{1, 2, 2, 3, 3};               // issue 3 (LPS+SCF held to LPS's)
    bool ratios_ok = true, targets_met = true;
    std::printf("\n%-15s %9s %9s %11s %7s %13s %10s %6s %6s  %s\n", "model", "setup_s", "best_s", "bond_upd/s", "ratio",
                "[q25, q75]", "ratio_best", "source", "target", "issue");
    for (std::size_t k = 0; k < M; ++k) {
        const double ratio = pd::io::quantile(block_ratio[k], 0.5), ratio_best = best_step[k] / best_step[0];
        const double q25 = pd::io::quantile(block_ratio[k], 0.25), q75 = pd::io::quantile(block_ratio[k], 0.75);
        const double rate = double(bonds.size()) * steps / best_step[k];  // bond updates per second
        ratios_ok = ratios_ok && std::isfinite(ratio) && ratio > 0 && std::isfinite(ratio_best) && ratio_best > 0;
        const bool meets = ratio <= target[k];
        if (k > 0) targets_met = targets_met && meets;
        std::printf("%-15s %9.3g %9.4g %11.4g %7.3f [%5.3f, %5.3f] %10.3f %6.3g %6.3g  %s\n", names[k].c_str(), best_setup[k],
                    best_step[k], rate, ratio, q25, q75, ratio_best, source[k], target[k],
                    k == 0 ? "-" : meets ? "met" : "NOT met");
        if (k > 0)
            run.summary({{"cost_ratio_" + names[k], ratio, source[k], pd::io::relative_error(ratio, source[k]), "-"},
                         {"cost_ratio_q25_" + names[k], q25, std::nan(""), std::nan(""), "-"},
                         {"cost_ratio_q75_" + names[k], q75, std::nan(""), std::nan(""), "-"},
                         {"cost_ratio_best_" + names[k], ratio_best, std::nan(""), std::nan(""), "-"},
                         {"bond_updates_per_s_" + names[k], rate, std::nan(""), std::nan(""), "1/s"}});
    }
    run.summary({{"wall_pmb", best_step[0], std::nan(""), std::nan(""), "s"},
                 {"bonds", double(bonds.size()), std::nan(""), std::nan(""), "-"},
                 {"bond_updates_per_s_pmb", double(bonds.size()) * steps / best_step[0], std::nan(""), std::nan(""), "1/s"}});

    // All runs finite and guarded (else exit 3 before here).
    std::printf("\n");
    run.property(ratios_ok, "every cost ratio (median and best-of-R) finite and positive");
    run.property(tips_ok, "every run's pulled end at u_end after the ramp (to 1e-9)");
    return run.finish("%zu nodes, %zu bonds, %d steps; all runs stable; issue targets (LPS <= 2, LPS+SCF <= 2, PALS <= 3, "
                      "correspondence <= 3 x PMB) %s; PMB %.3g s", body.size(), bonds.size(), steps,
                      targets_met ? "all met" : "NOT all met", best_step[0]);
}

int main(int argc, char** argv) { return pd::io::guarded_main("model_cost_3d", [&] { return run_case(argc, argv); }); }
