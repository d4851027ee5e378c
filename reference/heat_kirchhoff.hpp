// reference/heat_kirchhoff.hpp -- classical 1D conduction with a temperature-dependent conductivity
// k(T), independent of the peridynamics library.
//
// Steady bar (Kirchhoff transform): with Phi(T) = int_{T_ref}^{T} k(s) ds [W/m], the steady equation
// (k(T) T')' = 0 becomes Phi'' = 0, so Phi(T(x)) is linear in x between the held ends:
//   Phi(T(x)) = Phi(T_a) + (Phi(T_b) - Phi(T_a)) x / L,   flux q = -(Phi(T_b) - Phi(T_a)) / L [W/m^2].
//   Linear law k = k0 (1 + beta (T - T0)):  Phi = k0 (u + beta u^2 / 2), u = T - T0, so
//   T = T0 + 2 P / (k0 (1 + sqrt(1 + 2 beta P / k0)))  for Phi = P  (the root that tends to P/k0 as beta -> 0).
//   General k (a callable): Phi by GSL adaptive quadrature (QAGS, 1e-13 relative), T by Brent's
//   method (GSL) on Phi(T) = P to 1e-13 relative.
//
// Transient bar: rho c T_t = (k(T) T_x)_x on 0 < x < L, T(0, t) = T(L, t) = T_end, T(x, 0) = T0
// (rho c constant). Method of lines on n cells (cell centres, Dirichlet ends by the ghost cell
// 2 T_end - T), face fluxes in Kirchhoff form F = -(Phi(T_right) - Phi(T_left)) / h, which makes
// the scheme exact for every steady profile of the cell values and conservative; h = L/n inside and
// L/(2n) to the held end. Integrated by SUNDIALS CVODE (BDF, GMRES preconditioned by the exact
// tridiagonal Jacobian solved by the Thomas algorithm). Second order in space.
#pragma once

#include <functional>
#include <vector>

namespace pd::ref {

using Conductivity = std::function<double(double)>;  // k(T) [W/(m K)]

// Kirchhoff potential of the linear law, Phi(T) = k0 (u + beta u^2/2), u = T - T0 [W/m], and its inverse.
double kirchhoff_linear_phi(double k0, double beta, double T0, double T);
double kirchhoff_linear_inverse(double k0, double beta, double T0, double P);

// Steady temperature at x [m] of a bar [0, L] held at T_a (x = 0) and T_b (x = L), linear law
// (closed form). x may lie outside [0, L] (the same linear Phi extended).
double kirchhoff_linear_steady(double k0, double beta, double T0, double L, double T_a, double T_b, double x);

// The same for a general k(T) > 0 by quadrature and root finding (see the header).
class KirchhoffBar {
public:
    KirchhoffBar(Conductivity k, double L, double T_a, double T_b);
    double phi(double T) const;          // int_{T_a}^{T} k [W/m]
    double temperature(double x) const;  // steady T(x) [same unit as T_a]
    double flux() const;                 // q = -(Phi(T_b) - Phi(T_a)) / L, positive along +x [W/m^2]

private:
    Conductivity k_;
    double L_, T_a_, T_b_, phi_b_;
};

// EN 1993-1-2 (2005) eq. (3.13), carbon-steel conductivity [W/(m K)] of T [C], clamped to its
// range 20..1200 C: 54 - 3.33e-2 T below 800 C, 27.3 from 800 C; and its Kirchhoff potential in closed
// form, Phi(T) = int_20^T k [W/m] (54 u - 1.665e-2 (T^2 - 400) on 20..800, then linear).
double en1993_steel_k(double T);
double en1993_steel_phi(double T);

struct KBar1D {
    double L = 0.1;       // length [m]
    double rho_c = 0;     // volumetric heat capacity [J/(m^3 K)]
    double T0 = 20;       // initial temperature [C or K]
    double T_end = 1000;  // temperature held at both ends from t = 0
    Conductivity k;       // k(T) [W/(m K)]
    Conductivity phi;     // its Kirchhoff potential (any additive constant) [W/m]
};

struct KBarResult {
    std::vector<double> x, T;  // cell centres [m] and temperatures at t_end
    double t_cross = -1;       // time the centre first reaches T_target [s] (-1: not asked / not reached)
    long steps = 0;            // CVODE internal steps
};

// Integrates to t_end [s] with n cells (n even: the centre value is the mean of the two middle cells),
// CVODE rtol (atol = rtol |T_end - T0|); with T_target strictly between T0 and T_end also returns the
// first time the centre reaches it (bisection on CVODE's interpolant). Throws std::invalid_argument
// for bad sizes, std::runtime_error when CVODE fails.
KBarResult kbar_transient(const KBar1D& bar, int n, double t_end, double rtol = 1e-10, double T_target = -1e300);

}  // namespace pd::ref
