// problems/common/measure/shear_cube.hpp -- the homogeneous simple-shear probe of the viscoelastic cube drivers
// (problems/3d/viscoelastic_relaxation.cpp, numerical_viscosity.cpp): every node moved with
//   y = (I + (gamma/2)(e_x e_y + e_y e_x)) x   (engineering shear gamma, small-strain eps_xy = gamma/2),
// the node nearest the cube centre (L1 distance, the first in node order on a tie), and the node
// coordinates in the form reference/lps_shear.hpp reads.
#pragma once

#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace pd {

// Deformed positions under the engineering shear gamma [-] [m].
inline Field<3> sheared(const Body<3>& body, double gamma)
{
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) {
        y.c[0][i] += 0.5 * gamma * body.x.c[1][i];
        y.c[1][i] += 0.5 * gamma * body.x.c[0][i];
    }
    return y;
}

// The node nearest the point (a, a, a) [m] in the L1 distance; the first in node order on a tie.
inline std::size_t node_nearest_diagonal_point(const Body<3>& body, double a)
{
    auto dist = [&](std::size_t i) {
        double s = 0;
        for (int d = 0; d < 3; ++d) s += std::abs(body.x.c[d][i] - a);
        return s;
    };
    std::size_t c = 0;
    for (std::size_t i = 1; i < body.size(); ++i)
        if (dist(i) < dist(c)) c = i;
    return c;
}

// Node coordinates as a list of points [m].
inline std::vector<std::array<double, 3>> point_list(const Body<3>& body)
{
    std::vector<std::array<double, 3>> pts(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) pts[i] = {body.x.c[0][i], body.x.c[1][i], body.x.c[2][i]};
    return pts;
}

}  // namespace pd
