// problems/common/stability_atlas.hpp -- one cell of the stability atlas (problems/3d/stability_atlas.cpp):
// a small free 3D body changed along one extreme axis, one model, and the largest stable step of
// velocity Verlet, each as a factor of the Silling-Askari step dt_SA with the PMB spring (spec/000a
// eq. 3.14, time/critical_step.hpp):
//   bound   critical_step_gershgorin of the model's stiffness bound (time/explicit_step.hpp):
//           stable on the body linearised at the reference, by Gershgorin's theorem;
//   mode    2 / omega_max by power iteration, and chosen, the project's default step (explicit_step);
//   linear  2 / omega_max, omega_max^2 the largest eigenvalue of M^-1/2 K_s M^-1/2, K_s the symmetric
//           part of the stiffness assembled by finite differences (common/analysis/stiffness_matrix.hpp),
//           M = rho V: von Neumann's limit of velocity Verlet on the linearised body where K is
//           symmetric (the positional forces of time/explicit_step.hpp; NaN for history and rate-form
//           models, whose force at given positions is not their elastic force). The asymmetry is
//           recorded: the hourglass force is no gradient, and with C_hg >= 1 the limit falls below this;
//   stable  measured: runs of `steps` steps from random velocities of amplitude strain sqrt(E/rho)
//           (1e-3: the linear regime), unstable when the energy guard of pd::Explicit fires
//           (mechanical energy above 10 x the initial, checked every 10 steps); factor 1 first, then
//           doubled or halved until the bracket closes, bisected to rel_tol (common/stability_sweep.hpp).
// Newmark (average acceleration, time/newmark.hpp; unconditionally stable on a linear body): instead of
// the bisection, a ladder of factors (1 ... 1000 dt_SA, common/stability_sweep.hpp), the largest one
// stable with every smaller one; a step whose Newton iterations fail ends the ladder too (unstable_step
// newton_failed: no energy growth, the step's equations were not solved). Only the
// models with a positional force (no history, linear law: Newmark's tangent is the elastic one).
// Axes (Scene): m = delta/dx; jitter (every coordinate moved by up to jitter dx); nu at fixed E;
// damage (that fraction of the pairs broken at random before the run, no breaking during it; dt_SA
// is the undamaged body's, as pd_run computes it before bonds break); gap (two neighbours moved to
// gap dx apart: a near-duplicate point); partial volumes of boundary bonds (pa-pdlammps); strain (the
// velocity amplitude: large motion, the nonlinear regime).
#pragma once
#include "pd/core/lattice.hpp"
#include "pd/core/timer.hpp"
#include "pd/io/options.hpp"
#include "pd/models/dissipative_registry.hpp"
#include "pd/models/stiffness_bound.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/explicit_step.hpp"
#include "pd/time/newmark.hpp"
#include "pd/time/verlet.hpp"
#include "problems/common/analysis/stiffness_matrix.hpp"
#include "problems/common/stability_sweep.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <string>

namespace pd::atlas {

// The body of a cell: an n^3 lattice, changed along one axis (header).
struct Scene {
    int n = 6;              // points per edge
    double dx = 1e-3;       // lattice spacing [m]
    double m = 3.05;        // delta / dx
    double jitter = 0;      // coordinate noise, fraction of dx
    double E = 200e9;       // Young's modulus [Pa]
    double nu = 0.3;        // Poisson's ratio
    double rho = 7800;      // density [kg/m^3]
    double damage = 0;      // fraction of the pairs broken
    double gap = 1;         // distance of the near-duplicate pair / dx (1: none)
    bool partial = false;   // partial volumes (pa-pdlammps)
    double strain = 1e-3;   // amplitude of the random initial velocities / sqrt(E/rho) [-]
};

// A model of the atlas: a choice of the registries, with a dissipation or none.
struct Variant {
    std::string label;
    ModelChoice choice;
    Dissipation dissipation{};
};

struct Cell {
    long nodes = 0, bonds = 0, broken = 0;  // bonds and broken: ordered pairs
    double dt_sa = 0;                  // Silling-Askari step of the undamaged body [s]
    double bound = NAN, linear = NAN;  // factors of dt_SA (header)
    int negative = -1;                 // unstable modes of the linearised body (-1: not assembled)
    double asymmetry = NAN;            // of its stiffness (Linearised)
    double growth = NAN;               // their growth rate [1/s]
    double chosen = 0;                 // the project's default step (explicit_step) [s]
    double mode = NAN;                 // 2 / omega_max by power iteration (highest_frequency), factor of dt_SA
    io::StabilityResult stable;        // the runs and the measured factor (threshold)
    double wall_s = 0;                 // the whole cell [s]
};

namespace detail {
// A uniform number in [0, 1) from the unordered pair (i, j): the same for both bonds of a pair.
inline double pair_uniform(int i, int j)
{
    std::uint64_t h = std::uint64_t(std::min(i, j)) * 1000003u + std::uint64_t(std::max(i, j));
    h ^= h >> 33, h *= 0xff51afd7ed558ccdULL, h ^= h >> 33, h *= 0xc4ceb9fe1a85ec53ULL, h ^= h >> 33;
    return double(h >> 11) * 0x1.0p-53;
}
}  // namespace detail

// The scene with one of the body's axes set (m, jitter, damage, gap, partial; the mechanical atlas
// adds nu and strain, the heat atlas its contrasts); any other axis leaves the scene as it is.
inline void set_body_axis(Scene& s, const std::string& axis, double value)
{
    if (axis == "m") s.m = value;
    else if (axis == "jitter") s.jitter = value;
    else if (axis == "damage") s.damage = value;
    else if (axis == "gap") s.gap = value;
    else if (axis == "partial") s.partial = value > 0;
}

// Refuses body-axis values that make no body (exit status 2 through Options::fail).
inline void check_body_axes(const io::Options& opt, std::map<std::string, std::vector<double>>& values)
{
    for (double m : values["m"]) if (m < 1) opt.fail("option --m-values: every ratio must be >= 1");
    for (double j : values["jitter"]) if (!(j < 0.5)) opt.fail("option --jitter-values: below 0.5 (points would cross)");
    for (double f : values["damage"]) if (!(f < 1)) opt.fail("option --damage-values: fractions below 1");
    for (double g : values["gap"]) if (!(g > 0 && g <= 1)) opt.fail("option --gap-values: in (0, 1]");
}

// The cell's body: lattice, jitter (seeded), and the near-duplicate pair (the point nearest the
// centre and its +x neighbour, moved to gap dx from it).
inline Body<3> body(const Scene& s)
{
    Body<3> b = box<3>({{0, 0, 0}}, {{s.n * s.dx, s.n * s.dx, s.n * s.dx}}, s.dx);
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> u(-s.jitter * s.dx, s.jitter * s.dx);
    if (s.jitter > 0)
        for (int d = 0; d < 3; ++d)
            for (double& x : b.x.c[d]) x += u(gen);
    if (s.gap < 1) {
        auto nearest = [&](const Vec<3>& p) {
            std::size_t best = 0;
            for (std::size_t i = 1; i < b.size(); ++i)
                if (norm(b.x[i] - p) < norm(b.x[best] - p)) best = i;
            return best;
        };
        const double c = 0.5 * s.n * s.dx;
        const std::size_t i = nearest(Vec<3>{{c, c, c}});
        const std::size_t j = nearest(b.x[i] + Vec<3>{{s.dx, 0, 0}});
        b.x.c[0][j] = b.x.c[0][i] + s.gap * s.dx;
        b.x.c[1][j] = b.x.c[1][i], b.x.c[2][j] = b.x.c[2][i];
    }
    return b;
}

// The families, with the broken pairs marked (damage > 0).
inline Bonds bonds(const Scene& s, const Body<3>& b)
{
    BondOptions opt;
    if (s.partial) opt.partial_volume = PartialVolume::pa_pdlammps;
    Bonds bd = build_bonds(b, s.m * s.dx, opt);
    if (s.damage > 0) {
        bd.enable_damage();
        for (std::size_t i = 0; i < bd.nodes(); ++i)
            for (std::int64_t k = bd.begin(i); k < bd.end(i); ++k)
                if (detail::pair_uniform(int(i), bd.partner[k]) < s.damage) bd.intact[k] = 0;
    }
    return bd;
}

// fn(model) with the variant's model on the cell's bonds, its per-node constants formed from the
// intact bonds (as a scene does after breaks).
template <class Fn>
decltype(auto) with_variant(const Variant& v, const Body<3>& b, Bonds& bd, Fn&& fn)
{
    auto ready = [&](auto& model) {
        if constexpr (BondDependentModel<std::decay_t<decltype(model)>>) model.recompute(bd);
        return fn(model);
    };
    if (v.dissipation.kind == Dissipation::Kind::none) return with_model(v.choice, b, bd, ready);
    return with_dissipative_model(v.choice, v.dissipation, b, bd, ready);
}

// The linearised body (header): 2 / omega_max [s], and its unstable modes: eigenvalues of
// M^-1/2 K_s M^-1/2 below -1e-6 omega_max^2 (a stiffness that is not positive semi-definite: the
// body is unstable at every step, growing as exp(sqrt(-lambda_min) t)).
struct Linearised {
    double limit = NAN;          // 2 / omega_max [s]
    double asymmetry = 0;        // ||K - K^T||_F / ||K||_F (hourglass forces are not a gradient)
    int negative = 0;            // eigenvalues below -1e-6 omega_max^2
    double growth = 0;           // sqrt(-lambda_min) where negative > 0 [1/s]
};
template <class Model>
Linearised linearised(Model& model, const Body<3>& b, const Bonds& bd, double rho)
{
    const Eigen::MatrixXd K = fd_stiffness(model, b, bd, 1e-6 * b.dx);
    Eigen::VectorXd w(K.rows());  // M^-1/2 = 1 / sqrt(rho V)
    for (Eigen::Index r = 0; r < K.rows(); ++r) w(r) = 1 / std::sqrt(rho * b.volume[r / 3]);
    const Eigen::MatrixXd S = w.asDiagonal() * (0.5 * (K + K.transpose())) * w.asDiagonal();
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
    Linearised r;
    r.limit = 2 / std::sqrt(lambda.maxCoeff());
    r.asymmetry = (K - K.transpose()).norm() / K.norm();
    for (double l : lambda) r.negative += l < -1e-6 * lambda.maxCoeff();
    if (r.negative > 0) r.growth = std::sqrt(-lambda.minCoeff());
    return r;
}

// v less the rigid-body motion of the body (equal density): the translation and the rotation
// omega = I^-1 L about the centre of mass. A random field's rotation would turn the body by radians
// over Newmark's long steps, a geometric nonlinearity of its own; the elastic modes stay.
inline void without_rigid_motion(const Body<3>& b, Field<3>& v)
{
    double mass = 0;
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), p = Eigen::Vector3d::Zero(), L = Eigen::Vector3d::Zero();
    auto x = [&](std::size_t i) { return Eigen::Vector3d(b.x.c[0][i], b.x.c[1][i], b.x.c[2][i]); };
    auto w = [&](std::size_t i) { return Eigen::Vector3d(v.c[0][i], v.c[1][i], v.c[2][i]); };
    for (std::size_t i = 0; i < b.size(); ++i) mass += b.volume[i], c += b.volume[i] * x(i), p += b.volume[i] * w(i);
    c /= mass, p /= mass;
    Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i < b.size(); ++i) {
        const Eigen::Vector3d r = x(i) - c;
        L += b.volume[i] * r.cross(w(i) - p);
        I += b.volume[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    }
    const Eigen::Vector3d omega = I.ldlt().solve(L);
    for (std::size_t i = 0; i < b.size(); ++i) {
        const Eigen::Vector3d u = w(i) - p - omega.cross(x(i) - c);
        for (int d = 0; d < 3; ++d) v.c[d][i] = u(d);
    }
}

enum class Integrator { verlet, newmark };
constexpr long newton_failed = -2;  // StabilityPoint::unstable_step of a Newmark run whose Newton iterations failed

// One run at dt = factor dt_SA (header): stable or not, the energy growth, the step of the guard.
template <class Sim>
io::StabilityPoint trial(Sim& sim, const Scene& s, double dt_sa, double factor, long steps)
{
    const double speed = s.strain * std::sqrt(s.E / s.rho);  // [m/s]
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> v(-speed, speed);
    for (int d = 0; d < 3; ++d)
        for (double& c : sim.v.c[d]) c = v(gen);
    without_rigid_motion(sim.scene.body, sim.v);
    sim.start();
    io::StabilityPoint p{factor, factor * dt_sa, dt_sa};
    double e_max = sim.initial_energy();
    auto track = [&](const Energies& e) { e_max = std::max(e_max, e.kinetic + e.strain); };
    try {
        if constexpr (requires { sim.advance(steps, factor * dt_sa, 10, track); }) {
            sim.advance(steps, factor * dt_sa, 10, track);
        } else {
            for (long n = 1; n <= steps; ++n) {
                sim.step(factor * dt_sa);
                if (n % 10 == 0) track(sim.check_energy());
            }
        }
    } catch (const Unstable& u) {
        p.stable = false;
        p.unstable_step = u.step;
    } catch (const std::runtime_error&) {  // Newmark: Newton did not converge within a step
        p.stable = false;
        p.unstable_step = newton_failed;
    }
    p.energy_growth = e_max / sim.initial_energy();
    return p;
}

// The whole cell (header); rel_tol of the bisection, linear: assemble the stiffness; ladder: Newmark's
// factors. A model Newmark cannot integrate gives a cell with no runs (c.stable.points empty).
inline Cell cell(const Variant& v, const Scene& s, long steps, double rel_tol, bool linear, Integrator integrator = Integrator::verlet,
                 const std::vector<double>& ladder = {})
{
    io::Timer timer;
    Cell c;
    const Body<3> b = body(s);
    Bonds bd = bonds(s, b);
    const Elastic mat = Elastic::from_E_nu(s.E, s.nu);
    c.nodes = long(b.size()), c.bonds = long(bd.size());
    if (bd.has_damage()) c.broken = long(std::count(bd.intact.begin(), bd.intact.end(), 0));
    // pd_run's estimate: the PMB spring of the material (times 1 + gamma_b for a standard linear solid)
    const double gamma = v.dissipation.kind == Dissipation::Kind::viscoelastic ? v.dissipation.gamma_b : 0.0;
    const double cm = PMB::micromodulus({.material = mat, .dim = 3}, bd.influence, bd.delta) * (1 + gamma);
    c.dt_sa = critical_step_silling_askari(bd, s.rho, cm).dt;
    Variant w = v;
    w.choice.material = mat;
    if (gamma > 0) w.dissipation.tau_b = 10 * c.dt_sa;  // slow against the step: the instantaneous moduli rule
    with_variant(w, b, bd, [&](auto& model) {
        c.bound = critical_step_gershgorin(stiffness_bound_of(model, bd, b.x), s.rho).dt / c.dt_sa;
        const ExplicitStep e = explicit_step(model, bd, b, s.rho, cm);
        c.chosen = e.dt, c.mode = e.mode_step / c.dt_sa;
        if (linear && force_is_positional(model)) {
            const Linearised l = linearised(model, b, bd, s.rho);
            c.linear = l.limit / c.dt_sa, c.negative = l.negative, c.growth = l.growth, c.asymmetry = l.asymmetry;
        }
        return 0;
    });
    auto run = [&](double f) {
        return with_variant(w, b, bd, [&](auto& model) {
            using Model = std::decay_t<decltype(model)>;
            if constexpr (!HistoryModel<Model, 3>) {
                if (integrator == Integrator::newmark) {
                    Newmark<3, Model> sim(b, bd, model, s.rho);
                    return trial(sim, s, c.dt_sa, f, steps);
                }
            }
            Explicit<3, Model> sim(b, bd, model, s.rho);
            return trial(sim, s, c.dt_sa, f, steps);
        });
    };
    if (integrator == Integrator::verlet) {
        c.stable = io::stability_sweep({1.0}, run, 64.0, rel_tol, 1.0 / 64);
    } else if (with_variant(w, b, bd, [](auto& model) { return !HistoryModel<std::decay_t<decltype(model)>, 3> && force_is_positional(model); })) {
        bool bracketed = false;
        c.stable = io::stability_ladder(ladder, run, bracketed);
    }
    c.wall_s = timer.seconds();
    return c;
}

}  // namespace pd::atlas
