// Generalised Maxwell / standard linear solid point law (laws/maxwell.hpp) against closed forms
// (spec/000c V1-V2): SLS relaxation and creep, Prony step response, exactness of the exponential
// integrator (7.19) for piecewise-linear strain at dt = 0.01 tau ... 1000 tau against the analytic
// convolution of ramps, the dissipated energy against quadrature and against the energy stored in
// the branches, extreme steps (dt >> tau, dt << tau, 100 % strain) without NaN, and a deviatoric
// tensor relaxing as the closed form.
#include "pd/laws/maxwell.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

using pd::laws::Maxwell;
using pd::laws::MaxwellBranch;

namespace {
// Dashpot strain of a branch of time tau [s] under x(t) = (t - t0)_+ (unit ramp), from the
// convolution (7.18)/(7.26): h = (t - t0) - tau (1 - exp(-(t - t0)/tau)) for t > t0, else 0.
double ramp_response(double t, double t0, double tau)
{
    const double s = t - t0;
    return s > 0 ? s - tau * (1 - std::exp(-s / tau)) : 0.0;
}

// Piecewise-linear strain through (0, 0) and the knots (t_k, x_k): slopes and their changes.
struct Path {
    std::vector<double> t, x;  // knots [s], [-]; t[0] = 0, x[0] = 0
    double strain(double tt) const
    {
        for (std::size_t k = 1; k < t.size(); ++k)
            if (tt <= t[k]) return x[k - 1] + (x[k] - x[k - 1]) * (tt - t[k - 1]) / (t[k] - t[k - 1]);
        return x.back();
    }
    // Sum of ramps: slope change at knot k times the ramp response from t_k.
    double dashpot(double tt, double tau) const
    {
        double h = 0, prev = 0;
        for (std::size_t k = 0; k + 1 < t.size(); ++k) {
            const double slope = (x[k + 1] - x[k]) / (t[k + 1] - t[k]);
            h += (slope - prev) * ramp_response(tt, t[k], tau);
            prev = slope;
        }
        return h - prev * ramp_response(tt, t.back(), tau);  // held after the last knot
    }
};
}  // namespace

// V1 relaxation: a step eps0 at t = 0 (one step with dt = 0: the instantaneous modulus E_0), then
// held with dt = 0.37 tau: sigma = eps0 (E_inf + E_b e^{-t/tau}). The update of a held strain is
// h <- e h + (1 - e) eps0, exact; 60 steps of round-off: 1e-14 relative.
TEST(LawsMaxwell, SlsRelaxationMatchesClosedForm)
{
    const double E_inf = 2e9, E_b = 3e9, tau = 0.5, eps0 = 1e-3, dt = 0.37 * tau;  // [Pa], [Pa], [s], [-], [s]
    const Maxwell law = Maxwell::sls(E_inf, E_b, tau);
    auto s = law.step<double>({0.0}, 0.0, eps0, 0.0);
    EXPECT_NEAR(s.stress, eps0 * (E_inf + E_b), 1e-14 * E_inf);  // sigma(0+) = E_0 eps0 = 5e6 Pa
    EXPECT_EQ(s.dissipation, 0.0);
    for (int n = 1; n <= 60; ++n) {
        s = law.step(s.h, eps0, eps0, dt);
        const double ref = eps0 * (E_inf + E_b * std::exp(-n * dt / tau));
        ASSERT_NEAR(s.stress, ref, 1e-14 * eps0 * (E_inf + E_b)) << "step " << n;
    }
}

// V1 creep: stress sigma0 imposed from t = 0; eps(t) = sigma0/E_inf - sigma0 (1/E_inf - 1/E_0)
// e^{-t/tau_c}, tau_c = tau E_0/E_inf. Each step solves sigma^{n+1} = sigma0 for eps^{n+1} (the
// update is linear in eps^{n+1}, slope tangent(dt)). The law assumes eps linear in a step, the true
// creep is exponential: second-order error in dt. Measured: max error 9.6e-6 of sigma0/E_inf at
// dt = tau/20, 2.4e-6 at tau/40 (ratio 4.00).
TEST(LawsMaxwell, SlsCreepConvergesAtSecondOrder)
{
    const double E_inf = 1e9, E_b = 1e9, tau = 1, sigma0 = 1e6, t_end = 5;  // [Pa], [Pa], [s], [Pa], [s]
    const Maxwell law = Maxwell::sls(E_inf, E_b, tau);
    const double E0 = E_inf + E_b, tau_c = tau * E0 / E_inf;
    auto max_error = [&](int steps) {
        const double dt = t_end / steps;
        double eps = sigma0 / E0;  // instantaneous response [-]
        std::vector<double> h{0.0};
        double err = 0;
        for (int n = 1; n <= steps; ++n) {
            const auto trial = law.step(h, eps, eps, dt);
            const double eps1 = eps + (sigma0 - trial.stress) / law.tangent(dt);
            const auto s = law.step(h, eps, eps1, dt);
            EXPECT_NEAR(s.stress, sigma0, 1e-9 * sigma0);  // linear solve: stress met to round-off
            h = s.h, eps = eps1;
            const double ref = sigma0 / E_inf - sigma0 * (1 / E_inf - 1 / E0) * std::exp(-n * dt / tau_c);
            err = std::max(err, std::abs(eps - ref) / (sigma0 / E_inf));
        }
        return err;
    };
    const double e1 = max_error(100), e2 = max_error(200);
    EXPECT_LT(e1, 2e-5);                // dt = tau/20: O(dt^2) error, measured 9.6e-6 (bound: twice that)
    EXPECT_NEAR(e1 / e2, 4.0, 0.3);    // second order: halving dt divides the error by 4
}

// V2 Prony series, three branches, step eps0 then held with steps of varying size (dt from 0.001 tau_1
// to 1000 tau_3): sigma = eps0 (E_inf + sum E_i e^{-t/tau_i}) to round-off (1e-13 of E_0 eps0).
TEST(LawsMaxwell, PronyStepResponse)
{
    const Maxwell law{1e9, {{2e9, 1e-3}, {1.5e9, 0.1}, {0.5e9, 10}}};  // [Pa], {[Pa], [s]}
    const double eps0 = 2e-3, E0 = law.instantaneous_modulus();
    EXPECT_DOUBLE_EQ(E0, 5e9);
    auto s = law.step<double>({0.0, 0.0, 0.0}, 0.0, eps0, 0.0);
    double t = 0;
    for (double dt : {1e-6, 3e-4, 1e-3, 0.05, 0.5, 2.0, 7.0, 40.0, 1e4}) {
        s = law.step(s.h, eps0, eps0, dt);
        t += dt;
        double ref = law.E_inf;
        for (const auto& b : law.branches) ref += b.E * std::exp(-t / b.tau);
        EXPECT_NEAR(s.stress, eps0 * ref, 1e-13 * E0 * eps0) << "t = " << t;
    }
}

// The integrator is exact for strain linear in each step, any dt: a piecewise-linear strain (load,
// reverse, hold) whose knots fall on step ends, at dt/tau = 0.01, 0.1, 1, 10, 100, 1000. The reference
// is the closed-form convolution of ramps (Path::dashpot). Tolerance 1e-12 of the peak stress: the
// recurrence accumulates round-off of ~1e-16 per step over at most 3000 steps.
TEST(LawsMaxwell, ExactForPiecewiseLinearStrainAtAnyStep)
{
    const double tau = 1.0, E_inf = 1e9, E_b = 4e9;  // [s], [Pa], [Pa]
    const Maxwell law = Maxwell::sls(E_inf, E_b, tau);
    for (double ratio : {0.01, 0.1, 1.0, 10.0, 100.0, 1000.0}) {
        const double dt = ratio * tau;
        // Knots at multiples of dt: ramp up 10 steps, down 20 steps, hold 5 steps, up 3 steps.
        const Path p{{0, 10 * dt, 30 * dt, 35 * dt, 38 * dt}, {0, 1e-2, -5e-3, -5e-3, 2e-3}};
        std::vector<double> h{0.0};
        double x_n = 0, worst = 0;
        for (int n = 1; n <= 45; ++n) {
            const double x = p.strain(n * dt);
            const auto s = law.step(h, x_n, x, dt);
            const double ref = E_inf * x + E_b * (x - p.dashpot(n * dt, tau));
            worst = std::max(worst, std::abs(s.stress - ref));
            h = s.h, x_n = x;
        }
        EXPECT_LT(worst, 1e-12 * E_b * 1e-2) << "dt/tau = " << ratio;
    }
}

// Dissipated energy of one step against a composite Simpson quadrature of (E/tau) int r^2 dt with
// r(t) = x(t) - h(t) from the closed-form ODE solution (independent of the law). Random-looking
// steps, dt/tau from 1e-9 to 1e4: D >= 0 and |D - D_quad| <= 1e-9 D_quad + 1e-30 (Simpson with 2e5
// intervals on the decay scale min(dt, tau): relative error below 1e-12; the small-x series of g3 is
// checked at dt/tau = 1e-3 .. 0.09).
TEST(LawsMaxwell, StepDissipationMatchesQuadratureAndIsNonNegative)
{
    const double E = 3e9, tau = 2.0;  // [Pa], [s]
    const Maxwell law = Maxwell::sls(1e9, E, tau);
    const double cases[][4] = {  // dt/tau, h_n, x_n, x_np1
        {1e-9, 1e-3, 2e-3, 2.5e-3}, {1e-3, 0, 0, 1e-2}, {0.05, 2e-3, -1e-3, 4e-3}, {0.09, -1e-3, 1e-3, 1e-3},
        {0.5, 1e-2, 0, 0}, {1, 0, 1e-3, -1e-3}, {3, 5e-3, 5e-3, 5e-3}, {30, -2e-3, 1e-3, 1.0}, {1e4, 0, 0, 1.0}};
    for (const auto& c : cases) {
        const double dt = c[0] * tau, h_n = c[1], x_n = c[2], x1 = c[3];
        const auto s = law.step<double>({h_n}, x_n, x1, dt);
        // Quadrature of the exact r(t): dr/dt = slope - r/tau, r(0) = x_n - h_n.
        const double slope = (x1 - x_n) / dt, r0 = x_n - h_n;
        auto r = [&](double t) { return r0 * std::exp(-t / tau) - slope * tau * std::expm1(-t / tau); };
        const double T = std::min(dt, 40 * tau);  // beyond 40 tau, r = slope tau (added exactly below)
        const int N = 200000;
        double q = r(0) * r(0) + r(T) * r(T);
        for (int k = 1; k < N; ++k) q += (k % 2 ? 4 : 2) * r(k * T / N) * r(k * T / N);
        q *= T / (3.0 * N);
        q += (dt - T) * slope * tau * slope * tau;
        const double D_quad = E / tau * q;
        EXPECT_GE(s.dissipation, 0.0);
        EXPECT_NEAR(s.dissipation, D_quad, 1e-9 * D_quad + 1e-30) << "dt/tau = " << c[0];
    }
}

// A step eps0 held until relaxed dissipates exactly the energy stored in the branch spring at 0+,
// E_b eps0^2 / 2, whatever the steps (here dt = 0.7 tau then 1e3 tau): sum of D_step = 1/2 E_b eps0^2
// to round-off (1e-12 relative), and every D_step >= 0.
TEST(LawsMaxwell, RelaxationDissipatesTheStoredBranchEnergy)
{
    const double E_b = 2e9, eps0 = 3e-3;  // [Pa], [-]
    const Maxwell law = Maxwell::sls(1e9, E_b, 0.25);
    auto s = law.step<double>({0.0}, 0.0, eps0, 0.0);
    double total = 0;
    for (int n = 0; n < 80; ++n) {
        s = law.step(s.h, eps0, eps0, n < 79 ? 0.7 * 0.25 : 1e3 * 0.25);
        ASSERT_GE(s.dissipation, 0.0);
        total += s.dissipation;
    }
    EXPECT_NEAR(total, 0.5 * E_b * eps0 * eps0, 1e-12 * 0.5 * E_b * eps0 * eps0);  // 9000 J/m^3
}

// Extreme steps: dt = 1e8 tau (beta = 1 - 1e-8: h = x^{n+1}, the branch carries no stress), dt =
// 1e-14 tau (beta = 5e-15: h unchanged, the instantaneous modulus), 100 % strain; all finite.
TEST(LawsMaxwell, ExtremeStepsStayFiniteAndHaveTheRightLimits)
{
    const double E_inf = 1e9, E_b = 9e9, tau = 1e-6;  // [Pa], [Pa], [s]
    const Maxwell law = Maxwell::sls(E_inf, E_b, tau);
    const auto big = law.step<double>({0.0}, 0.0, 1.0, 1e8 * tau);  // ramp to 100 % strain in 1e8 tau
    ASSERT_TRUE(std::isfinite(big.stress) && std::isfinite(big.dissipation));
    // h = x - tau/dt (1 - e) ... exactly 1 - 1e-8: branch stress E_b 1e-8 = 90 Pa on top of E_inf = 1e9 Pa.
    EXPECT_NEAR(big.stress, E_inf * 1.0 + E_b * 1e-8, 1e-6 * E_b * 1e-8);
    // Dissipation of a ramp to 1 in dt >> tau: (E_b/tau) (tau/dt)^2 dt (1 + O(tau/dt)) = E_b 1e-8.
    EXPECT_NEAR(big.dissipation, E_b * 1e-8, 1e-6 * E_b * 1e-8);
    const auto tiny = law.step<double>({0.0}, 0.0, 1.0, 1e-14 * tau);
    ASSERT_TRUE(std::isfinite(tiny.stress));
    EXPECT_NEAR(tiny.stress, (E_inf + E_b) * 1.0, 1e-12 * (E_inf + E_b));  // E_0 at 100 % strain
    EXPECT_NEAR(tiny.h[0], 0.5e-14, 1e-20);                                  // beta = dt/(2 tau)
    EXPECT_NEAR(pd::laws::maxwell_coefficients(1e8, 1).beta, 1 - 1e-8, 1e-15);
    EXPECT_THROW(pd::laws::maxwell_coefficients(1, 0), std::invalid_argument);
    EXPECT_THROW(pd::laws::maxwell_coefficients(-1, 1), std::invalid_argument);
}

// Deviatoric tensor (E = 2 G per branch): a step e0 (traceless, with shear) held; the stress is
// 2 (G_inf + G_b e^{-t/tau}) e0 per component and the total dissipation G_b e0:e0 (= 1/2 (2 G_b) e0:e0).
TEST(LawsMaxwell, DeviatoricTensorRelaxes)
{
    using M = Eigen::Matrix3d;
    const double G_inf = 30e9, G_b = 15e9, tau = 1e-3;  // [Pa], [Pa], [s]
    const Maxwell law{2 * G_inf, {{2 * G_b, tau}}};
    M e0;
    e0 << 1e-3, 2e-4, 0, 2e-4, -4e-4, -1e-4, 0, -1e-4, -6e-4;
    auto s = law.step<M>({M::Zero()}, M::Zero(), e0, 0.0);
    double total = 0;
    for (int n = 1; n <= 20; ++n) {
        s = law.step(s.h, e0, e0, 0.3 * tau);
        total += s.dissipation;
        const M ref = 2 * (G_inf + G_b * std::exp(-n * 0.3)) * e0;
        ASSERT_LT((s.stress - ref).cwiseAbs().maxCoeff(), 1e-14 * 2 * (G_inf + G_b) * 1e-3) << "step " << n;
    }
    const double stored = G_b * (e0.array() * e0.array()).sum();  // 2.55e4 J/m^3 at 0+
    EXPECT_NEAR(total, stored * (1 - std::exp(-2 * 20 * 0.3)), 1e-12 * stored);  // r^2 decays as e^{-2t/tau}
}
