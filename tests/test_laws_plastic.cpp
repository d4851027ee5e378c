// Point laws of plasticity (laws/elastic.hpp, laws/johnson_cook.hpp, laws/j2.hpp), no bonds:
//  - the V7 table of spec/000b sec. 7 (Al 7075-T6, Table 5.1): dl and sigma_y of each row;
//  - consistency sigma_y + 3 G dl = sigma_eff_trial to round-off, hydrostatic stress unchanged;
//  - isochoric proportional straining against the closed-form hardening curve
//    a = ep + (A + B ep^n)/(3G) (a the von Mises equivalent total strain), in 1 and in 50 steps;
//  - extreme cases (rate 1e5 1/s, theta* -> 1 and beyond, dt >> 1, 100 % strain, ep = 0 with
//    n < 1, theta below theta_ref with non-integer m): finite results, each asserting its measure;
//  - dissipation sigma_y dl >= 0 and equal to the plastic work sigma : d eps_p.
#include "pd/laws/elastic.hpp"
#include "pd/laws/j2.hpp"
#include "pd/laws/johnson_cook.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pd::laws;

namespace {
constexpr double E = 71.7e9, nu = 0.33;           // Al 7075-T6, Table 5.1 [Pa], [-]
constexpr double G = E / (2 * (1 + nu));          // 26.9549 GPa [Pa]
constexpr double K = E / (3 * (1 - 2 * nu));      // [Pa]
constexpr double eps_d = std::numeric_limits<double>::epsilon();

JohnsonCook al7075(bool rate)
{
    // Table 5.1 (theta in degrees C: theta_ref 20, theta_melt 477).
    return {.A = 546e6, .B = 678e6, .n = 0.71, .C = rate ? 0.024 : 0.0, .epdot0 = 1.0, .m = 1.56, .theta_ref = 20, .theta_melt = 477};
}

// Half a unit in the 7th significant digit of a tabulated value: the table's own rounding.
double half_unit_7(double v) { return 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(v))) - 6); }

// An isochoric proportional strain of von Mises equivalent a: dev diag(1, -1/2, -1/2) a, plus a
// volumetric part b I.
Mat3 strain_path(double a, double b)
{
    Mat3 e = Mat3::Zero();
    e.diagonal() << a + b, -0.5 * a + b, -0.5 * a + b;
    return e;
}
}  // namespace

TEST(LawsPlastic, V7TableRows)
{
    struct Row { double trial, ep0, dt, theta; bool rate; double dl, sy; };
    const Row rows[] = {
        {700e6, 0.00, 1, 20, false, 1.809711e-3, 553.6583e6},
        {700e6, 0.05, 1, 20, false, 8.923842e-4, 627.8377e6},
        {900e6, 0.00, 1e-6, 20, true, 2.925625e-3, 663.4203e6},
        {900e6, 0.00, 1e-6, 200, true, 4.732476e-3, 517.3100e6},
        {900e6, 0.10, 1e-5, 20, true, 1.688512e-3, 763.4590e6},
    };
    for (const Row& r : rows) {
        const ScalarReturn s = radial_return(al7075(r.rate), G, r.trial, r.ep0, r.dt, r.theta);
        ASSERT_TRUE(s.plastic);
        // The table prints 7 significant digits: its rounding is the whole allowed difference.
        EXPECT_NEAR(s.dlambda, r.dl, half_unit_7(r.dl)) << "trial " << r.trial << " ep0 " << r.ep0;
        EXPECT_NEAR(s.sigma_eff, r.sy, half_unit_7(r.sy)) << "trial " << r.trial << " ep0 " << r.ep0;
        // Consistency (5.21) to round-off: a few ulps of the trial stress.
        EXPECT_NEAR(s.sigma_eff + 3 * G * s.dlambda, r.trial, 8 * eps_d * r.trial);
        EXPECT_DOUBLE_EQ(s.dissipation, s.sigma_eff * s.dlambda);
    }
}

TEST(LawsPlastic, ElasticBelowYieldAndHydrostaticUnchanged)
{
    const JohnsonCook jc = al7075(false);
    const IsotropicElastic el{K, G};
    // Elastic: equivalent strain a with 3 G a = 500 MPa < A = 546 MPa.
    const J2Update e = j2_strain_update(el, jc, strain_path(500e6 / (3 * G), 1e-3), {}, 1.0, 20);
    EXPECT_FALSE(e.scalar.plastic);
    EXPECT_NEAR(von_mises(e.stress), 500e6, 1e-9 * 500e6);  // closed form 3 G a; round-off
    // Plastic, with a volumetric strain b: the mean stress stays K 3 b exactly (5.18) up to round-off.
    const double b = 2e-3;
    const J2Update p = j2_strain_update(el, jc, strain_path(0.02, b), {}, 1.0, 20);
    ASSERT_TRUE(p.scalar.plastic);
    EXPECT_NEAR(p.stress.trace() / 3, 3 * K * b, 1e-12 * 3 * K * b);
    EXPECT_NEAR(p.history.eps_p.trace(), 0, 1e-15);  // plastic flow is deviatoric
    // Plastic strain tensor has the von Mises measure ep: sqrt(2/3 eps_p:eps_p) = dl (5.10)-(5.11).
    EXPECT_NEAR(std::sqrt(2.0 / 3.0 * (p.history.eps_p.array().square()).sum()), p.history.ep, 1e-14);
}

TEST(LawsPlastic, ProportionalStrainingFollowsClosedFormHardeningCurve)
{
    const JohnsonCook jc = al7075(false);
    const IsotropicElastic el{K, G};
    for (double ep_ref : {1e-4, 1e-2, 0.05, 0.2}) {
        // Closed form: sigma_eff = 3 G (a - ep) = A + B ep^n, so a = ep + (A + B ep^n)/(3 G).
        const double sy_ref = 546e6 + 678e6 * std::pow(ep_ref, 0.71);
        const double a = ep_ref + sy_ref / (3 * G);
        for (int steps : {1, 50}) {
            J2History h;
            J2Update u;
            for (int k = 1; k <= steps; ++k) {
                u = j2_strain_update(el, jc, strain_path(a * k / steps, 0), h, 1.0, 20);
                h = u.history;
            }
            // Proportional loading: backward Euler is exact for any step count; error = round-off
            // of the Newton residual (4 eps sigma) carried into ep through 1/(3G + h').
            EXPECT_NEAR(h.ep, ep_ref, 1e-12 * (1 + ep_ref)) << steps << " steps";
            EXPECT_NEAR(von_mises(u.stress), sy_ref, 1e-12 * sy_ref) << steps << " steps";
        }
    }
}

TEST(LawsPlastic, DissipationIsPlasticWorkAndNonNegative)
{
    const JohnsonCook jc = al7075(true);
    const IsotropicElastic el{K, G};
    J2History h;
    double total = 0;
    for (int k = 1; k <= 40; ++k) {
        // Loading, then unloading and reverse loading: a cyclic path.
        const double a = 0.03 * std::sin(0.2 * k);
        const J2Update u = j2_strain_update(el, jc, strain_path(a, 0), h, 1e-3, 20);
        const double work = (u.stress.array() * (u.history.eps_p - h.eps_p).array()).sum();  // sigma : d eps_p [J/m^3]
        EXPECT_GE(u.scalar.dissipation, 0);
        EXPECT_NEAR(u.scalar.dissipation, work, 1e-12 * (1 + std::abs(work)));  // identity; round-off
        total += u.scalar.dissipation;
        h = u.history;
    }
    EXPECT_GT(total, 0);  // the cycle did yield
}

TEST(LawsPlastic, ExtremeRate1e5)
{
    const JohnsonCook jc = al7075(true);
    const double trial = 5e9, dt = 1e-8;  // [Pa], [s]
    const ScalarReturn s = radial_return(jc, G, trial, 0, dt, 20);
    const double rate = s.dlambda / dt;
    EXPECT_GE(rate, 1e5);  // the case asked for
    ASSERT_TRUE(std::isfinite(s.sigma_eff));
    EXPECT_NEAR(s.sigma_eff + 3 * G * s.dlambda, trial, 8 * eps_d * trial);
    // sigma_y at the measured rate, closed form (A + B ep^n)(1 + C ln rate).
    EXPECT_NEAR(s.sigma_eff, (546e6 + 678e6 * std::pow(s.dlambda, 0.71)) * (1 + 0.024 * std::log(rate)), 1e-12 * trial);
}

TEST(LawsPlastic, ThermalSofteningNearAndAboveMelt)
{
    const JohnsonCook jc = al7075(true);
    for (double theta : {477.0 - 1e-9, 477.0, 600.0}) {
        const ScalarReturn s = radial_return(jc, G, 100e6, 0, 1e-3, theta);
        ASSERT_TRUE(std::isfinite(s.dlambda) && std::isfinite(s.sigma_eff));
        // theta* = 1 - 2.2e-12: 1 - theta*^m ~ m (1 - theta*) = 3.4e-12, sigma_y ~ 2e-3 Pa (< 1 Pa bound
        // below); at and above melt sigma_y = 0 exactly; dl = trial/(3G) to the same relative 1e-8.
        EXPECT_LT(s.sigma_eff, 1e-8 * 100e6);
        EXPECT_NEAR(s.dlambda, 100e6 / (3 * G), 1e-8 * 100e6 / (3 * G));
    }
    // Below theta_ref with a non-integer m: no pow of a negative base, factor 1.
    EXPECT_EQ(jc.thermal_factor(-50), 1.0);
    const ScalarReturn cold = radial_return(jc, G, 700e6, 0, 1, -50);
    ASSERT_TRUE(cold.plastic && std::isfinite(cold.dlambda));
    EXPECT_NEAR(cold.sigma_eff + 3 * G * cold.dlambda, 700e6, 8 * eps_d * 700e6);  // consistency to round-off
}

TEST(LawsPlastic, HugeTimeStepUsesTheRateFloor)
{
    const JohnsonCook jc = al7075(true);
    const double trial = 700e6;
    const ScalarReturn s = radial_return(jc, G, trial, 0, 1e9, 20);
    ASSERT_TRUE(s.plastic && std::isfinite(s.dlambda));
    EXPECT_LT(s.dlambda / 1e9, 1e-3);  // the rate lies below the floor epdot0/1000
    // Floor: sigma_y = (A + B dl^n)(1 + C ln 1e-3), closed form at the measured dl.
    EXPECT_NEAR(s.sigma_eff, (546e6 + 678e6 * std::pow(s.dlambda, 0.71)) * (1 + 0.024 * std::log(1e-3)), 1e-12 * trial);
    EXPECT_NEAR(s.sigma_eff + 3 * G * s.dlambda, trial, 8 * eps_d * trial);
}

TEST(LawsPlastic, HundredPercentStrainAndFirstYieldWithNBelowOne)
{
    const JohnsonCook jc = al7075(false);
    const IsotropicElastic el{K, G};
    // 100 % equivalent strain in one step.
    const J2Update u = j2_strain_update(el, jc, strain_path(1.0, 0), {}, 1.0, 20);
    ASSERT_TRUE(std::isfinite(u.history.ep));
    const double sy = 546e6 + 678e6 * std::pow(u.history.ep, 0.71);  // closed form at the measured ep
    EXPECT_NEAR(u.history.ep + sy / (3 * G), 1.0, 1e-13);               // a = ep + sigma_y/(3G); round-off
    EXPECT_GT(u.history.ep, 0.95);                                      // nearly all of it plastic
    // A trial a hair above A at ep = 0: the slope n B ep^(n-1) is infinite at 0; the return converges.
    const double trial = 546e6 * (1 + 1e-9);
    const ScalarReturn s = radial_return(jc, G, trial, 0, 1, 20);
    ASSERT_TRUE(s.plastic && std::isfinite(s.dlambda));
    EXPECT_GT(s.dlambda, 0);
    EXPECT_NEAR(s.sigma_eff + 3 * G * s.dlambda, trial, 8 * eps_d * trial);
    EXPECT_LT(s.iterations, 400);  // converged before the iteration cap
}

// dt = 0 (the instantaneous initial step of an explicit run, time/verlet.hpp start): no rate is
// defined, so the rate-dependent law returns as the rate-independent one. Reference: the first
// (rate-independent) row of the V7 table.
TEST(LawsPlastic, InstantaneousStepIsRateIndependent)
{
    const ScalarReturn s = radial_return(al7075(true), G, 700e6, 0.0, 0.0, 20);
    ASSERT_TRUE(s.plastic);
    EXPECT_NEAR(s.dlambda, 1.809711e-3, half_unit_7(1.809711e-3));
    EXPECT_NEAR(s.sigma_eff, 553.6583e6, half_unit_7(553.6583e6));
    EXPECT_THROW(radial_return(al7075(true), G, 700e6, 0.0, -1e-9, 20), std::invalid_argument);
}
