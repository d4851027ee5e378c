// A square plate [0, L]^2 on a lattice of spacing dx rotated by theta about its centre (the grid-
// orientation study of spec/002 ch. 5): the nodes of the rotated lattice inside the plate, each
// with a full cell volume dx^2; a half-cell offset puts no node on the mid-line at 0 deg. Its load:
// a sudden traction sigma on the top and bottom layers `depth` deep, as body forces whose total is
// sigma L per unit thickness (whatever nodes the layer holds at any rotation or refinement).
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/core/lattice.hpp"
#include "pd/io/options.hpp"

#include <cmath>

namespace pd::crack {

// The plate and material options of the grid-orientation drivers (spec/002 ch. 5), as registered.
struct GridPlateOptions {
    double &E, &rho, &Gc, &sigma, &L, &a0;
};
inline GridPlateOptions add_grid_plate_options(io::Options& opt)
{
    return {opt.add("E", 73.4e9, "Young's modulus", "Pa"), opt.add("rho", 2440, "density", "kg/m^3"),
            opt.add("Gc", 7.0013, "fracture energy (s0 = 2.1070e-4 at delta = 3 mm)", "J/m^2"),
            opt.add("sigma", 0.8e6, "sudden traction on top and bottom", "Pa"), opt.add("size", 0.25, "plate side", "m"),
            opt.add("crack", 0.05, "edge pre-crack length", "m")};
}

inline Body<2> rotated_plate(double L, double dx, double theta)
{
    Body<2> b;
    b.dx = dx;
    const double c = std::cos(theta), s = std::sin(theta);
    const long n = std::lround(std::ceil(0.75 * L / dx));  // covers the rotated square
    for (long j = -n; j <= n; ++j)
        for (long i = -n; i <= n; ++i) {
            const double u = (i + 0.5) * dx, v = (j + 0.5) * dx;
            const Vec<2> p{{0.5 * L + c * u - s * v, 0.5 * L + s * u + c * v}};
            if (p[0] > 0 && p[0] < L && p[1] > 0 && p[1] < L) b.push(p, dx * dx);
        }
    return b;
}

inline Boundary<2> layer_loads(const Body<2>& b, double L, double depth, double sigma)
{
    Boundary<2> bc;
    for (int side : {1, -1}) {
        const NodeSet layer = select(b, side > 0 ? in_box<2>({{-1, L - depth}}, {{2 * L, 2 * L}}) : in_box<2>({{-1, -L}}, {{2 * L, depth}}),
                                     "loaded layer");
        double V = 0;  // layer area per unit thickness [m^2]
        for (int i : layer) V += b.volume[i];
        bc.body_force({{0, side * sigma * L / V}}, layer);
    }
    return bc;
}

}  // namespace pd::crack
