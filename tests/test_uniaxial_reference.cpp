// reference/uniaxial_stretch (the closed forms of problems/3d/large_stretch.cpp): small-strain
// limits (linear elasticity: slope E, lateral contraction nu; PMB continuum: E = 1.5 K, nu = 1/4),
// the hypoelastic curve E ln(lambda) lambda^(-2 nu), SVK's lambda (lambda^2 - 1) E / 2, and the
// PMB continuum at a finite stretch against an independent 2D (theta, phi) midpoint quadrature.
#include "reference/uniaxial_stretch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace pd::ref;

namespace {
constexpr double E = 100e9, nu = 0.33;  // [Pa], [-]
const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
}  // namespace

// eps = 1e-6: the O(eps) nonlinearity is 1e-6 relative; 1e-5 leaves room for the quadrature.
TEST(UniaxialReference, SmallStrainIsLinearElasticity)
{
    const double eps = 1e-6;
    for (UniaxialLaw law : {UniaxialLaw::hypoelastic, UniaxialLaw::saint_venant_kirchhoff, UniaxialLaw::lps_continuum}) {
        const UniaxialPoint p = uniaxial_stress(law, K, G, 1 + eps);
        EXPECT_NEAR(p.P / (E * eps), 1.0, 1e-5) << static_cast<int>(law);
        EXPECT_NEAR((1 - p.mu) / (nu * eps), 1.0, 1e-5) << static_cast<int>(law);
    }
    const UniaxialPoint p = uniaxial_stress(UniaxialLaw::pmb_continuum, K, G, 1 + eps);
    EXPECT_NEAR(p.P / (1.5 * K * eps), 1.0, 1e-5);
    EXPECT_NEAR((1 - p.mu) / (0.25 * eps), 1.0, 1e-5);
}

TEST(UniaxialReference, HypoelasticAndSVKClosedForms)
{
    const UniaxialPoint h = uniaxial_stress(UniaxialLaw::hypoelastic, K, G, 2.0);
    EXPECT_NEAR(h.P / (E * std::log(2.0) * std::pow(2.0, -2 * nu)), 1.0, 1e-14);
    const UniaxialPoint s = uniaxial_stress(UniaxialLaw::saint_venant_kirchhoff, K, G, 1.5);
    EXPECT_NEAR(s.P / (E * 1.5 * 1.25 / 2), 1.0, 1e-14);
    EXPECT_NEAR(s.mu * s.mu, 1 - nu * 1.25, 1e-14);
}

// PMB continuum at lambda = 1.5 with the reference's mu: P_yy = 0 and P_xx by a 400 x 400
// midpoint rule over the whole sphere (error ~1e-5 relative).
TEST(UniaxialReference, PMBContinuumAgainstFullSphereQuadrature)
{
    const double l = 1.5;
    const UniaxialPoint p = uniaxial_stress(UniaxialLaw::pmb_continuum, K, G, l);
    const int N = 400;
    const double pi = std::numbers::pi, dth = pi / N, dph = 2 * pi / N;
    double Pxx = 0, Pyy = 0;
    for (int a = 0; a < N; ++a)
        for (int b = 0; b < N; ++b) {
            const double th = (a + 0.5) * dth, ph = (b + 0.5) * dph;
            const double n[3] = {std::cos(th), std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph)};
            const double Fn = std::sqrt(l * l * n[0] * n[0] + p.mu * p.mu * (n[1] * n[1] + n[2] * n[2]));
            const double w = 9 * K / (4 * pi) * (1 - 1 / Fn) * std::sin(th) * dth * dph;  // (9K/4pi)(1 - 1/|Fn|) dOmega
            Pxx += w * l * n[0] * n[0];
            Pyy += w * p.mu * n[1] * n[1];
        }
    EXPECT_NEAR(Pxx / p.P, 1.0, 1e-4);
    EXPECT_LT(std::abs(Pyy) / p.P, 1e-4);
}
