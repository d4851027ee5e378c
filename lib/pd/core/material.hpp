// Isotropic elastic constants and the "bulk modulus of dimension D" kappa_D used by PMB and LPS.
//   3D: kappa = K.  2D plane strain: kappa = K + G/3 (= lambda + mu).
//   2D plane stress: kappa = 9 K G / (3 K + 4 G) (= E / (2 (1 - nu))).  1D: kappa = E.
// kappa_D is the modulus for which the energy density of an isotropic stretch s is
// W = (D^2 / 2) kappa_D s^2 (3D: 9/2 K s^2; 2D: 2 kappa s^2; 1D: E s^2 / 2).
#pragma once
#include <string>

namespace pd {

enum class Plane { strain, stress };  // 2D reduction; ignored in 1D and 3D

struct Elastic {
    double K = 0;  // bulk modulus [Pa]
    double G = 0;  // shear modulus [Pa]

    static Elastic from_E_nu(double E, double nu) { return {E / (3 * (1 - 2 * nu)), E / (2 * (1 + nu))}; }
    double E() const { return 9 * K * G / (3 * K + G); }          // Young's modulus [Pa]
    double nu() const { return (3 * K - 2 * G) / (2 * (3 * K + G)); }  // Poisson's ratio [-]
};

// Bulk modulus of dimension D [Pa] (see header).
inline double kappa_dim(const Elastic& m, int dim, Plane plane)
{
    if (dim == 3) return m.K;
    if (dim == 1) return m.E();
    if (plane == Plane::strain) return m.K + m.G / 3;
    return 9 * m.K * m.G / (3 * m.K + 4 * m.G);
}

// Checks E > 0 and -1 < nu < 1/2 (the 3D material behind every reduction; 1D needs only E). Returns an empty string when
// valid, else a one-line message naming the parameter as the drivers' option (--E, --nu).
std::string validate_elastic(double E, double nu, int dim, Plane plane);

}  // namespace pd
