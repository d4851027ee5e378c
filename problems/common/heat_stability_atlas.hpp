// problems/common/heat_stability_atlas.hpp -- one cell of the heat stability atlas
// (problems/3d/heat_stability_atlas.cpp): the free cube of the mechanical atlas (stability_atlas.hpp:
// lattice, jitter, near-duplicate pair, partial volumes, broken pairs), adiabatic, with a heat model
// and a heat integrator, changed along one axis; steps as factors of the project's thermal step estimate
// dt_G = thermal_critical_step (heat/conduction.hpp: min_i rho c_i / g_i, g_i half the absolute row sum
// of the heat operator A, the Gershgorin bound; pd_run takes 0.5 dt_G):
//   linear  explicit Euler's exact limit on the assembled operator: theta' = B theta, B = diag(rho c)^-1 A,
//           stable while |1 + dt lambda| <= 1 for every eigenvalue lambda of B, i.e. dt <= min over
//           lambda != 0 of -2 Re(lambda) / |lambda|^2 (2 / |lambda_max| where B is similar to a symmetric
//           matrix: Agwai); an eigenvalue with Re > 0 (growing) makes the body unstable at every step;
//   stable  measured: runs of `steps` steps from random temperatures (T0 +- 1 K), unstable when a
//           temperature leaves the initial range widened by 10 x its width (pd_run's heat guard) or is
//           not finite. Explicit Euler: bisection as the mechanical atlas (common/stability_sweep.hpp);
//           implicit Euler and CVODE BDF (unconditionally stable schemes): a ladder of factors 1 ... 1e4,
//           the largest one stable with every smaller one (the search does not go further);
//   overshoot  the largest excursion of a temperature beyond the initial range, over its width, in a
//           run at the default step 0.5 dt_G (`steps` long) and over all stable runs of the cell: 0
//           where the discrete scheme keeps the maximum principle (A an M-matrix, as Agwai's: implicit
//           Euler at every step, explicit Euler while dt <= rho c_i / |A_ii|, for Agwai dt_G itself).
// Axes beyond the mechanical atlas': a conductivity contrast (ConductivityContrast,
// heat/conductivity.hpp, on the half x > L/2: the bonds crossing the interface conduct with the mean)
// and a heat-capacity contrast (rho c of that half), each from 1 to 1e6; the correspondence
// suppression coefficient C_hg.
#pragma once
#include "pd/heat/agwai.hpp"
#include "pd/heat/conductivity.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/time/heat_cvode.hpp"
#include "problems/common/stability_atlas.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace pd::atlas {

struct HeatScene {
    Scene geometry;             // n, dx, m, jitter, gap, partial, damage of the mechanical atlas
    double k = 16;              // conductivity [W/(m K)] (316L near room temperature)
    double rho_c = 3.9e6;       // volumetric heat capacity [J/(m^3 K)] (7800 kg/m^3 x 500 J/(kg K))
    double k_contrast = 1;      // k of the half x > L/2 over k of the other half [-]
    double c_contrast = 1;      // rho c of that half over the other's [-]
};

struct HeatVariant {
    std::string label;
    std::string model;  // agwai | correspondence
    double C_hg = 0;    // suppression coefficient (correspondence)
};

struct HeatCell {
    long nodes = 0, bonds = 0, broken = 0;  // bonds and broken: ordered pairs
    double dt_est = 0;                      // thermal_critical_step [s] (header)
    double linear = NAN;                    // explicit Euler's exact limit / dt_est (header)
    int growing = 0;                        // eigenvalues of B with Re > 1e-9 |lambda_max|
    double complexity = 0;                  // max |Im lambda| / |lambda_max| (0: a symmetrisable operator)
    io::StabilityResult stable;             // the runs and the measured factor
    bool bracketed = false;                 // an unstable run was found (false: stable up to the ladder's top)
    double overshoot_default = 0;           // header: the run at 0.5 dt_est
    double overshoot = 0;                   // header: over the stable runs
    double wall_s = 0;
};

// The half of the cube beyond x = L/2, where the contrasts apply.
inline bool far_half(const Body<3>& b, std::size_t i, const Scene& s) { return b.x.c[0][i] > 0.5 * s.n * s.dx; }

// fn(model) with the variant's heat model: the plain model without a conductivity contrast, else
// ConductivityContrast with node factors f_i.
template <class Fn>
decltype(auto) with_heat_variant(const HeatVariant& v, const HeatScene& s, const Body<3>& b, const Bonds& bd, Fn&& fn)
{
    auto wrapped = [&](auto params) {
        using Model = std::conditional_t<std::is_same_v<decltype(params), Agwai::Params>, Agwai, CorrespondenceHeat<3>>;
        if (s.k_contrast == 1) {
            params.k = s.k;
            Model m(params, b, bd);
            return fn(m);
        }
        std::vector<double> f(b.size(), 1.0);
        for (std::size_t i = 0; i < b.size(); ++i) f[i] = far_half(b, i, s.geometry) ? s.k_contrast : 1.0;
        ConductivityContrast<Model> m(params, Property::constant(s.k), b, bd, std::move(f));
        return fn(m);
    };
    if (v.model == "agwai") return wrapped(Agwai::Params{});
    return wrapped(CorrespondenceHeat<3>::Params{.C_hg = v.C_hg});
}

inline std::vector<double> heat_capacities(const HeatScene& s, const Body<3>& b)
{
    std::vector<double> rc(b.size(), s.rho_c);
    for (std::size_t i = 0; i < b.size(); ++i)
        if (far_half(b, i, s.geometry)) rc[i] *= s.c_contrast;
    return rc;
}

// Explicit Euler's limit on theta' = diag(rc)^-1 A theta (header) [s], the growing modes and the complexity.
template <class Model>
void heat_spectrum(const Model& model, const Bonds& bd, const std::vector<double>& rc, HeatCell& c)
{
    const Eigen::MatrixXd A(heat_operator(model, bd));
    Eigen::VectorXd w(A.rows());
    for (Eigen::Index r = 0; r < A.rows(); ++r) w(r) = 1 / rc[std::size_t(r)];
    const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(w.asDiagonal() * A, false).eigenvalues();
    const double top = lambda.cwiseAbs().maxCoeff();
    double limit = std::numeric_limits<double>::infinity();
    for (const auto& l : lambda) {
        if (std::abs(l) <= 1e-9 * top) continue;  // the uniform temperature (adiabatic body)
        if (l.real() > 1e-9 * top) ++c.growing;
        else limit = std::min(limit, -2 * l.real() / std::norm(l));
        c.complexity = std::max(c.complexity, std::abs(l.imag()) / top);
    }
    c.linear = limit / c.dt_est;
}

// One run at dt = factor dt_est (header): stable or not; over: its overshoot (header).
template <class Model>
io::StabilityPoint heat_trial(const Model& model, const Bonds& bd, const std::vector<double>& rc, HeatIntegrator integrator, double dt_est,
                              double factor, long steps, double& over)
{
    std::mt19937 gen(13);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> theta0(bd.nodes());
    for (double& t : theta0) t = 300 + u(gen);
    const auto [mn, mx] = std::minmax_element(theta0.begin(), theta0.end());
    const double lo = *mn, hi = *mx, width = hi - lo;
    auto field = make_temperature_field(model, bd, rc, HeatLoads{}, theta0, integrator, factor * dt_est);
    io::StabilityPoint p{factor, factor * dt_est, dt_est};
    over = 0;
    for (long n = 0; n < steps && p.stable; ++n) {
        field->advance();
        for (double t : field->theta) {
            const double e = std::max(t - hi, lo - t) / width;
            if (!std::isfinite(t) || e > 10) {
                p.stable = false, p.unstable_step = n + 1;
                break;
            }
            over = std::max(over, e);
        }
    }
    p.energy_growth = 1 + over;  // the stability table's growth column: 1 + overshoot
    return p;
}

// The whole cell (header): steps of the bisection's runs and of the run at the default step, ladder_steps
// of the ladder's; rel_tol of the bisection; ladder: the factors of the implicit schemes.
inline HeatCell heat_cell(const HeatVariant& v, const HeatScene& s, HeatIntegrator integrator, long steps, long ladder_steps, double rel_tol,
                          const std::vector<double>& ladder)
{
    io::Timer timer;
    HeatCell c;
    const Body<3> b = body(s.geometry);
    const Bonds bd = bonds(s.geometry, b);
    c.nodes = long(b.size()), c.bonds = long(bd.size());
    if (bd.has_damage()) c.broken = long(std::count(bd.intact.begin(), bd.intact.end(), 0));
    const std::vector<double> rc = heat_capacities(s, b);
    with_heat_variant(v, s, b, bd, [&](auto& model) {
        using Model = std::decay_t<decltype(model)>;
        const Conduction<Model> conduction(model, bd, rc, HeatLoads{});
        c.dt_est = thermal_critical_step(model, bd, conduction, std::vector<double>(b.size(), 300.0));
        heat_spectrum(model, bd, rc, c);
        auto run = [&](double f) {
            double over = 0;
            const long n = integrator == HeatIntegrator::explicit_euler ? steps : ladder_steps;
            io::StabilityPoint p = heat_trial(model, bd, rc, integrator, c.dt_est, f, n, over);
            if (p.stable) c.overshoot = std::max(c.overshoot, over);
            return p;
        };
        heat_trial(model, bd, rc, integrator, c.dt_est, 0.5, steps, c.overshoot_default);
        if (integrator == HeatIntegrator::explicit_euler) {
            c.stable = io::stability_sweep({1.0}, run, 64.0, rel_tol, 1.0 / 64);
            c.bracketed = !std::isnan(c.stable.threshold);
        } else {
            c.stable = io::stability_ladder(ladder, run, c.bracketed);
        }
        return 0;
    });
    c.wall_s = timer.seconds();
    return c;
}

}  // namespace pd::atlas
