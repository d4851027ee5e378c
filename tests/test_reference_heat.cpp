// Classical 1D heat references (reference/heat_1d.hpp) against the spec's printed values and
// closed forms (spec/000b sec. 5.7, T7).
#include "reference/heat_1d.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace {

pd::ref::HeatBar1D t7_bar()
{
    pd::ref::HeatBar1D b;  // L = 0.1 m, ends at 100 C from t = 0, interior at 0 C
    b.alpha = 50.0 / (7800.0 * 502.08);
    return b;
}

}  // namespace

TEST(ReferenceHeat, ExactSeriesEndsInitialAndLateSingleMode)
{
    const auto b = t7_bar();
    EXPECT_EQ(pd::ref::heat_bar_exact_temperature(b, 0.0, 10.0), 100.0);
    EXPECT_EQ(pd::ref::heat_bar_exact_temperature(b, 0.1, 10.0), 100.0);
    EXPECT_EQ(pd::ref::heat_bar_exact_temperature(b, 0.03, 0.0), 0.0);
    // At t = 60 s only the modes n = 1, 3 matter: T = 100 - 100 sum_{n=1,3} 4/(n pi) sin(n pi x/L)
    // exp(-alpha (n pi/L)^2 t); the n = 5 term bounds the rest.
    const double pi = std::numbers::pi, t = 60, x = 0.03;
    auto mode = [&](int n) { return 100 * 4 / (n * pi) * std::exp(-b.alpha * n * n * pi * pi / (b.L * b.L) * t); };
    const double two_modes = 100 - mode(1) * std::sin(pi * x / b.L) - mode(3) * std::sin(3 * pi * x / b.L);
    EXPECT_NEAR(pd::ref::heat_bar_exact_temperature(b, x, t), two_modes, 1.01 * mode(5));
    EXPECT_GT(std::abs(mode(3) * std::sin(3 * pi * x / b.L)), 1e4 * mode(5));  // the n = 3 term is resolved
}

TEST(ReferenceHeat, ExactSeriesAtEarlyTimeIsTheHalfSpaceSolution)
{
    // Before the two end fronts meet, T near x = 0 is the half-space solution 100 erfc(x / (2 sqrt(alpha t))).
    const auto b = t7_bar();
    const double t = 5, x = 0.004;
    EXPECT_NEAR(pd::ref::heat_bar_exact_temperature(b, x, t), 100 * std::erfc(x / (2 * std::sqrt(b.alpha * t))), 1e-9);
}

TEST(ReferenceHeat, CentreReaches50AtTheSpecContinuumTime)
{
    // spec/000b T7 [RECON]: the exact continuum answer is 74.163 s.
    EXPECT_NEAR(pd::ref::heat_bar_exact_time_to(t7_bar(), 0.05, 50), 74.163, 5e-4);
}

TEST(ReferenceHeat, FiniteDifferenceReproducesTheSourceClassicalColumn)
{
    // spec/000b Table 6.1, classical column (implicit Euler, dt = 10 s), to the printed digits.
    const auto b = t7_bar();
    const std::pair<int, double> table[] = {{10, 78.505}, {50, 78.635}, {100, 78.639}, {200, 78.640}, {500, 78.640}, {1000, 78.640}};
    for (const auto& [N, t50] : table) EXPECT_NEAR(pd::ref::heat_bar_fd_time_to(b, N, 10, 0.05, 50), t50, 5e-4) << N;
}

TEST(ReferenceHeat, FiniteDifferenceConvergesToTheContinuumTime)
{
    // Implicit Euler is first order in dt: halving dt halves the error once dx is fine.
    const auto b = t7_bar();
    const double exact = pd::ref::heat_bar_exact_time_to(b, 0.05, 50);
    const double e1 = pd::ref::heat_bar_fd_time_to(b, 400, 0.2, 0.05, 50) - exact;
    const double e2 = pd::ref::heat_bar_fd_time_to(b, 400, 0.1, 0.05, 50) - exact;
    EXPECT_GT(e1, 0);  // backward Euler lags behind: the crossing comes late
    EXPECT_NEAR(e1 / e2, 2.0, 0.05);
    EXPECT_LT(std::abs(e2), 0.1);
}

TEST(ReferenceHeat, InvalidInputsThrow)
{
    const auto b = t7_bar();
    EXPECT_THROW(pd::ref::heat_bar_exact_time_to(b, 0.05, 100), std::invalid_argument);
    EXPECT_THROW(pd::ref::heat_bar_exact_time_to(b, 0.0, 50), std::invalid_argument);
    EXPECT_THROW(pd::ref::heat_bar_fd_time_to(b, 1, 10, 0.05, 50), std::invalid_argument);
    EXPECT_THROW(pd::ref::heat_bar_fd_time_to(b, 10, 0, 0.05, 50), std::invalid_argument);
    EXPECT_THROW(pd::ref::heat_bar_fd_time_to(b, 10, 10, 0.05, 50, 20), std::runtime_error);
}
