// The composed scene (scene.hpp): the bonds own the influence function (PMB's micromodulus takes it
// from them), any type with the DamageRule protocol plugs into an explicit run, and the scene
// calls it in the documented order (break_bonds before each force evaluation, record after it).
#include "pd/core/lattice.hpp"
#include "pd/models/pmb.hpp"
#include "pd/scene.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

using namespace pd;

namespace {
constexpr double dx = 1e-3;

// A damage rule written here, not in the library: it breaks the pair of bond `k` at its
// `at`-th break_bonds call and logs every call ('b' break, 'r' record).
struct BreakOnePair {
    std::int64_t k = 0;
    int at = 0;
    int calls = 0;
    std::string log;
    long break_bonds(Bonds& b, const Field<3>&)
    {
        log += 'b';
        return ++calls == at ? b.break_pair(k) : 0;
    }
    template <class Model>
    const BondWork* bond_work(const Bonds&) const { return nullptr; }
    template <class Model>
    void record(const Model&, const Bonds&, const Field<3>&) { log += 'r'; }
};
}  // namespace

// 3D continuum micromodulus with omega = delta/|xi| (inv_xi): M1 = int_0^delta (delta/r) r 4 pi r^2 dr
// = 4 pi delta^4 / 3, c = 2 D^2 K / M1 = 27 K / (2 pi delta^4), not the 18 K / (pi delta^4) of omega = 1.
TEST(Scene, BondsCarryTheInfluenceFunction)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    const double delta = 2.5 * dx;
    const Bonds b = build_bonds(body, delta, {.influence = Influence::parse("inv_xi"), .keep = {}});
    const Elastic mat = Elastic::from_E_nu(200e9, 0.25);
    const PMB pmb({.material = mat, .dim = 3}, b);
    EXPECT_NEAR(pmb.c / (27 * mat.K / (2 * std::numbers::pi * std::pow(delta, 4))), 1.0, 1e-12);
    EXPECT_EQ(b.influence.kind, Influence::Kind::inv_xi);
}

TEST(Scene, AnyDamageRuleWithTheProtocolDrivesAnExplicitRun)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.5 * dx);
    PMB model({.material = Elastic::from_E_nu(200e9, 0.25), .dim = 3}, bonds);
    BreakOnePair rule{.k = 7, .at = 3, .calls = 0, .log = {}};
    Scene<3, PMB> scene(body, bonds, model);
    scene.set_damage(rule);
    EXPECT_TRUE(bonds.has_damage());  // set_damage enables the intact flags
    Explicit<3, PMB> sim(scene, 7850);
    sim.start();
    for (int n = 0; n < 3; ++n) sim.step(1e-8);
    EXPECT_EQ(rule.log, "brbrbrbr");  // start + 3 steps, each: break, force, record
    EXPECT_EQ(sim.broken_bonds, 2);   // both halves of the pair, at the third evaluation
    EXPECT_EQ(bonds.intact[7], 0);
    EXPECT_EQ(bonds.intact[bonds.reverse[7]], 0);
}
