// problems/common/measure/bar_stretch.hpp -- finite stretches of the gauge of a gripped bar (pd::bar_gauge,
// bar_sections.hpp) for large-deformation curves (problems/3d/large_stretch.cpp; spec/000b V5):
//   axial   lambda = 1 + (mean u_x of layer b - mean u_x of layer a) / dist
//   lateral mu_y, mu_z = least-squares slope of deformed vs reference y (z) over the mid-length
//           layer(s) (pd::lateral_stretch)
// and the equivalent strain of a principal stretch triple (a, b, c) in the Hencky measure,
//   eps_eq = sqrt(2/3 h':h'),  h' = dev diag(ln a, ln b, ln c).
#pragma once
#include "pd/core/field.hpp"
#include "problems/common/measure/bar_sections.hpp"

#include <cmath>

namespace pd {

struct GaugeStretches {
    double lambda = 1, mu_y = 1, mu_z = 1;  // axial and lateral stretches [-]
};

// Stretches of the gauge g under the displacement u of the reference positions x [m].
inline GaugeStretches gauge_stretches(const Field<3>& x, const Field<3>& u, const BarGauge& g)
{
    return {1 + (mean_axial_displacement(u, g.sec_b) - mean_axial_displacement(u, g.sec_a)) / g.dist,
            lateral_stretch(x, u, g.mid, 1), lateral_stretch(x, u, g.mid, 2)};
}

// sqrt(2/3 h':h') of the Hencky strain diag(ln a, ln b, ln c) [-].
inline double equivalent_strain(double a, double b, double c)
{
    const double h[3] = {std::log(a), std::log(b), std::log(c)}, m = (h[0] + h[1] + h[2]) / 3;
    return std::sqrt(2.0 / 3 * ((h[0] - m) * (h[0] - m) + (h[1] - m) * (h[1] - m) + (h[2] - m) * (h[2] - m)));
}

}  // namespace pd
