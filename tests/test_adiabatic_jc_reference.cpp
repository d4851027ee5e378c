// reference/j2_plasticity.hpp adiabatic_uniaxial_jc (the pre-necking reference of
// problems/3d/hopkinson_tension.cpp): elastic below A (sigma = E eps, P = (1 - nu eps)^2 sigma); a
// perfectly plastic, rate- and temperature-independent bar flows at sigma = A with ep = eps - A/E and
// heats by beta A ep/(rho c) (closed forms); with the 316L constants the curve converges in the
// number of steps; softening lowers the stress by the factor 1 - theta*^m of the reached temperature.
#include "reference/j2_plasticity.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd::ref;

namespace {
constexpr double E = 193e9, nu = 0.3, beta = 0.9, rho_c = 7900 * 500.0, T0 = 20;
}

TEST(AdiabaticUniaxialJC, ElasticBelowYieldAndPerfectlyPlasticAbove)
{
    const Hardening h{.A = 300e6, .B = 0, .n = 1, .C = 0, .epdot0 = 1};
    const double eps_end = 0.2;
    const auto s = adiabatic_uniaxial_jc(E, nu, h, {}, beta, rho_c, 0.0, T0, 1000, eps_end, 400);
    for (const UniaxialState& p : s) {
        if (E * p.eps <= h.A) {
            EXPECT_NEAR(p.sigma, E * p.eps, 1e-9 * h.A);
            EXPECT_EQ(p.ep, 0.0);
            EXPECT_NEAR(p.P, (1 - nu * p.eps) * (1 - nu * p.eps) * p.sigma, 1e-9 * h.A);
        } else {
            const double ep = p.eps - h.A / E;  // bisection to the last bit: round-off of the sums only
            EXPECT_NEAR(p.sigma, h.A, 1e-9 * h.A);
            EXPECT_NEAR(p.ep, ep, 1e-12);
            EXPECT_NEAR(p.theta - T0, beta * h.A * ep / rho_c, 1e-9 * (p.theta - T0));
            const double eps_t = -nu * h.A / E - 0.5 * ep;
            EXPECT_NEAR(p.P, (1 + eps_t) * (1 + eps_t) * h.A, 1e-9 * h.A);
        }
    }
}

// 316L of Table 9.2 at 1192 1/s to strain 0.3: 20000 steps (the driver's) against 40000: the explicit
// heat lags by one step, a first-order error; the two agree to 1e-4 in stress and temperature rise.
TEST(AdiabaticUniaxialJC, ConvergesInTheStepCountWith316L)
{
    const Hardening h{.A = 310.8e6, .B = 881.38e6, .n = 0.178, .C = 0.19, .epdot0 = 1000};
    const Softening soft{.m = 1.25, .theta_ref = 20, .theta_melt = 1387};
    const auto a = adiabatic_uniaxial_jc(E, nu, h, soft, beta, rho_c, 15.9e-6, T0, 1192, 0.3, 20000);
    const auto b = adiabatic_uniaxial_jc(E, nu, h, soft, beta, rho_c, 15.9e-6, T0, 1192, 0.3, 40000);
    EXPECT_NEAR(a.back().sigma / b.back().sigma, 1.0, 1e-4);
    EXPECT_NEAR((a.back().theta - T0) / (b.back().theta - T0), 1.0, 1e-4);
    EXPECT_GT(a.back().theta - T0, 50.0);  // the adiabatic heating is substantial at 0.3
    // The softened stress is the hardening times the rate factor times 1 - theta*^m at the end state;
    // the factor is taken at the imposed rate, which exceeds the plastic one by the elastic and thermal
    // strain rates (under 0.2 % of it once hardening is slow).
    const double rate_factor = 1 + h.C * std::log(1192 / h.epdot0);
    const double hard = (h.A + h.B * std::pow(b.back().ep, h.n)) * rate_factor;
    EXPECT_NEAR(b.back().sigma / (hard * soft.factor(b.back().theta)), 1.0, 2e-3);
    EXPECT_LT(soft.factor(b.back().theta), 0.99);  // theta ~ 90 C: softening at work
}
