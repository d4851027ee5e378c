// problems/pd_run_integrate.hpp -- the time loops of pd_run (problems/pd_run.cpp): the run settings,
// the step loop shared by both modes (pd::Unstable -> exit 3, files written so far kept), the
// heat-only loop and the mechanical loop (velocity Verlet) with the heat run following its clock.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/io/state_output.hpp"
#include "pd/core/timer.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/core/material.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/time/verlet.hpp"
#include "pd_run_heat.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace pd_run {

constexpr const char* program = "pd_run";
constexpr double dt_safety = 0.5;  // Silling & Askari's normal safety factor (spec/000a sec. 3.3.2)

struct Run {
    std::string model;
    double hourglass = 0;  // C_hg [-]
    pd::SurfaceCorrectionMethod surface = pd::SurfaceCorrectionMethod::none;
    pd::Elastic material;
    pd::Plane plane = pd::Plane::stress;
    double measure = 1, rho = 0, delta = 0, dx = 0;  // [m^(3-D)], [kg/m^3], [m], [m] (0: no lattice)
    pd::Influence influence;
    pd::PartialVolume partial_volume = pd::PartialVolume::none;
    double dt = 0;                                     // [s]; NaN = automatic
    long steps = 0, energy_every = 1, vtu_every = 0;
    double s0 = 0;                                     // critical stretch [-]; 0 = no bond breaking
    std::vector<long> output_steps;                    // sorted, unique
    std::filesystem::path out;
    bool mechanics = true;                             // false: heat only
    HeatSettings heat;                         // heat.model "none": no temperature field
};

[[noreturn]] inline void fail(const std::string& msg) { pd::io::fail_input(program, msg); }

// 5. The step loop of both modes: step(n) advances to step n, output(n) writes what step n asks for.
// Returns the exit status (3 when pd::Unstable stops the run; the files written so far stay).
template <class Step, class Output>
int step_loop(long steps, Step&& step, Output&& output)
{
    pd::io::Progress progress(program, steps, true);
    try {
        output(0);
        for (long n = 1; n <= steps; ++n) {
            step(n);
            output(n);
            progress.update(n);
        }
    } catch (const pd::Unstable& e) {
        progress.finish();
        std::cerr << program << ": " << e.what() << std::endl;
        return 3;
    }
    progress.finish();
    return 0;
}

inline bool listed(const Run& cfg, long n) { return std::binary_search(cfg.output_steps.begin(), cfg.output_steps.end(), n); }
inline bool vtu_step(const Run& cfg, long n) { return cfg.vtu_every > 0 && (n % cfg.vtu_every == 0 || n == cfg.steps); }

inline void report_heat(const HeatRun& heat)
{
    const auto [lo, hi] = std::minmax_element(heat.T.begin(), heat.T.end());
    std::printf("  thermal step %ld  t = %.6g s  T in [%.6g, %.6g]\n", heat.step, heat.t(), *lo, *hi);
}

// 4.-5. Heat only (--mechanics off): the steps are thermal steps.
template <int D>
int integrate_heat(const Run& cfg, const pd::io::PointCloud& pc, HeatRun& heat)
{
    std::unique_ptr<pd::io::PvdWriter> pvd;
    if (cfg.vtu_every > 0) pvd = std::make_unique<pd::io::PvdWriter>(cfg.out / "state.pvd");
    auto output = [&](long n) {
        if (!listed(cfg, n) && !vtu_step(cfg, n)) return;
        const pd::io::StateFields<D> f{.T = &heat.T, .Q = &heat.heat_flow()};
        if (listed(cfg, n)) pd::io::write_state<D>(cfg.out, n, pc, f);
        if (vtu_step(cfg, n)) pd::io::write_state_vtu<D>(cfg.out, n, heat.t(), pc, f, *pvd);
    };
    pd::io::Timer timer;
    const int status = step_loop(cfg.steps, [&](long n) { heat.advance(n == cfg.steps); }, output);
    if (status != 0) return status;
    report_heat(heat);
    std::printf("%s: done, %ld thermal steps in %.3g s; wrote %s\n", program, cfg.steps, timer.seconds(), cfg.out.string().c_str());
    return 0;
}

// 4.-5. Mechanics, with the heat run (if any) following the mechanical clock: after mechanical step
// n the heat takes thermal steps while (m + 1) dt_thermal <= n dt (relative slack 1e-12 for round-off).
template <int D, class Model>
int integrate(const Run& cfg, const pd::io::PointCloud& pc, const pd::Body<D>& body, pd::Bonds& bonds, Model& model,
              HeatRun* heat)
{
    pd::Explicit<D, Model> sim(body, bonds, model, cfg.rho);
    pd::NodeSet held;  // fixed points with zero initial displacement; the others hold their own u0
    for (std::size_t i = 0; i < pc.size(); ++i) {
        bool moved = false;
        for (int d = 0; d < D; ++d) {
            sim.u.c[d][i] = pc.u[d][i];
            sim.v.c[d][i] = pc.v[d][i];
            moved = moved || pc.u[d][i] != 0;
        }
        if (!pc.fixed[i]) continue;
        if (!moved) held.push_back(static_cast<int>(i));
        else
            for (int d = 0; d < D; ++d)
                sim.boundary.prescribe({pd::Prescribed::Kind::displacement, {static_cast<int>(i)}, d,
                                        pd::TimeFunction::constant(pc.u[d][i])});
    }
    if (!held.empty()) sim.boundary.fix(held);
    pd::CriticalStretch damage;  // bond breaking, only with --s0
    damage.s0 = cfg.s0;
    if (pc.no_fail_count() > 0) damage.no_fail = pc.no_fail;
    if (cfg.s0 > 0) sim.scene.set_damage(damage);
    sim.start();
    auto thermal_target = [&](long n) { return heat ? long(std::floor(double(n) * cfg.dt / heat->dt * (1 + 1e-12))) : 0L; };
    const long thermal_total = thermal_target(cfg.steps);

    pd::io::CsvWriter energy(cfg.out / "energy.csv", {"step", "t_s", "kinetic_J", "strain_J", "external_work_J", "total_J"});
    std::unique_ptr<pd::io::PvdWriter> pvd;
    if (cfg.vtu_every > 0) pvd = std::make_unique<pd::io::PvdWriter>(cfg.out / "state.pvd");
    pd::Energies last;
    auto output = [&](long n) {  // energy rows every k steps and at the end; states on request
        const bool e_step = n % cfg.energy_every == 0 || n == cfg.steps, s_step = listed(cfg, n), v_step = vtu_step(cfg, n);
        if (!(e_step || s_step || v_step)) return;
        last = sim.check_energy();  // throws pd::Unstable before a blown-up state is written
        if (e_step) energy.row({n, sim.t, last.kinetic, last.strain, last.external_work, last.total()});
        if (!(s_step || v_step)) return;
        pd::io::StateFields<D> f{.u = &sim.u, .v = &sim.v};
        std::vector<double> phi;  // point damage [-]
        if (cfg.s0 > 0) {
            phi = pd::point_damage(bonds);
            f.damage = &phi;
        }
        if (heat) f.T = &heat->T, f.Q = &heat->heat_flow();
        if (s_step) pd::io::write_state<D>(cfg.out, n, pc, f);
        if (v_step) pd::io::write_state_vtu<D>(cfg.out, n, sim.t, pc, f, *pvd);
    };
    auto step = [&](long n) {
        sim.step(cfg.dt);
        if (heat)
            while (heat->step < thermal_target(n)) heat->advance(heat->step + 1 == thermal_total);
    };
    pd::io::Timer timer;
    const int status = step_loop(cfg.steps, step, output);
    if (status != 0) return status;
    std::printf("\n  step %ld  t = %.6g s  kinetic %.6g J  strain %.6g J  external work %.6g J  total %.6g J\n",
                cfg.steps, sim.t, last.kinetic, last.strain, last.external_work, last.total());
    if (cfg.s0 > 0) std::printf("  broken bonds %ld of %zu (ordered pairs)\n", sim.broken_bonds, bonds.size());
    if (heat) report_heat(*heat);
    std::printf("%s: done, %ld steps in %.3g s; wrote %s\n", program, cfg.steps, timer.seconds(), cfg.out.string().c_str());
    return 0;
}

}  // namespace pd_run
