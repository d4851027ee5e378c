// Multi-level grids (core/refinement.hpp), variable-horizon families (core/variable_horizon.hpp) and the
// interpolation onto new nodes (core/mls.hpp): spec/002 V6 a, b, c, e, f and the ghost-force property
// of the dual horizon (sec. 2.6). References:
// geometry written out in the tests (sub-cell centres, volumes, distances), Newton's third law (a
// dual-horizon body's internal forces sum to zero), and the standard PMB family on a uniform grid.
#include "pd/bond_loop.hpp"
#include "pd/core/mls.hpp"
#include "pd/core/refinement.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/models/pmb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {
constexpr double h0 = 1e-3, m = 3.015;

// A 2D plate of 24 x 12 cells of side h0 (thickness 1 cm) with horizon m h0.
pd::RefinedGrid<2> plate()
{
    return pd::RefinedGrid<2>(pd::box<2>({{0, 0}}, {{24 * h0, 12 * h0}}, h0, 0.01), m * h0);
}

// The node of `g` nearest to p.
int nearest(const pd::RefinedGrid<2>& g, const pd::Vec<2>& p)
{
    int best = 0;
    for (std::size_t i = 1; i < g.size(); ++i)
        if (norm(g.x[i] - p) < norm(g.x[best] - p)) best = static_cast<int>(i);
    return best;
}

// The plate with its left half refined once (delta halves): the grid of a two-level interface.
pd::RefinedGrid<2> left_half_refined()
{
    pd::RefinedGrid<2> g = plate();
    std::vector<int> left;
    for (std::size_t i = 0; i < g.size(); ++i)
        if (g.x.c[0][i] < 12 * h0) left.push_back(static_cast<int>(i));
    g.split(left, pd::Refinement::delta);
    return g;
}

// Sum over nodes of f_i V_i and of |f_i| V_i for the PMB on the families, at a random displacement.
std::pair<double, double> force_balance(const pd::RefinedGrid<2>& g, const pd::HorizonFamilies& f)
{
    const pd::Body<2> body = g.body();
    const pd::PMB::Params p{.material = pd::Elastic::from_E_nu(200e9, 1.0 / 3), .dim = 2, .measure = body.measure};
    pd::PMB model(p, f.bonds);
    model.scale_bonds(pd::horizon_factors(f, [&](double delta) { return pd::PMB::micromodulus(p, pd::Influence{}, delta); }));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1e-6, 1e-6);
    pd::Field<2> y = body.x, force(body.size());
    for (int d = 0; d < 2; ++d)
        for (double& v : y.c[d]) v += u(rng);
    pd::internal_force(model, f.bonds, y, force);
    double sum = 0, size = 0;
    for (int d = 0; d < 2; ++d) {
        double s = 0;
        for (std::size_t i = 0; i < body.size(); ++i) s += force.c[d][i] * body.volume[i], size += std::abs(force.c[d][i]) * body.volume[i];
        sum = std::max(sum, std::abs(s));
    }
    return {sum, size};
}
}  // namespace

TEST(RefinedGrid, MethodBSplitsACellIntoItsSubCellsAndKeepsTheVolume)  // V6a
{
    pd::RefinedGrid<2> g = plate();
    double total = 0;
    for (double v : g.volume) total += v;
    const int p = nearest(g, {{5.5 * h0, 5.5 * h0}});
    g.split({p}, pd::Refinement::delta);
    g.split({g.first_child[p] + 3}, pd::Refinement::delta);  // a grandchild level
    double after = 0;
    for (std::size_t i = 0; i < g.size(); ++i) after += g.active[i] ? g.volume[i] : 0.0;
    EXPECT_NEAR(after, total, 1e-15 * total);  // sums of quarter volumes: a few ulps
    for (int c = 0; c < 4; ++c) {
        const int k = g.first_child[p] + c;
        EXPECT_NEAR(g.x.c[0][k], 5.5 * h0 + (c & 1 ? 0.25 : -0.25) * h0, 1e-18);  // round-off of coordinates ~5e-3 m
        EXPECT_NEAR(g.x.c[1][k], 5.5 * h0 + (c & 2 ? 0.25 : -0.25) * h0, 1e-18);
        EXPECT_EQ(g.volume[k], g.volume[p] / 4);
        EXPECT_EQ(g.h[k], h0 / 2);
        EXPECT_EQ(g.delta[k], m * h0 / 2);
        EXPECT_EQ(g.level[k], 1);
    }
    EXPECT_FALSE(g.active[p]);
    EXPECT_THROW(g.split({p}, pd::Refinement::delta), std::invalid_argument);  // split once only
}

TEST(RefinedGrid, NoCoarserNodeSeesTheNodeRefinedAround)  // V6b, both refinement types, two levels
{
    for (const pd::Refinement rule : {pd::Refinement::delta, pd::Refinement::m}) {
        pd::RefinedGrid<2> g = plate();
        const int n0 = nearest(g, {{12.5 * h0, 6.5 * h0}});
        const pd::Vec<2> X = g.x[n0];
        g.split(g.visibility_zone({n0}), rule);
        std::vector<int> children;
        for (int c = 0; c < 4; ++c) children.push_back(g.first_child[n0] + c);
        g.split(g.visibility_zone(children), rule);
        int level2 = 0;
        for (std::size_t i = 0; i < g.size(); ++i) {
            if (!g.active[i]) continue;
            level2 += g.level[i] == 2;
            if (g.level[i] < 2) {
                EXPECT_GT(norm(g.x[i] - X), g.delta[i]) << "node " << i << " level " << g.level[i];
            }
            EXPECT_EQ(g.level[g.ancestor(static_cast<int>(i))], 0) << i;  // V6f
        }
        EXPECT_GT(level2, 4 * 4 * 9);  // the zone holds whole families, not just the node
        for (int c : children) {  // V6f: the grandchildren of n0 map back to it
            ASSERT_GE(g.first_child[c], 0);
            for (int q = 0; q < 4; ++q) EXPECT_EQ(g.ancestor(g.first_child[c] + q), n0);
        }
    }
}

TEST(RefinedGrid, NestedRefinementKeepsNodesTwoLevelsFinerOutOfEveryHorizon)
{
    pd::RefinedGrid<2> g = plate();
    g.refine_nested([](const pd::Vec<2>& x, double s) { return x[0] < 12 * h0 - s; }, 3, pd::Refinement::delta);
    const std::vector<int> ids = g.ids();
    int deepest = 0;
    for (int i : ids) {
        deepest = std::max(deepest, g.level[i]);
        for (int j : ids)
            if (g.level[j] >= g.level[i] + 2) {
                EXPECT_GT(norm(g.x[j] - g.x[i]), g.delta[i]) << i << " sees " << j;
            }
    }
    EXPECT_EQ(deepest, 3);
}

TEST(RefinedGrid, InterfaceHorizonIsMTimesTheDistanceToTheNearestCoarserNode)  // V6e
{
    pd::RefinedGrid<2> g = left_half_refined();
    EXPECT_GT(g.interface_horizon(m), 0);
    // A child in the column next to the interface (x = 11.75 h0) has its nearest coarse node at
    // (12.5 h0, its parent's y): sqrt(0.75^2 + 0.25^2) h0 = sqrt(10)/4 h0 away.
    const int i = nearest(g, {{11.75 * h0, 6.25 * h0}});
    ASSERT_EQ(g.level[i], 1);
    EXPECT_NEAR(g.delta[i], m * std::sqrt(10.0) / 4 * h0, 1e-15);
    for (const double x : {2.25 * h0, 11.25 * h0}) {  // far from the interface; on the far side of an interface cell
        const int far = nearest(g, {{x, 6.25 * h0}});    // (nearest coarse node sqrt(26)/4 dx0 = 2.55 h away): unchanged
        EXPECT_EQ(g.delta[far], m * h0 / 2) << x;
    }
}

TEST(VariableHorizon, DualHorizonForcesSumToZeroAndSourceHorizonForcesDoNot)
{
    const pd::RefinedGrid<2> g = left_half_refined();
    for (const pd::PartialVolume pv : {pd::PartialVolume::none, pd::PartialVolume::pa_pdlammps, pd::PartialVolume::exact_area}) {
        const auto dual = pd::build_variable_horizon_bonds(g.body(), g.active_delta(), g.active_h(), pd::HorizonCoupling::dual, pv);
        const auto source = pd::build_variable_horizon_bonds(g.body(), g.active_delta(), g.active_h(), pd::HorizonCoupling::source, pv);
        EXPECT_EQ(std::count(dual.bonds.reverse.begin(), dual.bonds.reverse.end(), -1), 0);
        EXPECT_GT(std::count(source.bonds.reverse.begin(), source.bonds.reverse.end(), -1), 0);  // lost bonds at the interface
        const auto [sum_dual, size_dual] = force_balance(g, dual);
        const auto [sum_source, size_source] = force_balance(g, source);
        // Round-off: measured 8e-19 .. 2.5e-18 of sum |f| V (source: 2.6e-3 .. 2.9e-3); bound 1e-14.
        EXPECT_LT(sum_dual, 1e-14 * size_dual) << int(pv);
        EXPECT_GT(sum_source, 1e-4 * size_source) << int(pv);  // ghost forces
    }
}

TEST(VariableHorizon, OneHorizonGivesTheUniformFamilyAndItsForces)
{
    const pd::Body<2> lattice = pd::box<2>({{0, 0}}, {{24 * h0, 12 * h0}}, h0, 0.01);
    const pd::PMB::Params p{.material = pd::Elastic::from_E_nu(200e9, 1.0 / 3), .dim = 2, .measure = 0.01};
    for (const double ratio : {m, 3.0})  // 3: partners at exactly delta, kept by the round-off rule of build_bonds
    for (const pd::PartialVolume pv : {pd::PartialVolume::pa_pdlammps, pd::PartialVolume::exact_area}) {
        const pd::RefinedGrid<2> g(lattice, ratio * h0);
        pd::BondOptions options;
        options.partial_volume = pv;
        const pd::Bonds standard = pd::build_bonds(lattice, ratio * h0, options);
        const auto dual = pd::build_variable_horizon_bonds(g.body(), g.active_delta(), g.active_h(), pd::HorizonCoupling::dual, pv);
        ASSERT_EQ(dual.bonds.partner, standard.partner);
        pd::PMB a(p, standard), b(p, dual.bonds);
        b.scale_bonds(pd::horizon_factors(dual, [&](double delta) { return pd::PMB::micromodulus(p, pd::Influence{}, delta); }));
        for (std::size_t k = 0; k < a.coef.size(); ++k) EXPECT_NEAR(b.coef[k], a.coef[k], 1e-14 * a.coef[k]) << k;
    }
}

TEST(Interpolation, ChildrenGetAnyLinearFieldExactlyAndNothingFromAcrossACrack)  // V6c
{
    const pd::RefinedGrid<2> g0 = plate();
    const pd::Bonds bonds = [&] {  // the families of the initial grid, with the bonds across x = 10 h0 broken
        pd::Bonds b = pd::build_bonds(g0.body(), m * h0);
        b.enable_damage();
        for (std::size_t i = 0; i < g0.size(); ++i)
            pd::for_family(b, i, [&](std::int64_t k, int j) { b.intact[k] = (g0.x.c[0][i] < 10 * h0) == (g0.x.c[0][j] < 10 * h0); });
        return b;
    }();
    pd::Field<2> u(g0.size());  // u = a + B x, a written out
    for (std::size_t i = 0; i < g0.size(); ++i)
        u.c[0][i] = 1e-4 + 2e-3 * g0.x.c[0][i] - 5e-4 * g0.x.c[1][i], u.c[1][i] = -3e-5 + 7e-4 * g0.x.c[0][i] + 1e-3 * g0.x.c[1][i];
    for (const pd::Vec<2> at : {pd::Vec<2>{{9.5 * h0, 5.5 * h0}}, pd::Vec<2>{{0.5 * h0, 0.5 * h0}}}) {  // next to the crack; a corner
        pd::RefinedGrid<2> g = g0;
        const int p = nearest(g, at);
        g.split({p}, pd::Refinement::delta);
        std::vector<int> support{p};
        pd::for_intact_bonds(bonds, p, [&](std::int64_t, int j) { support.push_back(j); });
        for (int c = 0; c < 4; ++c) {
            const pd::Vec<2> z = g.x[g.first_child[p] + c];
            const std::vector<double> phi = pd::mls_weights(g0.x, support, z, 1.01 * m * h0 + h0);
            double ux = 0, uy = 0;
            for (std::size_t q = 0; q < support.size(); ++q) ux += phi[q] * u.c[0][support[q]], uy += phi[q] * u.c[1][support[q]];
            EXPECT_NEAR(ux, 1e-4 + 2e-3 * z[0] - 5e-4 * z[1], 1e-15) << c;  // round-off of O(1e-4) values
            EXPECT_NEAR(uy, -3e-5 + 7e-4 * z[0] + 1e-3 * z[1], 1e-15) << c;
            for (int j : support) EXPECT_LT(g0.x.c[0][j], 10 * h0);  // the support stays on the parent's side of the crack
        }
    }
    // A support on one line cannot fit a plane: the nearest node's value alone.
    const std::vector<double> phi = pd::mls_weights(g0.x, {0, 1, 2}, pd::Vec<2>{{1.2 * h0, 0.9 * h0}}, 4 * h0);
    EXPECT_EQ(phi, (std::vector<double>{0, 1, 0}));
}
