// Numerical-viscosity parameters (models/viscoelastic_numerical.hpp) against the values printed in
// spec/000c sec. 2.7 and V6 (Si3N4: E = 310 GPa, nu = 0.29, assumed rho = 3200 kg/m^3, dx = delta/m
// = 0.75 mm / 3.05): c_S = 6128 m/s, f_cS = 24.9 MHz; gamma_b = 0.0201, 0.21, 8.0 and tau_b = 6.32,
// 5.81, 2.13 ns for eta = 1.01, 1.1, 3.0; maximum phase asin(gamma_b/(2 + gamma_b)) = 0.57, 5.45, 53.1 deg.
// Tolerances: half a unit of the last printed digit (gamma_b: exact).
#include "pd/core/material.hpp"
#include "pd/models/viscoelastic_numerical.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

TEST(ViscoelasticNumerical, SpecV6Values)
{
    const pd::Elastic si3n4 = pd::Elastic::from_E_nu(310e9, 0.29);
    const double rho = 3200, dx = 0.75e-3 / 3.05;  // [kg/m^3], [m]
    EXPECT_NEAR(std::sqrt(si3n4.G / rho), 6128, 0.5);              // c_S [m/s]
    EXPECT_NEAR(std::sqrt(si3n4.G / rho) / dx, 24.9e6, 0.05e6);    // f_cS [Hz]
    const double eta[] = {1.01, 1.1, 3.0}, gamma[] = {0.0201, 0.21, 8.0}, tau_ns[] = {6.32, 5.81, 2.13}, phase[] = {0.57, 5.45, 53.1};
    const double half_digit_phase[] = {0.005, 0.005, 0.05};        // [deg]
    for (int c = 0; c < 3; ++c) {
        const pd::MaxwellShear p = pd::numerical_viscosity(si3n4.G, rho, dx, eta[c]);
        EXPECT_NEAR(p.gamma_b, gamma[c], 1e-12) << "eta " << eta[c];  // printed values are exact: eta^2 - 1
        EXPECT_NEAR(p.tau_b * 1e9, tau_ns[c], 0.005) << "eta " << eta[c];
        EXPECT_NEAR(std::asin(p.gamma_b / (2 + p.gamma_b)) * 180 / std::numbers::pi, phase[c], half_digit_phase[c]);
        // Without the 2 pi (erratum 7) tau_b is 2 pi times longer.
        EXPECT_NEAR(pd::numerical_viscosity(si3n4.G, rho, dx, eta[c], false).tau_b / p.tau_b, 2 * std::numbers::pi, 1e-12);
    }
    EXPECT_THROW(pd::numerical_viscosity(si3n4.G, rho, dx, 1.0), std::invalid_argument);
}
