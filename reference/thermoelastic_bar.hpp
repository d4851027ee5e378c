// reference/thermoelastic_bar.hpp -- classical thermoelasticity of a bar clamped at both ends, one end
// held at T0 + dT, the other at T0 (spec/000a sec. 2.11, 3.3; issue 20). Independent of the
// peridynamics library.
//
// Equations (one-way coupling: the temperature strains the bar, the strain does not heat it):
//   rho u_tt = d sigma/dx,  sigma = E (u_x - alpha theta),   rho c theta_t = k theta_xx,
//   u(0) = u(L) = 0,  theta(0, t) = dT r(t),  theta(L) = 0,  u = u_t = theta = 0 at t = 0,
// theta the temperature above T0 [K]; r(t) = s^3 (10 - 15 s + 6 s^2), s = min(t/t_r, 1), rises from 0 to 1
// over t_r with zero first and second derivatives at both ends (thermoelastic_ramp); t_r = 0 is a step. Semi-discretisation: M cells of h = L/M, nodes x_i = i h,
// unknowns u_i, v_i, theta_i at the M - 1 inner nodes (interleaved per node); sigma at the mid-cells,
//   sigma_(i+1/2) = E ((u_(i+1) - u_i)/h - alpha (theta_i + theta_(i+1))/2),
//   rho v_i' = (sigma_(i+1/2) - sigma_(i-1/2))/h,   rho c theta_i' = k (theta_(i+1) - 2 theta_i + theta_(i-1))/h^2.
// The wall stresses are sigma_(1/2) and sigma_(M-1/2): the clamped end node has no inertia, so they are
// the reactions of the walls per unit area. T_mid = theta at x = L/2 (M even).
// Integrators:
//   thermoelastic_bar_mri    SUNDIALS ARKODE MRIStep: the mechanics fast (ARKStep explicit RK4, fixed
//                            step h_f = fast_cfl h/c), the heat slow (MRIStep's default explicit
//                            third-order coupling, fixed step H = slow_fraction h^2/kappa rounded down to
//                            a whole number of fast steps, kappa = k/(rho c); h_f = H when that is smaller);
//   thermoelastic_bar_cvode  the same system in one, SUNDIALS CVODE BDF with Newton and a banded direct
//                            solver, relative tolerance rtol (absolute: rtol times alpha dT L, alpha dT c, dT).
// Both sample the wall stresses and T_mid at the given times; both throw std::runtime_error naming the
// SUNDIALS call that failed and std::invalid_argument for a bad bar.
#pragma once

#include <vector>

namespace pd::ref {

struct ThermoelasticBar {
    double L = 0;      // length [m]
    double E = 0;      // Young's modulus [Pa]
    double rho = 0;    // density [kg/m^3]
    double alpha = 0;  // linear thermal expansion coefficient [1/K]
    double k = 0;      // thermal conductivity [W/(m K)]
    double c = 0;      // specific heat [J/(kg K)]
    double dT = 0;     // temperature rise of the hot end [K]
    double ramp = 0;   // t_r: duration of its rise [s] (header); 0: a step at t = 0
    int cells = 0;     // M, even, >= 4
};

struct ThermoelasticHistory {
    std::vector<double> t_s;           // sample times [s]
    std::vector<double> stress_left;   // sigma at x = 0 [Pa]
    std::vector<double> stress_right;  // sigma at x = L [Pa]
    std::vector<double> T_mid;         // theta at x = L/2 [K above T0]
    long fast_steps = 0, slow_steps = 0;  // MRI: inner and outer steps; CVODE: steps (slow_steps 0)
    double wall_s = 0;                 // wall time of the integration [s]
};

// r(t) of the header [-].
double thermoelastic_ramp(double t, double t_r);

ThermoelasticHistory thermoelastic_bar_mri(const ThermoelasticBar& bar, const std::vector<double>& t_out, double fast_cfl = 0.5,
                                           double slow_fraction = 0.2);
ThermoelasticHistory thermoelastic_bar_cvode(const ThermoelasticBar& bar, const std::vector<double>& t_out, double rtol = 1e-8);

}  // namespace pd::ref
