// Agwai heat conduction, the heat loop and the Euler integrators (spec/000b sec. 3, V8, V12).
// Tolerances: 1e-10 on kappa_1 (GSL quadrature of M_1 to 1e-12 relative); 1e-9 relative on
// lattice sums of Q (~100-300 terms of mixed sign, each ~|Q|: cancellation of a few hundred ulps of
// the term scale); 1e-12 on the critical step and held/linear fields (a handful of roundings);
// 1e-10 on the stored heat (200 steps of ~40 nodes each accumulate round-off).
#include "pd/heat/agwai.hpp"
#include "pd/heat/conduction.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/parallel.hpp"

#include <gtest/gtest.h>

#include "heat_fixtures.hpp"

#include <cmath>
#include <numbers>

namespace {

constexpr double pi = std::numbers::pi;

using pd_test::cube;

// Index of the node nearest the centre of an n^D cube.
template <int D>
std::size_t centre_node(const pd::Body<D>& b, int n, double dx)
{
    std::size_t best = 0;
    double dmin = 1e300;
    for (std::size_t i = 0; i < b.size(); ++i) {
        double r = 0;
        for (int d = 0; d < D; ++d) r += std::pow(b.x.c[d][i] - 0.5 * n * dx, 2);
        if (r < dmin) dmin = r, best = i;
    }
    return best;
}

// Sum over the full cubic-lattice family |n| <= m of |n| (independent of the library).
double lattice_sum_abs_n(double m, int dim)
{
    const int r = int(std::floor(m));
    double s = 0;
    for (int a = -r; a <= r; ++a)
        for (int b = dim > 1 ? -r : 0; b <= (dim > 1 ? r : 0); ++b)
            for (int c = dim > 2 ? -r : 0; c <= (dim > 2 ? r : 0); ++c) {
                const double len = std::sqrt(double(a * a + b * b + c * c));
                if (len > 0 && len <= m * (1 + 1e-10)) s += len;
            }
    return s;
}

}  // namespace

TEST(Heat, MicroConductivityClosedForms)
{
    const double k = 50, delta = 3e-3, A = 1e-4, s = 2e-3;
    EXPECT_NEAR(pd::agwai_micro_conductivity(k, 1, delta, A), 2 * k / (A * delta * delta), 1e-10 * 2 * k / (A * delta * delta));
    EXPECT_NEAR(pd::agwai_micro_conductivity(k, 2, delta, s), 6 * k / (pi * s * std::pow(delta, 3)), 1e-10 * 6 * k / (pi * s * std::pow(delta, 3)));
    EXPECT_NEAR(pd::agwai_micro_conductivity(k, 3, delta, 1), 6 * k / (pi * std::pow(delta, 4)), 1e-10 * 6 * k / (pi * std::pow(delta, 4)));
    // spec/000b V9: kappa_1 = 1.1035e12 for k = 50, delta = 3.05 mm.
    EXPECT_NEAR(pd::agwai_micro_conductivity(50, 3, 3.05e-3, 1), 1.1035e12, 5e7);
}

// Q for theta = x^2/2 at an interior node, divided by k theta'' = k: the lattice ratio sum|n| V /M_1
// without correction (spec V12: 1.0491 for m = 3.05 in 3D), exactly 1 with the thermal correction.
template <int D>
void quadratic_field_case(double m, double measure)
{
    const int n = 14;  // the centre's neighbours have full families too (pair_mean)
    const double dx = 1e-3, k = 50;
    const auto body = cube<D>(n, dx, measure);
    const auto bonds = pd::build_bonds(body, m * dx);
    const std::size_t c = centre_node(body, n, dx);
    std::vector<double> theta(body.size()), Q;
    for (std::size_t i = 0; i < body.size(); ++i) theta[i] = 0.5 * body.x.c[0][i] * body.x.c[0][i];
    for (auto corr : {pd::ThermalCorrection::none, pd::ThermalCorrection::per_node, pd::ThermalCorrection::pair_mean}) {
        pd::Agwai model({k, measure, corr}, body, bonds);
        pd::heat_flow(model, bonds, theta, Q);
        // Continuum M_1 of the horizon, by hand: 1D A delta^2, 2D s 2 pi delta^3/3, 3D pi delta^4.
        const double delta = m * dx;
        const double M1 = D == 1 ? measure * delta * delta : D == 2 ? measure * 2 * pi * std::pow(delta, 3) / 3 : pi * std::pow(delta, 4);
        const double lattice = lattice_sum_abs_n(m, D) * std::pow(dx, D + 1) * measure / M1;
        const double expected = corr == pd::ThermalCorrection::none ? lattice : 1.0;
        EXPECT_NEAR(Q[c] / k, expected, 1e-9) << "D = " << D << " correction " << int(corr);
    }
}

TEST(Heat, QuadraticFieldIdentityInTheInterior)
{
    quadratic_field_case<1>(3.0, 1e-4);
    quadratic_field_case<2>(3.05, 2e-3);
    quadratic_field_case<3>(3.05, 1);
    // The spec's bulk numbers (V12): k_eff/k = sum|n|/(pi m^4) = 1.0491 (m = 3.05), TCF = 0.9532.
    EXPECT_NEAR(lattice_sum_abs_n(3.05, 3) / (pi * std::pow(3.05, 4)), 1.0491, 5e-5);
    const auto body = cube<3>(12, 1e-3);
    const auto bonds = pd::build_bonds(body, 3.05e-3);
    pd::Agwai model({50, 1, pd::ThermalCorrection::per_node}, body, bonds);
    EXPECT_NEAR(model.tcf[centre_node(body, 12, 1e-3)], 0.9532, 5e-5);
}

TEST(Heat, OneDimensionalHalfVolumeOuterNeighbourGivesExactlyK)
{
    // spec/000b V8 unit check: delta = 3 dx, half volume for the neighbour at |xi| = delta gives Q = k
    // for theta = x^2/2; full volumes give 4/3 k.
    const double dx = 1e-3, A = 1e-4, k = 50;
    const auto body = cube<1>(20, dx, A);
    std::vector<double> theta(body.size()), Q;
    for (std::size_t i = 0; i < body.size(); ++i) theta[i] = 0.5 * body.x.c[0][i] * body.x.c[0][i];
    const auto c = centre_node(body, 20, dx);
    pd::BondOptions half;
    half.partial_volume = pd::PartialVolume::pa_pdlammps;
    const auto b_half = pd::build_bonds(body, 3 * dx, half);
    pd::Agwai m_half({k, A}, body, b_half);
    pd::heat_flow(m_half, b_half, theta, Q);
    EXPECT_NEAR(Q[c], k, 1e-9 * k);
    const auto b_full = pd::build_bonds(body, 3 * dx);
    pd::Agwai m_full({k, A}, body, b_full);
    pd::heat_flow(m_full, b_full, theta, Q);
    EXPECT_NEAR(Q[c], 4.0 / 3 * k, 1e-9 * k);
}

TEST(Heat, ThermalCriticalStepHandValue)
{
    // 1D interior node, delta = 3 dx, full volumes: sum_j kappa_1 A dx/|xi| = kappa_1 A 2 (1 + 1/2 + 1/3).
    const double dx = 1e-3, A = 1e-4, k = 50, rho_c = 7800 * 502.08;
    const auto body = cube<1>(30, dx, A);
    const auto bonds = pd::build_bonds(body, 3 * dx);
    pd::Agwai model({k, A}, body, bonds);
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), {});
    const double kappa1 = 2 * k / (A * 9 * dx * dx);
    const double hand = rho_c / (kappa1 * A * 2 * (1 + 0.5 + 1.0 / 3));
    std::vector<double> theta(body.size(), 0.0);
    EXPECT_NEAR(pd::thermal_critical_step(model, bonds, heat, theta), hand, 1e-12 * hand);
}

TEST(Heat, InsulatedBarWithSourceStoresExactlyTheHeatPutIn)
{
    const double dx = 1e-3, A = 1e-4, k = 50, rho_c = 7800 * 502.08, s = 2e6;
    const auto body = cube<1>(40, dx, A);
    const auto bonds = pd::build_bonds(body, 3 * dx);
    pd::Agwai model({k, A}, body, bonds);
    pd::HeatLoads loads;
    loads.source.assign(body.size(), 0.0);
    for (std::size_t i = 0; i < 10; ++i) loads.source[i] = s;  // heated end
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    const double dt = 0.5 * pd::thermal_critical_step(model, bonds, heat, std::vector<double>(body.size(), 0.0));
    for (int scheme = 0; scheme < 2; ++scheme) {
        std::vector<double> theta(body.size(), 20.0);
        const int steps = 200;
        for (int n = 0; n < steps; ++n) scheme ? heat.implicit_euler(theta, 10 * dt) : heat.explicit_euler(theta, dt);
        double stored = 0;
        for (std::size_t i = 0; i < body.size(); ++i) stored += rho_c * (theta[i] - 20.0) * body.volume[i];
        const double put_in = s * 10 * dx * A * steps * (scheme ? 10 * dt : dt);
        EXPECT_NEAR(stored, put_in, 1e-10 * put_in) << (scheme ? "implicit" : "explicit");
        EXPECT_GT(theta[0], theta[39] + 1e-3);  // heat actually flowed from the heated end
    }
}

TEST(Heat, SteadyLinearProfileStaysSteady)
{
    // Fixed layers of delta = 3 dx at both ends with the linear values: every free node has a full,
    // symmetric family, so Q = 0 exactly for a linear field.
    const double dx = 1e-3, A = 1e-4, k = 50, rho_c = 3.9e6;
    const auto body = cube<1>(30, dx, A);
    const auto bonds = pd::build_bonds(body, 3 * dx);
    pd::Agwai model({k, A}, body, bonds);
    pd::HeatLoads loads;
    std::vector<double> line(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) line[i] = 10 + 3000 * body.x.c[0][i];
    for (int i : {0, 1, 2, 27, 28, 29}) loads.fixed.push_back(i), loads.fixed_value.push_back(line[i]);
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    std::vector<double> a = line, b = line;
    for (int n = 0; n < 100; ++n) heat.explicit_euler(a, 1e-3), heat.implicit_euler(b, 1.0);
    for (std::size_t i = 0; i < body.size(); ++i) {
        EXPECT_NEAR(a[i], line[i], 1e-12 * 100);
        EXPECT_NEAR(b[i], line[i], 1e-12 * 100);
    }
}

TEST(Heat, ConvectionCoolsTowardsAmbientAtTheLumpedRate)
{
    // Uniform temperature, uniform h: no conduction, d theta/dt = -h (theta - T_inf)/(rho c):
    // implicit Euler gives exactly (theta - T_inf) / (1 + h dt/rho c) per step.
    const double dx = 1e-3, A = 1e-4, rho_c = 3.9e6, h = 1e4, dt = 5;
    const auto body = cube<1>(10, dx, A);
    const auto bonds = pd::build_bonds(body, 3 * dx);
    pd::Agwai model({50, A}, body, bonds);
    pd::HeatLoads loads;
    loads.h.assign(body.size(), h);
    loads.T_inf = 20;
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    std::vector<double> theta(body.size(), 100.0);
    heat.implicit_euler(theta, dt);
    for (double t : theta) EXPECT_NEAR(t, 20 + 80 / (1 + h * dt / rho_c), 1e-9);
    std::vector<double> e(body.size(), 100.0);
    heat.explicit_euler(e, dt);
    for (double t : e) EXPECT_NEAR(t, 100 - dt * h * 80 / rho_c, 1e-9);  // cooling, not heating
}

// spec/000a V8: a surface flux q applied as r = q/Delta on a layer of thickness Delta delivers the
// power q S, and conduction passes it on without loss: after n explicit steps the heat content of the
// body is q S n dt (Agwai conserves heat; round-off of the sums only).
TEST(Heat, SurfaceFluxDeliversQTimesAreaThroughItsLayer)
{
    const int n = 8;
    const double dx = 1e-3, rho_c = 3e6, q = 2.5e5, dt = 0.05;  // [m], [J/(m^3 K)], [W/m^2], [s]
    const auto body = cube<3>(n, dx);
    const auto bonds = pd::build_bonds(body, 3.05 * dx);
    std::vector<int> layer;  // two cells deep on the face x = 0
    for (std::size_t i = 0; i < body.size(); ++i) if (body.x.c[0][i] < 2 * dx) layer.push_back(int(i));
    pd::HeatLoads loads;
    pd::add_surface_flux(loads, body.size(), layer, q, 2 * dx);
    double power = 0;
    for (std::size_t i = 0; i < body.size(); ++i) power += loads.source[i] * body.volume[i];
    const double S = (n * dx) * (n * dx);
    EXPECT_NEAR(power, q * S, 1e-12 * q * S);
    pd::Agwai model({1.6736}, body, bonds);
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    std::vector<double> theta(body.size(), 30.0);
    for (int s = 0; s < 20; ++s) heat.explicit_euler(theta, dt);
    double content = 0;
    for (std::size_t i = 0; i < body.size(); ++i) content += rho_c * (theta[i] - 30) * body.volume[i];
    EXPECT_NEAR(content, q * S * 20 * dt, 1e-10 * q * S * 20 * dt);
    EXPECT_GT(theta[layer[0]], theta[body.size() - 1]);  // and it enters at the face
}

TEST(Heat, BrokenBondsInsulate)
{
    const double dx = 1e-3, A = 1e-4;
    const auto body = cube<1>(20, dx, A);
    auto bonds = pd::build_bonds(body, 3 * dx);
    bonds.enable_damage();
    for (std::size_t i = 0; i < bonds.nodes(); ++i)
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k)
            if ((body.x.c[0][i] < 0.01) != (body.x.c[0][bonds.partner[k]] < 0.01)) bonds.intact[k] = 0;
    pd::Agwai model({50, A}, body, bonds);
    std::vector<double> theta(body.size()), Q;
    for (std::size_t i = 0; i < body.size(); ++i) theta[i] = body.x.c[0][i] < 0.01 ? 100 : 0;
    pd::heat_flow(model, bonds, theta, Q);
    for (double q : Q) EXPECT_EQ(q, 0.0);
}

TEST(Heat, OneAndTwoThreadsBitIdentical)
{
    const auto body = cube<3>(16, 1e-3);
    const auto bonds = pd::build_bonds(body, 3.05e-3);
    pd::Agwai model({50, 1, pd::ThermalCorrection::per_node}, body, bonds);
    std::vector<double> theta(body.size()), Q1, Q2;
    for (std::size_t i = 0; i < body.size(); ++i) theta[i] = std::sin(1e3 * body.x.c[0][i]) + body.x.c[1][i] * 7e2;
    pd::set_threads(1);
    pd::heat_flow(model, bonds, theta, Q1);
    pd::set_threads(2);
    pd::heat_flow(model, bonds, theta, Q2);
    for (std::size_t i = 0; i < Q1.size(); ++i) EXPECT_EQ(Q1[i], Q2[i]);
}

TEST(Heat, CvodeImplicitAndExplicitEulerAgreeOnTheBarTransient)
{
    // The same PD bar (ends held at 100, interior at 0) integrated three ways to t = 40 s: CVODE at
    // tight tolerance is the yardstick; explicit and implicit Euler converge to it at first order.
    const double dx = 2e-3, A = 1e-4, k = 50, rho_c = 7800 * 502.08, t_end = 40;
    const auto body = cube<1>(56, dx, A);  // 50 free cells + 3 held on each side
    const auto bonds = pd::build_bonds(body, 3 * dx);
    pd::Agwai model({k, A}, body, bonds);
    pd::HeatLoads loads;
    for (int i : {0, 1, 2, 53, 54, 55}) loads.fixed.push_back(i), loads.fixed_value.push_back(100);
    pd::Conduction<pd::Agwai> heat(model, bonds, std::vector<double>(body.size(), rho_c), loads);
    pd::CvodeOptions opt;
    opt.rtol = opt.atol = 1e-11;
    pd::HeatCvode<pd::Agwai> cv(heat, model, bonds, std::vector<double>(body.size(), 0.0), 0.0, opt);
    const std::vector<double> ref = cv.advance(t_end);
    EXPECT_GT(cv.stats().steps, 10);
    auto error = [&](bool implicit, int steps) {
        std::vector<double> theta(body.size(), 0.0);
        heat.apply_fixed(theta);
        for (int n = 0; n < steps; ++n) implicit ? heat.implicit_euler(theta, t_end / steps) : heat.explicit_euler(theta, t_end / steps);
        double e = 0;
        for (std::size_t i = 0; i < theta.size(); ++i) e = std::max(e, std::abs(theta[i] - ref[i]));
        return e;
    };
    const double dt_crit = pd::thermal_critical_step(model, bonds, heat, std::vector<double>(body.size(), 0.0));
    const int n_exp = int(std::ceil(t_end / (0.5 * dt_crit)));
    const double e1 = error(false, n_exp), e2 = error(false, 2 * n_exp);
    EXPECT_NEAR(e1 / e2, 2.0, 0.1);
    const double i1 = error(true, 40), i2 = error(true, 80);
    EXPECT_NEAR(i1 / i2, 2.0, 0.15);
    EXPECT_LT(i2, 1.0);
}
