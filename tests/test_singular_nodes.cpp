// The singular-node rule for correspondence with the critical-stretch criterion (damage/
// singular_nodes.hpp, time/verlet.hpp; spec/000c sec. 2.5): a node whose family is reduced to
// bonds in one plane has a singular shape tensor by construction (rank 2), so Explicit must break
// all its bonds (both directions) at the next step, leave every other node's remaining bonds, and
// respect no-fail nodes and the switch CriticalStretch::detach_singular.
#include "pd/damage/critical_stretch.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace pd;
using C3 = Correspondence<3>;

namespace {
constexpr double dx = 1e-3;

struct Case {
    long intact_of_c = 0, intact_total = 0, detached = 0;
};

// 5^3 block, node c at the centre keeps only its bonds in the plane z = z_c (and their reverses).
Case run(bool protect_c, bool rule_on)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{5 * dx, 5 * dx, 5 * dx}}, dx);
    Bonds bonds = build_bonds(body, 3.05 * dx);
    bonds.enable_damage();
    std::size_t c = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        if (std::abs(body.x.c[0][i] - 2.5 * dx) + std::abs(body.x.c[1][i] - 2.5 * dx) + std::abs(body.x.c[2][i] - 2.5 * dx) < 1e-9)
            c = i;
    for (std::int64_t k = bonds.begin(c); k < bonds.end(c); ++k)
        if (std::abs(body.x.c[2][bonds.partner[k]] - body.x.c[2][c]) > 1e-9) bonds.intact[k] = bonds.intact[bonds.reverse[k]] = 0;
    const long intact0 = std::count(bonds.intact.begin(), bonds.intact.end(), 1);
    C3 model({Elastic::from_E_nu(200e9, 0.3), C3::Law::linear, 0.02}, body, bonds);
    Explicit<3, C3> ex(body, bonds, model, 7850);
    CriticalStretch cs = CriticalStretch::uniform(1.0);  // no bond reaches it: only the rule breaks bonds
    cs.detach_singular = rule_on;
    if (protect_c) cs.protect({static_cast<int>(c)}, body.size());
    ex.scene.set_damage(cs);
    ex.start();
    for (int n = 0; n < 2; ++n) ex.step(1e-8);
    Case r;
    for (std::int64_t k = bonds.begin(c); k < bonds.end(c); ++k) r.intact_of_c += bonds.intact[k];
    r.intact_total = std::count(bonds.intact.begin(), bonds.intact.end(), 1);
    r.detached = cs.detached_nodes;
    EXPECT_GT(r.intact_total, 0);
    if (!protect_c && rule_on) {
        EXPECT_EQ(intact0 - r.intact_total, 2 * 24);  // c's in-plane bonds, both ways
    }
    return r;
}
}  // namespace

TEST(SingularNodes, CoplanarFamilyLosesAllBondsUnderTheRule)
{
    const Case on = run(false, true);
    EXPECT_EQ(on.intact_of_c, 0);
    EXPECT_EQ(on.detached, 1);
}

TEST(SingularNodes, NoFailNodeAndSwitchedOffRuleKeepTheBonds)
{
    // c's in-plane family: the 5 x 5 square of offsets (a, b), |a|, |b| <= 2 (the block), minus the
    // centre: 24 bonds, all within the horizon (a^2 + b^2 <= 8 < 3.05^2).
    EXPECT_EQ(run(true, true).intact_of_c, 24);
    EXPECT_EQ(run(false, false).intact_of_c, 24);
}
