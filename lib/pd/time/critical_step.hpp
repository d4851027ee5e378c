// Critical time steps of explicit central differences / velocity Verlet (spec/000a sec. 3.3.2).
//   Silling-Askari (3.14), per node, with the PMB spring constant per unit displacement c/|xi|:
//       dt_i = sqrt(2 rho_i / sum_j omega V_j c / |xi_ij|),  dt_crit = min_i dt_i
//   (Peridigm's form; in 1D it is (3.13) bounded with 1 - cos <= 2). c is the micromodulus of
//   the dimension (models/pmb.hpp); for other models it is the usual stand-in (sec. 1.9, 000b).
//   CFL (3.15): dt = h / c_wave, conservative with h = dx, unconservative with h = delta.
// The run uses dt = safety * dt_crit; the source's normal safety factor is 0.5.
#pragma once
#include "pd/core/bonds.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace pd {

// The source's normal safety factor on the Silling-Askari step (pd_run's default dt = 0.5 dt_crit;
// its margin on stiff and extreme scenes: problems/3d/stability_atlas.cpp).
inline constexpr double silling_askari_safety = 0.5;

struct CriticalStep {
    double dt = 0;  // [s]
    int node = -1;  // node that limits it
};

namespace detail {
// min_i sqrt(2 rho(i) / sum_k spring(k)) over the nodes with bonds: the one loop of the overloads below.
template <class Rho, class Spring>
CriticalStep silling_askari(const Bonds& b, Rho&& rho, Spring&& spring)
{
    CriticalStep r{std::numeric_limits<double>::infinity(), -1};
    for (std::size_t i = 0; i < b.nodes(); ++i) {
        double stiffness = 0;  // sum of the bond springs: force density per displacement [N/m^4 in 3D]
        for_family(b, i, [&](std::int64_t k, int) { stiffness += spring(k); });
        if (stiffness <= 0) continue;
        const double dt = std::sqrt(2 * rho(i) / stiffness);
        if (dt < r.dt) r = {dt, static_cast<int>(i)};
    }
    return r;
}
}  // namespace detail

inline CriticalStep critical_step_silling_askari(const Bonds& b, const std::vector<double>& rho, double c)
{
    return detail::silling_askari(b, [&](std::size_t i) { return rho[i]; },
                                  [&](std::int64_t k) { return b.omega[k] * b.volume[k] * c / b.length[k]; });
}

// The same with one density rho [kg/m^3] for every node.
inline CriticalStep critical_step_silling_askari(const Bonds& b, double rho, double c)
{
    return detail::silling_askari(b, [&](std::size_t) { return rho; }, [&](std::int64_t k) { return b.omega[k] * b.volume[k] * c / b.length[k]; });
}

// The same with a spring constant per bond, spring[k] = c_k omega V_j / |xi| [N/m^4 in 3D] (e.g.
// PMB::coef after scale_bonds: a surface correction or the micromoduli of variable horizons).
inline CriticalStep critical_step_silling_askari(const Bonds& b, double rho, const std::vector<double>& spring)
{
    return detail::silling_askari(b, [&](std::size_t) { return rho; }, [&](std::int64_t k) { return spring[k]; });
}

inline double critical_step_cfl(double h, double wave_speed) { return h / wave_speed; }

}  // namespace pd
