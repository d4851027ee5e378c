// Correspondence model, non-ordinary state-based (Silling et al. 2007; Warren 2009; spec/000b
// sec. 0, 1.5, 1.6 and errata 1-4; spec/000a sec. 2.7, 2.8). Per node i, over intact bonds:
//   shape tensor       K_i = sum_j omega xi (x) xi V_j                      (000b eq. 2.51, "H")
//   deformation grad.  F_i = (sum_j omega Y (x) xi V_j) K_i^-1               (2.50)
//   stress             P_i (first Piola-Kirchhoff) from a point law, below
//   force state        T_i<xi> = omega P_i K_i^-1 xi                         (erratum 1: not P^T)
//   bond force on i    (T_i<xi> - T_j<-xi>) V_j = omega (P_i K_i^-1 + P_j K_j^-1) xi V_j
// Stress laws:
//   Law::linear           small strain: eps = sym(F) - I, sigma = lambda tr(eps) I + 2 G eps, P = sigma
//                         (2D: plane strain, or plane stress with lambda* = 2 lambda G/(lambda + 2G)).
//   Law::saint_venant_kirchhoff  (3D) hyperelastic, objective: E = (F^T F - I)/2, S = lambda tr(E) I + 2 G E,
//                         P = F S = dW/dF, W = lambda tr(E)^2/2 + G E:E (a non-symmetric P: it tests erratum 1).
//   Law::flanagan_taylor  hypoelastic rate form on the unrotated Cauchy stress (3D only), advanced by
//                         update_stress(bonds, y, v, dt) (000b sec. 1.5 [CODE] steps 1-8, errata 2-3):
//                         sigma_hat += (K tr(d) I + 2 G dev(d)) dt, sigma = R sigma_hat R^T, P = J sigma F^-T.
// Littlewood hourglass control (000b sec. 1.6, stabilising sign of erratum 4), from both ends:
//   t_hg = C_hg c ((y_j - y_i - F xi) . M)/|xi| M,  M = Y/|Y|,  c = PMB micromodulus (18K/(pi delta^4) in 3D),
//   summed with F = F_i (bond i->j) and F = F_j (bond j->i): on i, C_hg c V_j ((2Y - (F_i + F_j) xi).M)/|xi| M.
//   No omega factor (as Peridigm). C_hg = 0 (default) switches it off; the source uses 0.02.
// A node whose K is singular (fewer than D independent intact bonds) gets K^-1 = 0 and F = I: no stress force.
// Usage: internal_force(model, bonds, y, f) (bond_loop.hpp) runs point_pass (K on damage, F, P) and the
// bond pass. With Law::flanagan_taylor call update_stress(bonds, y, v, dt) once per step, then
// internal_force at y_np1. Pass v = v_nph = (y_np1 - y_n)/dt with the mid-step configuration
// y = (y_n + y_np1)/2: L = Fdot F^-1 is then exactly skew for a rigid rotation (Cayley), so no
// spurious stress. Peridigm pairs v_nph with y_np1, which gives a spurious expansion
// N (1 - cos(theta/N)) per rotation theta in N steps (2.8e-2 K of stress for 90 degrees in 100 steps;
// tests/test_correspondence.cpp).
// Cost (issue 3; reports/3d/model_cost.md): the family sums K, F K (and Fdot K) are lane sums in the
// bond-loop order, K and sum omega xi V in the same pass as F once bonds can break; the i-end force
// P_i K_i^-1 sum_j omega xi V_j is summed once per node (kernel node_force); the bond kernel reads
// P_j K_j^-1 and F_j of node j (18 values per bond: what remains is this gather, about 6x PMB).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/bonds.hpp"
#include "pd/field.hpp"
#include "pd/influence.hpp"
#include "pd/lattice.hpp"
#include "pd/material.hpp"
#include "pd/models/pmb.hpp"
#include "pd/parallel.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace pd {

template <int D>
struct Correspondence {
    static_assert(D == 2 || D == 3, "correspondence is written for 2D and 3D");
    static constexpr bool has_point_pass = true;
    static constexpr bool ordinary = false;
    static constexpr int DD = D * D;            // entries of a D x D matrix
    static constexpr int DK = D * (D + 1) / 2;  // upper triangle of the symmetric K
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    static_assert(sizeof(Mat) == DD * sizeof(double), "the bond kernel reads std::vector<Mat> as D x D column-major blocks");
    enum class Law { linear, saint_venant_kirchhoff, flanagan_taylor };
    struct Params {
        Elastic material;
        Law law = Law::linear;
        double C_hg = 0;               // Littlewood hourglass coefficient [-]; 0 = off, source 0.02
        Plane plane = Plane::strain;   // 2D reduction of the linear law
        double measure = 1;            // 2D thickness [m] (hourglass micromodulus only)
    };

    Params par;
    double lambda = 0;                // Lame constant of the (reduced) linear law [Pa]
    double c_hg = 0;                  // C_hg times the PMB micromodulus [N/m^6 in 3D]
    Field<D> x;                       // reference positions [m]
    std::vector<double> wV;           // omega V_j per bond [m^3]
    std::vector<double> hg;           // c_hg V_j / |xi| per bond [N/m^4 in 3D]; empty when C_hg = 0
    Field<D> m_xi;                    // sum_j omega xi V_j over intact bonds [m^4 in 3D] (0 for a full family)
    Field<D> f_own;                   // P_i K_i^-1 m_xi: the i-end force summed over the family [N/m^3]
    std::vector<Mat> Kinv;            // K_i^-1 [m^-5 in 3D]
    std::vector<Mat> F;               // deformation gradient [-]
    std::vector<Mat> sigma;           // Cauchy stress [Pa] (Law::linear: the small-strain stress)
    std::vector<Mat> P;               // first Piola-Kirchhoff stress [Pa]
    std::vector<Mat> PKinv;           // P_i K_i^-1 [Pa/m^5 in 3D]
    std::vector<Mat> sigma_hat, R, V; // Flanagan-Taylor: unrotated stress [Pa], rotation, left stretch [-]

    Correspondence() = default;
    Correspondence(const Params& p, const Body<D>& body, const Bonds& b)
        : par(p), x(body.x), wV(b.size()), m_xi(b.nodes()), f_own(b.nodes()), Kinv(b.nodes(), Mat::Zero()), F(b.nodes(), Mat::Identity()),
          sigma(b.nodes(), Mat::Zero()), P(b.nodes(), Mat::Zero()), PKinv(b.nodes(), Mat::Zero())
    {
        if (D != 3 && p.law != Law::linear) throw std::invalid_argument("Correspondence: only Law::linear is written for 2D");
        const double K = p.material.K, G = p.material.G;
        lambda = K - 2 * G / 3;
        if (D == 2 && p.plane == Plane::stress) lambda = 2 * lambda * G / (lambda + 2 * G);
        c_hg = p.C_hg * pmb_micromodulus(kappa_dim(p.material, D, p.plane), D,
                                         horizon_moment(Influence{}, 1, b.delta, D, p.measure));
        for (std::size_t k = 0; k < b.size(); ++k) wV[k] = b.omega[k] * b.volume[k];
        if (c_hg != 0) {
            hg.resize(b.size());
            for (std::size_t k = 0; k < b.size(); ++k) hg[k] = c_hg * b.volume[k] / b.length[k];
        }
        if (p.law == Law::flanagan_taylor) {
            sigma_hat.assign(b.nodes(), Mat::Zero());
            R.assign(b.nodes(), Mat::Identity());
            V.assign(b.nodes(), Mat::Identity());
        }
        shape_tensors(b);
    }

    Col xi(std::size_t i, int j) const
    {
        Col r;
        for (int d = 0; d < D; ++d) r(d) = x.c[d][j] - x.c[d][i];
        return r;
    }

    // Family sums of node i over its intact bonds, in the lane order of bond_loop.hpp (8 partial
    // sums per entry, vectorised over bonds): N[q] = sum_j omega (z_j - z_i) (x) xi V_j for each of
    // the NZ fields z (y gives F K, v gives Fdot K), and, when WithK, K = sum_j omega xi (x) xi V_j
    // and m = sum_j omega xi V_j.
    template <bool Damaged, bool WithK, int NZ>
    void family_sums(const Bonds& b, std::size_t i, const std::array<const Field<D>*, NZ>& z, Mat* N, Mat* K, Col* m) const
    {
        constexpr int C = NZ * DD + (WithK ? DK + D : 0);
        detail::LaneSum<C> sum;
        const int* partner = b.partner.data();
        const double* wv = wV.data();
        const double* xc[D];
        double x_i[D];
        for (int d = 0; d < D; ++d) { xc[d] = x.c[d].data(); x_i[d] = xc[d][i]; }
        const double* zc[NZ > 0 ? NZ : 1][D];
        double z_i[NZ > 0 ? NZ : 1][D];
        for (int q = 0; q < NZ; ++q)
            for (int d = 0; d < D; ++d) { zc[q][d] = z[q]->c[d].data(); z_i[q][d] = zc[q][d][i]; }
        detail::for_lanes<Damaged>(b.offset[i], b.offset[i + 1], b.intact.data(), [&](std::int64_t k, int l, double keep) {
            const int j = partner[k];
            double w = wv[k];
            if constexpr (Damaged) w *= keep;
            double e[D], we[D];
            for (int d = 0; d < D; ++d) { e[d] = xc[d][j] - x_i[d]; we[d] = w * e[d]; }
            for (int q = 0; q < NZ; ++q)
                for (int a = 0; a < D; ++a) {
                    const double dz = zc[q][a][j] - z_i[q][a];
                    for (int c = 0; c < D; ++c) sum.s[q * DD + a + D * c][l] += dz * we[c];
                }
            if constexpr (WithK) {
                int t = NZ * DD;
                for (int a = 0; a < D; ++a)
                    for (int c = a; c < D; ++c) sum.s[t++][l] += e[a] * we[c];
                for (int a = 0; a < D; ++a) sum.s[t++][l] += we[a];
            }
        });
        for (int q = 0; q < NZ; ++q)
            for (int a = 0; a < D; ++a)
                for (int c = 0; c < D; ++c) N[q](a, c) = sum.total(q * DD + a + D * c);
        if constexpr (WithK) {
            int t = NZ * DD;
            for (int a = 0; a < D; ++a)
                for (int c = a; c < D; ++c) (*K)(a, c) = (*K)(c, a) = sum.total(t++);
            for (int a = 0; a < D; ++a) (*m)(a) = sum.total(t++);
        }
    }

    // K^-1, or 0 when K is singular (|det| below a relative 1e-12 of the scale of K^D).
    static Mat inverse_or_zero(const Mat& K)
    {
        const double scale = K.trace() / D;
        const double det = K.determinant();
        return scale > 0 && std::abs(det) > 1e-12 * std::pow(scale, D) ? Mat(K.inverse()) : Mat::Zero();
    }

    // K_i^-1 over intact bonds (000b eq. 2.51).
    void shape_tensors(const Bonds& b)
    {
        parallel_for(b.nodes(), [&](std::size_t i) {
            Mat K;
            Col m;
            if (b.has_damage()) family_sums<true, true, 0>(b, i, {}, nullptr, &K, &m);
            else family_sums<false, true, 0>(b, i, {}, nullptr, &K, &m);
            Kinv[i] = inverse_or_zero(K);
            for (int d = 0; d < D; ++d) m_xi.c[d][i] = m(d);
        });
    }

    // sum_j omega z (x) xi V_j K_i^-1 over intact bonds, z = field difference z_j - z_i (F from y, Fdot from v).
    Mat gradient(const Bonds& b, std::size_t i, const Field<D>& z) const
    {
        Mat N;
        if (b.has_damage()) family_sums<true, false, 1>(b, i, {&z}, &N, nullptr, nullptr);
        else family_sums<false, false, 1>(b, i, {&z}, &N, nullptr, nullptr);
        return N * Kinv[i];
    }

    // Second Piola-Kirchhoff stress S = lambda tr(E) I + 2 G E, E = (F^T F - I)/2.
    Mat svk_stress(const Mat& Fi) const
    {
        const Mat E = 0.5 * (Fi.transpose() * Fi - Mat::Identity());
        return lambda * E.trace() * Mat::Identity() + 2 * par.material.G * E;
    }

    // Small-strain stress sigma = lambda tr(eps) I + 2 G eps, eps = sym(F) - I.
    Mat linear_stress(const Mat& Fi) const
    {
        const Mat eps = 0.5 * (Fi + Fi.transpose()) - Mat::Identity();
        return lambda * eps.trace() * Mat::Identity() + 2 * par.material.G * eps;
    }

    // K^-1 (after damage, in the same pass over the bonds as F), F, then P and P K^-1.
    // Law::linear: P = sigma(F). Law::saint_venant_kirchhoff: P = F S, sigma = P F^T / J.
    // Law::flanagan_taylor: P = J sigma F^-T with the sigma of the last update_stress.
    template <int Dy>
    void point_pass(const Bonds& b, const Field<Dy>& y)
    {
        static_assert(Dy == D);
        if (b.has_damage()) stress_pass<true>(b, y);
        else stress_pass<false>(b, y);
    }

    // Bond kernel (bond_loop.hpp, with_kernel). The force density on i from bond k (i -> j),
    //   omega V_j (P_i K_i^-1 + P_j K_j^-1) xi  +  c_hg V_j/|xi| ((2Y - (F_i + F_j) xi).Y / |Y|^2) Y,
    // (second term only when Hourglass) is split: the i-end term summed over the family is
    // P_i K_i^-1 m_xi (node_force, once per node); bond_force gives the rest. Branch-free plain
    // arithmetic on raw arrays, so that the bond loop vectorises it; |Y| = 0 (a collapsed broken
    // bond) gives a zero hourglass force.
    template <bool Hourglass>
    struct Kernel {
        static constexpr bool ordinary = false;
        const double* x[D];        // reference positions [m]
        const double* f_own[D];    // P_i K_i^-1 m_xi [N/m^3]
        const double* wV;          // omega V_j per bond [m^3]
        const double* hg;          // c_hg V_j / |xi| per bond [N/m^4] (Hourglass only)
        const double* A;           // P K^-1 per node, D x D column-major blocks [Pa/m^5]
        const double* F;           // F per node, D x D column-major blocks [-] (Hourglass only)
        Vec<D> node_force(std::size_t i) const
        {
            Vec<D> f;
            for (int d = 0; d < D; ++d) f[d] = f_own[d][i];
            return f;
        }
        Vec<D> bond_force(std::size_t i, std::int64_t k, int j, const Vec<D>& Y) const
        {
            const double* Aj = A + DD * static_cast<std::size_t>(j);
            double e[D];
            for (int d = 0; d < D; ++d) e[d] = x[d][j] - x[d][i];
            Vec<D> f;
            for (int a = 0; a < D; ++a) {
                double s = 0;
                for (int c = 0; c < D; ++c) s += Aj[a + D * c] * e[c];
                f[a] = wV[k] * s;
            }
            if constexpr (Hourglass) {
                const double* Fi = F + DD * i;
                const double* Fj = F + DD * static_cast<std::size_t>(j);
                double proj = 0, y2 = 0;  // (2Y - (F_i + F_j) xi).Y and |Y|^2 [m^2]
                for (int a = 0; a < D; ++a) {
                    double g = 0;
                    for (int c = 0; c < D; ++c) g += (Fi[a + D * c] + Fj[a + D * c]) * e[c];
                    proj += (2 * Y[a] - g) * Y[a];
                    y2 += Y[a] * Y[a];
                }
                const double t = hg[k] * proj / (y2 > 0 ? y2 : 1.0);
                for (int a = 0; a < D; ++a) f[a] += t * Y[a];
            }
            return f;
        }
    };
    template <bool Hourglass>
    Kernel<Hourglass> kernel() const
    {
        Kernel<Hourglass> kn{};
        for (int d = 0; d < D; ++d) { kn.x[d] = x.c[d].data(); kn.f_own[d] = f_own.c[d].data(); }
        kn.wV = wV.data();
        kn.hg = Hourglass ? hg.data() : nullptr;
        kn.A = PKinv.empty() ? nullptr : PKinv.front().data();
        kn.F = F.empty() ? nullptr : F.front().data();
        return kn;
    }
    // Calls pass(kernel) with the hourglass term compiled in or out (bond_loop.hpp).
    template <class Pass>
    void with_kernel(Pass&& pass) const
    {
        if (c_hg != 0) pass(kernel<true>());
        else pass(kernel<false>());
    }

    // Force density on i from bond k (i -> j), both ends' states included [N/m^3]: the kernel's
    // plus the i-end term omega V_j P_i K_i^-1 xi of this bond.
    Vec<D> bond_force(std::size_t i, std::int64_t k, int j, const Vec<D>& Y) const
    {
        Vec<D> f = c_hg != 0 ? kernel<true>().bond_force(i, k, j, Y) : kernel<false>().bond_force(i, k, j, Y);
        const Col own = wV[k] * (PKinv[i] * xi(i, j));
        for (int d = 0; d < D; ++d) f[d] += own(d);
        return f;
    }

    // Energy density W_i [J/m^3]; call after point_pass. Law::saint_venant_kirchhoff: the exact
    // W = lambda tr(E)^2/2 + G E:E. Otherwise the bookkeeping value 1/2 sigma : eps, eps = sym(F) - I
    // (exact for Law::linear). Hourglass energy not included.
    template <int Dy>
    std::vector<double> energy_density(const Bonds& b, const Field<Dy>&) const
    {
        std::vector<double> W(b.nodes(), 0.0);
        for (std::size_t i = 0; i < b.nodes(); ++i) {
            const Mat eps = par.law == Law::saint_venant_kirchhoff
                                ? Mat(0.5 * (F[i].transpose() * F[i] - Mat::Identity()))
                                : Mat(0.5 * (F[i] + F[i].transpose()) - Mat::Identity());
            const Mat stress = par.law == Law::saint_venant_kirchhoff ? svk_stress(F[i]) : sigma[i];
            W[i] = 0.5 * (stress.array() * eps.array()).sum();
        }
        return W;
    }

    // Flanagan-Taylor update (3D): from F at y and Fdot at v, advance R, V, sigma_hat by dt [s]
    // and set sigma = R sigma_hat R^T (000b sec. 1.5 [CODE] steps 1-8; 000a sec. 2.7).
    template <int Dy>
    void update_stress(const Bonds& b, const Field<Dy>& y, const Field<Dy>& v, double dt)
    {
        static_assert(Dy == 3 && D == 3, "Flanagan-Taylor is written for 3D");
        const double K = par.material.K, G = par.material.G;
        const bool damaged = b.has_damage();
        parallel_for(b.nodes(), [&](std::size_t i) {
            Mat N[2], Ks;                                         // F K, Fdot K, K over intact bonds
            Col m;
            if (damaged) {
                family_sums<true, true, 2>(b, i, {&y, &v}, N, &Ks, &m);
                Kinv[i] = inverse_or_zero(Ks);
                for (int d = 0; d < D; ++d) m_xi.c[d][i] = m(d);
            } else {
                family_sums<false, false, 2>(b, i, {&y, &v}, N, nullptr, nullptr);
            }
            if (Kinv[i].isZero(0)) return;
            F[i] = N[0] * Kinv[i];
            const Mat Fdot = N[1] * Kinv[i];                      // step 1
            const Mat L = Fdot * F[i].inverse();                  // step 2
            const Mat Dr = 0.5 * (L + L.transpose()), Wr = 0.5 * (L - L.transpose());
            const Mat VD = V[i] * Dr;                             // step 3: z_i = eps_ijk (V D)_jk
            const Col z(VD(1, 2) - VD(2, 1), VD(2, 0) - VD(0, 2), VD(0, 1) - VD(1, 0));
            const Col w(Wr(2, 1), Wr(0, 2), Wr(1, 0));            // axial vector, W a = w x a
            const Col om = w + (V[i].trace() * Mat::Identity() - V[i]).inverse() * z;  // step 4
            Mat Om;                                               // Om a = om x a
            Om << 0, -om(2), om(1), om(2), 0, -om(0), -om(1), om(0), 0;
            const double o2 = om.squaredNorm();
            Mat Q = Mat::Identity();                              // step 5: Q = exp(dt Om), Rodrigues
            if (o2 > 1e-30) {
                const double o = std::sqrt(o2);
                Q += std::sin(dt * o) / o * Om + (1 - std::cos(dt * o)) / o2 * Om * Om;
            }
            R[i] = Q * R[i];                                      // step 6
            V[i] += dt * (L * V[i] - V[i] * Om);                  // step 7
            const Mat d = R[i].transpose() * Dr * R[i];           // step 8
            const double tr = d.trace();                          // erratum 2: K tr(d)
            sigma_hat[i] += dt * (K * tr * Mat::Identity() + 2 * G * (d - tr / 3 * Mat::Identity()));
            sigma[i] = R[i] * sigma_hat[i] * R[i].transpose();    // erratum 3
        });
    }

private:
    template <bool Damaged, int Dy>
    void stress_pass(const Bonds& b, const Field<Dy>& y)
    {
        parallel_for(b.nodes(), [&](std::size_t i) {
            Mat N, K;
            Col m;
            family_sums<Damaged, Damaged, 1>(b, i, {&y}, &N, &K, &m);
            if constexpr (Damaged) {
                Kinv[i] = inverse_or_zero(K);
                for (int d = 0; d < D; ++d) m_xi.c[d][i] = m(d);
            }
            if (Kinv[i].isZero(0)) {
                F[i] = Mat::Identity();
                P[i] = PKinv[i] = Mat::Zero();
                for (int d = 0; d < D; ++d) f_own.c[d][i] = 0;
                return;
            }
            F[i] = N * Kinv[i];
            if (par.law == Law::linear) {
                sigma[i] = linear_stress(F[i]);
                P[i] = sigma[i];
            } else if (par.law == Law::saint_venant_kirchhoff) {
                P[i] = F[i] * svk_stress(F[i]);                                   // P = F S
                sigma[i] = P[i] * F[i].transpose() / F[i].determinant();          // sigma = P F^T / J
            } else {
                P[i] = F[i].determinant() * sigma[i] * F[i].inverse().transpose();  // P = J sigma F^-T
            }
            PKinv[i] = P[i] * Kinv[i];
            for (int a = 0; a < D; ++a) {
                double s = 0;
                for (int c = 0; c < D; ++c) s += PKinv[i](a, c) * m_xi.c[c][i];
                f_own.c[a][i] = s;
            }
        });
    }
};

}  // namespace pd
