// Per-node correspondence kernels vectorised within the bond (3D, AVX2 and FMA; reports/3d/model_cost.md),
// for the nodes that do not sit in a chunk (correspondence_chunks.hpp).
// Both give the arithmetic of the generic code (Correspondence::family_sums, Kernel::bond_force)
// in its lanes and order (bond begin + l + 8 m to partial sum l, bond_loop.hpp):
//   family_force_avx2    f_i of the bond kernel: the partner products A_j xi and (F_i + F_j) xi are
//                        taken within the bond (3 broadcast xi components times 3 column loads of
//                        the node block, 4-padded columns of A = P K^-1 then of F), transposed, and
//                        the rest (Y, the hourglass formula of hourglass.hpp, sums) runs across 4 bonds;
//                        Out: also the bond work (bond_loop.hpp) of the 4-bond groups holding a bond
//                        with j > i, its force A_i xi omega V_j included (bond_work_avx2), its
//                        hourglass term left out when out->hourglass is false.
//   deformation_sum_avx2 N = sum_j omega (y_j - y_i) (x) xi V_j without damage, column-major in N[9]:
//                        each bond adds (y_j - y_i) w xi_c to column c as one 4-wide FMA (xpad, ypad:
//                        positions 4-padded per node, 2 loads per bond).
// Kn is Correspondence<3>::Kernel<Hourglass> (members x, wV, hg, blk, bond_force, hourglass_force,
// node_share, node_force).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/models/hourglass.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>

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
// 4 x 4 transpose, the first N rows of the result: r[b][d] -> out[d][b] for d < N.
template <int N = 3>
inline void transpose(const __m256d* r, __m256d* out)
{
    const __m256d t0 = _mm256_unpacklo_pd(r[0], r[1]), t1 = _mm256_unpackhi_pd(r[0], r[1]);
    const __m256d t2 = _mm256_unpacklo_pd(r[2], r[3]), t3 = _mm256_unpackhi_pd(r[2], r[3]);
    out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
    out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
    out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
    if constexpr (N == 4) out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}

// Bond work (bond_loop.hpp) of the 4 bonds k0 ... k0 + 3 of node i (partners jj) whose lanes are set
// in upper (j > i): fk their forces times keep, Y their deformed bonds. The arithmetic of
// detail::bond_work on the records (g0, g1, g2, w), 4 bonds at a time (one load and one store of
// each record); the other lanes' records are written back unchanged (one writer per record).
// Returns w of the upper lanes, the lowest double in the others.
inline __m256d bond_work_avx2(const BondWork& o, std::size_t i, std::int64_t k0, const int* jj, const __m256d* Y, const __m256d* fk,
                           __m256d upper, __m256d keep)
{
    double* rec = o.rec + 4 * k0;
    __m256d r[4], g[4];  // records of the 4 bonds; g[0..2] the force components, g[3] w
    for (int q = 0; q < 4; ++q) r[q] = _mm256_loadu_pd(rec + 4 * q);
    transpose<4>(r, g);
    if (o.y_old[0]) {
        __m256d s = _mm256_setzero_pd();
        for (int d = 0; d < 3; ++d) {
            const double* yo = o.y_old[d];
            const __m256d Yo = _mm256_sub_pd(_mm256_set_pd(yo[jj[3]], yo[jj[2]], yo[jj[1]], yo[jj[0]]), _mm256_set1_pd(yo[i]));
            s = _mm256_fmadd_pd(_mm256_add_pd(g[d], fk[d]), _mm256_sub_pd(Y[d], Yo), s);
        }
        __m256d dw = _mm256_div_pd(_mm256_mul_pd(_mm256_set1_pd(0.5), s), _mm256_loadu_pd(o.volume + k0));
        if (o.ratio) {
            const double* rt = o.ratio;
            const __m256d rj = _mm256_set_pd(rt[jj[3]], rt[jj[2]], rt[jj[1]], rt[jj[0]]);
            dw = _mm256_mul_pd(dw, _mm256_mul_pd(_mm256_set1_pd(0.5), _mm256_add_pd(_mm256_set1_pd(rt[i]), rj)));
        }
        g[3] = _mm256_add_pd(g[3], _mm256_and_pd(_mm256_mul_pd(keep, dw), upper));
    }
    for (int d = 0; d < 3; ++d) g[d] = _mm256_blendv_pd(g[d], fk[d], upper);
    const __m256d w = _mm256_blendv_pd(_mm256_set1_pd(std::numeric_limits<double>::lowest()), g[3], upper);
    transpose<4>(g, r);
    for (int q = 0; q < 4; ++q) _mm256_storeu_pd(rec + 4 * q, r[q]);
    return w;
}

template <bool Hourglass, bool AlongBond, bool Damaged, bool Out, class Kn>
Vec<3> family_force_avx2(const Kn& kn, std::size_t i, const Bonds& b, const Field<3>& y, const BondWork* out)
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
    __m256d w_max = _mm256_set1_pd(std::numeric_limits<double>::lowest());  // Out: bond work's w over j > i
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
            transpose(a, Ax);
            const __m256d w = _mm256_loadu_pd(kn.wV + k0);
            __m256d f[3], f_stress[3];
            for (int d = 0; d < 3; ++d) {
                Yx[d] = _mm256_sub_pd(_mm256_set_pd(yc[d][jj[3]], yc[d][jj[2]], yc[d][jj[1]], yc[d][jj[0]]), yi_[d]);
                f[d] = f_stress[d] = _mm256_mul_pd(w, Ax[d]);
            }
            if constexpr (Hourglass) {
                transpose(g, Gx);
                const __m256d t = hourglass_scalar<3, AlongBond>(Gx, Yx, _mm256_loadu_pd(kn.hg + k0));
                for (int d = 0; d < 3; ++d) f[d] = _mm256_fmadd_pd(t, Yx[d], f[d]);
            }
            __m256d keep = _mm256_set1_pd(1.0);
            if constexpr (Damaged) {
                std::int32_t flags;
                std::memcpy(&flags, b.intact.data() + k0, 4);
                keep = _mm256_cvtepi32_pd(_mm_cvtepu8_epi32(_mm_cvtsi32_si128(flags)));
            }
            if constexpr (Out) {
                const __m128i j4 = _mm_loadu_si128(reinterpret_cast<const __m128i*>(partner + k0));
                const __m256d upper = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_cmpgt_epi32(j4, _mm_set1_epi32(static_cast<int>(i)))));
                if (_mm256_movemask_pd(upper)) {  // families are sorted by partner: j < i groups skip this
                    transpose(o, Ox);
                    __m256d fk[3];
                    const __m256d* fb = Hourglass && !out->hourglass ? f_stress : f;  // the work with or without hourglass
                    for (int d = 0; d < 3; ++d) fk[d] = _mm256_mul_pd(_mm256_fmadd_pd(w, Ox[d], fb[d]), keep);
                    w_max = _mm256_max_pd(w_max, bond_work_avx2(*out, i, k0, jj, Yx, fk, upper, keep));
                }
            }
            if constexpr (Damaged)
                for (int d = 0; d < 3; ++d) f[d] = _mm256_mul_pd(f[d], keep);
            for (int d = 0; d < 3; ++d) acc[h][d] = _mm256_add_pd(acc[h][d], f[d]);
        }
    LaneSum<3> sum;
    double w_max_tail = std::numeric_limits<double>::lowest();
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
        if constexpr (Out)
            if (static_cast<std::size_t>(j) > i) {
                const double keep = b.intact[k];
                fk += keep * kn.node_share(i, k, j);
                if constexpr (Hourglass)
                    if (!out->hourglass) fk -= keep * kn.hourglass_force(i, k, j, Y);
                w_max_tail = std::max(w_max_tail, bond_work<3, false>(*out, i, k, j, Y.c.data(), fk.c.data(), keep));
            }
    }
    if constexpr (Out) {
        alignas(32) double m[4];
        _mm256_store_pd(m, w_max);
        out->w_max[i] = std::max({m[0], m[1], m[2], m[3], w_max_tail});
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
