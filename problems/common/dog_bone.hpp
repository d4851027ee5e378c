// problems/common/dog_bone.hpp -- a flat dog-bone tension specimen on near-cubic cells with cut
// cells along its curved outline (spec/000c sec. 3.2: "cells cut by the fillets get corrected volume
// and node position").
// Outline (x axial, y across, z through the thickness; symmetric about x = 0 and y = 0), half-width
//   h(x) = w_g/2                                          |x| <= l_g/2           (gauge)
//        = w_g/2 + R - sqrt(R^2 - (|x| - l_g/2)^2)         up to h = w_grip/2      (fillet, radius R,
//                                                                                 tangent to the gauge)
//        = w_grip/2                                       beyond                 (grips)
// over |x| <= x_end (the end cells cut there), thickness t everywhere.
// Cells: sides hx = dx along x (cells centred on x = i hx), hy = w_g/n_y across with n_y the odd number
// nearest w_g/dx (so that the gauge holds whole cells and a node row lies on y = 0), hz = t/n_z with
// n_z = max(1, round(t/dx)) (the thickness is uniform: no cell is cut in z). A cell whose x-y square
// the outline cuts keeps the area a = integral over its x-range of the covered y-length (midpoint rule,
// `quadrature` points), its node sits at the centroid of that area, volume a hz; cells covered less
// than `min_fraction` are dropped (their volume is counted in `dropped_volume`).
// Nodes are numbered with x fastest, then y, then z (the lattice order of core/lattice.hpp).
#pragma once
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pd {

struct DogBoneShape {
    double gauge_length = 12e-3, gauge_width = 3.77e-3, thickness = 1.85e-3;  // [m]
    double fillet_radius = 4e-3, grip_width = 10e-3;                          // [m]
    double x_end = 30e-3;                                                     // half-length of the body [m]

    // The fillet's axial length: where the arc reaches the grip width [m].
    double fillet_length() const
    {
        const double rise = 0.5 * (grip_width - gauge_width);
        return std::sqrt(fillet_radius * fillet_radius - (fillet_radius - rise) * (fillet_radius - rise));
    }
    double half_width(double x) const  // h(x) [m], header
    {
        const double s = std::abs(x) - 0.5 * gauge_length;
        if (s <= 0) return 0.5 * gauge_width;
        if (s >= fillet_length()) return 0.5 * grip_width;
        return 0.5 * gauge_width + fillet_radius - std::sqrt(fillet_radius * fillet_radius - s * s);
    }
    void validate() const
    {
        if (!(gauge_length > 0 && gauge_width > 0 && thickness > 0 && fillet_radius > 0 && grip_width >= gauge_width))
            throw std::invalid_argument("dog bone: lengths must be positive and the grip at least as wide as the gauge");
        if (2 * fillet_radius < grip_width - gauge_width)
            throw std::invalid_argument("dog bone: fillet radius must be >= (grip width - gauge width)/2");
        if (!(x_end > 0.5 * gauge_length + fillet_length()))
            throw std::invalid_argument("dog bone: the body must extend beyond the fillets");
    }
};

struct DogBone {
    Body<3> body;
    double hx = 0, hy = 0, hz = 0;  // cell sides [m]
    long cut_cells = 0;             // cells with a corrected volume and position
    double dropped_volume = 0;      // [m^3]
};

inline DogBone dog_bone(const DogBoneShape& s, double dx, double min_fraction = 0.1, int quadrature = 64)
{
    s.validate();
    if (!(dx > 0)) throw std::invalid_argument("dog bone: cell size dx must be positive");
    DogBone d;
    long ny = std::max(1L, std::lround(s.gauge_width / dx));
    if (ny % 2 == 0) ny += (s.gauge_width / dx > double(ny)) ? 1 : -1;  // odd: a row on y = 0
    ny = std::max(1L, ny);
    const long nz = std::max(1L, std::lround(s.thickness / dx));
    d.hx = dx, d.hy = s.gauge_width / double(ny), d.hz = s.thickness / double(nz);
    const long ix = static_cast<long>(std::ceil(s.x_end / d.hx - 0.5)), iy = std::lround(0.5 * s.grip_width / d.hy) + 1;
    for (long k = 0; k < nz; ++k) {
        const double z = (double(k) + 0.5) * d.hz - 0.5 * s.thickness;
        for (long j = -iy; j <= iy; ++j) {
            const double y0 = (double(j) - 0.5) * d.hy, y1 = y0 + d.hy;
            for (long i = -ix; i <= ix; ++i) {
                const double xc = double(i) * d.hx, x0 = xc - 0.5 * d.hx;
                double area = 0, mx = 0, my = 0;  // covered area and its first moments over the cell
                bool cut = false;
                for (int q = 0; q < quadrature; ++q) {
                    const double x = x0 + (q + 0.5) * d.hx / quadrature, h = std::abs(x) > s.x_end ? 0.0 : s.half_width(x);
                    const double a = std::max(0.0, std::min(y1, h) - std::max(y0, -h));  // covered y-length
                    cut = cut || a < d.hy * (1 - 1e-9);
                    const double w = d.hx / quadrature;
                    area += a * w, mx += a * w * x, my += a * w * 0.5 * (std::min(y1, h) + std::max(y0, -h));
                }
                const double full = d.hx * d.hy;
                if (area <= 0 || area < min_fraction * full) {
                    d.dropped_volume += area * d.hz;
                    continue;
                }
                if (cut) ++d.cut_cells;
                d.body.push({{cut ? mx / area : xc, cut ? my / area : 0.5 * (y0 + y1), z}}, (cut ? area : full) * d.hz);
            }
        }
    }
    return d;
}

}  // namespace pd
