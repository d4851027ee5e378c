// Correspondence (state-based) heat conduction with hourglass suppression (spec/000b sec. 3.4-3.5;
// Agwai; the thesis's suppression term with the stabilising sign):
//   shape tensor        K_i = sum_j omega xi (x) xi V_j                           [m^(D+2)...]
//   gradient            g_i = K_i^-1 sum_j omega (theta_j - theta_i) xi V_j          [K/m]
//   heat flux           q_i = k g_i (Lagrangian Fourier law with F = I; sign as the source: the
//                       balance below makes it diffusive, spec 3.4 [RECON])
//   heat-flow state     h_i<xi> = omega (K_i^-1 q_i) . xi    (the general form; 1/m_w only in 1D)
//   balance             Q_i = sum_j (h_i<xi> - h_j<-xi>) V_j = sum_j omega (a_i + a_j) . xi V_j,  a = K^-1 q
//   suppression         h_hg<xi> = C_hg kappa_1 (theta_j - theta_i - g_i . xi)/|xi|   (stabilising sign,
//                       erratum: the printed sign is anti-diffusive), from both ends:
//                       Q_hg,i = sum_j C_hg kappa_1 (2 (theta_j - theta_i) - (g_i + g_j) . xi)/|xi| V_j
//   with kappa_1 the Agwai micro-conductivity of the dimension (agwai.hpp). Exact for linear fields
//   (g exact, hourglass term 0) at every node with an invertible K; Q = k lap(theta) in the interior
//   for quadratic fields. The operator is linear in theta: add_operator() gives its matrix exactly.
// k(theta): conductivity.hpp (node i's flux at k(theta_i), the suppression at the bond's k).
// Deformation (spec/000a eq. 2.82, optional, set_deformation): the Lagrangian Fourier law
// q_i = k det(F_i) F_i^-1 F_i^-T g_i with the deformation gradients of a mechanical correspondence model
// (read at each point pass; the operator of add_operator is the one at the F of its call). Without it,
// or with F = I, q = k g; a rigid rotation leaves q unchanged.
// A node whose K is singular (models/shape_tensor.hpp) gets K^-1 = 0: no gradient, only the suppression term acts.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/models/shape_tensor.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/parallel.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pd {

template <int D>
struct CorrespondenceHeat {
    static constexpr bool has_point_pass = true;
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    struct Params {
        double k = 0;        // conductivity [W/(m K)]
        double C_hg = 0;     // hourglass suppression coefficient [-] (0 = off)
        double measure = 1;  // A [m^2] in 1D, thickness [m] in 2D, 1 in 3D (kappa_1 only)
    };

    Params par;
    double kappa1 = 0;             // Agwai micro-conductivity of the dimension
    Field<D> x;                    // reference positions [m]
    std::vector<Mat> Kinv;         // K_i^-1
    std::vector<Col> g, a;         // gradient [K/m] and K^-1 q per node
    const Bonds* bonds = nullptr;
    const std::vector<Mat>* deformation = nullptr;  // F per node (header); null: undeformed

    // Whether the heat operator follows attached deformation gradients (it changes with them).
    bool follows_deformation() const { return deformation != nullptr; }
    // Attaches the deformation gradients F [-] (kept by reference, one per node); nullptr detaches.
    void set_deformation(const std::vector<Mat>* F)
    {
        if (F && F->size() != Kinv.size()) throw std::invalid_argument("CorrespondenceHeat: one deformation gradient per node needed");
        deformation = F;
    }
    // det(F) F^-1 F^-T of node i: the conductivity tensor's factor in the reference configuration (2.82).
    Mat lagrangian(std::size_t i) const
    {
        if (!deformation) return Mat::Identity();
        const Mat& F = (*deformation)[i];
        const Mat Finv = F.inverse();
        return F.determinant() * Finv * Finv.transpose();
    }

    CorrespondenceHeat(const Params& p, const Body<D>& body, const Bonds& b)
        : par(p), x(body.x), Kinv(b.nodes(), Mat::Zero()), g(b.nodes(), Col::Zero()), a(b.nodes(), Col::Zero()), bonds(&b)
    {
        if (!(p.k > 0)) throw std::invalid_argument("CorrespondenceHeat: conductivity k must be positive");
        if (!(p.C_hg >= 0)) throw std::invalid_argument("CorrespondenceHeat: C_hg must be >= 0");
        kappa1 = agwai_micro_conductivity(p.k, D, b.delta, p.measure);
        shape_tensors(b);
    }

    Col xi(std::size_t i, int j) const
    {
        Col r;
        for (int d = 0; d < D; ++d) r(d) = x.c[d][j] - x.c[d][i];
        return r;
    }

    void shape_tensors(const Bonds& b)
    {
        parallel_for(b.nodes(), [&](std::size_t i) {
            Kinv[i] = inverse_or_zero(shape_tensor(b, x, i));  // models/shape_tensor.hpp
        });
    }

    void point_pass(const Bonds& b, const std::vector<double>& theta)
    {
        point_pass_scaled(b, theta, [](std::size_t) { return 1.0; });
    }
    double bond_heat(std::size_t i, std::int64_t k, int j, double dtheta) const { return bond_heat_scaled(i, k, j, dtheta, 1.0); }

    // Temperature-dependent conductivity (conductivity.hpp): node i's flux uses par.k s_i, the
    // suppression term of bond i-j the bond's factor s_ij (the caller's symmetric rule); s = 1 is
    // the constant-k model (multiplications by 1.0 are exact and folded by the compiler).
    template <class NodeScale>
    void point_pass_scaled(const Bonds& b, const std::vector<double>& theta, const NodeScale& s)
    {
        if (b.has_damage()) shape_tensors(b);
        parallel_for(b.nodes(), [&](std::size_t i) {
            Col sum = Col::Zero();
            for_intact_bonds(b, i, [&](std::int64_t k, int j) { sum += b.omega[k] * b.volume[k] * (theta[j] - theta[i]) * xi(i, j); });
            g[i] = Kinv[i] * sum;
            const Col grad = deformation ? Col(lagrangian(i) * g[i]) : g[i];  // (2.82); the undeformed g as it is
            a[i] = Kinv[i] * ((par.k * s(i)) * grad);
        });
    }

    double bond_heat_scaled(std::size_t i, std::int64_t k, int j, double dtheta, double s_ij) const
    {
        const Col e = xi(i, j);
        const double V = bonds->volume[k];
        double h = bonds->omega[k] * V * (a[i] + a[j]).dot(e);
        if (par.C_hg != 0) h += par.C_hg * kappa1 * s_ij * V / bonds->length[k] * (2 * dtheta - (g[i] + g[j]).dot(e));
        return h;
    }

    // Adds the exact matrix A (Q = A theta) of this linear operator to the triplets.
    void add_operator(const Bonds& b, std::vector<Eigen::Triplet<double>>& t) const
    {
        add_operator_scaled(b, t, [](std::size_t) { return 1.0; }, [](std::size_t, int) { return 1.0; });
    }

    // The same with node factors s(i) on the flux and bond factors s_bond(i, j) on the suppression
    // (the operator at frozen conductivities, point_pass_scaled / bond_heat_scaled).
    template <class NodeScale, class BondScale>
    void add_operator_scaled(const Bonds& b, std::vector<Eigen::Triplet<double>>& t, const NodeScale& s,
                             const BondScale& s_bond) const
    {
        // dg_i/dtheta_l = G_il = K_i^-1 omega xi_il V_l (l in family of i), dg_i/dtheta_i = -sum_l G_il.
        auto add_gradient = [&](std::size_t row, std::size_t node, const Col& c) {  // c . g_node
            Col sum = Col::Zero();
            for_intact_bonds(b, node, [&](std::int64_t k, int l) {
                const Col G = Kinv[node] * (b.omega[k] * b.volume[k] * xi(node, l));
                t.emplace_back(int(row), l, c.dot(G));
                sum += G;
            });
            t.emplace_back(int(row), int(node), -c.dot(sum));
        };
        for (std::size_t i = 0; i < b.nodes(); ++i)
            for_intact_bonds(b, i, [&](std::int64_t k, int j) {
                const Col e = xi(i, j);
                const double V = b.volume[k];
                // omega V (a_i + a_j) . xi, a = k s K^-1 g
                const Col w = b.omega[k] * V * par.k * e;
                add_gradient(i, i, lagrangian(i) * (Kinv[i].transpose() * (s(i) * w)));  // the factor is symmetric
                add_gradient(i, j, lagrangian(j) * (Kinv[j].transpose() * (s(j) * w)));
                if (par.C_hg != 0) {
                    const double c = par.C_hg * kappa1 * s_bond(i, j) * V / b.length[k];
                    t.emplace_back(int(i), j, 2 * c);
                    t.emplace_back(int(i), int(i), -2 * c);
                    add_gradient(i, i, -c * e);
                    add_gradient(i, j, -c * e);
                }
            });
    }
};

}  // namespace pd
