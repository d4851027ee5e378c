// problems/common/grips.hpp -- the two grip conditions of the bar specimens (pd::gripped_bar, x axial,
// bar [0, L] x [0, W] x [0, T], grips outside both ends) and their uniform uniaxial start field.
//   clamped: left grip fixed (all components zero), right grip pulled axially by `pull` with its
//            lateral components held at zero (seed 000b T2 [RECON], spec/000b sec. 5.2);
//   axial:   only the axial components prescribed, left u_x = 0 and right u_x = pull, the lateral
//            ones free (the quasi-static V2 bar, spec/000b sec. 5.2 V2).
// The prescriptions are added in this order: clamped: left x, y, z, right x, y, z; axial: left x,
// right x.
// Start field (warm start of the quasi-static solves): the uniform uniaxial-stress field of end
// displacement U, u_x = U clamp(x/L, 0, 1) (rigid grips), u_y = -nu eps (y - W/2),
// u_z = -nu eps (z - T/2), eps the axial strain (U/L, passed as computed by the caller); with
// clamped grips the lateral components are zero in the grips.
#pragma once

#include "pd/bc/boundary.hpp"
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <cstddef>

namespace pd {

enum class Grips { clamped, axial };

inline void grip_bar_ends(Boundary<3>& bc, const NodeSet& left, const NodeSet& right, const TimeFunction& pull, Grips kind)
{
    if (kind == Grips::clamped) {
        bc.fix(left);
        bc.prescribe({Prescribed::Kind::displacement, right, 0, pull});
        for (int d : {1, 2}) bc.prescribe({Prescribed::Kind::displacement, right, d, TimeFunction::constant(0)});
    } else {
        bc.prescribe({Prescribed::Kind::displacement, left, 0, TimeFunction::constant(0)});
        bc.prescribe({Prescribed::Kind::displacement, right, 0, pull});
    }
}

// Writes the start field into u (sized body.size()); see the file header.
inline void uniaxial_bar_field(const Body<3>& body, double L, double W, double T, double U, double eps, double nu, Grips kind,
                               Field<3>& u)
{
    for (std::size_t i = 0; i < body.size(); ++i) {
        const double x = body.x.c[0][i];
        u.c[0][i] = U * std::clamp(x / L, 0.0, 1.0);
        const double lateral = kind == Grips::clamped && !(x > 0 && x < L) ? 0.0 : 1.0;  // 0: inside a clamped grip
        u.c[1][i] = -lateral * nu * eps * (body.x.c[1][i] - W / 2);
        u.c[2][i] = -lateral * nu * eps * (body.x.c[2][i] - T / 2);
    }
}

}  // namespace pd
