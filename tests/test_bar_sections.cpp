// tests/test_bar_sections.cpp -- the gripped-bar helpers: gauge layers, axis nodes, grip reaction,
// section means and lateral stretch (problems/common/measure/bar_sections.hpp); grip conditions and the uniform
// uniaxial start field (problems/common/grips.hpp). References: hand counts on a 10 x 2 x 1 mm bar, dx = 0.5
// mm (nx = 20 layers, 4 x 2 nodes per layer), and affine fields whose slopes are known exactly.
#include "problems/common/grips.hpp"
#include "problems/common/measure/bar_sections.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd;

namespace {

constexpr double L = 10e-3, W = 2e-3, T = 1e-3, dx = 0.5e-3;  // [m]
constexpr double delta = 3.05 * dx;                            // [m]
constexpr double tight = 1e-12;  // round-off of sums over 8 to 16 nodes of O(1) relative terms

GrippedBar bar() { return gripped_bar(L, W, T, dx, 2 * delta); }

// Layers: a = round((5 - 1.525)/0.5 - 0.5) = round(6.45) = 6, b = round(13.05 - 0.5) = 13 (12.55),
// dist = 7 dx = 3.5 mm; mid-length layers 9 and 10 (nx = 20 even); 8 nodes per layer.
TEST(BarSections, GaugeLayersMatchHandCounts)
{
    const GrippedBar g = bar();
    const BarGauge s = bar_gauge(g.body, L, dx, delta);
    EXPECT_NEAR(s.dist, 7 * dx, tight * dx);
    ASSERT_EQ(s.sec_a.size(), 8u);
    ASSERT_EQ(s.sec_b.size(), 8u);
    EXPECT_EQ(s.mid.size(), 16u);
    for (int i : s.sec_a) EXPECT_NEAR(g.body.x.c[0][i], 6.5 * dx, tight * dx);
    for (int i : s.sec_b) EXPECT_NEAR(g.body.x.c[0][i], 13.5 * dx, tight * dx);
    for (int i : s.mid) EXPECT_TRUE(std::abs(g.body.x.c[0][i] - L / 2) < dx);
    for (std::size_t k = 1; k < s.sec_a.size(); ++k) EXPECT_LT(s.sec_a[k - 1], s.sec_a[k]);  // node order
    // delta longer than half the bar: the layers clamp to the end layers 0 and nx - 1 = 19.
    EXPECT_NEAR(bar_gauge(g.body, L, dx, 20 * L).dist, 19 * dx, tight * dx);
}

// Axis nodes: y centres 0.25, 0.75, 1.25, 1.75 mm, within dx of W/2 = 1 mm: 0.75 and 1.25; z centres
// 0.25, 0.75 mm, both within dx of T/2 = 0.5 mm: 4 of the 8 nodes of a layer.
TEST(BarSections, AxisNodesOfASection)
{
    const GrippedBar g = bar();
    const BarGauge s = bar_gauge(g.body, L, dx, delta);
    int on_axis = 0;
    for (int i : s.sec_a) on_axis += near_bar_axis(g.body, i, W, T, dx);
    EXPECT_EQ(on_axis, 4);
}

// f_x = -3 N/m^3 on every node of the right grip: F = 3 V n_grip (reaction of the grip, positive).
TEST(BarSections, GripReactionSumsTheGripNodes)
{
    const GrippedBar g = bar();
    Field<3> f(g.body.size());
    for (int i : g.right) f.c[0][i] = -3.0;
    for (int i : g.left) f.c[0][i] = 100.0;  // other nodes do not count
    const double V = dx * dx * dx;
    EXPECT_NEAR(axial_reaction(f, g.body, g.right), 3.0 * V * g.right.size(), tight * 3.0 * V * g.right.size());
}

// Affine field u_x = eps x, u_y = (mu_y - 1)(y - W/2), u_z = (mu_z - 1)(z - T/2): the gauge strain is
// eps and the lateral stretches of the mid-length layers are mu_y, mu_z.
TEST(BarSections, AffineFieldGivesItsStrainAndStretches)
{
    const GrippedBar g = bar();
    const BarGauge s = bar_gauge(g.body, L, dx, delta);
    const double eps = 0.01, mu_y = 0.9967, mu_z = 0.9971;
    Field<3> u(g.body.size());
    for (std::size_t i = 0; i < g.body.size(); ++i) {
        u.c[0][i] = eps * g.body.x.c[0][i];
        u.c[1][i] = (mu_y - 1) * (g.body.x.c[1][i] - W / 2);
        u.c[2][i] = (mu_z - 1) * (g.body.x.c[2][i] - T / 2);
    }
    EXPECT_NEAR(mean_axial_displacement(u, s.sec_a), eps * 6.5 * dx, tight * eps * dx);
    const double measured = (mean_axial_displacement(u, s.sec_b) - mean_axial_displacement(u, s.sec_a)) / s.dist;
    EXPECT_NEAR(measured, eps, tight * eps);
    EXPECT_NEAR(lateral_stretch(g.body.x, u, s.mid, 1), mu_y, tight);
    EXPECT_NEAR(lateral_stretch(g.body.x, u, s.mid, 2), mu_z, tight);
}

TEST(BarGrips, PrescriptionsInOrder)
{
    const GrippedBar g = bar();
    Boundary<3> clamped, axial;
    grip_bar_ends(clamped, g.left, g.right, TimeFunction::constant(1e-4), Grips::clamped);
    grip_bar_ends(axial, g.left, g.right, TimeFunction::constant(1e-4), Grips::axial);
    ASSERT_EQ(clamped.prescribed.size(), 6u);
    for (int k = 0; k < 6; ++k) {
        EXPECT_EQ(clamped.prescribed[k].component, k % 3);
        EXPECT_EQ(clamped.prescribed[k].nodes, k < 3 ? g.left : g.right);
        EXPECT_EQ(clamped.prescribed[k].kind, Prescribed::Kind::displacement);
    }
    ASSERT_EQ(axial.prescribed.size(), 2u);
    EXPECT_EQ(axial.prescribed[0].nodes, g.left);
    EXPECT_EQ(axial.prescribed[1].nodes, g.right);
    EXPECT_EQ(axial.prescribed[0].component, 0);
    EXPECT_EQ(axial.prescribed[1].component, 0);
}

// u_x = U clamp(x/L, 0, 1): 0 in the left grip, U in the right one; lateral -nu eps (y - W/2) in
// the bar, and in the grips too unless they are clamped.
TEST(BarGrips, UniaxialStartField)
{
    const GrippedBar g = bar();
    const double U = 1e-4, eps = U / L, nu = 0.3;
    for (Grips kind : {Grips::clamped, Grips::axial}) {
        Field<3> u(g.body.size());
        uniaxial_bar_field(g.body, L, W, T, U, eps, nu, kind, u);
        for (std::size_t i = 0; i < g.body.size(); ++i) {
            const double x = g.body.x.c[0][i], y = g.body.x.c[1][i], z = g.body.x.c[2][i];
            const bool grip = x < 0 || x > L;
            EXPECT_NEAR(u.c[0][i], x < 0 ? 0 : x > L ? U : U * x / L, tight * U);
            const double scale = kind == Grips::clamped && grip ? 0.0 : 1.0;
            EXPECT_NEAR(u.c[1][i], -scale * nu * eps * (y - W / 2), tight * U);
            EXPECT_NEAR(u.c[2][i], -scale * nu * eps * (z - T / 2), tight * U);
        }
    }
}

}  // namespace
