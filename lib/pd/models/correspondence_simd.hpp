// Per-node correspondence kernels vectorised within the bond (3D, AVX2 and FMA; issue 3, round 3
// of reports/3d/model_cost.md), for the nodes that do not sit in a chunk (correspondence_chunks.hpp).
// Both give the arithmetic of the generic code (Correspondence::family_sums, Kernel::bond_force)
// in its lanes and order (bond begin + l + 8 m to partial sum l, bond_loop.hpp):
//   family_force_avx2    f_i of the bond kernel: the partner products A_j xi and (F_i + F_j) xi are
//                        taken within the bond (3 broadcast xi components times 3 column loads of
//                        the node block, 4-padded columns of A = P K^-1 then of F), transposed, and
//                        the rest (Y, hourglass projection, division, sums) runs across 4 bonds;
//                        Out: also each bond's whole force (A_i xi omega V_j included) in out[d][k].
//   deformation_sum_avx2 N = sum_j omega (y_j - y_i) (x) xi V_j without damage, column-major in N[9]:
//                        each bond adds (y_j - y_i) w xi_c to column c as one 4-wide FMA (xpad, ypad:
//                        positions 4-padded per node, 2 loads per bond).
// Kn is Correspondence<3>::Kernel<Hourglass> (members x, wV, hg, blk, bond_force, node_share, node_force).
#pragma once
#include <cstddef>
#include <new>
#include "pd/bond_loop.hpp"
#include "pd/bonds.hpp"
#include "pd/field.hpp"

#include <cstdint>
#include <cstring>

#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#define PD_CORRESPONDENCE_AVX2 1
#endif

namespace pd::detail {

inline constexpr int correspondence_block = 24;  // doubles per node block: 3 columns x (A 4, F 4)
struct Aligned64 {  // allocator of 64-byte aligned doubles (a block starts a cache line)
    using value_type = double;
    template <class U>
    struct rebind { using other = Aligned64; };  // only ever rebound to double
    double* allocate(std::size_t n) { return static_cast<double*>(::operator new(n * sizeof(double), std::align_val_t{64})); }
    void deallocate(double* p, std::size_t) { ::operator delete(p, std::align_val_t{64}); }
    friend bool operator==(Aligned64, Aligned64) { return true; }
};

#ifdef PD_CORRESPONDENCE_AVX2
// 4 x 4 transpose of the first 3 entries: r[b][d] -> out[d][b].
inline void transpose3(const __m256d* r, __m256d* out)
{
    const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
    const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
    out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
    out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
}

template <bool Hourglass, bool Damaged, bool Out, class Kn>
Vec<3> family_force_avx2(const Kn& kn, std::size_t i, const Bonds& b, const Field<3>& y, double* const* out)
{
    const std::int64_t kb = b.offset[i], ke = b.offset[i + 1];
    const int* partner = b.partner.data();
    const double* yc[3] = {y.c[0].data(), y.c[1].data(), y.c[2].data()};
    __m256d xi_[3], yi_[3], Fi[3], Ai[3], acc[2][3];
    for (int d = 0; d < 3; ++d) {
        Ai[d] = Out ? _mm256_load_pd(kn.blk + correspondence_block * i + 8 * d) : _mm256_setzero_pd();
        xi_[d] = _mm256_set1_pd(kn.x[d][i]);
        yi_[d] = _mm256_set1_pd(yc[d][i]);
        Fi[d] = Hourglass ? _mm256_loadu_pd(kn.blk + correspondence_block * i + 8 * d + 4) : _mm256_setzero_pd();
        acc[0][d] = acc[1][d] = _mm256_setzero_pd();
    }
    std::int64_t k = kb;
    for (; k + lanes <= ke; k += lanes)
        for (int h = 0; h < 2; ++h) {
            const std::int64_t k0 = k + 4 * h;
            __m256d a[4], g[4], o[4], Ax[3], Gx[3], Yx[3], Ox[3];
            int jj[4];
            for (int q = 0; q < 4; ++q) {
                const int j = jj[q] = partner[k0 + q];
                const double* Bj = kn.blk + correspondence_block * static_cast<std::size_t>(j);
                __m256d e[3];
                for (int d = 0; d < 3; ++d) e[d] = _mm256_sub_pd(_mm256_broadcast_sd(kn.x[d] + j), xi_[d]);
                a[q] = _mm256_mul_pd(_mm256_load_pd(Bj), e[0]);
                a[q] = _mm256_fmadd_pd(_mm256_load_pd(Bj + 8), e[1], a[q]);
                a[q] = _mm256_fmadd_pd(_mm256_load_pd(Bj + 16), e[2], a[q]);
                if constexpr (Out)
                    o[q] = _mm256_fmadd_pd(Ai[2], e[2], _mm256_fmadd_pd(Ai[1], e[1], _mm256_mul_pd(Ai[0], e[0])));
                if constexpr (Hourglass) {
                    g[q] = _mm256_mul_pd(_mm256_add_pd(Fi[0], _mm256_load_pd(Bj + 4)), e[0]);
                    g[q] = _mm256_fmadd_pd(_mm256_add_pd(Fi[1], _mm256_load_pd(Bj + 12)), e[1], g[q]);
                    g[q] = _mm256_fmadd_pd(_mm256_add_pd(Fi[2], _mm256_load_pd(Bj + 20)), e[2], g[q]);
                }
            }
            transpose3(a, Ax);
            const __m256d w = _mm256_loadu_pd(kn.wV + k0);
            __m256d f[3];
            for (int d = 0; d < 3; ++d) {
                Yx[d] = _mm256_sub_pd(_mm256_set_pd(yc[d][jj[3]], yc[d][jj[2]], yc[d][jj[1]], yc[d][jj[0]]), yi_[d]);
                f[d] = _mm256_mul_pd(w, Ax[d]);
            }
            if constexpr (Hourglass) {
                transpose3(g, Gx);
                const __m256d two = _mm256_set1_pd(2.0);
                __m256d proj = _mm256_mul_pd(_mm256_fmsub_pd(two, Yx[0], Gx[0]), Yx[0]);
                __m256d y2 = _mm256_mul_pd(Yx[0], Yx[0]);
                for (int d = 1; d < 3; ++d) {
                    proj = _mm256_fmadd_pd(_mm256_fmsub_pd(two, Yx[d], Gx[d]), Yx[d], proj);
                    y2 = _mm256_fmadd_pd(Yx[d], Yx[d], y2);
                }
                const __m256d den = _mm256_blendv_pd(_mm256_set1_pd(1.0), y2, _mm256_cmp_pd(y2, _mm256_setzero_pd(), _CMP_GT_OQ));
                const __m256d t = _mm256_div_pd(_mm256_mul_pd(_mm256_loadu_pd(kn.hg + k0), proj), den);
                for (int d = 0; d < 3; ++d) f[d] = _mm256_fmadd_pd(t, Yx[d], f[d]);
            }
            __m256d keep = _mm256_set1_pd(1.0);
            if constexpr (Damaged) {
                std::int32_t flags;
                std::memcpy(&flags, b.intact.data() + k0, 4);
                keep = _mm256_cvtepi32_pd(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(flags)));
            }
            if constexpr (Out) {
                transpose3(o, Ox);
                for (int d = 0; d < 3; ++d) _mm256_storeu_pd(out[d] + k0, _mm256_mul_pd(_mm256_fmadd_pd(w, Ox[d], f[d]), keep));
            }
            if constexpr (Damaged)
                for (int d = 0; d < 3; ++d) f[d] = _mm256_mul_pd(f[d], keep);
            for (int d = 0; d < 3; ++d) acc[h][d] = _mm256_add_pd(acc[h][d], f[d]);
        }
    LaneSum<3> sum;
    for (int d = 0; d < 3; ++d) {
        _mm256_storeu_pd(sum.s[d], acc[0][d]);
        _mm256_storeu_pd(sum.s[d] + 4, acc[1][d]);
    }
    for (int l = 0; k < ke; ++k, ++l) {
        const int j = partner[k];
        Vec<3> Y;
        for (int d = 0; d < 3; ++d) Y[d] = yc[d][j] - yc[d][i];
        Vec<3> fk = kn.bond_force(i, k, j, Y);
        if constexpr (Damaged) fk *= static_cast<double>(b.intact[k]);
        for (int d = 0; d < 3; ++d) sum.s[d][l] += fk[d];
        if constexpr (Out) fk += static_cast<double>(b.intact[k]) * kn.node_share(i, k, j);
        if constexpr (Out) for (int d = 0; d < 3; ++d) out[d][k] = fk[d];
    }
    const Vec<3> fn = kn.node_force(i);
    Vec<3> r;
    for (int d = 0; d < 3; ++d) r[d] = sum.total(d) + fn[d];
    return r;
}

inline void deformation_sum_avx2(const Bonds& b, std::size_t i, const double* xpad, const double* ypad, const double* wV, double* N)
{
    const std::int64_t kb = b.offset[i], ke = b.offset[i + 1];
    const int* partner = b.partner.data();
    const __m256d xi_ = _mm256_load_pd(xpad + 4 * i), yi_ = _mm256_load_pd(ypad + 4 * i);
    LaneSum<9> sum;
    for (int l = 0; l < lanes && kb + l < ke; ++l) {
        __m256d acc[3] = {_mm256_setzero_pd(), _mm256_setzero_pd(), _mm256_setzero_pd()};
        for (std::int64_t k = kb + l; k < ke; k += lanes) {
            const std::size_t j = static_cast<std::size_t>(partner[k]);
            const __m256d we = _mm256_mul_pd(_mm256_set1_pd(wV[k]), _mm256_sub_pd(_mm256_load_pd(xpad + 4 * j), xi_));
            const __m256d dz = _mm256_sub_pd(_mm256_load_pd(ypad + 4 * j), yi_);
            acc[0] = _mm256_fmadd_pd(dz, _mm256_permute4x64_pd(we, 0x00), acc[0]);
            acc[1] = _mm256_fmadd_pd(dz, _mm256_permute4x64_pd(we, 0x55), acc[1]);
            acc[2] = _mm256_fmadd_pd(dz, _mm256_permute4x64_pd(we, 0xaa), acc[2]);
        }
        for (int c = 0; c < 3; ++c) {
            alignas(32) double t[4];
            _mm256_store_pd(t, acc[c]);
            for (int a = 0; a < 3; ++a) sum.s[a + 3 * c][l] = t[a];
        }
    }
    for (int e = 0; e < 9; ++e) N[e] = sum.total(e);
}
#endif

}  // namespace pd::detail
