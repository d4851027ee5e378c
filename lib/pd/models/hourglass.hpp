// pd/models/hourglass.hpp -- the Littlewood hourglass force of the correspondence model (spec/000b
// sec. 1.6, stabilising sign of erratum 4; models/correspondence.hpp), written once for every
// execution policy of the bond pass. The force on i from bond i -> j, both ends' terms summed, is
//   t Y,   t = hg ((2Y - Gx).Y) / |Y|^2,   Gx = (F_i + F_j) xi,   hg = C_hg c V_j / |xi|,
// with |Y| in place of |Y|^2 for HourglassDirection::bond (Peridigm's form, the force along Y rather
// than along Y/|Y|), and t = 0 for a collapsed bond (|Y| = 0). T is a number (per-node code) or a
// vector of lanes (GCC vector extension: 4 bonds of one node in the AVX2 kernel, W nodes of a chunk);
// S, the per-bond coefficient, is a number or lanes. The policy gathers Gx and Y.
#pragma once
#include <cmath>
#include <cstddef>
#include <type_traits>

namespace pd {

// sqrt of a number or of every lane.
template <class T>
T lane_sqrt(T v)
{
    if constexpr (std::is_arithmetic_v<T>) return std::sqrt(v);
    else {
        for (std::size_t l = 0; l < sizeof(T) / sizeof(double); ++l) v[l] = std::sqrt(v[l]);
        return v;
    }
}

// t of the header [N/m^5 in 3D, times m with AlongBond].
template <int D, bool AlongBond, class T, class S>
T hourglass_scalar(const T* Gx, const T* Y, S hg)
{
    T proj = (2.0 * Y[0] - Gx[0]) * Y[0], y2 = Y[0] * Y[0];  // (2Y - Gx).Y and |Y|^2 [m^2]
    for (int a = 1; a < D; ++a) {
        proj += (2.0 * Y[a] - Gx[a]) * Y[a];
        y2 += Y[a] * Y[a];
    }
    const T zero{};
    const T den = AlongBond ? lane_sqrt(y2) : y2;  // |Y| or |Y|^2
    return hg * proj / (y2 > zero ? den : zero + 1.0);
}

}  // namespace pd
