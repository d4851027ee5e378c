// reference/uniaxial_stretch.hpp -- closed-form (or one-dimensional-quadrature) uniaxial-stress
// curves of the continuum laws behind the models of problems/3d/large_stretch.cpp, for an axial
// stretch lambda = 1 + nominal strain, lateral stretch mu from the free lateral surfaces
// (sigma_yy = sigma_zz = 0). Independent of the peridynamics library.
//   Hypoelastic, Flanagan-Taylor (sigma_hat' = K tr(d) I + 2G dev(d), no rotation in uniaxial
//   tension): d_xx = lambda'/lambda, d_yy = -nu d_xx, so Cauchy sigma = E ln(lambda),
//   mu = lambda^-nu, engineering P = sigma mu^2 = E ln(lambda) lambda^(-2 nu).
//   Saint Venant-Kirchhoff (S = lambda_L tr(E) I + 2G E, E = (F^T F - I)/2): S_yy = 0 gives
//   E_yy = -nu E_xx, so P = F S: P_xx = E lambda (lambda^2 - 1)/2, mu = sqrt(1 - nu (lambda^2 - 1))
//   (the section collapses at lambda^2 = 1 + 1/nu).
//   PD continuum (homogeneous F = diag(lambda, mu, mu), full spherical family, constant
//   influence; P = integral of T<xi> (x) xi dV, Silling 2007 eq. for the collapsed stress):
//     PMB (bond force c s M, c = 18K/(pi delta^4)):  P = (9K/(4 pi)) int_S (1 - 1/|F n|) F n (x) n dOmega
//     LPS (t = 3K theta |xi|/m + 15G/m e_d, m = 4 pi delta^5/5), and PALS with its normalised base
//     functions (identical on a full sphere: omega = 3/m, sigma = 15/(2m), (sigma x)•e_d = 0):
//       theta = (3/(4 pi)) int_S (|F n| - 1) dOmega,
//       P = (1/(4 pi)) int_S [3K theta + 15G (|F n| - 1 - theta/3)] F n (x) n / |F n| dOmega.
//   Both reduce to linear elasticity at small strain (PMB with nu = 1/4: E = 1.5 K; LPS: E, nu).
//   The integrals are axisymmetric: Simpson in the polar angle (2000 intervals, error < 1e-12
//   relative); mu by bisection on P_yy(mu) = 0.
#pragma once

namespace pd::ref {

struct UniaxialPoint {
    double P = 0;      // engineering stress = first Piola P_xx = axial force / initial area [Pa]
    double sigma = 0;  // Cauchy (true) axial stress P / mu^2 [Pa]
    double mu = 1;     // lateral stretch [-]
};

enum class UniaxialLaw { hypoelastic, saint_venant_kirchhoff, pmb_continuum, lps_continuum };

// Uniaxial-stress state at axial stretch lambda > 0 for elastic constants K, G [Pa].
UniaxialPoint uniaxial_stress(UniaxialLaw law, double K, double G, double lambda);

// max dP/dlambda on [1, lambda_max] over dP/dlambda at 1 (>= 1; 100 forward differences): how
// far the law stiffens beyond its reference tangent (an ADR density built on that tangent must
// cover it). SVK: (3 lambda^2 - 1)/2 at the end; hypoelastic: 1 (it softens).
double max_tangent_ratio(UniaxialLaw law, double K, double G, double lambda_max);

}  // namespace pd::ref
