// Seed 001 (spec/001_004 V2, V3): constants of the Duran 50 plate and exact counts on its grid.
// 100 x 40 mm plate, dx = 1 mm, nodes at cell centres (x = 0.5 ... 99.5 mm, y = 0.5 ... 39.5 mm),
// families |xi| <= 3.5 dx (seed 001's neighbour search) and 3 dx (its delta), pre-crack segment
// (0, 20)-(50, 20) mm, bonds touching the segment count as cut (precrack.hpp).
// References: the spec's [DERIVED] values, re-derived by hand in the comments, and an independent
// brute force in exact integer arithmetic (doubled coordinates) that calls no library routine.
#include "pd/core/bonds.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/pmb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

using namespace pd;

namespace {

constexpr int NX = 100, NY = 40;  // cells of the plate
constexpr double DX = 1e-3;       // lattice spacing [m]

// Brute force over all node pairs in doubled integer coordinates (node (i, j) at (2i + 1, 2j + 1),
// crack from (0, 40) to (100, 40)); r2x4 = (2 r / dx)^2, i.e. 49 for 3.5 dx and 36 for 3 dx.
struct BruteCounts {
    long unique_bonds = 0, cut_bonds = 0;
    std::vector<int> total, broken;  // per node (i + NX j)
};
BruteCounts brute_force(long r2x4)
{
    auto orient = [](long px, long py, long qx, long qy, long rx, long ry) {
        const long v = (qx - px) * (ry - py) - (qy - py) * (rx - px);
        return (v > 0) - (v < 0);
    };
    BruteCounts c;
    c.total.assign(NX * NY, 0);
    c.broken.assign(NX * NY, 0);
    const long ax = 0, ay = 40, bx = 100, by = 40;
    for (int a = 0; a < NX * NY; ++a)
        for (int b = a + 1; b < NX * NY; ++b) {
            const long px = 2 * (a % NX) + 1, py = 2 * (a / NX) + 1, qx = 2 * (b % NX) + 1, qy = 2 * (b / NX) + 1;
            if ((qx - px) * (qx - px) + (qy - py) * (qy - py) > r2x4) continue;
            ++c.unique_bonds;
            ++c.total[a];
            ++c.total[b];
            const int d1 = orient(ax, ay, bx, by, px, py), d2 = orient(ax, ay, bx, by, qx, qy);
            const int d3 = orient(px, py, qx, qy, ax, ay), d4 = orient(px, py, qx, qy, bx, by);
            if (d1 * d2 <= 0 && d3 * d4 <= 0) {  // closed segments meet (touching counts)
                ++c.cut_bonds;
                ++c.broken[a];
                ++c.broken[b];
            }
        }
    return c;
}

// Library path: full family, then the bonds rejected by cut_by_segment marked broken.
struct LibraryCounts {
    long unique_bonds = 0, cut_bonds = 0;
    std::vector<double> phi;
};
LibraryCounts library_counts(double delta)
{
    const Body<2> body = box<2>({{0, 0}}, {{NX * DX, NY * DX}}, DX);
    Bonds b = build_bonds(body, delta);
    const auto keep = cut_by_segment(body, {{0, 0.020}}, {{0.050, 0.020}});
    b.enable_damage();
    long cut = 0;
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            if (!keep(static_cast<int>(i), b.partner[k])) { b.intact[k] = 0; ++cut; }
    return {static_cast<long>(b.size()) / 2, cut / 2, point_damage(b)};
}

int node(double x_mm, double y_mm) { return static_cast<int>(x_mm - 0.5) + NX * static_cast<int>(y_mm - 0.5); }

}  // namespace

// V2: c0 = 9E/(pi t delta^3) = 9 * 65e9 / (pi * 27e-9) = 6.8967e18 N/m^6 (t = 1 m);
// s0 = sqrt(4 pi G0/(9 E delta)) = sqrt(2563.54 / 1.755e9) = 1.20859e-3; b = 12e6/1e-3 = 1.2e10 N/m^3.
// Tolerance 1e-4 relative: the spec prints four significant digits.
TEST(Seed001, PlaneStressConstantsMatchSpecV2)
{
    const Elastic duran = Elastic::from_E_nu(65e9, 1.0 / 3.0);
    EXPECT_NEAR(PMB::micromodulus({duran, 2, Plane::stress, 1.0}, Influence{}, 3e-3) / 6.897e18, 1.0, 1e-4);
    EXPECT_NEAR(s0_pmb(204, 65e9, 3e-3, 2, Plane::stress) / 1.2086e-3, 1.0, 1e-4);
}

// Unique bonds by hand: sum over the half family of offsets (a, b) of (100 - |a|)(40 - |b|).
// 3 dx: (1,0) 99*40 + (2,0) 98*40 + (3,0) 97*40 + (0,1) 100*39 + (0,2) 100*38 + (0,3) 100*37
// + (+-1,1) 2*99*39 + (+-1,2) 2*99*38 + (+-2,1) 2*98*39 + (+-2,2) 2*98*38 = 53,498 (spec: 53,498).
// 3.5 dx adds the offsets with 9 < a^2 + b^2 = 10 <= 12.25: (+-1,3) 2*99*37 + (+-3,1) 2*97*39
// = 14,892 -> 68,390 (spec: 68,390).
TEST(Seed001, UniqueBondCountsMatchSpecV3AndBruteForce)
{
    const BruteCounts b35 = brute_force(49), b30 = brute_force(36);
    EXPECT_EQ(b35.unique_bonds, 68390);
    EXPECT_EQ(b30.unique_bonds, 53498);
    EXPECT_EQ(library_counts(3.5 * DX).unique_bonds, 68390);
    EXPECT_EQ(library_counts(3 * DX).unique_bonds, 53498);
}

// Cut bonds: spec 1,290 (3.5 dx) and 894 (3 dx); reproduced by the integer brute force and by
// build_bonds + cut_by_segment.
TEST(Seed001, PrecrackCutsSpecV3BondCounts)
{
    const BruteCounts b35 = brute_force(49), b30 = brute_force(36);
    EXPECT_EQ(b35.cut_bonds, 1290);
    EXPECT_EQ(b30.cut_bonds, 894);
    const LibraryCounts l35 = library_counts(3.5 * DX), l30 = library_counts(3 * DX);
    EXPECT_EQ(l35.cut_bonds, 1290);
    EXPECT_EQ(l30.cut_bonds, 894);
    // The library's per-node damage equals the brute force's broken/total at every node (1e-14:
    // point_damage sums nodal volumes of 1e-6 m^3 in floating point).
    for (int i = 0; i < NX * NY; ++i) {
        ASSERT_NEAR(l35.phi[i], static_cast<double>(b35.broken[i]) / b35.total[i], 1e-14) << "node " << i;
        ASSERT_NEAR(l30.phi[i], static_cast<double>(b30.broken[i]) / b30.total[i], 1e-14) << "node " << i;
    }
}

// Initial damage (unweighted: all V_j equal, no partial volumes), hand counts with offsets (a, b),
// a^2 + b^2 <= 12.25 (36 per interior node: rows b = 0: 6, +-1: 7 each, +-2: 5 each, +-3: 3 each):
// - first row y = 20.5: every bond to b <= -1 crosses: 7 + 5 + 3 = 15 -> 15/36;
// - second row y = 21.5: b <= -2: 5 + 3 = 8/36; third row y = 22.5: b = -3: 3/36; fourth: 0;
// - left edge (0.5, 20.5): family a >= 0: 3 + 2*4 + 2*3 + 2*2 = 21, cut b = -1: 4, -2: 3, -3: 2 -> 9/21;
// - tip (49.5, 20.5): the bond reaches y = 20 at x = 49.5 + a/(2|b|) <= 50, i.e. a <= |b|:
//   b = -1: a = -3..1 (5), b = -2: all 5, b = -3: all 3 -> 13/36;
// - (50.5, 20.5): a <= -|b|: b = -1: a = -3..-1 (3), b = -2: a = -2 (1) -> 4/36 (two of them
//   touch the tip (50, 20) exactly and count as cut);
// - 3 dx family (28: rows b = 0: 6, +-1: 5 each, +-2: 5 each, +-3: 1 each): first row
//   b = -1: 5, -2: 5, -3: 1 -> 11/28.
// Tolerance 1e-14: exact ratios of small integers; point_damage sums volumes in floating point.
TEST(Seed001, InitialDamageMatchesSpecV3HandCounts)
{
    const auto phi = library_counts(3.5 * DX).phi;
    const double eps = 1e-14;
    EXPECT_NEAR(phi[node(30.5, 20.5)], 15.0 / 36, eps);
    EXPECT_NEAR(phi[node(30.5, 19.5)], 15.0 / 36, eps);  // mirror row below the crack
    EXPECT_NEAR(phi[node(30.5, 21.5)], 8.0 / 36, eps);
    EXPECT_NEAR(phi[node(30.5, 22.5)], 3.0 / 36, eps);
    EXPECT_NEAR(phi[node(30.5, 23.5)], 0.0, eps);
    EXPECT_NEAR(phi[node(0.5, 20.5)], 9.0 / 21, eps);
    EXPECT_NEAR(phi[node(49.5, 20.5)], 13.0 / 36, eps);
    EXPECT_NEAR(phi[node(50.5, 20.5)], 4.0 / 36, eps);
    EXPECT_NEAR(phi[node(70.5, 20.5)], 0.0, eps);
    EXPECT_NEAR(library_counts(3 * DX).phi[node(30.5, 20.5)], 11.0 / 28, eps);
}
