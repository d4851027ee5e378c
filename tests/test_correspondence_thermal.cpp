// Thermal expansion of the correspondence models (models/correspondence.hpp header; spec/000a
// eq. 2.81 and verification case V7), on a block long enough for the chunk path:
// - linear law: a free body at y = (1 + eps) x has sigma = 0 and no force at any node (surface nodes,
//   hourglass control and broken bonds included); a body held at y = x is under sigma = -3 K eps I in
//   3D and -E/(1 - nu) eps in 2D plane stress (the classical constrained thermal stress, V7);
// - Flanagan-Taylor: a free body expanding with the temperature ramp keeps sigma_hat at the closed form
//   of the discrete sum 3 K (sum_n de_n/(1 + e_mid,n) - e) (O(K eps^2), V7's "stays 0"); a clamped body
//   heated in one step is under -3 K eps I after that step's update (V9: the thermal strain increment is
//   non-zero in the step where theta changes) and stays there while theta is held;
// - J2 plasticity (PlasticCorrespondence): the same constrained stress while elastic, none when free;
// - the viscoelastic wrapper: the same, taken once per step however many trials it evaluates;
// - theta = theta_ref is the isothermal result bit for bit; the refusals.
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

using namespace pd;

namespace {
constexpr double dx = 1e-3, alpha = 1.2e-5, theta_ref = 293.15, heat = 50;  // [m], [1/K], [K], [K]
const Elastic mat = Elastic::from_E_nu(200e9, 0.25);
using C3 = Correspondence<3>;

Body<3> block() { return box<3>({{0, 0, 0}}, {{16 * dx, 5 * dx, 4 * dx}}, dx); }

template <int D>
Field<D> scaled(const Body<D>& body, double s)
{
    Field<D> y = body.x;
    for (int d = 0; d < D; ++d) for (auto& v : y.c[d]) v *= s;
    return y;
}
template <int D>
double max_norm(const Field<D>& f)
{
    double m = 0;
    for (std::size_t i = 0; i < f.size(); ++i) m = std::max(m, norm(f[i]));
    return m;
}
// Largest entry of |sigma_i - s I| over the nodes with a regular shape tensor [Pa].
template <class Mats, class Model>
double max_off(const Mats& sigma, const Model& m, double s)
{
    double e = 0;
    for (std::size_t i = 0; i < sigma.size(); ++i) {
        if (m.Kinv[i].isZero(0)) continue;
        auto d = sigma[i];
        d.diagonal().array() -= s;
        e = std::max(e, d.cwiseAbs().maxCoeff());
    }
    return e;
}
}  // namespace

TEST(CorrespondenceThermal, LinearFreeExpansionIsStressFree)
{
    const Body<3> body = block();
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat, p = 3 * mat.K * eps;
    const Field<3> y = scaled(body, 1 + eps);
    for (bool damaged : {false, true})
        for (double C_hg : {0.0, 0.02}) {
            Bonds b = build_bonds(body, 3 * dx);
            if (damaged) {
                b.enable_damage();
                for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(static_cast<std::int64_t>(k));
            }
            C3 iso({.material = mat, .C_hg = C_hg}, body, b), th({.material = mat, .C_hg = C_hg}, body, b);
            th.set_thermal_expansion({alpha, theta_ref, &theta});
            Field<3> f_iso, f;
            internal_force(iso, b, y, f_iso);
            internal_force(th, b, y, f);
            const double scale = max_norm(f_iso);  // the isothermal forces of the same y
            ASSERT_GT(scale, 0);
            // F = (1 + eps) I to round-off (N K^-1 of the family sums), so both are round-off of F times K.
            EXPECT_LT(max_norm(f), 1e-11 * scale) << "damaged " << damaged << " C_hg " << C_hg;
            EXPECT_LT(max_off(th.sigma, th, 0.0), 1e-10 * p);
        }
}

TEST(CorrespondenceThermal, LinearClampedBodyIsUnderTheConstrainedThermalStress)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const double eps = alpha * heat;
    for (bool node_matrices : {true, false}) {
        C3 m({.material = mat, .node_matrices = node_matrices}, body, b);
        m.set_thermal_expansion({alpha, theta_ref, &theta});
        Field<3> f;
        internal_force(m, b, body.x, f);
        m.sync_node_matrices();
        EXPECT_LT(max_off(m.sigma, m, -3 * mat.K * eps), 1e-14 * mat.K);  // V7: -3 K alpha dtheta, to F's round-off
        const std::vector<double> W = m.energy_density(b, body.x);            // 9/2 K eps^2, constrained
        for (std::size_t i = 0; i < W.size(); ++i)
            if (!m.Kinv[i].isZero(0)) {  // round-off of F (W is quadratic in the strain)
                ASSERT_NEAR(W[i], 4.5 * mat.K * eps * eps, 1e-10 * mat.K * eps * eps) << i;
            }
    }
    // 2D plane stress: the in-plane constrained stress -E/(1 - nu) eps.
    const Body<2> plate = box<2>({{0, 0}}, {{12 * dx, 6 * dx}}, dx);
    const Bonds b2 = build_bonds(plate, 3 * dx);
    const std::vector<double> theta2(plate.size(), theta_ref + heat);
    Correspondence<2> m2({.material = mat, .plane = Plane::stress, .measure = dx}, plate, b2);
    m2.set_thermal_expansion({alpha, theta_ref, &theta2});
    Field<2> f2;
    internal_force(m2, b2, plate.x, f2);
    const double E = 9 * mat.K * mat.G / (3 * mat.K + mat.G), nu = (3 * mat.K - 2 * mat.G) / (2 * (3 * mat.K + mat.G));
    EXPECT_LT(max_off(m2.sigma, m2, -E / (1 - nu) * eps), 1e-14 * E);
}

TEST(CorrespondenceThermal, ReferenceTemperatureGivesTheIsothermalForcesBitForBit)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref);
    Field<3> y = scaled(body, 1.001);
    for (std::size_t i = 0; i < y.size(); ++i) y.c[1][i] += 2e-4 * body.x.c[0][i] * body.x.c[0][i] / dx;
    C3 iso({.material = mat, .C_hg = 0.02}, body, b), th({.material = mat, .C_hg = 0.02}, body, b);
    th.set_thermal_expansion({alpha, theta_ref, &theta});
    Field<3> f_iso, f;
    internal_force(iso, b, y, f_iso);
    internal_force(th, b, y, f);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f.c[d], f_iso.c[d]);
}

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

TEST(CorrespondenceThermal, PlasticCorrespondenceTakesTheMechanicalStrain)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat);
    const laws::JohnsonCook law{.A = 5e8, .B = 1e8, .n = 0.5};  // 3 K eps = 0.24 GPa: elastic
    const double eps = alpha * heat;
    for (bool free : {false, true}) {
        PlasticCorrespondence m({.material = mat}, body, b, law);
        m.set_thermal_expansion({alpha, theta_ref, &theta});
        Field<3> f;
        internal_force(m, b, free ? scaled(body, 1 + eps) : body.x, f);
        const double s = free ? 0.0 : -3 * mat.K * eps;
        EXPECT_LT(max_off(m.model.sigma, m.model, s), 1e-10 * 3 * mat.K * eps) << "free " << free;  // round-off of F
        if (free) {  // P = J sigma F^-T = 0: far below 3 K eps / dx, the force density the thermal stress would leave
            EXPECT_LT(max_norm(f), 1e-3 * 3 * mat.K * eps / dx);
        }
    }
}

TEST(CorrespondenceThermal, RefusesWhatIsNotWritten)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + heat), short_theta(3, theta_ref);
    C3 svk({.material = mat, .law = C3::Law::saint_venant_kirchhoff}, body, b);
    EXPECT_THROW(svk.set_thermal_expansion({alpha, theta_ref, &theta}), std::invalid_argument);
    C3 lin({.material = mat}, body, b);
    EXPECT_THROW(lin.set_thermal_expansion({alpha, theta_ref, &short_theta}), std::invalid_argument);
    const Body<2> plate = box<2>({{0, 0}}, {{8 * dx, 6 * dx}}, dx);
    const Bonds b2 = build_bonds(plate, 3 * dx);
    const std::vector<double> theta2(plate.size(), theta_ref);
    Correspondence<2> strain({.material = mat, .plane = Plane::strain, .measure = dx}, plate, b2);
    EXPECT_THROW(strain.set_thermal_expansion({alpha, theta_ref, &theta2}), std::invalid_argument);
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
