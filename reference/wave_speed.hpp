// reference/wave_speed.hpp -- dispersion of a plane longitudinal wave in linearised 3D PMB and LPS,
// and the speed of a pulse's energy centroid. Independent of the peridynamics library.
//
// Wave u_x = U exp(i(k x - w t)), u_y = u_z = 0 (uniaxial strain), in a body with a complete
// family everywhere (infinite body, or laterally periodic slab). Linearising the bond stretch,
// e = (xi_x/|xi|) (u_j - u_i), and summing over the family H (xi_x = x-component of the bond xi,
// r = |xi|, dV its volume, omega(r) the influence):
//   PMB (Silling & Askari 2005):  rho w^2 = c sum_H omega (xi_x^2 / r^3) (1 - cos k xi_x) dV,
//                                 c = 18 K / M1, M1 = integral over the ball of omega r dV (continuum).
//   LPS (Silling et al. 2007, the force state of models/lps.hpp linearised; derivation in
//   reports/3d/wave_block.md):     rho w^2 = (9K - 15G) S1^2 / m^2 + 30 G S2 / m,
//       m = sum omega r^2 dV,  S1 = sum omega xi_x sin(k xi_x) dV,  S2 = sum omega (xi_x/r)^2 (1 - cos k xi_x) dV.
// Both give rho w^2 -> (K + 4G/3) k^2 as k -> 0 for an isotropic family (PMB with G = 3K/5).
// The family sum H is either the continuum ball |xi| <= delta (Gauss-Legendre in r and cos angle)
// or a simple cubic lattice family of spacing dx, |xi| <= delta (1 + 1e-10), dV = beta dx^3 with
// beta the optional PA-PDLAMMPS partial volume (spec/002 sec. 3.2).
// Velocity Verlet (step dt) maps w to W with sin(W dt / 2) = w dt / 2 (von Neumann), so its group
// velocity is dw/dk / sqrt(1 - (w dt/2)^2).
// Pulse: v_x(x, 0) = v0 exp(-((x - x0)/w_p)^2), u = 0 has the energy spectrum E(k) ~ exp(-k^2 w_p^2 / 2);
// each Fourier mode keeps its energy and carries it at its group velocity, so the energy centroid of
// each half pulse moves at the energy-weighted mean group velocity
//   <c_g> = int E(k) c_g(k) dk / int E(k) dk   (k in [0, kmax], kmax = pi/dx on a lattice).
#pragma once

#include <functional>
#include <vector>

namespace pd::ref {

struct WaveMaterial {
    enum class Model { pmb, lps } model = Model::pmb;
    double K = 0;      // bulk modulus [Pa]
    double G = 0;      // shear modulus [Pa] (LPS only; PMB implies G = 3K/5)
    double rho = 0;    // density [kg/m^3]
    double delta = 0;  // horizon [m]
    std::function<double(double r)> omega = [](double) { return 1.0; };  // influence omega(|xi|) [-]
};

// Local P-wave speed sqrt((K + 4G/3)/rho) [m/s]; for PMB G = 3K/5, i.e. sqrt(9K/(5 rho)).
double p_wave_speed(const WaveMaterial& mat);

class LongitudinalDispersion {
public:
    // Continuum family: the ball |xi| <= delta by n_gauss x n_gauss Gauss-Legendre points.
    static LongitudinalDispersion continuum(const WaveMaterial& mat, int n_gauss = 96);
    // Simple cubic lattice family of spacing dx [m]; pa_pdlammps scales dV by beta.
    static LongitudinalDispersion lattice(const WaveMaterial& mat, double dx, bool pa_pdlammps);

    double omega2(double k) const;           // w^2 [rad^2/s^2] at wave number k [1/m]
    double omega(double k) const;            // w [rad/s]
    double phase_velocity(double k) const;   // w/k [m/s]
    double group_velocity(double k, double dt = 0) const;  // dW/dk [m/s]; dt > 0: Verlet-discrete
    double k_max() const { return k_max_; }  // edge of the Brillouin zone pi/dx, or +inf [1/m]
    std::size_t points() const { return xi_x_.size(); }  // family points (bonds) summed

private:
    struct Sums { double a = 0, da = 0; };   // rho w^2 and its k-derivative
    Sums sums(double k) const;
    WaveMaterial mat_;
    double c_ = 0;       // PMB micromodulus 18 K / M1 (continuum M1) [N/m^6]
    double m_ = 0;       // LPS weighted volume sum omega r^2 dV [m^5]
    double k_max_ = 0;   // [1/m]
    std::vector<double> xi_x_, r_, w_dV_;  // per family point: xi_x [m], |xi| [m], omega dV [m^3]
};

// Energy-weighted averages over the pulse spectrum E(k) ~ exp(-k^2 w_p^2 / 2), k in [0, min(kmax, 12/w_p)]
// (the weight beyond 12/w_p is below e^-72): mean group velocity [m/s] (Verlet step dt, 0 = exact
// time) and mean w^2 [rad^2/s^2].
double mean_group_velocity(const LongitudinalDispersion& disp, double pulse_width, double dt = 0);
double mean_omega2(const LongitudinalDispersion& disp, double pulse_width);

// Measurement helpers for sampled histories. Least-squares slope dy/dt over the samples with
// t >= t0 (NaN if fewer than two), and the largest relative deviation max_n |s_n / s_0 - 1|.
double least_squares_slope(const std::vector<double>& t, const std::vector<double>& y, double t0);
double max_relative_deviation(const std::vector<double>& s);

}  // namespace pd::ref
