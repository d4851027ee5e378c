// The PMB fracture run shared by the crack drivers (problems/2d: crack branching, Kalthoff-Winkler,
// grid orientation; problems/3d: crack branching): bond-based PMB with omega = 1 (spec/002 sec. 2.3;
// c = 9E/(pi delta^3 t) plane stress, 48E/(5 pi delta^3) plane strain, 12E/(pi delta^4) in 3D, i.e.
// the implied nu = 1/3, 1/4, 1/4), critical stretch s0 from Gc (spec/002 eq. 2.15a/b/c), velocity
// Verlet (verlet.hpp) with the given boundary, and damage phi (eq. 2.17) handed to a sampler every
// `every` steps and after the last; the loop is restartable (io/checkpoints.hpp). Rayleigh speed
// by Viktorov's approximation c_R = c_s (0.862 + 1.14 nu)/(1 + nu), c_s = sqrt(E / (2 (1 + nu) rho)).
// Also the CSV writers of the damage field and of the crack-path level curve (crack_metrics.hpp).
#pragma once
#include "problems/common/crack/crack_metrics.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/io/checkpoints.hpp"
#include "pd/io/csv.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/adaptive_refinement.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <malloc.h>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pd::crack {

struct Material2D {
    double E = 0;     // Young's modulus [Pa]
    double rho = 0;   // density [kg/m^3]
    double Gc = 0;    // fracture energy [J/m^2]
    Plane plane = Plane::stress;
    double nu() const { return plane == Plane::stress ? 1.0 / 3.0 : 0.25; }  // implied by 2D PMB
};

struct Material3D {
    double E = 0;     // Young's modulus [Pa]
    double rho = 0;   // density [kg/m^3]
    double Gc = 0;    // fracture energy [J/m^2]
    double nu() const { return 0.25; }  // implied by 3D PMB
};

// Rayleigh wave speed [m/s] (Viktorov's approximation, see header).
inline double rayleigh_speed(double E, double nu, double rho)
{
    return std::sqrt(E / (2 * (1 + nu) * rho)) * (0.862 + 1.14 * nu) / (1 + nu);
}

struct RunInfo {
    double s0 = 0, c = 0;          // critical stretch [-], micromodulus [N/m^6 per unit thickness]
    double dt = 0, dt_crit = 0;    // time step and Silling-Askari critical step [s]
    long steps = 0;
    long broken = 0;               // ordered bonds broken during the run
    double wall = 0;               // [s]
};

// PMB model, s0 and the critical step for the body (unit thickness) and bonds.
inline PMB make_pmb(const Material2D& mat, const Bonds& bonds, RunInfo& info)
{
    const PMB::Params p{.material = Elastic::from_E_nu(mat.E, mat.nu()), .dim = 2, .plane = mat.plane};
    PMB model(p, bonds);
    info.c = model.c;
    info.s0 = s0_pmb(mat.Gc, mat.E, bonds.delta, 2, mat.plane);
    info.dt_crit = critical_step_silling_askari(bonds, mat.rho, model.c).dt;
    return model;
}

// 3D: c = 18 K/(pi delta^4) = 12 E/(pi delta^4) at nu = 1/4 (spec/002 eq. 2.13a), s0 of eq. 2.15a.
inline PMB make_pmb(const Material3D& mat, const Bonds& bonds, RunInfo& info)
{
    const PMB::Params p{.material = Elastic::from_E_nu(mat.E, mat.nu()), .dim = 3};
    PMB model(p, bonds);
    info.c = model.c;
    info.s0 = s0_pmb(mat.Gc, mat.E, bonds.delta, 3, Plane::stress);
    info.dt_crit = critical_step_silling_askari(bonds, mat.rho, model.c).dt;
    return model;
}

// What run_fracture does besides integrating: nodes whose bonds never break, the progress line of
// core/timer.hpp on stderr (drivers pass !quick; it stays off in CI logs), and checkpoints of the
// loop (io/checkpoints.hpp) with the sampler's own state (what it has accumulated: tip histories,
// the last damage field), visited in both directions.
struct FractureOptions {
    NodeSet no_fail;
    bool show_progress = false;
    io::Checkpoints* checkpoints = nullptr;
    std::function<void(StateArchive&)> sampler_state;
};

// Integrates to t_end with steps dt <= min(dt_max, safety dt_crit) (equal steps); sample(t, phi, sim)
// at t = 0, every `every` steps and at the end. Unstable propagates (files written by the sampler
// stay on disk). Under --resume the loop continues from its checkpoint (the sampler is not called
// again for the samples it had taken).
template <int D, class Mat, class Sample>
RunInfo run_fracture(const Body<D>& body, Bonds& bonds, const Mat& mat, const Boundary<D>& boundary,
                     double dt_max, double safety, double t_end, long every, Sample&& sample, const FractureOptions& o = {})
{
    io::Timer timer;
    RunInfo info;
    if (!bonds.has_damage()) bonds.enable_damage();
    PMB model = make_pmb(mat, bonds, info);
    const double dt_bound = std::min(dt_max, safety * info.dt_crit);
    pd::require_steps(std::ceil(t_end / dt_bound * (1 - 1e-12)), "--t-end / dt");
    info.steps = static_cast<long>(std::ceil(t_end / dt_bound * (1 - 1e-12)));  // 1e-12: t_end a multiple of dt_bound
    info.dt = t_end / info.steps;
    CriticalStretch damage = CriticalStretch::uniform(info.s0);
    if (!o.no_fail.empty()) damage.protect(o.no_fail, body.size());
    Explicit<D, PMB> sim(body, bonds, model, mat.rho);
    sim.boundary = boundary;
    sim.scene.set_damage(damage);
    io::Checkpoints none;
    auto state = [&](StateArchive& ar) {
        sim.state(ar), timer.state(ar, "fracture.wall");
        if (o.sampler_state) o.sampler_state(ar);
    };
    const long energy_every = 100;  // stability guard cadence (steps)
    io::Progress progress("fracture run", info.steps, o.show_progress);
    auto start = [&] {
        sim.start();
        sample(sim.t, point_damage(bonds), sim);
    };
    (o.checkpoints ? *o.checkpoints : none).loop(info.steps, state, start, [&](long n) {
        sim.step(info.dt);
        progress.update(n);
        if (n % energy_every == 0) sim.check_energy();
        if (n % every == 0 || n == info.steps) sample(sim.t, point_damage(bonds), sim);
        return true;
    });
    info.broken = sim.broken_bonds;
    info.wall = timer.seconds();
    return info;
}
template <class Sample>
RunInfo run_fracture_2d(const Body<2>& body, Bonds& bonds, const Material2D& mat, const Boundary<2>& boundary,
                        double dt_max, double safety, double t_end, long every, Sample&& sample, const FractureOptions& o = {})
{
    return run_fracture<2>(body, bonds, mat, boundary, dt_max, safety, t_end, every, std::forward<Sample>(sample), o);
}

// The adaptive run (time/adaptive_refinement.hpp): the same PMB, s0 of each horizon from Gc (eq.
// 2.15), from the coarse grid of `grid`, with steps dt = min(dt_max, safety dt_fine) to t_end (equal
// steps; dt_fine: the Silling-Askari step of the coarse grid scaled by delta_finest / delta_0, as that
// step is proportional to the horizon at fixed m). sample(t, run) at t = 0,
// every `every` steps and at the end (run: the AdaptiveFracture, whose body, bonds and damage
// change). The step is checked against the current critical step after every grid update. No
// checkpoints (a grid that changes is not in the archive format).
struct AdaptiveInfo {
    RunInfo run;
    AdaptiveStats stats;
    std::size_t nodes_final = 0;
    long coarse_broken = 0;  // AdaptiveFracture::coarse_bonds_broken at the end
};
template <int D, class Mat, class Sample>
AdaptiveInfo run_fracture_adaptive(RefinedGrid<D> grid, AdaptiveScene<D> scene, const AdaptiveOptions& opt, const Mat& mat,
                                   double dt_max, double safety, double t_end, long every, Sample&& sample, bool show_progress)
{
    // Every grid update allocates the bond arrays anew (megabytes): served from the heap rather than by
    // fresh zeroed pages from the system, they cost no page faults (a third of the update time).
    mallopt(M_MMAP_THRESHOLD, 1 << 30), mallopt(M_TRIM_THRESHOLD, 1 << 30);
    io::Timer timer;
    AdaptiveInfo out;
    const double measure = grid.measure;
    scene.pmb = {.material = Elastic::from_E_nu(mat.E, mat.nu()), .dim = D, .measure = measure};
    if constexpr (D == 2) scene.pmb.plane = mat.plane;
    scene.rho = mat.rho;
    const Plane plane = scene.pmb.plane;
    scene.s0 = [&mat, plane](double delta) { return s0_pmb(mat.Gc, mat.E, delta, D, plane); };
    const double h0 = grid.h.at(0), delta0 = grid.delta.at(0), scale = std::pow(0.5, opt.levels);
    const double delta_fine = opt.rule == Refinement::delta ? delta0 * scale : opt.rule == Refinement::m ? delta0 : opt.m_level(opt.levels) * h0 * scale;
    AdaptiveFracture<D> run(std::move(grid), std::move(scene), opt);
    const double dt_target = std::min(dt_max, safety * run.critical_step() * delta_fine / delta0);
    pd::require_steps(std::ceil(t_end / dt_target * (1 - 1e-12)), "--t-end / dt");
    out.run.steps = static_cast<long>(std::ceil(t_end / dt_target * (1 - 1e-12)));
    out.run.dt = t_end / out.run.steps;
    out.run.dt_crit = run.critical_step();
    io::Progress progress("adaptive fracture run", out.run.steps, show_progress);
    sample(0.0, run);
    long updates = run.stats().updates;
    for (long n = 1; n <= out.run.steps; ++n) {
        run.step(out.run.dt);
        if (run.stats().updates != updates) {
            updates = run.stats().updates;
            out.run.dt_crit = std::min(out.run.dt_crit, run.critical_step());
            if (out.run.dt > run.critical_step())
                throw std::runtime_error("adaptive run: the time step " + std::to_string(out.run.dt) + " s exceeds the critical step " +
                                         std::to_string(run.critical_step()) + " s of the refined grid at step " + std::to_string(n) +
                                         " (lower --dt-factor)");
        }
        progress.update(n);
        if (n % 100 == 0) run.sim().check_energy();
        if (n % every == 0 || n == out.run.steps) sample(run.sim().t, run);
    }
    out.run.broken = run.broken_bonds();
    out.run.wall = timer.seconds();
    out.stats = run.stats();
    out.nodes_final = run.body().size();
    out.coarse_broken = run.coarse_bonds_broken();
    return out;
}

// Pre-crack as broken bonds (intact = 0 where cut(i, j), i.e. the bond crosses the crack), so
// that phi counts them (spec/002 sec. 3.5, seed 001: the 0.41 contour hugs the pre-crack); returns
// the number of ordered bonds broken. cut(i, j) must be symmetric (precrack.hpp evaluates (min, max) for both orders).
inline long break_bonds(Bonds& bonds, const std::function<bool(int, int)>& cut)
{
    if (!bonds.has_damage()) bonds.enable_damage();
    long n = 0;
    for (std::size_t i = 0; i < bonds.nodes(); ++i)
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k)
            if (bonds.intact[k] && cut(static_cast<int>(i), bonds.partner[k])) bonds.intact[k] = 0, ++n;
    return n;
}

// damage.csv: x_m, y_m, phi of the nodes with phi > 0 (the others are undamaged).
inline void write_damage_csv(const std::filesystem::path& path, const Field<2>& x, const std::vector<double>& phi)
{
    io::CsvWriter csv(path, {"x_m", "y_m", "phi"}, false);
    for (std::size_t i = 0; i < x.size(); ++i)
        if (phi[i] > 0) csv.row({x.c[0][i], x.c[1][i], phi[i]});
    csv.flush();
}

// crack_path.csv: the segments of the level curve phi = level on the node lattice (angle: its rotation).
inline std::size_t write_crack_path_csv(const std::filesystem::path& path, const Body<2>& body, const std::vector<double>& phi,
                                        double level = path_level, double angle = 0)
{
    const std::vector<Segment> segs = level_curve(lattice_scalar(body.x, phi, body.dx, angle), level);
    io::CsvWriter csv(path, {"x0_m", "y0_m", "x1_m", "y1_m"}, false);
    for (const Segment& s : segs) csv.row({s.a[0], s.a[1], s.b[0], s.b[1]});
    csv.flush();
    return segs.size();
}

}  // namespace pd::crack
