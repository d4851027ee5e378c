// Implicit Euler keeps its sparse LU factorisation across steps only while the operator is the same
// (conduction.hpp, operator_may_have_changed): a bond that breaks between two steps, or a deformation
// gradient that changes (correspondence heat with set_deformation), must reach the next step.
// Reference: a fresh Conduction built on the changed bonds or at the changed F, one step from the same
// temperatures.
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace {

constexpr double dx = 1e-3, thickness = 1e-3, rho_c = 3.9e6;  // [m], [m], [J/(m^3 K)]

pd::Body<2> plate() { return pd::box<2>(pd::Vec<2>{0, 0}, pd::Vec<2>{12 * dx, 6 * dx}, dx, thickness); }

std::vector<double> ramp(const pd::Body<2>& b)
{
    std::vector<double> t(b.size());
    for (std::size_t i = 0; i < t.size(); ++i) t[i] = 300 + 5e3 * b.x.c[0][i] + 1e3 * std::sin(3e3 * b.x.c[1][i]);
    return t;
}

TEST(ImplicitEuler, BondsBrokenBetweenStepsReachTheNextStep)
{
    const pd::Body<2> body = plate();
    pd::Bonds bonds = pd::build_bonds(body, 3.05 * dx);
    bonds.enable_damage();
    pd::Agwai model({16, thickness}, body, bonds);
    const std::vector<double> rc(body.size(), rho_c);
    pd::Conduction<pd::Agwai> heat(model, bonds, rc, {});
    std::vector<double> theta = ramp(body);
    const double dt = 50 * pd::thermal_critical_step(model, bonds, heat, theta);
    heat.implicit_euler(theta, dt);  // factorised on the intact body
    auto left = [&](std::size_t i) { return body.x.c[0][i] < 6 * dx; };
    for (std::size_t i = 0; i < bonds.nodes(); ++i)  // a cut through the middle: the halves insulate each other
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k)
            if (left(i) != left(std::size_t(bonds.partner[k]))) bonds.intact[k] = 0;
    std::vector<double> expected = theta;
    pd::Conduction<pd::Agwai> fresh(model, bonds, rc, {});
    fresh.implicit_euler(expected, dt);
    double heat_left = 0;  // held by the left half before the step [J / (rho c)]
    for (std::size_t i = 0; i < body.size(); ++i) heat_left += left(i) ? body.volume[i] * theta[i] : 0.0;
    heat.implicit_euler(theta, dt);
    for (std::size_t i = 0; i < theta.size(); ++i) EXPECT_EQ(theta[i], expected[i]);  // the same matrix, the same LU
    double after = 0;
    for (std::size_t i = 0; i < body.size(); ++i) after += left(i) ? body.volume[i] * theta[i] : 0.0;
    EXPECT_NEAR(after, heat_left, 1e-12 * heat_left);  // nothing crossed the cut (to the LU solve's round-off)
}

TEST(ImplicitEuler, ChangedDeformationReachesTheNextStep)
{
    const pd::Body<2> body = plate();
    const pd::Bonds bonds = pd::build_bonds(body, 3.05 * dx);
    using Mat = pd::CorrespondenceHeat<2>::Mat;
    std::vector<Mat> F(body.size(), Mat::Identity());
    pd::CorrespondenceHeat<2> model({16, 1.0, thickness}, body, bonds);
    model.set_deformation(&F);
    const std::vector<double> rc(body.size(), rho_c);
    pd::Conduction<pd::CorrespondenceHeat<2>> heat(model, bonds, rc, {});
    std::vector<double> theta = ramp(body);
    const double dt = 50 * pd::thermal_critical_step(model, bonds, heat, theta);
    heat.implicit_euler(theta, dt);  // factorised at F = I
    for (Mat& f : F) f(0, 0) = 1.5;  // stretched along x: conducts less along x (det F F^-1 F^-T)
    std::vector<double> expected = theta, stale = theta;
    pd::CorrespondenceHeat<2> at_f({16, 1.0, thickness}, body, bonds);
    at_f.set_deformation(&F);
    pd::Conduction<pd::CorrespondenceHeat<2>> fresh(at_f, bonds, rc, {});
    fresh.implicit_euler(expected, dt);
    pd::CorrespondenceHeat<2> at_i({16, 1.0, thickness}, body, bonds);
    pd::Conduction<pd::CorrespondenceHeat<2>> undeformed(at_i, bonds, rc, {});
    undeformed.implicit_euler(stale, dt);  // what a stale factorisation would give
    heat.implicit_euler(theta, dt);
    double diff = 0, gap = 0;
    for (std::size_t i = 0; i < theta.size(); ++i)
        diff = std::max(diff, std::abs(theta[i] - expected[i])), gap = std::max(gap, std::abs(stale[i] - expected[i]));
    EXPECT_GT(gap, 1e-3);             // F matters here: the test can tell the two apart
    EXPECT_LE(diff, 1e-12 * 300);     // the same operator (assembled in the same order)
}

}  // namespace
