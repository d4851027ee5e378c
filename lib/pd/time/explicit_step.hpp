// pd/time/explicit_step.hpp -- the explicit step the project chooses, from the highest natural frequency
// of the body linearised at its reference configuration (power iteration on its own force), and the
// step a stiffness bound guarantees.
//   A = M^-1 K, K v = -(f(x + eps v) - f(x)) / eps (force density per displacement), M = rho:
//   omega_max^2 = the largest eigenvalue of A. For a model whose force is the gradient of an energy,
//   A is self-adjoint in <a, b> = sum_i rho V_i a_i.b_i, and the Rayleigh quotient <v, A v> / <v, v>
//   of the power iterates rises to omega_max^2 from below (an estimate, not a bound).
//   Velocity Verlet is stable on the linearised body for dt < 2 / omega_max (spec/000a sec. 3.3.2).
// explicit_step: dt = safety x min(dt_SA, 2 / omega_max), dt_SA the Silling-Askari step with the PMB
// spring c (eq. 3.14, time/critical_step.hpp). On an undamaged body 2 / omega_max lies above dt_SA for
// every model of problems/3d/stability_atlas.cpp, so dt_SA sets the step as before; the mode step
// takes over where dt_SA cannot see the stiffness: correspondence families left with a few intact
// bonds (stiffer as K^-1 grows; 2 / omega_max = 0.24 dt_SA with 90 % of the pairs broken).
// Probed on the models whose force is a function of the positions alone (PMB, LPS, PALS, correspondence
// with the linear law); the others through the elastic model with their tangent (highest_frequency).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/stiffness_bound.hpp"
#include "pd/time/critical_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <type_traits>

namespace pd {

// Power iterations of highest_frequency: the Rayleigh quotient of the atlas' bodies is within 1 % of
// omega_max^2 after 30 (problems/3d/stability_atlas.cpp, column factor_mode against factor_linear).
inline constexpr int highest_mode_iterations = 60;

// The models whose force is a function of the positions alone (correspondence: with the linear law),
// which the power iteration probes directly.
template <class Model>
inline constexpr bool positional_force = std::is_same_v<Model, PMB> || std::is_same_v<Model, LPS> || std::is_same_v<Model, PALS> ||
                                         std::is_same_v<Model, Correspondence<2>> || std::is_same_v<Model, Correspondence<3>>;

// Whether this model's force at given positions is its elastic force (positional_force, and the linear
// law for correspondence): then the stiffness assembled from it is the one velocity Verlet sees.
template <class Model>
bool force_is_positional(const Model& model)
{
    if constexpr (requires { model.par.law; }) return positional_force<Model> && model.par.law == Model::Law::linear;
    else return positional_force<Model>;
}

namespace detail {
// Power iteration on a positional force (header).
template <int D, class Model>
double power_iteration(Model& model, const Bonds& b, const Body<D>& body, double rho, int iterations)
{
    const std::size_t n = body.size();
    const double eps = 1e-7 * b.delta;  // largest probe displacement [m]: linear to ~1e-7 relative
    Field<D> v(n), y = body.x, f0, f;
    internal_force(model, b, body.x, f0);
    std::mt19937 gen(5);
    std::normal_distribution<double> N01;
    for (int d = 0; d < D; ++d)
        for (double& c : v.c[d]) c = N01(gen);
    double lambda = 0;  // the largest Rayleigh quotient [1/s^2]
    for (int it = 0; it < iterations; ++it) {
        double norm2 = 0, vmax = 0;  // <v, v> / rho; max |v|
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) norm2 += body.volume[i] * v.c[d][i] * v.c[d][i], vmax = std::max(vmax, std::abs(v.c[d][i]));
        if (!(vmax > 0)) break;
        const double h = eps / vmax;
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) y.c[d][i] = body.x.c[d][i] + h * v.c[d][i];
        internal_force(model, b, y, f);
        double vAv = 0;  // <v, A v> / rho
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                const double Av = -(f.c[d][i] - f0.c[d][i]) / (h * rho);
                vAv += body.volume[i] * v.c[d][i] * Av;
                v.c[d][i] = Av / std::sqrt(norm2);
            }
        lambda = std::max(lambda, vAv / norm2);
    }
    return lambda > 0 ? std::sqrt(lambda) : std::numeric_limits<double>::quiet_NaN();
}
}  // namespace detail

// omega_max [rad/s] of the body linearised at x (header), rho [kg/m^3]. The model's per-node constants
// must belong to the bonds (recompute after breaks). Models without a positional force are probed
// through the elastic model with their tangent at the reference: correspondence with another law
// through its linear-law twin (the same tangent at F = I), an inelastic model through the elastic
// model it wraps (.lps, .pals, .model), a standard linear solid with its instantaneous moduli,
// omega^2 times 1 + gamma_b (conservative, as stiffness_bound_of).
template <int D, class Model>
double highest_frequency(Model& model, const Bonds& b, const Body<D>& body, double rho, int iterations = highest_mode_iterations)
{
    auto& e = elastic_part(model);  // models/stiffness_bound.hpp
    using E = std::decay_t<decltype(e)>;
    double omega = std::numeric_limits<double>::quiet_NaN();
    if constexpr (positional_force<E>) {
        if (force_is_positional(e)) omega = detail::power_iteration(e, b, body, rho, iterations);
        else if constexpr (requires { e.par.law; }) {  // correspondence with another law: its linear-law twin
            typename E::Params p = e.par;
            p.law = E::Law::linear;
            E twin(p, body, b);
            omega = detail::power_iteration(twin, b, body, rho, iterations);
        }
    }
    return std::sqrt(instantaneous_stiffness_factor(model)) * omega;
}

// Critical step of velocity Verlet from a bound G [N/m^4 per m in 3D]: by Gershgorin every
// eigenvalue omega^2 of M^-1 K lies below max_ia G_ia / rho, and velocity Verlet is stable for
// omega dt < 2 (spec/000a sec. 3.3.2), so dt = 2 min_ia sqrt(rho / G_ia) is stable on the body
// linearised at the reference; the node is the one that sets it.
template <int D>
CriticalStep critical_step_gershgorin(const Field<D>& G, double rho)
{
    CriticalStep r{std::numeric_limits<double>::infinity(), -1};
    for (std::size_t i = 0; i < G.size(); ++i)
        for (int d = 0; d < D; ++d)
            if (G.c[d][i] > 0 && 2 * std::sqrt(rho / G.c[d][i]) < r.dt) r = {2 * std::sqrt(rho / G.c[d][i]), static_cast<int>(i)};
    return r;
}

// The explicit step the project chooses (header).
struct ExplicitStep {
    double dt = 0;                // safety x min(dt_SA, 2 / omega_max) [s]
    CriticalStep silling_askari;  // dt_SA and the node that sets it
    double mode_step = std::numeric_limits<double>::quiet_NaN();  // 2 / omega_max [s] (NaN: not estimated)
    bool mode_limits = false;     // the mode step, not dt_SA, set dt
};

// c: the micromodulus of the Silling-Askari spring c omega V / |xi| [N/m^6 in 3D]; rho [kg/m^3].
template <int D, class Model>
ExplicitStep explicit_step(Model& model, const Bonds& b, const Body<D>& body, double rho, double c, double safety = silling_askari_safety)
{
    ExplicitStep s;
    s.silling_askari = critical_step_silling_askari(b, rho, c);
    s.mode_step = 2 / highest_frequency(model, b, body, rho);
    s.mode_limits = s.mode_step < s.silling_askari.dt;
    s.dt = safety * (s.mode_limits ? s.mode_step : s.silling_askari.dt);
    return s;
}

}  // namespace pd
