// Temperature-dependent conductivity k(theta) for the heat models (spec/000a
// sec. 3.9 for temperature-dependent properties). ConductivityOfTheta<Model> wraps a heat model built
// with unit conductivity (k = 1 W/(m K)) and scales it by k(theta) [W/(m K)], a Property
// (properties.hpp: constant, piecewise or table):
//   Agwai (bond-based)   q_ij = k_ij kappa_1(k=1) (theta_j - theta_i)/|xi|,
//                        k_ij = (k(theta_i) + k(theta_j)) / 2   (the mean of the end conductivities:
//                        symmetric in i, j, so the heat leaving i through the bond enters j and the
//                        total heat is conserved; one k evaluation per node and step, not per bond;
//                        it differs from k((theta_i + theta_j)/2) by O(k'' dtheta^2), second order
//                        like the model itself).
//   correspondence       q_i = k(theta_i) g_i (Fourier's law at the node's temperature), the
//                        suppression term of bond i-j with the same k_ij as Agwai.
// Q(theta) = A(s(theta)) theta with A the linear operator at frozen node factors s_i = k(theta_i):
// the implicit integrators iterate on it (Picard, conduction.hpp), CVODE uses it as its approximate
// Jacobian (heat_cvode.hpp). A material contrast: node factors f_i (optional) make node i's
// conductivity f_i k(theta_i), the same rules then hold with s_i = f_i k(theta_i) (the arithmetic bond
// mean keeps heat conserved across an interface); ConductivityContrast<Model> is the linear case, a
// constant k with node factors (a bimaterial body, problems/common/heat_stability_atlas.hpp). A
// constant k without factors never goes through this wrapper: with_conductivity() builds the plain
// model then, so constant-k scenes keep their code path and results bit for bit.
// Explicit Euler: thermal_critical_step_k() bounds the step with the largest k over a temperature
// range (by the maximum principle, [min, max] of the initial and held temperatures when there is no
// source), Property::max_over.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/heat/properties.hpp"
#include "pd/core/parallel.hpp"

#include <Eigen/Sparse>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

namespace pd {

// OfTheta = false: a constant k with node factors (ConductivityContrast), linear in theta (implicit
// Euler factorises once, CVODE's Jacobian is exact).
template <class Model, bool OfTheta>
struct ScaledConductivity {
    static constexpr bool has_point_pass = true;
    static constexpr bool nonlinear = OfTheta;  // Q is not linear in theta: implicit schemes iterate
    using Params = typename Model::Params;

    Model base;              // the model at k = 1 W/(m K)
    Property k;              // k(theta) [W/(m K)]
    std::vector<double> node_factor;  // f_i [-] (header); empty: 1 at every node
    std::vector<double> s;   // f_i k(theta_i) at the last point pass [W/(m K)]; 0 before the first one
                             // (ConductivityContrast: formed at construction)

    // params: the model's parameters (its k is ignored and set to 1); factors: f_i, one per node, or none.
    template <int D>
    ScaledConductivity(typename Model::Params params, Property k_of_theta, const Body<D>& body, const Bonds& b,
                       std::vector<double> factors = {})
        : base(unit(params), body, b), k(std::move(k_of_theta)), node_factor(std::move(factors)), s(b.nodes(), 0.0)
    {
        if (!node_factor.empty() && node_factor.size() != b.nodes())
            throw std::invalid_argument("conductivity: one conductivity factor per node");
        for (double f : node_factor)
            if (!(f > 0)) throw std::invalid_argument("conductivity: conductivity factors must be positive");
        if (!OfTheta && !k.is_constant()) throw std::invalid_argument("ConductivityContrast: k must be constant (else ConductivityOfTheta)");
        if (!OfTheta) point_pass(b, std::vector<double>(b.nodes(), 0.0));  // its conductivities, once
    }
    double factor(std::size_t i) const { return node_factor.empty() ? 1.0 : node_factor[i]; }
    bool follows_deformation() const
    {
        if constexpr (requires { base.follows_deformation(); }) return base.follows_deformation();
        else return false;
    }

    void point_pass(const Bonds& b, const std::vector<double>& theta)
    {
        parallel_for(b.nodes(), [&](std::size_t i) { s[i] = factor(i) * k(theta[i]); });
        if constexpr (Model::has_point_pass) base.point_pass_scaled(b, theta, [this](std::size_t i) { return s[i]; });
    }
    double bond_heat(std::size_t i, std::int64_t kb, int j, double dtheta) const
    {
        return base.bond_heat_scaled(i, kb, j, dtheta, 0.5 * (s[i] + s[j]));  // symmetric bond rule
    }

    // The linear operator at the conductivities of the last point pass (Q = A theta exactly there).
    void add_operator(const Bonds& b, std::vector<Eigen::Triplet<double>>& t) const
    {
        auto s_bond = [this](std::size_t i, int j) { return 0.5 * (s[i] + s[j]); };
        if constexpr (requires { base.add_operator_scaled(b, t, [](std::size_t) { return 1.0; }, s_bond); }) {
            base.add_operator_scaled(b, t, [this](std::size_t i) { return s[i]; }, s_bond);
        } else {
            add_bond_operator(b, t, [&](std::size_t i, std::int64_t kb) { return s_bond(i, b.partner[kb]) * base.coef[kb]; });
        }
    }

private:
    static typename Model::Params unit(typename Model::Params p)
    {
        p.k = 1;
        return p;
    }
};
template <class Model>
using ConductivityOfTheta = ScaledConductivity<Model, true>;
template <class Model>
using ConductivityContrast = ScaledConductivity<Model, false>;

// Calls f(model) with the plain model when k is constant (k(theta) = k(0) everywhere) and with
// ConductivityOfTheta<Model> otherwise: the choice is made once, outside every loop.
template <class Model, int D, class F>
decltype(auto) with_conductivity(typename Model::Params params, const Property& k, const Body<D>& body, const Bonds& b, F&& f)
{
    if (k.is_constant()) {
        params.k = k(0.0);
        Model m(params, body, b);
        return f(m);
    }
    ConductivityOfTheta<Model> m(params, k, body, b);
    return f(m);
}

// Explicit-Euler critical step [s] with k(theta) <= k_max on [theta_lo, theta_hi]: the Gershgorin
// bound of the operator with every conductivity set to k_max (times its node factor) (thermal_critical_step). For Agwai every
// entry of the operator grows with the conductivities, so the bound holds for any field in that range;
// for correspondence heat it is the bound of the k_max operator (an estimate for mixed conductivities).
// For a plain model it is thermal_critical_step. (thermal_critical_step on the wrapper itself uses the
// conductivities of the last point pass: the step re-evaluated at the current field.)
template <class Model>
double thermal_critical_step_k(const Model& model, const Bonds& b, const Conduction<Model>& c,
                               const std::vector<double>& theta, double theta_lo, double theta_hi)
{
    if constexpr (requires { model.k.max_over(theta_lo, theta_hi); }) {
        Model bound = model;
        const double k_max = model.k.max_over(theta_lo, theta_hi);
        for (std::size_t i = 0; i < bound.s.size(); ++i) bound.s[i] = model.factor(i) * k_max;
        return thermal_critical_step(bound, b, c, theta);
    } else {
        return thermal_critical_step(model, b, c, theta);
    }
}

}  // namespace pd
