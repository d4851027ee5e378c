// Agwai bond-based heat conduction (spec/000b sec. 3.1-3.3, 3.6; Agwai, Guven & Madenci):
//   pairwise heat flow   q = kappa_1 (theta_j - theta_i) / |xi|,   Q_i = sum_j q V_j   [W/m^3]
//   micro-conductivity   kappa_1 = 2 D k / M_1,  M_1 = int_H |xi| dV  (horizon_moment, p = 1), i.e.
//                        1D 2k/(A delta^2), 2D 6k/(pi s delta^3), 3D 6k/(pi delta^4)   (000b eqs. 6.4-6.6)
//   (from equating the micro-potential z = kappa_1 theta^2/(2|xi|) summed over a full horizon with
//   the classical k |grad theta|^2 / 2 for a linear field).
// Thermal correction factor (000b sec. 3.6, with the factor-2 erratum of eq. 6.31 fixed): the same
// equation summed over the node's actual, possibly truncated family, for the test field
// theta = x + y + z:
//   TCF_i = M_1 / S_i,  S_i = sum_j V_j (e . xi)^2 / |xi|,  e = (1, ..., 1)      (3D: pi delta^4 / S_i)
// applied either as the source's fork does (ThermalCorrection::per_node: node i uses TCF_i on its
// own bonds; not conservative: bond i-j carries TCF_i on i and TCF_j on j) or conservatively
// (ThermalCorrection::pair_mean: (TCF_i + TCF_j)/2 on both ends).
// Conductance per bond coef_k = kappa_1 TCF V_j / |xi| [W/(m^3 K)], so bond_heat = coef_k dtheta.
// The volumes are the bond volumes of Bonds (partial volumes included).
// k(theta): conductivity.hpp wraps a model built with k = 1 and scales each bond by its conductivity.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/influence.hpp"
#include "pd/core/lattice.hpp"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

enum class ThermalCorrection { none, per_node, pair_mean };

inline ThermalCorrection parse_thermal_correction(const std::string& s)
{
    if (s == "none" || s == "off") return ThermalCorrection::none;
    if (s == "per-node" || s == "on") return ThermalCorrection::per_node;
    if (s == "pair-mean") return ThermalCorrection::pair_mean;
    throw std::invalid_argument("thermal correction must be none|per-node|pair-mean, got '" + s + "'");
}

// kappa_1 = 2 D k / M_1 [W/(m^(D+... ) K)]: k [W/(m K)], delta [m], measure A [m^2] (1D), s [m] (2D), 1 (3D).
inline double agwai_micro_conductivity(double k, int dim, double delta, double measure)
{
    return 2.0 * dim * k / horizon_moment(Influence{}, 1, delta, dim, measure);
}

struct Agwai {
    static constexpr bool has_point_pass = false;
    struct Params {
        double k = 0;                                   // conductivity [W/(m K)]
        double measure = 1;                             // A [m^2] in 1D, thickness [m] in 2D, 1 in 3D
        ThermalCorrection correction = ThermalCorrection::none;
    };

    Params par;
    double kappa1 = 0;          // micro-conductivity [W/(m^(D+2) K)... per unit |xi| and V]
    std::vector<double> tcf;    // thermal correction factor per node [-] (1 without correction)
    std::vector<double> coef;   // conductance per bond kappa_1 TCF V_j/|xi| [W/(m^3 K)]

    template <int D>
    Agwai(const Params& p, const Body<D>& body, const Bonds& b) : par(p), tcf(b.nodes(), 1.0), coef(b.size())
    {
        if (!(p.k > 0)) throw std::invalid_argument("Agwai: conductivity k must be positive");
        if (!(p.measure > 0)) throw std::invalid_argument("Agwai: measure (1D area, 2D thickness) must be positive");
        const double M1 = horizon_moment(Influence{}, 1, b.delta, D, p.measure);
        kappa1 = agwai_micro_conductivity(p.k, D, b.delta, p.measure);
        if (p.correction != ThermalCorrection::none)
            for (std::size_t i = 0; i < b.nodes(); ++i) {
                double S = 0;
                for_family(b, i, [&](std::int64_t k, int j) {
                    double ex = 0;
                    for (int d = 0; d < D; ++d) ex += body.x.c[d][j] - body.x.c[d][i];
                    S += b.volume[k] * ex * ex / b.length[k];
                });
                tcf[i] = S > 0 ? M1 / S : 1.0;
            }
        for (std::size_t i = 0; i < b.nodes(); ++i)
            for_family(b, i, [&](std::int64_t k, int j) {
                const double f = p.correction == ThermalCorrection::pair_mean ? 0.5 * (tcf[i] + tcf[j]) : tcf[i];
                coef[k] = kappa1 * f * b.volume[k] / b.length[k];
            });
    }

    double bond_heat(std::size_t, std::int64_t k, int, double dtheta) const { return coef[k] * dtheta; }
    // Conductivity of the bond s [W/(m K)] times the conductance of a model built with k = 1
    // (temperature-dependent k, conductivity.hpp).
    double bond_heat_scaled(std::size_t, std::int64_t k, int, double dtheta, double s) const { return s * coef[k] * dtheta; }
};

}  // namespace pd
