// LPS, linear peridynamic solid (Silling et al. 2007; spec/000b sec. 1.2, spec/002 sec. 2.2),
// written once for D = 1, 2, 3 with the dimension-D bulk modulus kappa_D (material.hpp):
//   weighted volume  m_i = sum_j omega |xi|^2 V_j                                   (4.8)
//   dilatation       theta_i = (D/m_i) sum_j omega |xi| e V_j,  e = |Y| - |xi|      (4.8)
//   deviatoric ext.  e_d = e - theta_i |xi| / D                                     (4.9)
//   energy           W_i = kappa_D theta_i^2 / 2 + (alpha_i/2) sum_j omega e_d^2 V_j  (4.10)
//   force state      t_i = D kappa_D theta_i omega |xi| / m_i + alpha_i omega e_d   (4.11)
//   shear constant   alpha_i = a_D G / m_i, a_3 = 15 (4.13), a_2 = 8, a_1 = 0.
// 3D is the source's model. 1D is V1's bar (t = omega E theta |xi| / m). 2D uses the in-plane
// split e_d = e - theta |xi|/2 with kappa_2D = K + G/3 (plane strain) or 9KG/(3K+4G) (plane
// stress): an isotropic stretch s gives W = 2 kappa_2D s^2 and a pure shear eps = diag(a, -a)
// gives W = 2 G a^2, the classical in-plane energies (tests/test_models.cpp checks both).
// Pair force on i: (t_i<xi> + t_j<-xi>) V_j Y/|Y|. m_i is fixed at the reference configuration;
// theta_i and the forces sum only intact bonds.
#pragma once
#include "pd/bonds.hpp"
#include "pd/field.hpp"
#include "pd/material.hpp"
#include "pd/parallel.hpp"

#include <vector>

namespace pd {

struct LPS {
    static constexpr bool has_point_pass = true;
    struct Params {
        Elastic material;
        int dim = 3;
        Plane plane = Plane::strain;   // 2D reduction
    };
    int dim = 3;
    double kappa = 0;              // kappa_D [Pa]
    double G = 0;                  // shear modulus [Pa]
    std::vector<double> m;         // weighted volume m_i [m^5 in 3D]
    std::vector<double> p_coef;    // D kappa / m_i [Pa/m^5]
    std::vector<double> alpha;     // a_D G / m_i [Pa/m^5]
    std::vector<double> theta;     // dilatation, updated by point_pass [-]
    const Bonds* bonds = nullptr;

    LPS() = default;
    LPS(const Params& p, const Bonds& b)
        : dim(p.dim), kappa(kappa_dim(p.material, p.dim, p.plane)), G(p.material.G),
          m(b.nodes(), 0.0), p_coef(b.nodes()), alpha(b.nodes()), theta(b.nodes(), 0.0), bonds(&b)
    {
        const double a_D = dim == 3 ? 15.0 : dim == 2 ? 8.0 : 0.0;
        for (std::size_t i = 0; i < b.nodes(); ++i) {
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) m[i] += b.omega[k] * b.length[k] * b.length[k] * b.volume[k];
            const double inv_m = m[i] > 0 ? 1.0 / m[i] : 0.0;  // isolated node: no force
            p_coef[i] = dim * kappa * inv_m;
            alpha[i] = a_D * G * inv_m;
        }
    }

    // theta_i = (D/m_i) sum_j omega |xi| e V_j over intact bonds.
    template <int D>
    void point_pass(const Bonds& b, const Field<D>& y)
    {
        parallel_for(b.nodes(), [&](std::size_t i) {
            double sum = 0;
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                if (b.has_damage() && !b.intact[k]) continue;
                const double L = b.length[k];
                sum += b.omega[k] * L * (norm(y[b.partner[k]] - y[i]) - L) * b.volume[k];
            }
            theta[i] = m[i] > 0 ? D * sum / m[i] : 0.0;
        });
    }

    // (t_i + t_j) V_j / |Y|: force on i is this times Y.
    double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const
    {
        const double L = bonds->length[k], w = bonds->omega[k];
        const double e = ylen - L;
        const double ti = w * (p_coef[i] * theta[i] * L + alpha[i] * (e - theta[i] * L / dim));
        const double tj = w * (p_coef[j] * theta[j] * L + alpha[j] * (e - theta[j] * L / dim));
        return (ti + tj) * bonds->volume[k] / ylen;
    }

    // W_i (4.10) [J/m^3]; call after point_pass at the same y.
    template <int D>
    std::vector<double> energy_density(const Bonds& b, const Field<D>& y) const
    {
        std::vector<double> W(b.nodes(), 0.0);
        parallel_for(b.nodes(), [&](std::size_t i) {
            double dev = 0;
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                if (b.has_damage() && !b.intact[k]) continue;
                const double L = b.length[k];
                const double ed = norm(y[b.partner[k]] - y[i]) - L - theta[i] * L / dim;
                dev += b.omega[k] * ed * ed * b.volume[k];
            }
            W[i] = 0.5 * kappa * theta[i] * theta[i] + 0.5 * alpha[i] * dev;
        });
        return W;
    }
};

}  // namespace pd
