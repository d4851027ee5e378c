// Thermal expansion of the correspondence rate forms (spec/000a eq. 2.81, V7, V9, V12, eq. 4.44):
// Flanagan-Taylor free expansion at its O(K eps^2) closed form, the increment taken in the step theta
// changes, moduli and alpha depending on theta; the viscoelastic wrapper takes it once per step.
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"

#include <gtest/gtest.h>

#include "correspondence_thermal_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

using namespace pd;
using namespace pd_test::correspondence_thermal_fixtures;

// The rate form over n steps of dt from y_n to y_n+1 (mid-step configuration and v_nph, as Explicit).
namespace {
void rate_step(C3& m, const Bonds& b, const Field<3>& y0, const Field<3>& y1, double dt)
{
    Field<3> mid = y0, v = y0;
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < y0.size(); ++i) {
            mid.c[d][i] = 0.5 * (y0.c[d][i] + y1.c[d][i]);
            v.c[d][i] = (y1.c[d][i] - y0.c[d][i]) / dt;
        }
    m.update_stress(b, mid, v, dt);
    m.point_pass(b, y1);
}
}  // namespace

TEST(CorrespondenceThermal, FlanaganTaylorFreeExpansionKeepsTheUnrotatedStressAtItsSecondOrderValue)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta(body.size(), theta_ref);
    C3 m({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    m.set_thermal_expansion({alpha, theta_ref, &theta});
    const int steps = 20;
    const double dt = 1e-7;
    const double big = 2000;  // K: a large ramp so that the O(eps^2) term is well above round-off
    double sum = 0, e_prev = 0;   // sum_n de_n/(1 + e_mid,n): the trace of d dt per direction
    Field<3> y0 = body.x;
    for (int n = 1; n <= steps; ++n) {
        const double dth = big * n / steps, e = alpha * dth;
        std::fill(theta.begin(), theta.end(), theta_ref + dth);
        const Field<3> y1 = scaled(body, 1 + e);
        rate_step(m, b, y0, y1, dt);
        sum += (e - e_prev) / (1 + 0.5 * (e + e_prev));
        e_prev = e, y0 = y1;
    }
    const double expected = 3 * mat.K * (sum - e_prev);  // 3 K (ln(1 + e) - e) to O(e^3)
    EXPECT_GT(std::abs(expected), 1e-3 * 3 * mat.K * e_prev);  // the second-order term is resolved
    EXPECT_LT(std::abs(expected), 3 * mat.K * e_prev * e_prev);  // and is O(K eps^2): "stays 0" to that order
    EXPECT_LT(max_off(m.sigma_hat, m, expected), 1e-9 * 3 * mat.K * e_prev);  // round-off of 20 updates (the sum itself is exact)
    // Without thermal expansion the same motion in one step is under +3 K e/(1 + e/2).
    C3 iso({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    rate_step(iso, b, body.x, scaled(body, 1 + e_prev), dt);
    const double one_step = 3 * mat.K * e_prev / (1 + 0.5 * e_prev);
    EXPECT_LT(max_off(iso.sigma_hat, iso, one_step), 1e-9 * one_step);
}

TEST(CorrespondenceThermal, FlanaganTaylorClampedBodyTakesTheIncrementInTheStepTheTemperatureChanges)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta(body.size(), theta_ref);
    C3 m({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    m.set_thermal_expansion({alpha, theta_ref, &theta});
    const double dt = 1e-7, s = -3 * mat.K * alpha * heat;
    rate_step(m, b, body.x, body.x, dt);
    EXPECT_EQ(max_off(m.sigma, m, 0.0), 0.0);  // theta = theta_ref: no increment
    std::fill(theta.begin(), theta.end(), theta_ref + heat);
    rate_step(m, b, body.x, body.x, dt);
    EXPECT_LT(max_off(m.sigma, m, s), 1e-12 * std::abs(s));  // the step theta changed in
    rate_step(m, b, body.x, body.x, dt);
    EXPECT_LT(max_off(m.sigma, m, s), 1e-12 * std::abs(s));  // held: no further increment
    // A body that starts at theta != theta_ref: the same stress as the linear law after the first update.
    std::vector<double> hot(body.size(), theta_ref + heat);
    C3 m2({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    m2.set_thermal_expansion({alpha, theta_ref, &hot});
    rate_step(m2, b, body.x, body.x, dt);
    EXPECT_LT(max_off(m2.sigma, m2, s), 1e-12 * std::abs(s));
    m2.reset_rate_state();  // back to the reference state, theta^n = theta_ref
    rate_step(m2, b, body.x, body.x, dt);
    EXPECT_LT(max_off(m2.sigma, m2, s), 1e-12 * std::abs(s));
}

// spec/000b V12 and eq. 4.44: with d = 0 and theta changing, s_hat and sigma_H scale by G^(n+1)/G^n and
// K^(n+1)/K^n, so sigma_hat = D(theta) : eps_hat is kept at fixed strain (E and nu both vary, so the two
// ratios differ); a clamped body heated in two steps under a linear alpha(theta) is under
// -3 K int alpha dtheta (the mean of the two ends' alpha is exact for a linear alpha).
TEST(CorrespondenceThermal, TemperatureDependentModuliRescaleTheUnrotatedStress)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta(body.size(), theta_ref);
    const double dt = 1e-7, dT = 100;
    auto moduli = [](double th) { return Elastic::from_E_nu(200e9 * (1 - 1e-3 * (th - theta_ref)), 0.25 + 2e-4 * (th - theta_ref)); };
    C3 m({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    m.set_thermal_expansion({0.0, theta_ref, &theta});
    m.set_temperature_dependence({.material = moduli, .alpha = [](double) { return 0.0; }});
    Field<3> y = body.x;  // a shear and a stretch: both parts of sigma_hat non-zero
    for (std::size_t i = 0; i < body.size(); ++i) y.c[0][i] += 1e-3 * body.x.c[1][i] + 2e-3 * body.x.c[0][i];
    rate_step(m, b, body.x, y, dt);
    const std::vector<C3::Mat> before = m.sigma_hat;
    std::fill(theta.begin(), theta.end(), theta_ref + dT);
    rate_step(m, b, y, y, dt);  // d = 0
    const Elastic m0 = moduli(theta_ref), m1 = moduli(theta_ref + dT);
    ASSERT_GT(std::abs(m1.K / m0.K - m1.G / m0.G), 0.05);
    double err = 0, scale = 0;
    for (std::size_t i = 0; i < body.size(); ++i) {
        if (m.Kinv[i].isZero(0)) continue;
        const double pH = before[i].trace() / 3;
        C3::Mat expect = before[i] * (m1.G / m0.G);
        expect.diagonal().array() += pH * (m1.K / m0.K - m1.G / m0.G);
        err = std::max(err, (m.sigma_hat[i] - expect).cwiseAbs().maxCoeff()), scale = std::max(scale, before[i].cwiseAbs().maxCoeff());
    }
    EXPECT_GT(scale, 1e6);
    EXPECT_LT(err, 1e-12 * scale);  // a few roundings of a 3x3 scaling (the increment is zero: d = 0)
    // alpha(theta) linear, constant moduli: two heating steps of dT from theta_ref on a clamped body.
    const double a0 = alpha, a1 = 2e-3 * alpha;  // alpha = a0 + a1 (theta - theta_ref)
    std::fill(theta.begin(), theta.end(), theta_ref);
    C3 c({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    c.set_thermal_expansion({a0, theta_ref, &theta});
    c.set_temperature_dependence({.material = {}, .alpha = [&](double th) { return a0 + a1 * (th - theta_ref); }});
    for (int step = 1; step <= 2; ++step) {
        std::fill(theta.begin(), theta.end(), theta_ref + step * dT);
        rate_step(c, b, body.x, body.x, dt);
        const double T = step * dT, s = -3 * mat.K * (a0 * T + 0.5 * a1 * T * T);  // -3 K int alpha dtheta
        EXPECT_LT(max_off(c.sigma, c, s), 1e-12 * std::abs(s)) << "step " << step;  // round-off of two increments
    }
    C3 lin({.material = mat}, body, b);
    EXPECT_THROW(lin.set_temperature_dependence({.material = moduli, .alpha = {}}), std::invalid_argument);
    C3 cold({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
    EXPECT_THROW(cold.set_temperature_dependence({.material = moduli, .alpha = {}}), std::invalid_argument);  // no temperatures yet
}

// The viscoelastic wrapper: a clamped body heated in one step is under -3 K eps I (the branch sees only
// the deviator, which stays 0), however many trials the step takes, and stays there while theta is held;
// a free body expanding with theta keeps sigma at the O(K eps^2) of the elastic Flanagan-Taylor update.
TEST(CorrespondenceThermal, ViscoelasticCorrespondenceTakesTheIncrementOncePerStep)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta(body.size(), theta_ref);
    const double dt = 1e-7, s = -3 * mat.K * alpha * heat, eps = alpha * heat;
    for (bool free : {false, true}) {
        C3 ft({.material = mat, .law = C3::Law::flanagan_taylor}, body, b);
        ViscoelasticCorrespondence ve(ft, {.gamma_b = 8, .tau_b = 1e-6}, body.x);
        ft.set_thermal_expansion({alpha, theta_ref, &theta});  // attached after the wrapper: taken at its next trial
        std::fill(theta.begin(), theta.end(), theta_ref);
        Field<3> f;
        internal_force(ve, b, body.x, dt, f), ve.commit();
        EXPECT_EQ(max_off(ft.sigma, ft, 0.0), 0.0);
        std::fill(theta.begin(), theta.end(), theta_ref + heat);
        const Field<3> y = free ? scaled(body, 1 + eps) : body.x;
        const double expect = free ? 0.0 : s, tol = free ? 3 * mat.K * eps * eps : 1e-12 * std::abs(s);
        for (int trial = 0; trial < 3; ++trial) {  // trials of one step do not accumulate the increment
            internal_force(ve, b, y, dt, f);
            EXPECT_LT(max_off(ft.sigma, ft, expect), tol) << "free " << free << " trial " << trial;
        }
        ve.commit();
        internal_force(ve, b, y, dt, f), ve.commit();  // held: no further increment
        EXPECT_LT(max_off(ft.sigma, ft, expect), tol) << "free " << free << " held";
    }
}
