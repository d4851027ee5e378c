// reference/bar_1d.hpp -- classical references for the fixed-free elastic bar released from a
// uniform axial strain (free axial vibration). Independent of the peridynamics library.
//
// Problem: bar of length l [m], Young's modulus E [Pa], density rho [kg/m^3], clamped at x = 0,
// free at x = l; u(x,0) = eps0 x, v(x,0) = 0; wave equation rho u_tt = E u_xx, c = sqrt(E/rho).
// Source: spec/000b_models.md sec. 5.1 (T1) and V1; thesis Eq. (4.36) f_n = (2n-1)/4 sqrt(E/(rho l^2)).
//
// Contents:
//   bar_frequency                exact natural frequencies f_n [Hz]
//   bar_modal_displacement       exact modal series u(x,t), truncated to n_terms modes
//   bar_tip_displacement_exact   closed form (triangle wave) of u(l,t) from d'Alembert
//   fe_bar_frequency             lowest eigenfrequency of the lumped linear FE bar (Eigen)
//   fe_bar_tip_history           lumped linear FE bar integrated by SUNDIALS CVODE
//   fe_bar_modal_tip_history     exact solution of the same semi-discrete FE system (discrete modes)
//   dominant_frequency           first natural frequency measured on a sampled signal
//   zero_crossing_frequency      its first stage: mean period between zero crossings
//   integral_relative_error      E1 = sum|a - ref| / sum|ref| (spec 5.1 reconstruction metric)
#pragma once

#include <vector>

namespace pd::ref {

// Exact natural frequency of mode n >= 1 of the fixed-free bar [Hz]:
// f_n = (2n-1)/4 sqrt(E/(rho l^2)) (thesis Eq. 4.36). E [Pa], rho [kg/m^3], l [m].
double bar_frequency(int n, double E, double rho, double l);

// Exact modal series of the released bar, first n_terms modes [m]:
// u(x,t) = sum_n b_n sin(k_n x) cos(w_n t), k_n = (2n-1) pi/(2l), w_n = c k_n,
// b_n = 2 eps0 (-1)^(n+1) / (l k_n^2). x [m], t [s], eps0 [-].
double bar_modal_displacement(double x, double t, double E, double rho, double l, double eps0,
                              int n_terms);

// Closed-form tip displacement u(l,t) [m]: triangle wave of period 4l/c, amplitude eps0 l,
// u(l,0) = eps0 l, falling linearly to -eps0 l at t = 2l/c and back (d'Alembert).
double bar_tip_displacement_exact(double t, double E, double rho, double l, double eps0);

// Sampled tip history: t_s [s] and tip_m [m] at n_out+1 equally spaced times in [0, t_end].
struct FeBarResult {
    std::vector<double> t_s;    // sample times [s]
    std::vector<double> tip_m;  // tip displacement u(l,t) [m]
};

// Lumped linear FE bar (N >= 2 nodes, dx = l/(N-1), node 0 clamped), M u'' + K u = 0 integrated
// as a first-order system of size 2(N-1) by CVODE (Adams, Newton with banded direct solver,
// rtol 1e-10, atol 1e-12 eps0 l on u and 1e-12 eps0 c on v). Every mode must be resolved at this
// tolerance, so the cost grows ~ N^2 t_end: N = 200 takes ~1 s per T1 (2 cores, -O3).
// Throws std::runtime_error if CVODE fails.
FeBarResult fe_bar_tip_history(int N, double E, double rho, double l, double eps0, double t_end,
                               int n_out);

// Exact solution of the same lumped FE system by its closed-form discrete modes (no time
// integration): u_j(t) = sum_n a_n sin(k_n x_j) cos(w_n^h t), w_n^h = (2c/dx) sin(k_n dx/2).
FeBarResult fe_bar_modal_tip_history(int N, double E, double rho, double l, double eps0,
                                     double t_end, int n_out);

// Lowest eigenfrequency of the lumped linear FE bar [Hz], from Eigen's SelfAdjointEigenSolver
// on M^{-1/2} K M^{-1/2}.
double fe_bar_frequency(int N, double E, double rho, double l);

// First natural frequency [Hz] of a sampled quasi-periodic signal (t [s] increasing, any unit for
// signal): zero-crossing estimate (below) refined by maximising a Hann-windowed sine fit around it
// (method documented in bar_1d.cpp). Isolates the fundamental even when the harmonics are not
// exact multiples of it (dispersive discrete bars). Returns NaN if fewer than two full periods.
double dominant_frequency(const std::vector<double>& t, const std::vector<double>& signal,
                          double f_guess);

// Mean repetition frequency [Hz] from zero crossings (Schmitt trigger with hysteresis 1/4 of the
// peak amplitude, linear interpolation, least-squares fit of crossing times). f_guess [Hz] sets
// the minimum crossing separation 0.5/f_guess. Exact on a triangle wave; NaN if < 2 periods.
double zero_crossing_frequency(const std::vector<double>& t, const std::vector<double>& signal,
                               double f_guess);

// Integral relative error E1 = sum_i |a_i - ref_i| / sum_i |ref_i| on equal-length, uniformly
// sampled series (the uniform dt cancels), i.e. int|a - ref| dt / int|ref| dt. Throws
// std::invalid_argument on size mismatch, empty input or an all-zero reference.
double integral_relative_error(const std::vector<double>& a, const std::vector<double>& ref);

}  // namespace pd::ref
