// The composed scene (scene.hpp): the bonds own the influence function (PMB's micromodulus takes it
// from them), any type with the DamageRule protocol plugs into an explicit run, and the scene
// calls it in the documented order (break_bonds before each force evaluation, record after it);
// a heat component (a temperature field) takes its thermal steps on its own clock, before the forces
// of the mechanical step, and belongs to the scene's checkpoint.
#include "pd/core/lattice.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/models/pmb.hpp"
#include "pd/scene.hpp"
#include "pd/time/heat_cvode.hpp"
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

// A damage rule that breaks nothing and notes the thermal step count of `field` at each force evaluation.
struct SeeHeat {
    const TemperatureField* field = nullptr;
    std::vector<long> seen;
    long break_bonds(Bonds&, const Field<3>&) { return seen.push_back(field->step), 0; }
    template <class Model>
    const BondWork* bond_work(const Bonds&) const { return nullptr; }
    template <class Model>
    void record(const Model&, const Bonds&, const Field<3>&) {}
};

// An insulated body heated uniformly by s [W/m^3]: no heat flows between nodes, so each explicit
// thermal step of dt_th raises every temperature by exactly s dt_th / (rho c).
struct HeatedBox {
    Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.5 * dx);
    PMB model{{.material = Elastic::from_E_nu(200e9, 0.25), .dim = 3}, bonds};
    static constexpr double rho_c = 4e6, s = 1e9, theta0 = 20;  // [J/(m^3 K)], [W/m^3], [K]
    std::unique_ptr<ConductingField<Agwai>> field(double dt_th)
    {
        HeatLoads loads;
        loads.source.assign(body.size(), s);
        return make_temperature_field(Agwai({.k = 50}, body, bonds), bonds, std::vector<double>(body.size(), rho_c), loads,
                                      std::vector<double>(body.size(), theta0), HeatIntegrator::explicit_euler, dt_th);
    }
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

TEST(Scene, HeatComponentStepsOnItsOwnClockBeforeTheForces)
{
    const double dt = 1e-8;
    for (const double ratio : {3.0, 2.5}) {  // N_sync = 3, and a thermal step of 2.5 mechanical steps
        HeatedBox h;
        auto field = h.field(ratio * dt);
        SeeHeat rule{.field = field.get(), .seen = {}};
        Scene<3, PMB> scene(h.body, h.bonds, h.model);
        scene.set_damage(rule);
        scene.set_heat(*field);
        Explicit<3, PMB> sim(scene, 7850);
        sim.start();
        const int steps = 10;
        for (int n = 0; n < steps; ++n) sim.step(dt);
        ASSERT_EQ(rule.seen.size(), steps + 1u);
        for (int n = 0; n <= steps; ++n)  // the evaluation of step n sees the thermal steps m with m ratio <= n
            EXPECT_EQ(rule.seen[n], static_cast<long>(std::floor(n / ratio + 1e-9))) << "ratio " << ratio << ", step " << n;
        const double expected = HeatedBox::theta0 + rule.seen.back() * HeatedBox::s * ratio * dt / HeatedBox::rho_c;
        for (double T : field->theta) EXPECT_NEAR(T, expected, 1e-12 * expected) << "ratio " << ratio;
    }
}

TEST(Scene, HeatComponentIsPartOfTheCheckpoint)
{
    const double dt = 1e-8;
    auto run = [&](int first, int second, bool via_checkpoint) {
        HeatedBox h;
        auto field = h.field(2 * dt);
        Scene<3, PMB> scene(h.body, h.bonds, h.model);
        scene.set_heat(*field);
        Explicit<3, PMB> sim(scene, 7850);
        sim.start();
        for (int n = 0; n < first; ++n) sim.step(dt);
        if (via_checkpoint) {
            StateArchive saved;
            sim.state(saved);
            const std::string file = ::testing::TempDir() + "scene_heat.pdstate";
            saved.write(file);
            HeatedBox h2;
            auto field2 = h2.field(2 * dt);
            Scene<3, PMB> scene2(h2.body, h2.bonds, h2.model);
            scene2.set_heat(*field2);
            Explicit<3, PMB> resumed(scene2, 7850);
            StateArchive loading = StateArchive::read(file);
            resumed.state(loading);
            for (int n = 0; n < second; ++n) resumed.step(dt);
            return std::make_pair(field2->theta, field2->step);
        }
        for (int n = 0; n < second; ++n) sim.step(dt);
        return std::make_pair(field->theta, field->step);
    };
    const auto straight = run(7, 6, false), resumed = run(7, 6, true);
    EXPECT_EQ(straight.second, 6);  // 13 steps of dt, thermal steps of 2 dt
    EXPECT_EQ(resumed.second, straight.second);
    EXPECT_EQ(resumed.first, straight.first);  // bit for bit
}
