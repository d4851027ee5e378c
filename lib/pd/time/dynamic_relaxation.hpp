// Adaptive dynamic relaxation (ADR): the quasi-static balance f_int(u) + b = 0 (spec/000a
// sec. 3.5, eq. 3.26) solved matrix-free by damped fictitious dynamics (Kilic & Madenci 2010,
// "An adaptive dynamic relaxation method for quasi-static simulations using the peridynamic
// theory", Theor. Appl. Fract. Mech. 53, 194-204; Underwood 1983):
//   fictitious time step       dt = 1
//   diagonal density           lambda_ia >= 1/4 dt^2 sum_(j,b) |K_(ia)(jb)|   (K&M eq. 17, Gershgorin)
//   start-up                   v^{1/2} = dt F^0 / (2 lambda)                  (K&M eq. 14)
//   local stiffness            K^n_ia = -(F^n_ia - F^{n-1}_ia) / (lambda_ia dt v^{n-1/2}_ia)   (eq. 16)
//   damping (Rayleigh)         c_n = 2 sqrt(u^T K^n u / u^T u), 0 if negative  (eq. 15)
//   central difference         v^{n+1/2} = ((2 - c_n dt) v^{n-1/2} + 2 dt F^n / lambda) / (2 + c_n dt)
//                              u^{n+1} = u^n + dt v^{n+1/2}                   (eq. 13)
// with F = f_int + b on the free components; a prescribed displacement component is held at its
// value g(t_load) and is not integrated. The diagonal density is the Gershgorin row sum of the
// stiffness linearised at the reference configuration (stiffness_bound.hpp: exact row sums for
// PMB, triangle-inequality bounds for LPS, PALS and correspondence with its hourglass springs;
// the PMB formula with a stand-in micromodulus c for any other model) times `safety` (default
// 1.2: covers the geometric stiffness of finite stretches).
// Convergence: ||F V|| over the free components <= tol * force scale, the scale being the larger
// of ||b V|| (all components) and the reaction norm ||(f_int + b) V|| over the constrained ones
// (or a user value; ||f_int V|| when both are zero). A solve that reaches max_iter, or whose residual turns non-finite, returns
// converged = false with a message: never silently. Round-off floor: y = x + u is rounded at the
// scale of the coordinates, so a bond extension |Y| - |xi| carries an error ~ 1e-16 max|x| and the
// relative residual cannot go much below 1e-16 max|x| / (strain dx) (1D bar, 400 nodes, strain
// 5e-4: stalls at 4e-10); a tighter tol ends as not converged. Iterations grow ~ linearly with
// the nodes across the body per decade of residual (1D PMB to 1e-8: 365, 750, 1501, 2976
// iterations for 50, 100, 200, 400 nodes).
// Forces come from the scene (scene.hpp); a damage rule is refused (bonds breaking during the
// fictitious iterations have no meaning). A history model (HistoryModel) gets its trial state over
// load_step [s] (default 1: a pseudo time; only rate-dependent laws read it) from the committed
// history at every iteration; the caller commits after a converged solve.
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/bond_loop.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/rate_form.hpp"
#include "pd/models/stiffness_bound.hpp"  // the diagonal densities
#include "pd/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {

struct RelaxationResult {
    bool converged = false;
    long iterations = 0;                         // force evaluations after the initial one
    double residual = 0;                         // final ||F V||_free / force_scale [-]
    double force_scale = 0;                      // [N]
    std::vector<std::pair<long, double>> history;  // (iteration, relative residual) every history_every
    double wall_s = 0;                           // [s]
    std::string message;                         // why it stopped
};

template <int D, class Model>
class DynamicRelaxation {
public:
    Scene<D, Model> scene;     // forces (scene.hpp): body, bonds, model
    double safety = 1.2;       // lambda = safety * dt^2/4 * G (see header) [-]
    double load_step = 1;      // the step handed to a history model (header) [s]
    long history_every = 100;  // residual history stride [iterations]
    double force_scale = 0;    // [N]; > 0 overrides the automatic scale

    // Density from stiffness_bound(model, bonds, x) (PMB, LPS, PALS, correspondence).
    explicit DynamicRelaxation(const Scene<D, Model>& s) : DynamicRelaxation(s, stiffness_bound(s.model, s.bonds, s.body.x)) {}
    // Density from given Gershgorin row sums G [N/m^5 in 3D], e.g. stiffness_bound_micromodulus.
    DynamicRelaxation(const Scene<D, Model>& s, Field<D> row_sum) : scene(s), G_(std::move(row_sum))
    {
        if (G_.size() != body().size() || scene.bonds.nodes() != body().size())
            throw std::invalid_argument("DynamicRelaxation: body, bonds and stiffness bound sizes differ");
        reject_unwrapped_rate_form(scene.model, "DynamicRelaxation");
    }
    DynamicRelaxation(const Body<D>& body, Bonds& bonds, Model& model) : DynamicRelaxation(Scene<D, Model>(body, bonds, model)) {}
    DynamicRelaxation(const Body<D>& body, Bonds& bonds, Model& model, Field<D> row_sum)
        : DynamicRelaxation(Scene<D, Model>(body, bonds, model), std::move(row_sum)) {}

    // Relaxes u (in/out: the initial guess, e.g. the previous load level) to the equilibrium at
    // t_load: prescribed displacements g(t_load), body forces at t_load.
    RelaxationResult solve(Field<D>& u, const Boundary<D>& bc, double t_load, double tol, long max_iter)
    {
        if (!(tol > 0)) throw std::invalid_argument("DynamicRelaxation: tolerance must be positive");
        if (max_iter < 0) throw std::invalid_argument("DynamicRelaxation: max_iter must be >= 0");
        if (u.size() != body().size()) throw std::invalid_argument("DynamicRelaxation: displacement field size differs from the body");
        if (scene.has_damage_rule()) throw std::invalid_argument("DynamicRelaxation: no bond breaking during a solve (header)");
        const io::Timer timer;
        const std::size_t n = body().size();
        constexpr double dt = 1;  // fictitious time step (K&M: any value, lambda scales with dt^2)
        setup(u, bc, t_load);
        for (int d = 0; d < D; ++d) v_.c[d].assign(n, 0.0);
        RelaxationResult r;
        double res = evaluate(u, r);
        r.history.push_back({0, res});
        // Start-up, K&M eq. 14: v^{1/2} = dt F^0 / (2 lambda).
        for_free([&](int d, std::size_t i) { v_.c[d][i] = dt * F_.c[d][i] / (2 * lambda_.c[d][i]); });
        long it = 0;
        while (!(res <= tol) && std::isfinite(res) && it < max_iter) {
            for_free([&](int d, std::size_t i) { u.c[d][i] += dt * v_.c[d][i]; });  // eq. 13
            for (int d = 0; d < D; ++d) F_prev_.c[d] = F_.c[d];
            ++it;
            res = evaluate(u, r);
            if (history_every > 0 && it % history_every == 0) r.history.push_back({it, res});
            // Rayleigh quotient with the diagonal local stiffness (eqs. 15, 16).
            double num = 0, den = 0;
            for_free([&](int d, std::size_t i) {
                const double ud = u.c[d][i], vd = v_.c[d][i];
                den += ud * ud;
                if (vd != 0) num += ud * ud * (-(F_.c[d][i] - F_prev_.c[d][i]) / (lambda_.c[d][i] * dt * vd));
            });
            double c = (num > 0 && den > 0) ? 2 * std::sqrt(num / den) : 0.0;
            c = std::min(c, 2 / dt);  // c dt <= 2 keeps 2 - c dt >= 0: the old velocity is never reversed
            for_free([&](int d, std::size_t i) {  // eq. 13
                v_.c[d][i] = ((2 - c * dt) * v_.c[d][i] + 2 * dt * F_.c[d][i] / lambda_.c[d][i]) / (2 + c * dt);
            });
        }
        r.iterations = it;
        r.residual = res;
        r.converged = res <= tol;
        if (r.history.back().first != it) r.history.push_back({it, res});
        std::ostringstream msg;
        if (r.converged) msg << "converged";
        else if (!std::isfinite(res)) msg << "residual became non-finite at iteration " << it;
        else msg << "not converged in " << max_iter << " iterations (relative residual " << res << " > " << tol << ")";
        r.message = msg.str();
        r.wall_s = timer.seconds();
        return r;
    }

    // Load stepping: solves at each t in t_levels in order, warm-starting from the previous u.
    // Stops after the first level that does not converge (its result is the last one returned).
    std::vector<RelaxationResult> solve_steps(Field<D>& u, const Boundary<D>& bc, const std::vector<double>& t_levels,
                                              double tol, long max_iter)
    {
        std::vector<RelaxationResult> out;
        for (double t : t_levels) {
            out.push_back(solve(u, bc, t, tol, max_iter));
            if (!out.back().converged) break;
        }
        return out;
    }

    const Field<D>& density() const { return lambda_; }             // lambda [kg/m^3 per unit fictitious time^2]
    const Field<D>& internal_force_density() const { return f_; }  // f_int at the last iterate [N/m^3]
    // Reaction force [N] summed over the constrained components: -sum (f_int + b) V per component.
    Vec<D> reaction() const
    {
        Vec<D> R{};
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body().size(); ++i)
                if (constrained_[i * D + d]) R[d] -= (f_.c[d][i] + b_.c[d][i]) * body().volume[i];
        return R;
    }

private:
    Field<D> G_, lambda_, v_, F_, F_prev_, f_, b_;
    const Body<D>& body() const { return scene.body; }
    std::vector<std::uint8_t> constrained_;

    template <class Fn>
    void for_free(Fn&& fn) const
    {
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body().size(); ++i)
                if (!constrained_[i * D + d]) fn(d, i);
    }

    void setup(Field<D>& u, const Boundary<D>& bc, double t_load)
    {
        const std::size_t n = body().size();
        constrained_.assign(n * D, 0);
        for (const auto& p : bc.prescribed) {
            if (p.kind != Prescribed::Kind::displacement)
                throw std::invalid_argument("DynamicRelaxation: prescribed velocities have no quasi-static meaning; prescribe displacements");
            const double g = p.g(t_load);
            for (int i : p.nodes) {
                constrained_[i * D + p.component] = 1;
                u.c[p.component][i] = g;
            }
        }
        lambda_.resize(n);
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                // K&M eq. 17 with dt = 1; an unconnected node (G = 0) keeps unit density.
                const double g = safety * 0.25 * G_.c[d][i];
                lambda_.c[d][i] = g > 0 ? g : 1.0;
            }
        v_.resize(n);
        F_.resize(n);
        F_prev_.resize(n);
        b_.resize(n);
        bc.external(t_load, b_);
    }

    // F = f_int(x + u) + b on free components (0 on constrained ones); returns the relative residual.
    double evaluate(const Field<D>& u, RelaxationResult& r)
    {
        scene.internal_forces(u, u, load_step, f_);
        double rr = 0, bb = 0, reac = 0, ff = 0;
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body().size(); ++i) {
                const double V = body().volume[i];
                const double Fi = f_.c[d][i] + b_.c[d][i];
                bb += b_.c[d][i] * b_.c[d][i] * V * V;
                ff += f_.c[d][i] * f_.c[d][i] * V * V;
                if (constrained_[i * D + d]) {
                    F_.c[d][i] = 0;
                    reac += Fi * Fi * V * V;
                } else {
                    F_.c[d][i] = Fi;
                    rr += Fi * Fi * V * V;
                }
            }
        double scale = force_scale > 0 ? force_scale : std::sqrt(std::max(bb, reac));
        if (scale == 0) scale = std::sqrt(ff);  // unloaded and unconstrained: relative to ||f_int V||
        r.force_scale = scale;
        return scale > 0 ? std::sqrt(rr) / scale : 0.0;
    }
};

}  // namespace pd
