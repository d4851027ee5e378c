// problems/common/bar_supports.hpp -- supports that make the tangent of a gripped bar regular (pd::gripped_bar,
// x axial, bar [0, L] x [0, W] x [0, T], lattice dx) when its grips hold u_x only (pd::Grips::axial):
// u_y, u_z of the node nearest the centre and u_z of its nearest +y lattice neighbour remove the
// lateral translations and the rotation about x (Newton-Raphson, problems/3d/bar_stiffness.cpp).
#pragma once
#include "pd/core/lattice.hpp"

#include <cmath>
#include <utility>
#include <vector>

namespace pd {

// Three supports (u_y, u_z of the node nearest the centre, u_z of its nearest +y lattice neighbour)
// fix the translations y, z and the rotation about x, which the grips (u_x only) leave free: the
// tangent would be singular. They are statically determinate, so at equilibrium their reactions
// vanish (the grips load only along x) and the deformation is that of the unsupported bar.
inline std::vector<std::pair<int, int>> lateral_supports(const Body<3>& body, double L, double W, double T, double dx)
{
    auto nearest = [&](double x, double y, double z) {
        int best = 0;
        double d2 = INFINITY;
        for (std::size_t i = 0; i < body.size(); ++i) {
            const double ex = body.x.c[0][i] - x, ey = body.x.c[1][i] - y, ez = body.x.c[2][i] - z;
            if (ex * ex + ey * ey + ez * ez < d2) d2 = ex * ex + ey * ey + ez * ez, best = static_cast<int>(i);
        }
        return best;
    };
    const int a = nearest(L / 2, W / 2, T / 2);
    const int b = nearest(body.x.c[0][a], body.x.c[1][a] + dx, body.x.c[2][a]);
    return {{a, 1}, {a, 2}, {b, 2}};
}

}  // namespace pd
