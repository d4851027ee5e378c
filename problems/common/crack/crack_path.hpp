// Crack path as a level curve of the damage phi (seed 001 uses phi = 0.41, spec/001_004 A.2
// item 11): marching squares on the node lattice (a square lattice of spacing h, possibly rotated
// by an angle), linear interpolation on the cell edges, saddle cells resolved by the cell mean;
// cells with a missing corner node are skipped. Exact for a linear field.
#pragma once
#include "pd/core/field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pd::crack {

// Node values on a square lattice of spacing h rotated by `angle` about `origin`: node (i, j) at
// origin + R(angle) (i h, j h); nan where the lattice has no node.
struct LatticeScalar {
    Vec<2> origin{};
    double h = 0, angle = 0;  // [m], [rad]
    long nx = 0, ny = 0;
    std::vector<double> v;
    double at(long i, long j) const { return v[j * nx + i]; }
    Vec<2> point(double i, double j) const
    {
        const double c = std::cos(angle), s = std::sin(angle);
        return origin + Vec<2>{{c * i * h - s * j * h, s * i * h + c * j * h}};
    }
};

// Maps nodes that lie on such a lattice (to 1e-6 h) onto it; throws if a node is off-lattice.
inline LatticeScalar lattice_scalar(const Field<2>& x, const std::vector<double>& value, double h, double angle = 0)
{
    if (x.size() == 0 || !(h > 0)) throw std::invalid_argument("lattice_scalar: needs nodes and h > 0");
    const double c = std::cos(angle), s = std::sin(angle);
    std::vector<double> gi(x.size()), gj(x.size());
    double imin = 1e300, jmin = 1e300;
    for (std::size_t q = 0; q < x.size(); ++q) {
        gi[q] = (c * x.c[0][q] + s * x.c[1][q]) / h, gj[q] = (-s * x.c[0][q] + c * x.c[1][q]) / h;
        imin = std::min(imin, gi[q]), jmin = std::min(jmin, gj[q]);
    }
    LatticeScalar g;
    g.h = h, g.angle = angle;
    std::vector<long> I(x.size()), J(x.size());
    for (std::size_t q = 0; q < x.size(); ++q) {
        I[q] = std::lround(gi[q] - imin), J[q] = std::lround(gj[q] - jmin);
        if (std::abs(gi[q] - imin - I[q]) > 1e-6 || std::abs(gj[q] - jmin - J[q]) > 1e-6)  // 1e-6 h: coordinate round-off
            throw std::invalid_argument("lattice_scalar: node off the lattice");
        g.nx = std::max(g.nx, I[q] + 1), g.ny = std::max(g.ny, J[q] + 1);
    }
    g.origin = Vec<2>{{c * imin * h - s * jmin * h, s * imin * h + c * jmin * h}};
    g.v.assign(g.nx * g.ny, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t q = 0; q < x.size(); ++q) g.v[J[q] * g.nx + I[q]] = value[q];
    return g;
}

struct Segment {
    Vec<2> a{}, b{};  // [m]
};

// Marching squares: segments of the level curve value = level (see header).
inline std::vector<Segment> level_curve(const LatticeScalar& g, double level)
{
    std::vector<Segment> out;
    for (long j = 0; j + 1 < g.ny; ++j)
        for (long i = 0; i + 1 < g.nx; ++i) {
            // corners counter-clockwise: (i,j), (i+1,j), (i+1,j+1), (i,j+1)
            const long ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
            double f[4];
            bool ok = true;
            for (int q = 0; q < 4; ++q) ok = ok && !std::isnan(f[q] = g.at(ci[q], cj[q]));
            if (!ok) continue;
            // crossing point on edge e (corners e, e+1), if the level separates them
            std::vector<Vec<2>> cross;
            std::vector<int> edge;
            for (int e = 0; e < 4; ++e) {
                const int q = (e + 1) % 4;
                if ((f[e] >= level) == (f[q] >= level)) continue;
                const double w = (level - f[e]) / (f[q] - f[e]);  // linear interpolation along the edge
                cross.push_back(g.point(ci[e] + w * (ci[q] - ci[e]), cj[e] + w * (cj[q] - cj[e])));
                edge.push_back(e);
            }
            if (cross.size() == 2) out.push_back({cross[0], cross[1]});
            else if (cross.size() == 4) {
                // saddle: corners 0 and 2 on the same side; the cell mean decides whether they connect
                const bool centre_high = 0.25 * (f[0] + f[1] + f[2] + f[3]) >= level;
                const bool c0_high = f[0] >= level;
                if (centre_high == c0_high) out.push_back({cross[0], cross[1]}), out.push_back({cross[2], cross[3]});
                else out.push_back({cross[1], cross[2]}), out.push_back({cross[3], cross[0]});
            }
        }
    return out;
}

}  // namespace pd::crack
