// problems/common/measure/bar_stretch.hpp -- finite stretches of the gauge of a gripped bar (pd::bar_gauge,
// bar_sections.hpp) for large-deformation curves (problems/3d/large_stretch.cpp; spec/000b V5):
//   axial   lambda = 1 + (mean u_x of layer b - mean u_x of layer a) / dist
//   lateral mu_y, mu_z = least-squares slope of deformed vs reference y (z) over the mid-length
//           layer(s) (pd::lateral_stretch)
// and the equivalent strain of a principal stretch triple (a, b, c) in the Hencky measure,
//   eps_eq = sqrt(2/3 h':h'),  h' = dev diag(ln a, ln b, ln c).
// The stretched bar's state (seed 000b sec. 4.8): engineering stress P = F/(l1 l3) from the pulled
// grip's reaction (pd::grip_stress), the stretches above, the true stress sigma = P/(mu_y mu_z) (the
// section shrinks by mu_y mu_z; the stress is uniaxial, so the von Mises stress is |sigma|) and the
// equivalent strain of (lambda, mu_y, mu_z).
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

struct BarStretchState {
    double P = 0, lambda = 1, mu_y = 1, mu_z = 1, sigma = 0, eps_eq = 0;  // [Pa], stretches [-], true stress [Pa], [-]
    // False when the gauge turned nonphysical (e.g. a section inside out): sigma and eps_eq are then meaningless.
    bool physical() const { return std::isfinite(lambda) && lambda > 0 && mu_y > 0 && mu_z > 0; }
};

// State of the gripped bar s under the displacement u with internal force density f [N/m^3] (header).
inline BarStretchState measure_bar_stretch(const Field<3>& f, const Field<3>& u, const GaugedBar& s)
{
    BarStretchState b{.P = grip_stress(f, s)};
    const GaugeStretches g = gauge_stretches(s.bar.body.x, u, s.gauge);
    b.lambda = g.lambda, b.mu_y = g.mu_y, b.mu_z = g.mu_z;
    b.sigma = b.P / (b.mu_y * b.mu_z);  // true stress: F over the deformed section l1 mu_y x l3 mu_z
    b.eps_eq = equivalent_strain(b.lambda, b.mu_y, b.mu_z);
    return b;
}

}  // namespace pd
