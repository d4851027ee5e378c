// pd/models/stiffness_bound.hpp -- Gershgorin row sums of the stiffness linearised at the reference
// configuration, per model: the diagonal density of adaptive dynamic relaxation
// (dynamic_relaxation.hpp; Kilic & Madenci 2010 eq. 17: lambda_ia >= 1/4 dt^2 sum_(j,b) |K_(ia)(jb)|).
// Exact row sums for PMB; triangle-inequality bounds for LPS, PALS and correspondence with its
// hourglass springs; the PMB formula with a stand-in micromodulus c for any other model. Each
// bound's linearisation is written above its function. critical_step_gershgorin (time/explicit_step.hpp)
// turns a bound into a velocity-Verlet step that is stable on the linearised body.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/shape_tensor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pd {

namespace detail {
// Unit bond direction n = xi / |xi| from the reference positions.
template <int D>
inline Vec<D> bond_direction(const Field<D>& x, std::size_t i, int j, double L)
{
    Vec<D> n;
    for (int d = 0; d < D; ++d) n[d] = (x.c[d][j] - x.c[d][i]) / L;
    return n;
}
template <int D>
inline double norm1(const Vec<D>& n)
{
    double s = 0;
    for (int d = 0; d < D; ++d) s += std::abs(n[d]);
    return s;
}
}  // namespace detail

// Gershgorin row sums G_ia = sum_(j,b) |K_(ia)(jb)| [N/m^4 per m of displacement, in 3D N/m^5] of
// a pair-spring stiffness with spring constant k_k = c omega V_j / |xi| per bond (the linearised
// PMB: K_ij = -k n n^T, K_ii = sum_j k n n^T), so G_ia = 2 sum_j k_j |n_a| ||n||_1.
template <int D>
Field<D> stiffness_bound_springs(const Bonds& b, const Field<D>& x, const std::vector<double>& spring)
{
    Field<D> G(b.nodes());
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for_family(b, i, [&](std::int64_t k, int j) {
            const Vec<D> n = detail::bond_direction(x, i, j, b.length[k]);
            const double w = 2 * spring[k] * detail::norm1(n);
            for (int d = 0; d < D; ++d) G.c[d][i] += w * std::abs(n[d]);
        });
    return G;
}

// PMB: exact Gershgorin row sums of the stiffness at the reference configuration (k = PMB::coef).
template <int D>
Field<D> stiffness_bound(const PMB& model, const Bonds& b, const Field<D>& x)
{
    return stiffness_bound_springs(b, x, model.coef);
}

// Stand-in for any model: the PMB formula with micromodulus c [N/m^6 in 3D] (as the critical step).
template <int D>
Field<D> stiffness_bound_micromodulus(const Bonds& b, const Field<D>& x, double c)
{
    std::vector<double> spring(b.size());
    for (std::size_t k = 0; k < b.size(); ++k) spring[k] = c * b.omega[k] * b.volume[k] / b.length[k];
    return stiffness_bound_springs(b, x, spring);
}

// LPS linearised at the reference (lps.hpp, with beta = p - alpha/D):
//   df_i = sum_k wV_k n_k [ L_k (beta_i dtheta_i + beta_j dtheta_j) + (alpha_i + alpha_j) n_k.(du_j - du_i) ]
//   dtheta_i = (D/m_i) sum_l wV_l L_l n_l.(du_(j_l) - du_i)
// Row bound by the triangle inequality, with T_i = (D/m_i) sum_l wV_l L_l 2 ||n_l||_1 (row sum of dtheta_i):
//   G_ia = sum_k wV_k (alpha_i + alpha_j) |n_a| 2 ||n||_1 + |beta_i| |sum_k wV_k L_k n_a| T_i
//          + sum_k wV_k L_k |n_a| |beta_j| T_j.
template <int D>
Field<D> stiffness_bound(const LPS& model, const Bonds& b, const Field<D>& x)
{
    const std::size_t nn = b.nodes();
    std::vector<double> T(nn, 0.0), beta(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        beta[i] = model.p_coef[i] - model.alpha[i] / model.dim;
        double s = 0;
        for_family(b, i, [&](std::int64_t k, int j) { s += model.wV[k] * b.length[k] * 2 * detail::norm1(detail::bond_direction(x, i, j, b.length[k])); });
        T[i] = model.m[i] > 0 ? model.dim * s / model.m[i] : 0.0;
    }
    Field<D> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        Vec<D> first{};  // sum_k wV_k L_k n_k: zero for a symmetric (interior) family
        for_family(b, i, [&](std::int64_t k, int j) {
            const double L = b.length[k];
            const Vec<D> n = detail::bond_direction(x, i, j, L);
            const double pair = model.wV[k] * (model.alpha[i] + model.alpha[j]) * 2 * detail::norm1(n);
            for (int d = 0; d < D; ++d) {
                G.c[d][i] += (pair + model.wV[k] * L * std::abs(beta[j]) * T[j]) * std::abs(n[d]);
                first[d] += model.wV[k] * L * n[d];
            }
        });
        for (int d = 0; d < D; ++d) G.c[d][i] += std::abs(beta[i]) * std::abs(first[d]) * T[i];
    }
    return G;
}

// PALS linearised at the reference (pals.hpp; t = 0 there, so only d t along n contributes):
//   d t_k = L_k [a_ik dtheta_i - (w_ik/3) dq_i + a_jk dtheta_j - (w_jk/3) dq_j] + (s_ik + s_jk) de_k,
//   a_ik = w_ik A_i - s_ik/3,  A_i = K + 2G m_sigma_i/9,  de_l = n_l.(du_(j_l) - du_i),
//   dtheta_i = sum_l w_il L_l de_l,  dq_i = sum_l s_il L_l de_l  (q = (2G sigma x)•e, p = A theta - q/3),
// with w = omega V_j and s = 2G sigma V_j of either end (negative values allowed). Row bound by
// the triangle inequality (a functional sum_l c_l de_l has row sum <= sum_l |c_l| 2 ||n_l||_1):
//   G_ia = sum_k |s_ik + s_jk| |n_a| 2 ||n||_1                                    (pair term)
//        + sum_l |X_a w_il + Y_a s_il| L_l 2 ||n_l||_1,  X_a = sum_k n_a L a_ik, Y_a = -sum_k n_a L w_ik/3
//        + sum_k |n_a| L_k (|a_jk| Tw_j + |w_jk| Ts_j / 3),  Tw_j = sum_l |w_jl| L_l 2 ||n_l||_1 (Ts: s).
inline Field<3> stiffness_bound(const PALS& model, const Bonds& b, const Field<3>& x)
{
    const std::size_t nn = b.nodes();
    std::vector<double> A(nn), Tw(nn, 0.0), Ts(nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i) {
        A[i] = model.K + 2 * model.G * model.m_sigma[i] / 9;
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const double r = b.length[k] * 2 * detail::norm1(detail::bond_direction(x, i, j, b.length[k]));
            Tw[i] += std::abs(model.w_i[k]) * r;
            Ts[i] += std::abs(model.s_i[k]) * r;
        });
    }
    Field<3> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        Vec<3> X{}, Y{};
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const double L = b.length[k];
            const Vec<3> n = detail::bond_direction(x, i, j, L);
            const double a_i = model.w_i[k] * A[i] - model.s_i[k] / 3, a_j = model.w_j[k] * A[j] - model.s_j[k] / 3;
            const double pair = std::abs(model.s_i[k] + model.s_j[k]) * 2 * detail::norm1(n);
            const double far = L * (std::abs(a_j) * Tw[j] + std::abs(model.w_j[k]) * Ts[j] / 3);
            for (int d = 0; d < 3; ++d) {
                G.c[d][i] += (pair + far) * std::abs(n[d]);
                X[d] += n[d] * L * a_i;
                Y[d] -= n[d] * L * model.w_i[k] / 3;
            }
        });
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const double L = b.length[k];
            const double r = L * 2 * detail::norm1(detail::bond_direction(x, i, j, L));
            for (int d = 0; d < 3; ++d) G.c[d][i] += std::abs(X[d] * model.w_i[k] + Y[d] * model.s_i[k]) * r;
        });
    }
    return G;
}

// Correspondence linearised at the reference (F = I, P = 0; the same tangent for every Law:
// dP = C : sym(dF) with Lame lambda, G), from the model's Params and the bonds only:
//   dF_i = sum_l (du_(j_l) - du_i) (x) g_il,  g_il = omega V_l K_i^-1 xi_l,  h_i = sum_l g_il,
//   df_i = dP_i h_i + sum_k dP_j r_k,  r_k = omega V_k K_j^-1 xi_k  (j = partner of bond k),
//   dP_i h = sum_l C(h, g_il) (du_(j_l) - du_i),  C_ac(h, g) = lambda h_a g_c + G delta_ac g.h + G g_a h_c.
// Row bound (each difference counted twice, |g.h| <= sum_b |g_b||h_b|), S1_i = sum_l ||g_il||_1,
// S_ib = sum_l |g_il,b|:
//   G_ia = 2 [lambda |h_a| S1_i + G sum_b |h_b| S_ib + G ||h||_1 S_ia]
//        + 2 sum_k [lambda |r_ka| S1_j + G sum_b |r_kb| S_jb + G ||r_k||_1 S_ja]
// plus the Littlewood term linearised, c_hg V_k/|xi| ((2 d eta - (dF_i + dF_j) xi).n) n, with
// |g_il.xi_k| <= |g_il| |xi_k| and Sg_i = sum_l |g_il|:
//        + sum_k c_hg V_k |n_a| ||n||_1 (4/|xi_k| + 2 (Sg_i + Sg_j)).
// K_i^-1 = 0 where K_i is singular, with the rule of models/shape_tensor.hpp.
template <int D>
Field<D> stiffness_bound(const Correspondence<D>& model, const Bonds& b, const Field<D>& x)
{
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    const auto& par = model.par;
    const double Gs = par.material.G;
    double lam = par.material.K - 2 * Gs / 3;
    if (D == 2 && par.plane == Plane::stress) lam = 2 * lam * Gs / (lam + 2 * Gs);
    const double c_hg = par.C_hg * pmb_micromodulus(kappa_dim(par.material, D, par.plane), D,
                                                    horizon_moment(Influence{}, 1, b.delta, D, par.measure));
    const std::size_t nn = b.nodes();
    auto xi = [&](std::size_t i, int j) {
        Col e;
        for (int d = 0; d < D; ++d) e(d) = x.c[d][j] - x.c[d][i];
        return e;
    };
    std::vector<Mat> Kinv(nn, Mat::Zero());
    std::vector<Col> h(nn, Col::Zero()), S(nn, Col::Zero());
    std::vector<double> S1(nn, 0.0), Sg(nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i) {
        const Mat K = shape_tensor(b, x, i);
        if (!shape_tensor_regular(K)) continue;
        Kinv[i] = K.inverse();
        // A plain loop: as a for_intact_bonds lambda GCC contracts these sums into FMAs differently
        // (the bound moves by ulps, and with it the iteration counts of dynamic relaxation).
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (b.has_damage() && !b.intact[k]) continue;
            const Col g = b.omega[k] * b.volume[k] * (Kinv[i] * xi(i, b.partner[k]));
            h[i] += g;
            S[i] += g.cwiseAbs();
            S1[i] += g.template lpNorm<1>();
            Sg[i] += g.norm();
        }
    }
    Field<D> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        const Col ha = h[i].cwiseAbs();
        Col row = 2 * (lam * S1[i] * ha + Gs * ha.dot(S[i]) * Col::Ones() + Gs * ha.sum() * S[i]);
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const Col e = xi(i, j);
            const Col ra = (b.omega[k] * b.volume[k] * (Kinv[j] * e)).cwiseAbs();
            row += 2 * (lam * S1[j] * ra + Gs * ra.dot(S[j]) * Col::Ones() + Gs * ra.sum() * S[j]);
            if (c_hg != 0) {
                const double L = e.norm();
                const Col na = e.cwiseAbs() / L;
                row += c_hg * b.volume[k] * na.sum() * (4 / L + 2 * (Sg[i] + Sg[j])) * na;
            }
        });
        for (int d = 0; d < D; ++d) G.c[d][i] = row(d);
    }
    return G;
}

// The elastic model with a model's tangent at the reference: the model itself, or the elastic model an
// inelastic one wraps (.lps of PlasticLPS and ViscoelasticLPS, .pals of PlasticPALS, .model of the
// inelastic correspondence). Shared by stiffness_bound_of and highest_frequency (time/explicit_step.hpp).
template <class Model>
auto& elastic_part(Model& model)
{
    if constexpr (requires { model.lps; }) return model.lps;
    else if constexpr (requires { model.pals; }) return model.pals;
    else if constexpr (requires { model.model; }) return model.model;
    else return model;
}

// The factor of a model's instantaneous stiffness over its elastic part's: 1 + gamma_b for a standard
// linear solid (its instantaneous shear modulus is G (1 + gamma_b); conservative for the bulk part), else 1.
template <class Model>
double instantaneous_stiffness_factor(const Model& model)
{
    if constexpr (requires { model.gamma_b; }) return 1 + model.gamma_b;
    else return 1.0;
}

// The bound of any model: that of its elastic part, times its instantaneous stiffness factor.
template <class Model, int D>
Field<D> stiffness_bound_of(const Model& model, const Bonds& b, const Field<D>& x)
{
    Field<D> G = stiffness_bound(elastic_part(model), b, x);
    if constexpr (requires { model.gamma_b; })
        for (int d = 0; d < D; ++d)
            for (double& g : G.c[d]) g *= instantaneous_stiffness_factor(model);
    return G;
}

}  // namespace pd
