// Method A node generation (core/refinement.hpp, spec/002 sec. 4.4, Fig. 3.5a, eq. 3.4): midpoints
// inserted around a kept parent. References: positions and cell areas written out by hand (a coarse
// cell of side h0 overlapped by fine cells of side h0/2 centred h0/2 from its edge loses strips of
// width h0/4), the printed eq. 3.4 for one, three and five finer neighbours, and the body's volume.
#include "pd/core/refinement.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace {
constexpr double h0 = 1e-3, m = 3.015, t = 0.01;
constexpr double V0 = h0 * h0 * t, V1 = V0 / 4;  // a cell's volume at levels 0 and 1 [m^3]

// 8 x 8 cells of side h0, centres at (i + 1/2) h0.
pd::RefinedGrid<2> square() { return pd::RefinedGrid<2>(pd::box<2>({{0, 0}}, {{8 * h0, 8 * h0}}, h0, t), m * h0); }

// The node at cell-centre coordinates (i, j) of the initial lattice (halves allowed), -1 if none.
int at(const pd::RefinedGrid<2>& g, double i, double j)
{
    for (std::size_t k = 0; k < g.size(); ++k)
        if (std::abs(g.x.c[0][k] - (i + 0.5) * h0) < 1e-9 * h0 && std::abs(g.x.c[1][k] - (j + 0.5) * h0) < 1e-9 * h0) return static_cast<int>(k);
    return -1;
}

double total_volume(const pd::RefinedGrid<2>& g)
{
    double v = 0;
    for (double x : g.volume) v += x;
    return v;
}

// The number j of eq. 3.4: finer nodes within the fine diagonal sqrt(2) h0/2 of node q.
int finer_neighbours(const pd::RefinedGrid<2>& g, int q)
{
    int j = 0;
    for (std::size_t k = 0; k < g.size(); ++k)
        j += g.level[k] > g.level[q] && norm(g.x[k] - g.x[q]) <= std::sqrt(2.0) * h0 / 2 * (1 + 1e-9);
    return j;
}
}  // namespace

TEST(MidpointRefinement, TheParentStaysAndGainsTheMidpointsToItsAdjacentNodes)
{
    pd::RefinedGrid<2> g = square();
    const int p = at(g, 3, 3);
    g.insert_midpoints({p}, pd::Refinement::delta);
    ASSERT_EQ(g.size(), 64u + 8);  // 9 nodes with the parent (Fig. 3.5a)
    EXPECT_EQ(at(g, 3, 3), p);
    EXPECT_EQ(g.level[p], 1);
    EXPECT_DOUBLE_EQ(g.h[p], h0 / 2);
    EXPECT_DOUBLE_EQ(g.delta[p], m * h0 / 2);
    for (double di : {-0.5, 0.0, 0.5})
        for (double dj : {-0.5, 0.0, 0.5}) {
            const int c = at(g, 3 + di, 3 + dj);
            ASSERT_GE(c, 0) << di << " " << dj;
            EXPECT_TRUE(g.active[c]);
            EXPECT_EQ(g.level[c], 1);
            EXPECT_EQ(g.ancestor(c), p);
        }
    // At the body's edge and corner: no midpoints outwards (no adjacent node there).
    g.insert_midpoints({at(g, 0, 5)}, pd::Refinement::delta);
    EXPECT_EQ(g.size(), 72u + 5);
    g.insert_midpoints({at(g, 7, 7)}, pd::Refinement::delta);
    EXPECT_EQ(g.size(), 77u + 3);
    // A neighbour of a refined node shares three midpoints with it.
    g.insert_midpoints({at(g, 4, 3)}, pd::Refinement::delta);
    EXPECT_EQ(g.size(), 80u + 5);
    std::set<std::pair<long long, long long>> positions;
    for (std::size_t k = 0; k < g.size(); ++k) positions.insert({std::llround(g.x.c[0][k] / h0 * 4), std::llround(g.x.c[1][k] / h0 * 4)});
    EXPECT_EQ(positions.size(), g.size());  // no node made twice
}

TEST(MidpointRefinement, InterfaceVolumesAreTheUncoveredCellAreaAsEq34PrintsForOneThreeAndFiveFinerNeighbours)
{
    {  // one refined node: its edge neighbour (j = 3) loses a strip h0/4 x h0 = V1, its corner neighbour (j = 1) h0/4 x h0/4 = V1/4
        pd::RefinedGrid<2> g = square();
        g.insert_midpoints({at(g, 3, 3)}, pd::Refinement::delta);
        const int edge = at(g, 4, 3), corner = at(g, 4, 4);
        EXPECT_EQ(finer_neighbours(g, edge), 3);
        EXPECT_EQ(finer_neighbours(g, corner), 1);
        EXPECT_NEAR(g.volume[edge], V0 - V1, 1e-12 * V0);       // eq. 3.4, j = 3
        EXPECT_NEAR(g.volume[corner], V0 - V1 / 4, 1e-12 * V0);  // eq. 3.4, j = 1
        for (double di : {-0.5, 0.0, 0.5})
            for (double dj : {-0.5, 0.0, 0.5}) EXPECT_NEAR(g.volume[at(g, 3 + di, 3 + dj)], V1, 1e-12 * V0);
        EXPECT_NEAR(total_volume(g), 64 * V0, 1e-12 * V0);
    }
    {  // an edge and a diagonal refined neighbour (j = 5): two strips less their h0/4 x h0/4 overlap, 7 V1/4
        pd::RefinedGrid<2> g = square();
        g.insert_midpoints({at(g, 3, 3), at(g, 4, 2)}, pd::Refinement::delta);
        const int q = at(g, 4, 3);
        EXPECT_EQ(finer_neighbours(g, q), 5);
        EXPECT_NEAR(g.volume[q], V0 - 7 * V1 / 4, 1e-12 * V0);  // eq. 3.4, j = 5
        EXPECT_NEAR(total_volume(g), 64 * V0, 1e-12 * V0);
    }
    {  // two refined corner neighbours (j = 2): two corners of V1/4 each; eq. 3.4 prints 3 V1/4
        pd::RefinedGrid<2> g = square();
        g.insert_midpoints({at(g, 3, 4), at(g, 3, 2)}, pd::Refinement::delta);
        const int q = at(g, 4, 3);
        EXPECT_EQ(finer_neighbours(g, q), 2);
        EXPECT_NEAR(g.volume[q], V0 - V1 / 2, 1e-12 * V0);
    }
}

TEST(MidpointRefinement, KeepsTheBodysVolumeOverLevelsAndEdgesIn2DAnd3D)
{
    std::mt19937 rng(3);
    for (int trial = 0; trial < 4; ++trial) {
        pd::RefinedGrid<2> g = square();
        for (int level = 0; level < 2; ++level) {  // random active nodes of the finest level, edges included
            std::vector<int> pick;
            for (std::size_t k = 0; k < g.size(); ++k)
                if (g.level[k] == level && std::uniform_real_distribution<double>(0, 1)(rng) < 0.3) pick.push_back(static_cast<int>(k));
            g.insert_midpoints(pick, pd::Refinement::m);
        }
        EXPECT_NEAR(total_volume(g), 64 * V0, 1e-12 * 64 * V0);
        for (std::size_t k = 0; k < g.size(); ++k) {
            EXPECT_GT(g.volume[k], 0) << k;
            EXPECT_LE(g.volume[k], V0 * (1 + 1e-12)) << k;  // no cell grows beyond an initial cell here
            EXPECT_DOUBLE_EQ(g.delta[k], m * h0);           // m refinement keeps delta
        }
    }
    // An L-shaped plate: the midpoint of the diagonal across the re-entrant corner keeps 3/4 of its cell.
    pd::RefinedGrid<2> ell(pd::fill<2>({{0, 0}}, {{8 * h0, 8 * h0}}, h0, [](const pd::Vec<2>& p) { return p[0] < 4 * h0 || p[1] < 4 * h0; }, t),
                           m * h0);
    ell.insert_midpoints({at(ell, 3, 4), at(ell, 4, 3)}, pd::Refinement::delta);
    EXPECT_NEAR(ell.volume[at(ell, 3.5, 3.5)], 3 * V1 / 4, 1e-12 * V0);
    EXPECT_NEAR(total_volume(ell), 48 * V0, 1e-12 * V0);
    pd::RefinedGrid<3> cube(pd::box<3>({{0, 0, 0}}, {{4 * h0, 4 * h0, 4 * h0}}, h0), m * h0);
    int centre = -1;
    for (std::size_t k = 0; k < cube.size(); ++k)
        if (norm(cube.x[k] - pd::Vec<3>{{1.5 * h0, 1.5 * h0, 1.5 * h0}}) < 1e-9 * h0) centre = static_cast<int>(k);
    cube.refine_nested([&](const pd::Vec<3>& p, double) { return norm(p - cube.x[centre]) < 0.1 * h0; }, 1, pd::Refinement::delta, {},
                       pd::NodeGeneration::midpoint);
    EXPECT_EQ(cube.size(), 64u + 26);  // 27 nodes with the parent
    double v = 0;
    for (double x : cube.volume) v += x;
    EXPECT_NEAR(v, 64 * h0 * h0 * h0, 1e-12 * 64 * h0 * h0 * h0);
}

TEST(MidpointRefinement, InterfaceHorizonOfAMidpointGridIsThreeOrThreeSqrtTwoFineSpacings)  // V6e on Method A
{
    pd::RefinedGrid<2> g = square();
    std::vector<int> block;
    for (double i : {2, 3, 4})
        for (double j : {2, 3, 4}) block.push_back(at(g, i, j));
    g.insert_midpoints(block, pd::Refinement::delta);
    EXPECT_GT(g.interface_horizon(3), 0);
    const double h1 = h0 / 2;
    EXPECT_NEAR(g.delta[at(g, 1.5, 1.5)], 3 * std::sqrt(2.0) * h1, 1e-12 * h0);  // the corner midpoint: coarse node at sqrt(2) h1
    EXPECT_NEAR(g.delta[at(g, 1.5, 3)], 3 * h1, 1e-12 * h0);                      // an edge midpoint: coarse node at h1
    EXPECT_NEAR(g.delta[at(g, 3, 3)], m * h1, 1e-12 * h0);                        // inside: the nominal horizon
}

TEST(MidpointRefinement, RefusesRotatedLatticesAndMixingWithMethodB)
{
    pd::RefinedGrid<2> rotated(pd::box<2>({{0, 0}}, {{4 * h0, 4 * h0}}, h0), m * h0, 0.1);
    EXPECT_THROW(rotated.insert_midpoints({0}, pd::Refinement::delta), std::invalid_argument);
    pd::RefinedGrid<2> b = square(), a = square();
    b.split({0}, pd::Refinement::delta);
    EXPECT_THROW(b.insert_midpoints({1}, pd::Refinement::delta), std::invalid_argument);
    a.insert_midpoints({0}, pd::Refinement::delta);
    EXPECT_THROW(a.split({1}, pd::Refinement::delta), std::invalid_argument);
    EXPECT_THROW(a.insert_midpoints({1000}, pd::Refinement::delta), std::invalid_argument);
    EXPECT_THROW(a.refine_around({5}, 1, pd::Refinement::delta), std::invalid_argument);  // no cell tree
    const std::size_t before = a.size();
    a.insert_midpoints({at(a, 4, 4), at(a, 4, 4)}, pd::Refinement::delta);  // listed twice: refined once
    EXPECT_EQ(a.size(), before + 8);
    EXPECT_EQ(a.level[at(a, 4, 4)], 1);
}
