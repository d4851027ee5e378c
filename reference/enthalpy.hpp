// reference/enthalpy.hpp -- exact sensible enthalpy of carbon steel with the EN 1993-1-2 specific
// heat, and the adiabatic heating times it implies (spec/000a sec. 3.9 and V2; seed 000a sec. 3.8.2,
// eqs. 3.36-3.37). Independent of the peridynamics library: the branches are integrated here by
// hand, not through pd::Property.
//
//   q(theta) = int_20^theta c(T) dT  [J/kg], branch antiderivatives (theta in C):
//     20..600    425 T + a1 T^2/2 - 1.69e-3 T^3/3 + 2.22e-6 T^4/4      (a1 = 7.73e-1, erratum E14)
//     600..735   666 T - 13002 ln(738 - T)
//     735..900   545 T + 17820 ln(T - 731)
//     900..1200  650 T
//   q(1200) = 827063.84 J/kg (eq. 3.37); with the printed a1 = 7.33e-1 it is 819871.84 J/kg.
// Uniform volumetric source s [W/m^3] on an adiabatic body of density rho [kg/m^3], starting at
// theta0: rho dq = s dt, so the time to reach theta is t = rho (q(theta) - q(theta0)) / s and the
// temperature at time t is the inverse of q (Brent's method, GSL).
#pragma once

namespace pd::ref {

struct CarbonSteelCp {
    double a1 = 7.73e-1;  // linear coefficient of the cubic branch [J/(kg K^2)]; 7.33e-1 as printed
};

// c(theta) [J/(kg K)] for 20 <= theta <= 1200 C; throws std::invalid_argument outside.
double carbon_steel_specific_heat(double theta, const CarbonSteelCp& law = {});

// q(theta) [J/kg] from 20 C, for 20 <= theta <= 1200 C; throws std::invalid_argument outside.
double carbon_steel_enthalpy(double theta, const CarbonSteelCp& law = {});

// Temperature [C] with q(theta) = q, for 0 <= q <= q(1200), to 1e-12 relative; throws outside.
double carbon_steel_temperature_at_enthalpy(double q, const CarbonSteelCp& law = {});

// Time [s] for an adiabatic body (rho [kg/m^3], uniform source s [W/m^3]) to heat from theta0 to
// theta [C]: rho (q(theta) - q(theta0)) / s.
double adiabatic_heating_time(double rho, double s, double theta0, double theta, const CarbonSteelCp& law = {});

}  // namespace pd::ref
