// pd/models/correspondence_point_pass.hpp -- the point pass of the correspondence model: the definitions
// of Correspondence<D>'s family sums (K, m and the deformation sums N = sum_j omega (z_j - z_i) (x) xi V_j
// in the lane order of bond_loop.hpp, with K^-1 kept for families whose intact flags did not change),
// of stress_pass (per chunk of translated families, per node with AVX2, or per node in lanes) and of
// node_stress (F = N K^-1, the stress law, P K^-1 and the i-end force P_i K_i^-1 m_xi), declared and
// described in models/correspondence.hpp, which includes this file at its end.
#pragma once
#include "pd/models/correspondence.hpp"

namespace pd {

// A damaged pass's sums of node i (the point pass, the Flanagan-Taylor update): N over the NZ fields,
// and K^-1 and m formed again only where the family's intact flags changed since (k_formed_). K and m
// come from their own sums (NZ = 0), whichever pass forms them: summed beside N, their lane layout
// depended on NZ, and with AVX-512 the rounding did too, so a K^-1 formed by the Flanagan-Taylor
// update (NZ = 2) differed in its last bits from the one a restart's point pass (NZ = 1) forms, and a
// resumed run was not bit for bit the uninterrupted one (tests/test_checkpoint.cpp).
template <int D>
template <int NZ>
inline void Correspondence<D>::damaged_sums(const Bonds& b, std::size_t i, const std::array<const Field<D>*, NZ>& z, Mat* N)
{
    family_sums<true, false, NZ>(b, i, z, N, nullptr, nullptr);
    if (k_formed_.unchanged(b, i)) return;
    Mat K;
    Col m;
    family_sums<true, true, 0>(b, i, {}, nullptr, &K, &m);
    Kinv[i] = inverse_or_zero(K);
    for (int d = 0; d < D; ++d) m_xi.c[d][i] = m(d);
    k_formed_.formed(b, i);
}

// Family sums of node i over its intact bonds, in the lane order of bond_loop.hpp (8 partial
// sums per entry, vectorised over bonds): N[q] = sum_j omega (z_j - z_i) (x) xi V_j for each of
// the NZ fields z (y gives F K, v gives Fdot K), and, when WithK, K = sum_j omega xi (x) xi V_j
// and m = sum_j omega xi V_j.
template <int D>
template <bool Damaged, bool WithK, int NZ>
inline void Correspondence<D>::family_sums(const Bonds& b, std::size_t i, const std::array<const Field<D>*, NZ>& z, Mat* N, Mat* K, Col* m) const
{
    constexpr int C = NZ * DD + (WithK ? DK + D : 0);
    const double* wv = wV.data();
    const double* xc[D];
    double x_i[D];
    for (int d = 0; d < D; ++d) { xc[d] = x.c[d].data(); x_i[d] = xc[d][i]; }
    const double* zc[NZ > 0 ? NZ : 1][D];
    double z_i[NZ > 0 ? NZ : 1][D];
    for (int q = 0; q < NZ; ++q)
        for (int d = 0; d < D; ++d) { zc[q][d] = z[q]->c[d].data(); z_i[q][d] = zc[q][d][i]; }
    const std::array<double, C> S = detail::lane_sums<C, Damaged>(b, i, [&](std::int64_t k, int j, double keep, auto&& add) {
        double w = wv[k];
        if constexpr (Damaged) w *= keep;
        double e[D], we[D];
        for (int d = 0; d < D; ++d) { e[d] = xc[d][j] - x_i[d]; we[d] = w * e[d]; }
        for (int q = 0; q < NZ; ++q)
            for (int a = 0; a < D; ++a) {
                const double dz = zc[q][a][j] - z_i[q][a];
                for (int c = 0; c < D; ++c) add(q * DD + a + D * c, dz * we[c]);
            }
        if constexpr (WithK) {
            int t = NZ * DD;
            for (int a = 0; a < D; ++a)
                for (int c = a; c < D; ++c) add(t++, e[a] * we[c]);
            for (int a = 0; a < D; ++a) add(t++, we[a]);
        }
    });
    for (int q = 0; q < NZ; ++q)
        for (int a = 0; a < D; ++a)
            for (int c = 0; c < D; ++c) N[q](a, c) = S[q * DD + a + D * c];
    if constexpr (WithK) {
        int t = NZ * DD;
        for (int a = 0; a < D; ++a)
            for (int c = a; c < D; ++c) (*K)(a, c) = (*K)(c, a) = S[t++];
        for (int a = 0; a < D; ++a) (*m)(a) = S[t++];
    }
}

template <int D>
template <bool Damaged, int Dy>
inline void Correspondence<D>::stress_pass(const Bonds& b, const Field<Dy>& y)
{
#ifdef PD_CORRESPONDENCE_AVX2
    constexpr bool fast = !Damaged && D == 3;
    if constexpr (fast)
        parallel_for(b.nodes(), [&](std::size_t i) {
            for (int d = 0; d < D; ++d) ypad[4 * i + d] = y.c[d][i];
        });
#else
    constexpr bool fast = false;
#endif
#ifdef PD_CHUNK_WIDTH
    if constexpr (fast)
        if (!soa.empty()) {  // chunks of W nodes, then the other nodes
            const double* yc[3] = {y.c[0].data(), y.c[1].data(), y.c[2].data()};
            auto chunk = [&](std::size_t q) {
                const int i0 = runs.chunk_start[q], run = runs.chunk_run[q];
                const std::int64_t tb = templates.begin[run];
                double N[DD][detail::chunk_width];
                detail::chunk_deformation_sums(templates.bond.data() + tb, templates.begin[run + 1] - tb, i0, yc, N);
                if (par.law == Law::linear && regular[q]) return chunk_linear_stress(i0, N);
                for (int l = 0; l < detail::chunk_width; ++l) {
                    Mat Nl;
                    for (int e = 0; e < DD; ++e) Nl(e % D, e / D) = N[e][l];
                    node_stress(static_cast<std::size_t>(i0 + l), Nl);
                }
            };
            if (for_chunks_then_rest(runs, b, chunk, [&](std::size_t i) { node_stress(i, this->deformation_sum(b, i)); })) {
                matrices_partial = !par.node_matrices && par.law == Law::linear;
                return void(blocks_partial = true);
            }
        }
#endif
    blocks_partial = matrices_partial = false;  // node_stress below writes every block and matrix
    if constexpr (Damaged) k_formed_.track(b);
    parallel_for(b.nodes(), [&](std::size_t i) {
        Mat N;
        if constexpr (fast) N = this->deformation_sum(b, i);  // this->: dependent, so a build without AVX2 never looks it up
        else if constexpr (Damaged) damaged_sums<1>(b, i, {&y}, &N);
        else family_sums<false, false, 1>(b, i, {&y}, &N, nullptr, nullptr);
        node_stress(i, N);
    });
}

#ifdef PD_CHUNK_WIDTH
// Law::linear for the W nodes of a chunk, vectorised (correspondence_chunks.hpp), then the
// per-node copies.
template <int D>
inline void Correspondence<D>::chunk_linear_stress(int i0, const double (*N)[detail::chunk_width])
{
    double Fl[DD][detail::chunk_width], S[DD][detail::chunk_width], A[DD][detail::chunk_width];
    const double* mxi[3] = {m_xi.c[0].data(), m_xi.c[1].data(), m_xi.c[2].data()};
    double* fo[3] = {f_own.c[0].data(), f_own.c[1].data(), f_own.c[2].data()};
    detail::chunk_linear_stress(i0, N, kinv_soa.data(), soa_n, mxi, lambda, par.material.G, chunk_thermal(), Fl, S, A, soa.data(), fo);
    for (int l = 0; l < detail::chunk_width; ++l) {
        const std::size_t i = static_cast<std::size_t>(i0 + l);
        if (!par.node_matrices && !block_read[i]) continue;  // sync_node_matrices
        for (int e = 0; e < DD; ++e) {
            F[i](e % D, e / D) = Fl[e][l];
            sigma[i](e % D, e / D) = S[e][l];
            PKinv[i](e % D, e / D) = A[e][l];
        }
        P[i] = sigma[i];
        if (block_read[i]) write_node_block(i);
    }
}
#endif
// F = N K^-1, the stress law, P K^-1 and the i-end force of node i (K^-1 already current).
template <int D>
inline void Correspondence<D>::node_stress(std::size_t i, const Mat& N)
{
    if (Kinv[i].isZero(0)) {
        F[i] = Mat::Identity();
        P[i] = PKinv[i] = Mat::Zero();
        for (int d = 0; d < D; ++d) f_own.c[d][i] = 0;
        write_block(i);
        return;
    }
    F[i] = N * Kinv[i];
    node_stress_at_F(i);
}
// The stress law at F[i], P K^-1 and the i-end force of node i (K^-1 regular).
template <int D>
inline void Correspondence<D>::node_stress_at_F(std::size_t i)
{
    if (par.law == Law::linear) {
        sigma[i] = linear_stress(F[i]);
        if (thermal.active()) sigma[i].diagonal().array() -= thermal_pressure(i);
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
    write_block(i);
}

#ifdef PD_CORRESPONDENCE_AVX2
// N = sum_j omega (y_j - y_i) (x) xi V_j of node i without damage (3D, correspondence_simd.hpp).
template <int D>
inline auto Correspondence<D>::deformation_sum(const Bonds& b, std::size_t i) const -> Mat
{
    double N[DD];
    detail::deformation_sum_avx2(b, i, xpad.data(), ypad.data(), wV.data(), N);
    Mat M;
    for (int e = 0; e < DD; ++e) M(e % D, e / D) = N[e];
    return M;
}
#endif

// blocks of node i from PKinv[i] and F[i] (3D).
template <int D>
inline void Correspondence<D>::write_block(std::size_t i)
{
    if (!soa.empty()) {
        const std::size_t n = soa_n;
        for (int e = 0; e < DD; ++e) {
            soa[e * n + i] = PKinv[i](e % D, e / D);
            soa[(DD + e) * n + i] = F[i](e % D, e / D);
        }
    }
    write_node_block(i);
}
template <int D>
inline void Correspondence<D>::write_node_block(std::size_t i) const
{
    if constexpr (D == 3) {
        double* B = blocks.data() + BS * i;
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) {
                B[8 * c + a] = PKinv[i](a, c);
                B[8 * c + 4 + a] = F[i](a, c);
            }
    }
}

}  // namespace pd
