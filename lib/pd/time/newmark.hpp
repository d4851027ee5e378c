// Implicit dynamics by the Newmark method with beta = 1/4, gamma = 1/2 (average acceleration,
// trapezoidal rule; spec/000a sec. 3.4, eq. 3.25):
//   u_{n+1} = u_n + dt v_n + dt^2/4 (a_n + a_{n+1}),  v_{n+1} = v_n + dt/2 (a_n + a_{n+1}),
// with a_{n+1} from the balance rho a_{n+1} = f(u_{n+1}) + b_{n+1}, solved by Newton iterations on
// the nodal residual r = (f + b - rho a_{n+1}) V over the free dofs, with a_{n+1} =
// 4/dt^2 (u_{n+1} - u_n - dt v_n) - a_n and the effective tangent K_eff = K + 4/dt^2 diag(rho V)
// (K of solve/tangent.hpp). Predictor u^0 = u_n + dt v_n + dt^2/2 a_n. Converged when
// ||r|| <= tol x max(||f V||, ||rho a V||, ||b V||, ||rho a_n V||, ||rho v_n V|| / dt) (free dofs;
// the terms of step n keep the scale finite when u and a cross zero together; 0 = 0 at rest).
// The factorisation of K_eff is kept across iterations and steps (modified Newton) while each
// iteration reduces the residual by reuse_ratio; otherwise (or when dt changes) it is rebuilt. A
// linear problem (1D bars: bonds do not rotate) is thus solved in one iteration per step with one
// factorisation for the whole run (two force evaluations per step: predictor and check).
// Unconditionally stable and, for a linear system, energy-conserving: the discrete energy
// 1/2 v^T M v + 1/2 u^T K u is exactly constant; the frequencies are lowered,
// omega_h dt = 2 atan(omega dt / 2) (period elongation; no numerical damping).
// Boundary and energy conventions as Explicit (verlet.hpp): a prescribed displacement component
// takes g(t_{n+1}), a prescribed velocity u_n + dt/2 (g(t_n) + g(t_{n+1})); constrained velocities
// follow the trapezoidal rule; energies and the guard (check_energy, Unstable) are the same. A step
// whose Newton iterations fail throws std::runtime_error with the reason (never silently).
// Forces come from the scene (scene.hpp), as in Explicit. No bond breaking: a scene with a damage
// rule is refused (a bond that breaks inside a step changes the tangent discontinuously; not needed
// by the elastic cases that use Newmark); no history models (the tangent is of the elastic model).
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/bond_loop.hpp"
#include "pd/models/rate_form.hpp"
#include "pd/solve/linear_solver.hpp"
#include "pd/solve/tangent.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace pd {

template <int D, class Model>
class Newmark {
    static_assert(!HistoryModel<Model, D>, "Newmark: no history models (header)");

public:
    Scene<D, Model> scene;            // forces (scene.hpp): body, bonds, model
    std::vector<double> rho;          // density per node [kg/m^3]
    Boundary<D> boundary;
    double energy_limit = 10;         // stability guard factor (verlet.hpp)
    double tol = 1e-10;               // relative residual of a step [-]
    int max_iter = 20;                // Newton iterations per step
    double reuse_ratio = 0.1;         // keep the factorisation while the residual falls this much
    LinearSolver linear = detail::is_ordinary<Model>() ? LinearSolver::cholesky : LinearSolver::lu;

    Field<D> u, v, a;                 // [m], [m/s], [m/s^2]
    double t = 0;                     // [s]
    long step_count = 0, iterations = 0, factorisations = 0;

    Newmark(const Scene<D, Model>& s, double density)
        : scene(s), rho(s.body.size(), density), u(s.body.size()), v(s.body.size()), a(s.body.size()), f_(s.body.size()), b_(s.body.size())
    {
        if (!(density > 0)) throw std::invalid_argument("density rho must be positive");
        reject_unwrapped_rate_form(s.model, "Newmark");
    }
    Newmark(const Body<D>& body, Bonds& bonds, Model& model, double density) : Newmark(Scene<D, Model>(body, bonds, model), density) {}

    // Call after initial u, v and the boundary are set: forces and accelerations at t.
    void start()
    {
        if (scene.has_damage_rule()) throw std::invalid_argument("Newmark: no bond breaking (header); use pd::Explicit with a damage rule");
        const std::size_t n = body().size();
        std::vector<std::uint8_t> constrained(n * D, 0);
        for (const auto& p : boundary.prescribed)
            for (int i : p.nodes) constrained[i * D + p.component] = 1;
        dofs_ = DofMap(constrained);
        scene.internal_forces(u, u, 0.0, f_);
        boundary.external(t, b_);
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) a.c[d][i] = free(i, d) ? (f_.c[d][i] + b_.c[d][i]) / rho[i] : 0.0;
        const Energies e = energies();
        initial_energy_ = e.kinetic + e.strain;
        double mass = 0;
        for (std::size_t i = 0; i < n; ++i) mass += rho[i] * body().volume[i];
        energy_floor_ = 0.5 * mass * roundoff_speed * roundoff_speed;
    }

    void step(double dt)
    {
        if (!(dt > 0)) throw std::invalid_argument("time step dt must be positive");
        if (dofs_.index.empty()) throw std::logic_error("Newmark: call start() before step()");
        const std::size_t n = body().size();
        const Field<D> u_n = u, v_n = v, a_n = a, f_n = f_, b_n = b_;
        const double kinetic_constrained_old = constrained_kinetic();
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) u.c[d][i] += dt * v.c[d][i] + 0.5 * dt * dt * a.c[d][i];  // predictor
        for (const auto& p : boundary.prescribed)
            for (int i : p.nodes)
                u.c[p.component][i] = p.kind == Prescribed::Kind::displacement
                                          ? p.g(t + dt)
                                          : u_n.c[p.component][i] + 0.5 * dt * (p.g(t) + p.g(t + dt));
        boundary.external(t + dt, b_);
        const double c = 4 / (dt * dt);  // [1/s^2]
        if (dt != dt_factor_) stale_ = true;
        double prev = INFINITY;
        for (int it = 0;; ++it) {
            const double res = residual(u_n, v_n, a_n, c, dt);
            if (!std::isfinite(res)) fail("residual became non-finite", it);
            if (res <= tol) break;
            if (it == max_iter) fail("Newton iterations did not converge (relative residual " + std::to_string(res) + ")", it);
            if (res > reuse_ratio * prev) stale_ = true;
            if (stale_) factorise(c, dt, u_n);
            Eigen::VectorXd du;
            std::string failure;
            if (!solver_.solve(r_, du, failure)) fail(failure, it);
            for (std::size_t i = 0; i < n; ++i)
                for (int d = 0; d < D; ++d)
                    if (const int q = dofs_.index[i * D + d]; q >= 0) u.c[d][i] += du[q];
            ++iterations;
            prev = res;
        }
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                a.c[d][i] = c * (u.c[d][i] - u_n.c[d][i] - dt * v_n.c[d][i]) - a_n.c[d][i];
                v.c[d][i] = v_n.c[d][i] + 0.5 * dt * (a_n.c[d][i] + a.c[d][i]);
            }
        t += dt;
        ++step_count;
        // External work: body forces on every node, reactions on constrained components (verlet.hpp).
        double work = 0;
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                const double du = u.c[d][i] - u_n.c[d][i];
                const double load = free(i, d) ? 0.5 * (b_.c[d][i] + b_n.c[d][i]) : -0.5 * (f_.c[d][i] + f_n.c[d][i]);
                work += load * du * body().volume[i];
            }
        external_work_ += work + constrained_kinetic() - kinetic_constrained_old;
    }

    Energies energies()  // call after start() or step(): the model's state is at y
    {
        return detail::body_energies(scene.model, scene.bonds, body(), scene.positions(), v, rho, external_work_);
    }

    // The guard of verlet.hpp: throws Unstable when KE + SE exceeds energy_limit x (initial + |W_ext|).
    Energies check_energy()
    {
        const Energies e = energies();
        const double mech = e.kinetic + e.strain;
        if (detail::energy_guard_tripped(e, energy_limit, initial_energy_, energy_floor_)) {
            std::ostringstream m;
            m << "unstable at step " << step_count << " (t = " << t << " s): mechanical energy " << mech << " J exceeds "
              << energy_limit << " x (initial + external work)";
            throw Unstable(m.str(), step_count, 0);
        }
        return e;
    }

    const Field<D>& internal_force_density() const { return f_; }
    double initial_energy() const { return initial_energy_; }

private:
    Field<D> f_, b_;
    DofMap dofs_;
    Colouring colouring_;
    SparseSolver solver_;
    Eigen::VectorXd r_;
    bool stale_ = true;
    double dt_factor_ = 0;  // dt of the current factorisation [s]
    double external_work_ = 0, initial_energy_ = 0, energy_floor_ = 0;  // [J]
    static constexpr double roundoff_speed = 1e-10;  // [m/s], as verlet.hpp

    bool free(std::size_t i, int d) const { return dofs_.index[i * D + d] >= 0; }
    const Body<D>& body() const { return scene.body; }

    // r = (f + b - rho a_{n+1}) V on the free dofs; relative residual (header).
    double residual(const Field<D>& u_n, const Field<D>& v_n, const Field<D>& a_n, double c, double dt)
    {
        scene.internal_forces(u_n, u, dt, f_);
        r_.setZero(dofs_.free);
        double rr = 0, ff = 0, ma = 0, bb = 0, mv = 0, man = 0;
        for (std::size_t i = 0; i < body().size(); ++i)
            for (int d = 0; d < D; ++d) {
                const int q = dofs_.index[i * D + d];
                if (q < 0) continue;
                const double V = body().volume[i];
                const double acc = c * (u.c[d][i] - u_n.c[d][i] - dt * v_n.c[d][i]) - a_n.c[d][i];
                r_[q] = (f_.c[d][i] + b_.c[d][i] - rho[i] * acc) * V;
                rr += r_[q] * r_[q];
                ff += f_.c[d][i] * f_.c[d][i] * V * V;
                ma += rho[i] * acc * rho[i] * acc * V * V;
                bb += b_.c[d][i] * b_.c[d][i] * V * V;
                mv += rho[i] * v_n.c[d][i] * rho[i] * v_n.c[d][i] * V * V;
                man += rho[i] * a_n.c[d][i] * rho[i] * a_n.c[d][i] * V * V;
            }
        const double scale = std::sqrt(std::max({ff, ma, bb, man, mv / (dt * dt)}));
        return scale > 0 ? std::sqrt(rr) / scale : 0.0;
    }

    // K_eff = K + c diag(rho V) at the current y (the step from u_n), factorised.
    void factorise(double c, double dt, const Field<D>& u_n)
    {
        if (colouring_.colour.empty() && !std::is_same_v<Model, PMB>) colouring_ = colour_bond_graph(scene.bonds, tangent_reach<Model>());
        Eigen::SparseMatrix<double> K = tangent(scene.model, body(), scene.bonds, scene.positions(), dofs_, colouring_);
        for (std::size_t i = 0; i < body().size(); ++i)
            for (int d = 0; d < D; ++d)
                if (const int q = dofs_.index[i * D + d]; q >= 0) K.coeffRef(q, q) += c * rho[i] * body().volume[i];
        std::string failure;
        if (!solver_.factorise(K, linear, 1e-12, 0, failure)) fail(failure, 0);
        scene.internal_forces(u_n, u, dt, f_);  // the finite-difference tangent leaves the model's state perturbed
        ++factorisations;
        stale_ = false;
        dt_factor_ = dt;
    }

    [[noreturn]] void fail(const std::string& why, int it) const
    {
        std::ostringstream m;
        m << "Newmark step " << step_count + 1 << " (t = " << t << " s), iteration " << it << ": " << why;
        throw std::runtime_error(m.str());
    }

    double constrained_kinetic() const  // [J]
    {
        return detail::constrained_kinetic(body(), v, rho, [&](std::size_t i, int d) { return !free(i, d); });
    }
};

}  // namespace pd
