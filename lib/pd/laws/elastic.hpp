// pd/laws/elastic.hpp -- isotropic linear elasticity as a point law (knows nothing of bonds).
//   sigma = K tr(eps) I + 2 G dev(eps),  dev(a) = a - tr(a)/3 I                     (Hooke)
//   von Mises equivalent stress sigma_eff = sqrt(3/2 s:s), s = dev(sigma)    (spec/000b eq. 5.8)
// Small-strain, 3D. K bulk and G shear modulus, as pd::Elastic (material.hpp).
// Lame form in D = 2 or 3 dimensions, for a deformation gradient F (the correspondence laws):
//   small strain eps = sym(F) - I,  Green-Lagrange strain E = (F^T F - I)/2,
//   sigma (or S) = lambda tr(e) I + 2 G e  (2D: lambda of the plane condition, material.hpp).
#pragma once
#include <Eigen/Dense>

#include <cmath>

namespace pd::laws {

using Mat3 = Eigen::Matrix3d;

// Deviator a - tr(a)/3 I.
inline Mat3 deviator(const Mat3& a) { return a - a.trace() / 3 * Mat3::Identity(); }

// sigma_eff = sqrt(3/2 s:s) of the deviator s [Pa].
inline double von_mises(const Mat3& s)
{
    const Mat3 d = deviator(s);
    return std::sqrt(1.5 * (d.array() * d.array()).sum());
}

template <class M>
M small_strain(const M& F) { return 0.5 * (F + F.transpose()) - M::Identity(); }
template <class M>
M green_lagrange(const M& F) { return 0.5 * (F.transpose() * F - M::Identity()); }
template <class M>
M lame_stress(const M& e, double lambda, double G) { return lambda * e.trace() * M::Identity() + 2 * G * e; }

// The small-strain law in entry form, as the chunk kernels vectorise it (models/correspondence_chunks.hpp):
//   sigma = G (F + F^T) + (lambda (tr F - 3) - 2 G) I,
// lame_stress(small_strain(F)) with its terms grouped otherwise (equal to round-off). F and sigma are
// column-major 3 x 3 arrays of T, a number or a vector of lanes (one node per lane).
template <class T>
void small_strain_stress(const T* F, double lambda, double G, T* sigma)
{
    const T tr = F[0] + F[4] + F[8] - 3.0;
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) sigma[a + 3 * c] = G * (F[a + 3 * c] + F[c + 3 * a]) + (a == c ? lambda * tr - 2 * G : T{});
}

struct IsotropicElastic {
    double K = 0;  // bulk modulus [Pa]
    double G = 0;  // shear modulus [Pa]

    // sigma = K tr(eps) I + 2 G dev(eps) [Pa], eps the (elastic) small strain [-].
    Mat3 stress(const Mat3& eps) const { return K * eps.trace() * Mat3::Identity() + 2 * G * deviator(eps); }
    // Strain energy density W = K tr(eps)^2/2 + G dev(eps):dev(eps) [J/m^3].
    double energy(const Mat3& eps) const
    {
        const Mat3 d = deviator(eps);
        return 0.5 * K * eps.trace() * eps.trace() + G * (d.array() * d.array()).sum();
    }
};

}  // namespace pd::laws
