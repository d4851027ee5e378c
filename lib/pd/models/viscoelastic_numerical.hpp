// Numerical viscosity: Maxwell-branch parameters that damp the node-to-node shear-wave transit
// frequency (Biondani 2018 sec. 8.4.2, eqs. 8.27-8.29 with 7.33; spec/000c sec. 2.7, V6, erratum 7):
//   c_S = sqrt(G/rho)  (8.27),  f_cS = c_S / dx  (8.28),  f_P = eta f_cS,  f_0 = f_cS / eta  (8.29)
//   with w_P = 1/tau_b and w_0 = w_P/(1 + gamma_b) (7.33):  gamma_b = eta^2 - 1,
//   tau_b = 1/(2 pi eta f_cS)  (f -> w with 2 pi; erratum 7: the source does not state it; without
//   it, tau_b = 1/(eta f_cS)).
// Low frequencies keep the elastic G (thesis convention alpha_inf = alpha_LPS, erratum 8), high
// frequencies see eta^2 G. Feeds ViscoelasticLPS::Params and ViscoelasticCorrespondence::Params.
#pragma once
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pd {

struct MaxwellShear {
    double gamma_b = 0;  // G_b / G [-]
    double tau_b = 0;    // relaxation time [s]
};

// G [Pa], rho [kg/m^3], dx lattice spacing [m], eta > 1 damping coefficient [-].
inline MaxwellShear numerical_viscosity(double G, double rho, double dx, double eta, bool two_pi = true)
{
    if (!(G > 0) || !(rho > 0) || !(dx > 0)) throw std::invalid_argument("numerical_viscosity: G, rho and dx must be positive");
    if (!(eta > 1)) throw std::invalid_argument("numerical_viscosity: eta must be > 1");
    const double f_cS = std::sqrt(G / rho) / dx;  // (8.27-8.28) [Hz]
    return {eta * eta - 1, 1 / ((two_pi ? 2 * std::numbers::pi : 1.0) * eta * f_cS)};
}

}  // namespace pd
