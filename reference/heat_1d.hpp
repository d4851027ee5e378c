// reference/heat_1d.hpp -- classical references for 1D transient heat conduction in a bar whose
// two ends are suddenly held at T_end while the interior starts at T0 (spec/000b sec. 5.7, T7,
// and V8). Independent of the peridynamics library.
//
// Problem: rho c T_t = k T_xx on 0 < x < L, T(0,t) = T(L,t) = T_end, T(x,0) = T0; diffusivity
// alpha = k/(rho c) [m^2/s].
//
// Contents:
//   heat_bar_exact_temperature   Fourier series of the continuum solution
//   heat_bar_exact_time_to       time at which a point reaches a temperature (continuum; GSL root)
//   heat_bar_fd_time_to          the source's "classical" column: 3-point finite differences on
//                                N+1 nodes (dx = L/N, Dirichlet end nodes), implicit Euler with a
//                                fixed step, linear interpolation in time of the crossing
// Spec reconstruction (T7): L = 0.1 m, alpha = 50/(7800 * 502.08) = 1.27674e-5 m^2/s, T0 = 0,
// T_end = 100, centre to 50: exact 74.163 s; FD with dt = 10 s: 78.505 (N = 10), 78.635 (50),
// 78.639 (100), 78.640 s (200 and more).
#pragma once

#include <vector>

namespace pd::ref {

struct HeatBar1D {
    double L = 0.1;          // length [m]
    double alpha = 0;        // diffusivity k/(rho c) [m^2/s]
    double T0 = 0;           // initial interior temperature [C or K]
    double T_end = 100;      // temperature held at both ends from t = 0 [C or K]
};

// Continuum temperature [same unit as T0] at x [m], t > 0 [s]:
// T = T_end + (T0 - T_end) sum_{n odd} 4/(n pi) sin(n pi x/L) exp(-alpha (n pi/L)^2 t),
// summed until the terms fall below 1e-16 of |T0 - T_end| (t = 0 returns T0 inside, T_end at the ends).
double heat_bar_exact_temperature(const HeatBar1D& bar, double x, double t);

// Continuum time [s] at which the point x first reaches T_target (strictly between T0 and T_end),
// by bracketing and Brent's method (GSL) to 1e-12 relative. Throws std::invalid_argument otherwise.
double heat_bar_exact_time_to(const HeatBar1D& bar, double x, double T_target);

// Time [s] at which the node nearest x of the 3-point finite-difference bar (N intervals, N+1 nodes,
// end nodes held at T_end) first reaches T_target under implicit Euler with step dt [s], the
// crossing linearly interpolated between the two steps around it. Throws std::invalid_argument for
// N < 2, dt <= 0, or a target not strictly between T0 and T_end; std::runtime_error if the target
// is not reached within t_max [s].
double heat_bar_fd_time_to(const HeatBar1D& bar, int N, double dt, double x, double T_target, double t_max = 1e6);

// Temperatures of the same finite-difference bar (N+1 nodes x_i = i L/N) after `steps` implicit-Euler
// steps of dt [s]. Throws std::invalid_argument for N < 2, dt <= 0 or steps < 0.
std::vector<double> heat_bar_fd_profile(const HeatBar1D& bar, int N, double dt, int steps);

}  // namespace pd::ref
