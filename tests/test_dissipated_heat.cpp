// Heat from dissipation in a scene (scene.hpp, DissipativeModel; spec/000a eqs. 3.22-3.24 with
// erratum E11, verification case V9): with a prescribed constant dissipated power p and conduction
// off, the temperature rises by p N_sync(MH) dt / (rho c) at every N_sync(MH)-th mechanical step and
// not in between, the accumulator holds the heat not yet released and is emptied at each release,
// the total rise p T / (rho c) does not depend on N_sync(MH), held nodes keep their temperature, the
// accumulator is part of the checkpoint, CVODE refuses deposited heat, and N_sync(MH) = 0 releases none.
#include "pd/core/lattice.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/models/pmb.hpp"
#include "pd/scene.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pd;

namespace {
constexpr double dx = 1e-3, rho_c = 4e6, p = 2e10, theta0 = 300, dt = 1e-8;  // [m], [J/(m^3 K)], [W/m^3], [K], [s]

// PMB that dissipates the prescribed power p: step_heat = p dt_step (set by the test after start()).
struct DissipatingPMB : PMB {
    using PMB::PMB;
    double heat_per_step = 0;  // [J/m^3]
    double step_heat(std::size_t) const { return heat_per_step; }
};
static_assert(DissipativeModel<DissipatingPMB>);

struct Box {
    Body<3> body = box<3>({{0, 0, 0}}, {{3 * dx, 3 * dx, 3 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.5 * dx);
    Bonds isolated = build_bonds(body, 0.5 * dx);  // no bonds: conduction off
    DissipatingPMB model{PMB::Params{.material = Elastic::from_E_nu(200e9, 0.25), .dim = 3}, bonds};
    std::unique_ptr<ConductingField<Agwai>> field(double dt_th, std::vector<int> held = {})
    {
        HeatLoads loads;
        for (int i : held) loads.fixed.push_back(i), loads.fixed_value.push_back(theta0);
        return make_temperature_field(Agwai({.k = 50}, body, isolated), isolated, std::vector<double>(body.size(), rho_c), loads,
                                      std::vector<double>(body.size(), theta0), HeatIntegrator::explicit_euler, dt_th);
    }
};
}  // namespace

TEST(DissipatedHeat, ReleasedEveryNsyncStepsAndItsTotalDoesNotDependOnNsync)
{
    const int steps = 60;
    for (long nsync : {1L, 6L, 7L, 12L}) {
        Box b;
        auto field = b.field(dt, {0});  // node 0 held
        Scene<3, DissipatingPMB> scene(b.body, b.bonds, b.model);
        scene.set_heat(*field, nsync);
        Explicit<3, DissipatingPMB> sim(scene, 7850);
        sim.start();
        b.model.heat_per_step = p * dt;
        for (int n = 1; n <= steps; ++n) {
            sim.step(dt);
            // The last release, at step r (a multiple of N_sync), came before step r's force evaluation:
            // the field holds the heat of steps 1 .. r - 1, the accumulator that of steps r .. n.
            const long r = n / nsync * nsync;
            const double in_field = double(std::max(r - 1, 0L)) * p * dt;
            ASSERT_NEAR(field->theta[1], theta0 + in_field / rho_c, 1e-12 * theta0) << "N_sync " << nsync << ", step " << n;
            ASSERT_NEAR(sim.scene.accumulated_heat()[1], n * p * dt - in_field, 1e-9 * p * dt) << "N_sync " << nsync << ", step " << n;
            ASSERT_EQ(field->theta[0], theta0);  // held
        }
        // After the last release: all but the heat of the steps since the last release.
        sim.step(dt);  // step 61: releases the heat of steps 1 .. 60 when N_sync divides 60, 61 for N_sync 1
        const long last = (steps + 1) / nsync * nsync;
        EXPECT_NEAR(field->theta[1], theta0 + (last - 1) * p * dt / rho_c, 1e-12 * theta0) << nsync;
    }
}

// p T / (rho c) with T = 60 dt, N_sync(MH) = 1, 6, 12, 60: the same total once released.
TEST(DissipatedHeat, TotalRiseIsPTOverRhoC)
{
    for (long nsync : {1L, 6L, 12L, 60L}) {
        Box b;
        auto field = b.field(dt);
        Scene<3, DissipatingPMB> scene(b.body, b.bonds, b.model);
        scene.set_heat(*field, nsync);
        Explicit<3, DissipatingPMB> sim(scene, 7850);
        sim.start();
        b.model.heat_per_step = p * dt;
        for (int n = 1; n <= 60; ++n) sim.step(dt);
        b.model.heat_per_step = 0;  // steps 61 .. 61 + nsync - 1 release the rest and add none
        for (long n = 1; n <= nsync; ++n) sim.step(dt);
        for (double T : field->theta) EXPECT_NEAR(T, theta0 + p * 60 * dt / rho_c, 1e-12 * theta0) << "N_sync " << nsync;
        for (double e : sim.scene.accumulated_heat()) EXPECT_EQ(e, 0.0);
    }
}

TEST(DissipatedHeat, AccumulatorIsPartOfTheCheckpoint)
{
    auto run = [&](bool via_checkpoint) {
        Box b;
        auto field = b.field(dt);
        Scene<3, DissipatingPMB> scene(b.body, b.bonds, b.model);
        scene.set_heat(*field, 7);
        Explicit<3, DissipatingPMB> sim(scene, 7850);
        sim.start();
        b.model.heat_per_step = p * dt;
        for (int n = 0; n < 10; ++n) sim.step(dt);  // 3 steps of heat in the accumulator
        if (!via_checkpoint) {
            for (int n = 0; n < 5; ++n) sim.step(dt);
            return field->theta;
        }
        StateArchive saved;
        sim.state(saved);
        const std::string file = ::testing::TempDir() + "dissipated_heat.pdstate";
        saved.write(file);
        Box b2;
        auto field2 = b2.field(dt);
        Scene<3, DissipatingPMB> scene2(b2.body, b2.bonds, b2.model);
        scene2.set_heat(*field2, 7);
        Explicit<3, DissipatingPMB> resumed(scene2, 7850);
        StateArchive loading = StateArchive::read(file);
        resumed.state(loading);
        b2.model.heat_per_step = p * dt;
        for (int n = 0; n < 5; ++n) resumed.step(dt);
        return field2->theta;
    };
    const std::vector<double> straight = run(false), resumed = run(true);
    EXPECT_EQ(resumed, straight);
    EXPECT_NEAR(straight[1], theta0 + 13 * p * dt / rho_c, 1e-12 * theta0);  // released at step 14: steps 1 .. 13
}

TEST(DissipatedHeat, RefusalsAndBadInput)
{
    Box b;
    HeatLoads loads;
    auto cv = make_temperature_field(Agwai({.k = 50}, b.body, b.isolated), b.isolated, std::vector<double>(b.body.size(), rho_c), loads,
                                     std::vector<double>(b.body.size(), theta0), HeatIntegrator::cvode, dt);
    EXPECT_THROW(cv->deposit(std::vector<double>(b.body.size(), 1.0)), std::invalid_argument);
    auto field = b.field(dt);
    EXPECT_THROW(field->deposit(std::vector<double>(3, 1.0)), std::invalid_argument);
    Scene<3, DissipatingPMB> scene(b.body, b.bonds, b.model);
    EXPECT_THROW(scene.set_heat(*field, -1), std::invalid_argument);
}

// N_sync(MH) = 0, weak coupling: the field follows its own clock and the dissipation never reaches it.
TEST(DissipatedHeat, ZeroSyncReleasesNothing)
{
    Box b;
    auto field = b.field(dt);
    Scene<3, DissipatingPMB> scene(b.body, b.bonds, b.model);
    scene.set_heat(*field, 0);
    Explicit<3, DissipatingPMB> sim(scene, 7850);
    sim.start();
    b.model.heat_per_step = p * dt;
    for (int n = 1; n <= 20; ++n) sim.step(dt);
    EXPECT_EQ(field->step, 20);  // the thermal clock ran
    for (double T : field->theta) EXPECT_EQ(T, theta0);
    EXPECT_TRUE(sim.scene.accumulated_heat().empty());
}
