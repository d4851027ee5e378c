// Correspondence kernels for chunks of translated families (3D, no damage; stencil_runs.hpp).
// W nodes i0 .. i0 + W - 1 (the W lanes of one vector) whose families are translates of i0's: bond
// r of lane l has partner j_r + l, so node j's values are W contiguous doubles, and xi_r, omega V_r
// and the hourglass coefficient hg_r are node i0's, one scalar each per W bonds. The formulas are
// those of Correspondence (correspondence.hpp), summed bond by bond in family order per lane:
//   deformation sums   N_l = sum_r (y_(j_r + l) - y_(i0 + l)) (x) omega V_r xi_r
//   bond force         f_l = sum_r A_(j_r + l) omega V_r xi_r
//                          + hg_r ((2Y - (F_l + F_(j_r + l)) xi_r).Y / |Y|^2) Y,   Y = y_(j_r + l) - y_(i0 + l)
//                      plus the i-end term P_l K_l^-1 m_xi of the point pass (f_own),
// with A = P K^-1 and F read from structure-of-arrays copies (entry a + 3 c of node j at
// soa[(a + 3 c) n + j] for A, soa[(9 + a + 3 c) n + j] for F); W = 8 (AVX-512) or 4 (AVX2),
// chunk_simd.hpp.
#pragma once
#include "pd/chunk_simd.hpp"

#include <cstdint>

#ifdef PD_CHUNK_WIDTH
namespace pd::detail {

// Node i0's bonds: the template of the chunk.
struct ChunkBonds {
    const std::int64_t* offset;
    const int* partner;
    const double* x[3];  // reference positions [m]
    const double* wV;    // omega V_j per bond [m^3]
    const double* hg;    // c_hg V_j / |xi| per bond [N/m^4]; unused without hourglass control
};

// N[a + 3 c][l] = sum_r (y_a(j_r + l) - y_a(i0 + l)) omega V_r xi_r,c  (F K of lane l).
inline void chunk_deformation_sums(const ChunkBonds& t, int i0, const double* const y[3], double (*N)[PD_CHUNK_WIDTH])
{
    const vchunk yi[3] = {load_chunk(y[0] + i0), load_chunk(y[1] + i0), load_chunk(y[2] + i0)};
    vchunk acc[9] = {};
    for (std::int64_t k = t.offset[i0]; k < t.offset[i0 + 1]; ++k) {
        const int j = t.partner[k];
        double we[3];
        for (int c = 0; c < 3; ++c) we[c] = t.wV[k] * (t.x[c][j] - t.x[c][i0]);
        for (int a = 0; a < 3; ++a) {
            const vchunk dz = load_chunk(y[a] + j) - yi[a];
            for (int c = 0; c < 3; ++c) acc[a + 3 * c] += dz * we[c];
        }
    }
    for (int e = 0; e < 9; ++e) store_chunk(N[e], acc[e]);
}

// f_a(i0 + l) for the W lanes [N/m^3]: the bond sums above plus f_own.
template <bool Hourglass>
inline void chunk_forces(const ChunkBonds& t, int i0, const double* const y[3], const double* soa, std::size_t n,
                         const double* const f_own[3], double* const f[3])
{
    const vchunk yi[3] = {load_chunk(y[0] + i0), load_chunk(y[1] + i0), load_chunk(y[2] + i0)};
    vchunk Fi[9];
    if constexpr (Hourglass)
        for (int e = 0; e < 9; ++e) Fi[e] = load_chunk(soa + (9 + e) * n + i0);
    vchunk acc[3] = {};
    for (std::int64_t k = t.offset[i0]; k < t.offset[i0 + 1]; ++k) {
        const int j = t.partner[k];
        double xi[3], we[3];
        for (int c = 0; c < 3; ++c) {
            xi[c] = t.x[c][j] - t.x[c][i0];
            we[c] = t.wV[k] * xi[c];
        }
        for (int a = 0; a < 3; ++a)
            for (int c = 0; c < 3; ++c) acc[a] += load_chunk(soa + (a + 3 * c) * n + j) * we[c];
        if constexpr (Hourglass) {
            vchunk Y[3], y2 = {}, gY = {};
            for (int a = 0; a < 3; ++a) {
                Y[a] = load_chunk(y[a] + j) - yi[a];
                vchunk g = {};
                for (int c = 0; c < 3; ++c) g += (Fi[a + 3 * c] + load_chunk(soa + (9 + a + 3 * c) * n + j)) * xi[c];
                y2 += Y[a] * Y[a];
                gY += g * Y[a];
            }
            const vchunk den = y2 > vchunk{} ? y2 : splat(1.0);  // |Y| = 0 (collapsed bond): no hourglass force
            const vchunk s = t.hg[k] * (2.0 * y2 - gY) / den;
            for (int a = 0; a < 3; ++a) acc[a] += s * Y[a];
        }
    }
    for (int a = 0; a < 3; ++a) store_chunk(f[a] + i0, acc[a] + load_chunk(f_own[a] + i0));
}

}  // namespace pd::detail
#endif
