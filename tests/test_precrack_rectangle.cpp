// Pre-crack rectangle in 3D (damage/precrack.hpp, cut_by_rectangle): bonds that touch the
// rectangle, its edges included, count as cut, whatever the round-off of the lattice coordinates.
// Scene: 20 x 10 x 3 cells, dx = 1 mm, nodes at cell centres; crack rectangle in the plane
// y = 5 mm from x = 0 to x = 10 mm, through the whole thickness (z from -1 to 4 mm).
// Reference: an independent brute force in exact integer arithmetic (doubled coordinates: node
// (i, j, l) at (2i + 1, 2j + 1, 2l + 1), crack plane y = 10, edge x = 20) calling no library routine.
#include "pd/core/bonds.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using namespace pd;

namespace {

constexpr int NX = 20, NY = 10, NZ = 3;
constexpr double DX = 1e-3;  // lattice spacing [m]

// Cut bonds (unordered) with |xi|^2 <= r2x4 / 4 dx^2, by exact integer arithmetic.
long brute_force_cuts(long r2x4)
{
    long cuts = 0;
    const int n = NX * NY * NZ;
    auto coord = [](int a, int axis) {
        const int i = a % NX, j = (a / NX) % NY, l = a / (NX * NY);
        return 2L * (axis == 0 ? i : axis == 1 ? j : l) + 1;
    };
    for (int a = 0; a < n; ++a)
        for (int b = a + 1; b < n; ++b) {
            const long px = coord(a, 0), py = coord(a, 1), pz = coord(a, 2);
            const long qx = coord(b, 0), qy = coord(b, 1), qz = coord(b, 2);
            if ((qx - px) * (qx - px) + (qy - py) * (qy - py) + (qz - pz) * (qz - pz) > r2x4) continue;
            if ((py - 10) * (qy - 10) > 0) continue;  // same side of the plane (no node lies on it: y odd)
            // Hit point x = N / D with D = qy - py != 0; z is always inside (the rectangle spans the thickness).
            const long D = qy - py, N = px * D + (10 - py) * (qx - px);
            const bool inside = D > 0 ? (N >= 0 && N <= 20 * D) : (N <= 0 && N >= 20 * D);
            if (inside) ++cuts;
        }
    return cuts;
}

long library_cuts(double delta)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{NX * DX, NY * DX, NZ * DX}}, DX);
    const Bonds b = build_bonds(body, delta);
    const auto keep = cut_by_rectangle(body, {{0, 5 * DX, -DX}}, {{10 * DX, 0, 0}}, {{0, 0, 5 * DX}});
    long cut = 0;
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            if (!keep(static_cast<int>(i), b.partner[k])) ++cut;
    return cut / 2;
}

}  // namespace

// Exact counts: every bond through the rectangle's edge x = 10 mm (e.g. (9.5, 4.5) - (10.5, 5.5))
// is cut, as the 2D segment rule of seed 001 (spec/001_004 V3) counts tip-touching bonds.
TEST(PrecrackRectangle, CutBondsEqualExactBruteForceIncludingEdgeTouchingBonds)
{
    for (const long r2x4 : {36L, 49L}) {  // family radius 3 dx and 3.5 dx
        const long expected = brute_force_cuts(r2x4);
        EXPECT_GT(expected, 0);
        EXPECT_EQ(library_cuts(std::sqrt(r2x4 / 4.0) * DX), expected) << "family radius^2 = " << r2x4 / 4.0 << " dx^2";
    }
}
