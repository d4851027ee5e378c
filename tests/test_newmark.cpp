// Newmark, beta = 1/4, gamma = 1/2 (time/newmark.hpp), against closed forms of the trapezoidal
// rule: a one-spring oscillator follows u_n = u0 cos(n theta), theta = 2 atan(omega dt / 2), at
// any step (also far beyond the explicit limit omega dt = 2); a linear multi-dof bar conserves its
// energy to round-off with one factorisation for the whole run.
#include "pd/models/lps.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/newmark.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace pd;

namespace {
constexpr double E = 200e9, rho = 7800, A = 1e-4, dx = 0.01;  // [Pa], [kg/m^3], [m^2], [m]
}

// Two nodes, one bond of length dx, delta = dx, node 0 fixed. 1D PMB with the continuum
// micromodulus c = 2E/(A delta^2) (pmb.hpp): the node carries the spring K = V c V / dx and the mass
// rho V, so omega = sqrt(2E/rho)/dx, written here from the constants alone. A 1D bond does not
// rotate: the oscillator is linear and the discrete solution is exactly u0 cos(n theta) (u_1 =
// u0 (1 - x)/(1 + x) = u0 cos theta, x = (omega dt/2)^2, and the three-term recurrence). The
// tolerance 1e-9 u0 covers the Newton tolerance (1e-10 of the force scale) and round-off over
// 200 steps.
TEST(Newmark, OscillatorFollowsTrapezoidalClosedForm)
{
    const Body<1> body = box<1>({{0}}, {{2 * dx}}, dx, A);
    Bonds bonds = build_bonds(body, dx);
    PMB pmb({.material = Elastic::from_E_nu(E, 0.25), .dim = 1, .measure = A}, bonds);
    const double omega = std::sqrt(2 * E / rho) / dx;  // [rad/s]
    const double u0 = 1e-3 * dx;                       // [m]
    for (double wdt : {0.5, 2.0, 10.0}) {
        Newmark<1, PMB> nm(body, bonds, pmb, rho);
        nm.boundary.fix({0});
        nm.u.c[0][1] = u0;
        nm.start();
        const double dt = wdt / omega, theta = 2 * std::atan(wdt / 2);
        double err = 0;
        for (int n = 1; n <= 200; ++n) {
            nm.step(dt);
            err = std::max(err, std::abs(nm.u.c[0][1] - u0 * std::cos(n * theta)));
        }
        const double period_error = wdt / theta - 1;  // T_h / T - 1 = omega / omega_h - 1
        std::printf("[ newmark ] omega dt = %4.1f: max |u - u0 cos(n theta)| / u0 = %.2e, period error %.4f, %ld factorisations\n",
                    wdt, err / u0, period_error, nm.factorisations);
        EXPECT_LT(err / u0, 1e-9) << "omega dt = " << wdt;
        EXPECT_EQ(nm.factorisations, 1);
        EXPECT_EQ(nm.iterations, 200);
    }
}

// 1D bar, 40 cells, delta = 3 dx, clamp layer of 3 cells held fixed, released from u = eps x: PMB and
// LPS (1D: linear). The trapezoidal rule conserves 1/2 v^T M v + 1/2 u^T K u exactly, and for these
// models the strain energy sum W_i V_i is that quadratic form, so KE + SE stays at its initial
// value up to the Newton tolerance and round-off (bound 1e-10 relative over 400 steps) at
// dt = 10 dx sqrt(rho/E), about 6 times the explicit limit 2/omega_max of this lattice
// (omega_max^2 <= 4 sum_q k_q / (rho V) = (8/9)(1 + 1/2 + 1/3) E/(rho dx^2) with the springs k_q of PMB). The clamp does no
// work (it does not move). One factorisation serves the whole run, one iteration each step.
template <class Model>
void check_energy(Model& model, Bonds& bonds, const Body<1>& body, const char* name)
{
    const double eps = 1e-3;
    Newmark<1, Model> nm(body, bonds, model, rho);
    NodeSet clamp;
    for (std::size_t i = 0; i < body.size(); ++i)
        if (body.x.c[0][i] < 0) clamp.push_back(static_cast<int>(i));
        else nm.u.c[0][i] = eps * body.x.c[0][i];
    nm.boundary.fix(clamp);
    nm.start();
    const double E0 = nm.initial_energy();
    const double dt = 10 * dx * std::sqrt(rho / E);  // [s]
    double drift = 0;
    for (int n = 0; n < 400; ++n) {
        nm.step(dt);
        const Energies e = nm.check_energy();
        drift = std::max(drift, std::abs(e.total() - E0) / E0);
    }
    std::printf("[ newmark ] %s bar: energy drift %.2e over 400 steps, %ld iterations, %ld factorisations\n", name, drift,
                nm.iterations, nm.factorisations);
    EXPECT_LT(drift, 1e-10);
    EXPECT_EQ(nm.factorisations, 1);
    EXPECT_EQ(nm.iterations, 400);
}

TEST(Newmark, LinearBarConservesEnergy)
{
    const double delta = 3 * dx;
    const Body<1> body = box<1>({{-delta}}, {{40 * dx}}, dx, A);
    Bonds bonds = build_bonds(body, delta);
    PMB pmb({.material = Elastic::from_E_nu(E, 0.25), .dim = 1, .measure = A}, bonds);
    LPS lps({Elastic::from_E_nu(E, 0.25), 1}, bonds);
    check_energy(pmb, bonds, body, "PMB");
    check_energy(lps, bonds, body, "LPS");
}

// A failed step is reported, never silent: one Newton iteration allowed on a problem that needs
// none to converge is fine, but zero iterations with a non-zero residual throws.
TEST(Newmark, FailedStepThrows)
{
    const Body<1> body = box<1>({{0}}, {{2 * dx}}, dx, A);
    Bonds bonds = build_bonds(body, dx);
    PMB pmb({.material = Elastic::from_E_nu(E, 0.25), .dim = 1, .measure = A}, bonds);
    Newmark<1, PMB> nm(body, bonds, pmb, rho);
    nm.max_iter = 0;
    nm.boundary.fix({0});
    nm.u.c[0][1] = 1e-5;
    nm.start();
    EXPECT_THROW(nm.step(1e-6), std::runtime_error);
}
