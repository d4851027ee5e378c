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
#include "pd/models/dissipative_registry.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/explicit_step.hpp"
#include "pd/time/verlet.hpp"
#include "pd_run_checkpoint.hpp"
#include "pd_run_conventions.hpp"
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
constexpr double dt_safety = pd::silling_askari_safety;  // Silling & Askari's normal safety factor (spec/000a sec. 3.3.2)

struct Run {
    std::string model;
    double hourglass = 0;  // C_hg [-]
    Conventions conventions;  // ours or Peridigm's, per choice (pd_run_conventions.hpp)
    pd::SurfaceCorrectionMethod surface = pd::SurfaceCorrectionMethod::none;
    pd::Elastic material;
    pd::Plane plane = pd::Plane::stress;
    double measure = 1, rho = 0, delta = 0, dx = 0;  // [m^(3-D)], [kg/m^3], [m], [m] (0: no lattice)
    pd::Influence influence;
    pd::PartialVolume partial_volume = pd::PartialVolume::none;
    double dt = 0;                                     // [s]; NaN = automatic
    long steps = 0, energy_every = 1, vtu_every = 0;
    double s0 = 0;                                     // critical stretch [-]; 0 = no bond breaking
    pd::Dissipation dissipation;                       // plasticity or a standard linear solid (pd_run_dissipation.hpp)
    long nsync_mh = 1;                                 // mechanical steps between releases of the dissipated heat
    std::vector<long> output_steps;                    // sorted, unique
    std::filesystem::path out;
    bool mechanics = true;                             // false: heat only
    HeatSettings heat;                         // heat.model "none": no temperature field
    Checkpoints checkpoints;                           // --checkpoint-every, --restart (pd_run_checkpoint.hpp)
};

[[noreturn]] inline void fail(const std::string& msg) { pd::io::fail_input(program, msg); }

// 5. The step loop of both modes, from the checkpoint's step (0 for a new run) to `steps`: step(n)
// advances to step n, output(n) writes what step n asks for, state(ar) visits the run's checkpoint
// state (pd_run_checkpoint.hpp), written every cp.every steps and when a stop signal arrived.
// Returns the exit status: 3 when pd::Unstable stops the run (the files written so far stay),
// 128 + the signal's number after a stop signal (the checkpoint and the CSV files written); 3 also
// when a solver (CVODE) cannot continue.
template <class Step, class Output, class State>
int step_loop(const Checkpoints& cp, long steps, Step&& step, Output&& output, State&& state)
{
    pd::io::Progress progress(program, steps, true);
    try {
        if (!cp.restart) output(0);
        for (long n = cp.first + 1; n <= steps; ++n) {
            step(n);
            output(n);
            progress.update(n);
            const int signal = stop_signal;
            if (cp.possible && ((cp.every > 0 && n % cp.every == 0) || signal != 0)) cp.write(n, state);
            if (signal != 0) {
                progress.finish();
                std::cerr << program << ": stopped by " << (signal == SIGINT ? "SIGINT" : "SIGTERM") << " after step " << n
                          << (cp.possible ? "; checkpoint " + cp.file.string() + " (continue with --restart " + cp.file.string() + ")"
                                          : "; no checkpoint with --thermal-integrator cvode")
                          << std::endl;
                return 128 + signal;
            }
        }
    } catch (const pd::Unstable& e) {
        progress.finish();
        std::cerr << program << ": " << e.what() << std::endl;
        return 3;
    } catch (const pd::SolverFailure& e) {  // CVODE could not continue the heat run
        progress.finish();
        std::cerr << program << ": " << e.what() << std::endl;
        return 3;
    }
    progress.finish();
    return 0;
}

inline bool listed(const Run& cfg, long n) { return std::binary_search(cfg.output_steps.begin(), cfg.output_steps.end(), n); }
inline bool vtu_step(const Run& cfg, long n) { return cfg.vtu_every > 0 && (n % cfg.vtu_every == 0 || n == cfg.steps); }

// The VTU snapshots and their .pvd series; a restart re-lists the snapshots written before it.
class VtuSeries {
public:
    explicit VtuSeries(const Run& cfg) : out_(cfg.out), every_(cfg.vtu_every), last_(cfg.steps), relist_(cfg.checkpoints.same_folder)
    {
        if (cfg.vtu_every > 0) pvd_ = std::make_unique<pd::io::PvdWriter>(cfg.out / "state.pvd");
    }
    template <int D>
    void write(long n, double t, const pd::io::PointCloud& pc, const pd::io::StateFields<D>& f)
    {
        pd::io::write_state_vtu<D>(out_, n, t, pc, f, *pvd_);
        steps_.push_back(double(n)), times_.push_back(t);
    }
    void state(pd::StateArchive& ar)
    {
        ar("pd_run.vtu_steps", steps_), ar("pd_run.vtu_times", times_);
        if (ar.saving() || !pvd_) return;
        std::vector<double> steps, times;  // the earlier snapshots are listed where their files are
        for (std::size_t q = 0; q < steps_.size() && relist_; ++q)
            if (on_cadence(step_number(steps_[q]), every_, last_)) {
                pvd_->add(times_[q], pd::io::step_file(out_, long(steps_[q]), "vtu"));
                steps.push_back(steps_[q]), times.push_back(times_[q]);
            }
        steps_ = steps, times_ = times;
    }

private:
    std::filesystem::path out_;
    long every_, last_;
    bool relist_;
    std::unique_ptr<pd::io::PvdWriter> pvd_;
    std::vector<double> steps_, times_;  // of the snapshots written (steps as numbers)
};

inline void report_heat(HeatRun& heat)
{
    const pd::TemperatureField& f = heat.field();
    const auto [lo, hi] = std::minmax_element(f.theta.begin(), f.theta.end());
    std::printf("  thermal step %ld  t = %.6g s  T in [%.6g, %.6g]\n", f.step, f.t(), *lo, *hi);
}

// 4.-5. Heat only (--mechanics off): the steps are thermal steps.
template <int D>
int integrate_heat(const Run& cfg, const pd::io::PointCloud& pc, HeatRun& heat)
{
    VtuSeries vtu(cfg);
    auto output = [&](long n) {
        if (!listed(cfg, n) && !vtu_step(cfg, n)) return;
        const pd::io::StateFields<D> f{.T = &heat.T(), .Q = &heat.field().heat_flow()};
        if (listed(cfg, n)) pd::io::write_state<D>(cfg.out, n, pc, f);
        if (vtu_step(cfg, n)) vtu.write<D>(n, heat.field().t(), pc, f);
    };
    auto state = [&](pd::StateArchive& ar) {
        heat.field().state(ar);
        heat.log_state(ar);
        vtu.state(ar);
    };
    heat.last_step = cfg.steps;
    if (cfg.checkpoints.restart) state(*cfg.checkpoints.restart);
    pd::io::Timer timer;
    const int status = step_loop(cfg.checkpoints, cfg.steps, [&](long) { heat.field().advance(); }, output, state);
    if (status != 0) return status;
    report_heat(heat);
    std::printf("%s: done, %ld thermal steps in %.3g s; wrote %s\n", program, cfg.steps, timer.seconds(), cfg.out.string().c_str());
    return 0;
}

// The mechanical step (pd/time/explicit_step.hpp): without --dt, dt_safety x the smaller of the
// Silling-Askari step with the PMB micromodulus c and 2 / omega_max of the model's body; printed with
// the reason, and a given --dt compared with it. Then the heat follows the step (--nsync-mk).
template <int D, class Model>
void choose_step(Run& cfg, Model& model, const pd::Bonds& bonds, const pd::Body<D>& body, double c, HeatRun* heat)
{
    const pd::ExplicitStep s = pd::explicit_step(model, bonds, body, cfg.rho, c, dt_safety);
    const double crit = s.mode_limits ? s.mode_step : s.silling_askari.dt;  // [s]
    if (std::isnan(cfg.dt)) {
        cfg.dt = s.dt;
        if (s.mode_limits)
            std::printf("dt = %.17g s (%.2g x 2/omega_max = %.6g s of the body's highest mode, below the Silling-Askari critical step "
                        "%.6g s at node %d)\n", cfg.dt, dt_safety, s.mode_step, s.silling_askari.dt, s.silling_askari.node);
        else
            std::printf("dt = %.17g s (%.2g x Silling-Askari critical step %.6g s at node %d; highest mode 2/omega_max = %.6g s)\n", cfg.dt,
                        dt_safety, s.silling_askari.dt, s.silling_askari.node, s.mode_step);
    } else {
        std::printf("dt = %.17g s (given; critical step %.6g s, ratio %.3g)\n", cfg.dt, crit, cfg.dt / crit);
        if (cfg.dt > crit) std::printf("warning: --dt exceeds the critical step; the run may go unstable\n");
    }
    if (heat && cfg.heat.nsync_mk > 0) heat->follow_mechanics(cfg.heat.nsync_mk, cfg.dt);
    std::fflush(stdout);
}

// Damage during a run (--s0): choose_step sees the intact body, and a damaged correspondence body's
// highest mode can be several times faster (reports/3d/stability_atlas.md). Each time another
// recheck_fraction of the bonds has broken, 2/omega_max of the body with its bonds as they are (a copy
// of the run's model, linearised at the reference: pd::highest_frequency) is estimated again; a step
// above dt_safety x that is reported with the step number. The run goes on (its energy guard stops it
// if it blows up); the fix is a smaller --dt.
constexpr double recheck_fraction = 0.05;
struct DamageStepWatch {
    long next = -1;    // broken bonds at which to look again (-1: the first look not yet due)
    int warnings = 0;  // looks that found dt too large
    template <int D, class Model>
    void look(long n, long broken, double dt, const Model& model, const pd::Bonds& bonds, const pd::Body<D>& body, double rho)
    {
        const long every = std::max(1L, static_cast<long>(recheck_fraction * double(bonds.size())));
        if (next < 0) next = every;
        if (broken < next) return;
        next = broken + every;
        Model probe = model;  // the run's model keeps its point-pass state for the energies of step n
        const double omega = pd::highest_frequency(probe, bonds, body, rho);  // [1/s]; 0: no bond left
        if (!(omega > 0)) return;
        const double allowed = dt_safety * 2 / omega;
        if (dt <= allowed) return;
        ++warnings;
        std::printf("warning: step %ld, %ld of %zu bonds broken: the damaged body's highest mode allows dt = %.6g s (%.2g x 2/omega_max); "
                    "dt = %.6g s is %.3g x that (a smaller --dt is safer)\n", n, broken, bonds.size(), allowed, dt_safety, dt, dt / allowed);
        std::fflush(stdout);
    }
};

// 4.-5. Mechanics, with the heat run (if any) as the scene's heat component (pd/scene.hpp): before
// the forces of mechanical step n it takes the thermal steps m with m dt_thermal <= n dt (relative
// slack 1e-12 for round-off; pd/heat/temperature_field.hpp).
template <int D, class Model>
int integrate(const Run& cfg, const pd::io::PointCloud& pc, const pd::Body<D>& body, pd::Bonds& bonds, Model& model,
              HeatRun* heat)
{
    attach_thermal_expansion(model, cfg.heat, heat, cfg.model, fail);
    if constexpr (requires { model.pts.set_temperature_field(nullptr); })  // Johnson-Cook softening reads the run's temperatures
        if (heat) model.pts.set_temperature_field(&heat->T());
    pd::Explicit<D, Model> sim(body, bonds, model, cfg.rho);
    sim.energy_books = true;  // hourglass work and the energy released by broken bonds (pd/time/verlet.hpp)
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
    if constexpr (requires { model.thermal_expansion(); }) damage.thermal = model.thermal_expansion();
    if (cfg.s0 > 0) sim.scene.set_damage(damage);
    sim.scene.rate_pairing = {.end_of_step = cfg.conventions.end_of_step,
                              .initial_velocity_step = cfg.conventions.initial_velocity ? cfg.dt : 0.0};
    if (heat) {
        sim.scene.set_heat(heat->field(), cfg.nsync_mh);
        heat->last_step = heat->field().due(cfg.steps, cfg.dt);
    }

    // energy.csv, the books of pd::Energies; a dissipative model adds the heat its dissipation generated
    // since step 0, released or not.
    std::vector<std::string> columns{"step",           "t_s",          "kinetic_J",          "strain_J",         "external_work_J",
                                     "total_J",        "hourglass_work_J", "dissipated_J", "damage_released_J", "balance_error_J"};
    constexpr bool dissipative = pd::DissipativeModel<Model>;
    if (dissipative) columns.push_back("dissipated_heat_J");
    const std::size_t width = columns.size();
    pd::io::CsvWriter energy(cfg.out / "energy.csv", columns);
    std::vector<double> energy_rows;  // the rows of energy.csv, for the checkpoint (width per row)
    auto energy_row = [&](const std::vector<double>& r) {
        std::vector<pd::io::CsvCell> cells{static_cast<long>(r[0])};
        cells.insert(cells.end(), r.begin() + 1, r.end());
        energy.row(cells);
        energy_rows.insert(energy_rows.end(), r.begin(), r.end());
    };
    double dissipated = 0;  // [J]
    auto add_step_heat = [&] {  // after each committed step (pd/scene.hpp: what e_abs accumulates)
        if constexpr (dissipative)
            for (std::size_t i = 0; i < body.size(); ++i) dissipated += model.step_heat(i) * body.volume[i];
    };
    VtuSeries vtu(cfg);
    auto state = [&](pd::StateArchive& ar) {  // the run's part of a checkpoint
        sim.state(ar);
        std::vector<double> rows = ar.saving() ? energy_rows : std::vector<double>{};
        ar("pd_run.energy_rows", rows), ar("pd_run.dissipated_heat", dissipated);
        if (!ar.saving())
            for (std::size_t q = 0; q + width <= rows.size(); q += width)
                if (on_cadence(step_number(rows[q]), cfg.energy_every, cfg.steps)) energy_row({rows.begin() + q, rows.begin() + q + width});
        vtu.state(ar);
        if (heat) heat->log_state(ar);  // the field itself is the scene's
    };
    pd::Energies last;
    if (cfg.checkpoints.restart) state(*cfg.checkpoints.restart), last = sim.energies();
    else sim.start(), add_step_heat();
    auto output = [&](long n) {  // energy rows every k steps and at the end; states on request
        const bool e_step = n % cfg.energy_every == 0 || n == cfg.steps, s_step = listed(cfg, n), v_step = vtu_step(cfg, n);
        if (!(e_step || s_step || v_step)) return;
        last = sim.check_energy();  // throws pd::Unstable before a blown-up state is written
        if (e_step) {
            std::vector<double> r{double(n),        sim.t,           last.kinetic,           last.strain,  last.external_work,
                                  last.total(),     last.hourglass_work, last.dissipated, last.damage_released, last.balance};
            if (dissipative) r.push_back(dissipated);
            energy_row(r);
        }
        if (!(s_step || v_step)) return;
        pd::io::StateFields<D> f{.u = &sim.u, .v = &sim.v};
        std::vector<double> phi;  // point damage [-]
        if (cfg.s0 > 0) {
            phi = pd::point_damage(bonds);
            f.damage = &phi;
        }
        if (heat) f.T = &heat->T(), f.Q = &heat->field().heat_flow();
        if constexpr (requires { model.pts.ep; }) f.ep = &model.pts.ep;
        if (s_step) pd::io::write_state<D>(cfg.out, n, pc, f);
        if (v_step) vtu.write<D>(n, sim.t, pc, f);
    };
    DamageStepWatch watch;
    auto step = [&](long n) {
        if constexpr (pd::DissipativeModel<Model>)  // the heat released in step n raises the heat guard's ceiling
            if (heat && cfg.nsync_mh > 0 && n % cfg.nsync_mh == 0) {
                const std::vector<double>& e = sim.scene.accumulated_heat();
                heat->allow_rise(*std::max_element(e.begin(), e.end()) / cfg.heat.rho_cv);
            }
        sim.step(cfg.dt);
        add_step_heat();
        if (cfg.s0 > 0) watch.look(n, sim.broken_bonds, cfg.dt, model, bonds, body, cfg.rho);
    };
    pd::io::Timer timer;
    const int status = step_loop(cfg.checkpoints, cfg.steps, step, output, state);
    if (status != 0) return status;
    std::printf("\n  step %ld  t = %.6g s  kinetic %.6g J  strain %.6g J  external work %.6g J  total %.6g J  balance error %.3g J\n",
                cfg.steps, sim.t, last.kinetic, last.strain, last.external_work, last.total(), last.balance);
    if (cfg.s0 > 0)
        std::printf("  broken bonds %ld of %zu (ordered pairs); dt above the damaged body's step at %d of the rechecks every %.0f %% of the bonds\n",
                    sim.broken_bonds, bonds.size(), watch.warnings, 100 * recheck_fraction);
    if (heat) report_heat(*heat);
    std::printf("%s: done, %ld steps in %.3g s; wrote %s\n", program, cfg.steps, timer.seconds(), cfg.out.string().c_str());
    return 0;
}

}  // namespace pd_run
