// Thermal expansion of PMB, LPS, LPS with SCF and PALS under a temperature field, on a bar long enough
// for the chunk path (nodes 3 .. 16 of each 20-node row): theta = theta_ref gives the isothermal forces
// bit for bit, the force is minus the gradient of the energy, the chunk path agrees with the per-node path.
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include "energy_gradient.hpp"
#include "thermal_expansion_fixtures.hpp"

#include <random>
#include <vector>

using namespace pd;
using namespace pd_test::thermal_expansion_fixtures;

TEST(ThermalExpansion, ReferenceTemperatureGivesTheIsothermalForcesBitForBit)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> U(-1e-6, 1e-6);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    std::vector<Field<3>> iso;
    for_each_model(b, body, nullptr, [&](const char*, auto& model) { internal_force(model, b, y, iso.emplace_back()); });
    int q = 0;
    for_each_model(b, body, &theta, [&](const char* name, auto& model) {
        Field<3> f;
        internal_force(model, b, y, f);
        for (int d = 0; d < 3; ++d) EXPECT_EQ(f.c[d], iso[q].c[d]) << name;
        ++q;
    });
}

// E = sum_i W_i V_i with the temperatures held: central differences at a corner, a surface and a
// bulk node. Tolerance 1e-6 of |f_i V_i| (step 1e-9 m against displacements 1e-7 m, thermal
// extensions ~1e-7 m; as LPS_SCF.ForceIsEnergyGradientWithNonUniformSCF).
TEST(ThermalExpansion, ForceIsEnergyGradientUnderATemperatureField)
{
    const double h = 1e-9;
    const Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> U(-1e-7, 1e-7), T(-10, 10);
    std::vector<double> theta(body.size());
    for (auto& t : theta) t = theta_ref + heat + T(gen);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    for_each_model(b, body, &theta, [&](const char* name, auto& model) {
        pd_test::expect_force_is_energy_gradient(model, b, body, y, {0, 2 + 2 * 6, 2 + 2 * 6 + 3 * 36}, h, 1e-6, name);
    });
}

// The chunk path (undamaged bonds) against the per-node path (the same bonds with damage enabled and
// none broken) under a non-uniform temperature: the same terms summed in another order, so equal to
// round-off (1e-12 of the largest force).
TEST(ThermalExpansion, ChunkedAndPerNodePathsAgreeUnderATemperatureField)
{
    const Body<3> body = bar();
    std::mt19937 gen(7);
    std::uniform_real_distribution<double> T(-10, 10), U(-1e-7, 1e-7);
    std::vector<double> theta(body.size());
    for (auto& t : theta) t = theta_ref + heat + T(gen);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    expect_chunk_path_matches_per_node(body, y, [&](const Bonds& b, auto&& fn) { for_each_model(b, body, &theta, fn); });
}
