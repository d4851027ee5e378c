// Correspondence kernels for chunks of translated families (3D, no damage; translated_families.hpp).
// W nodes i0 .. i0 + W - 1 (the W lanes of one vector) whose families are translates of i0's: bond
// r of lane l has partner j_r + l, so node j's values are W contiguous doubles, and xi_r, omega V_r
// and the hourglass coefficient hg_r are those of the run's template family (TemplateBond, one
// cache line per bond, shared by all chunks of the run), one scalar each per W bonds. The formulas are
// those of Correspondence (correspondence.hpp), summed bond by bond in family order per lane:
//   deformation sums   N_l = sum_r (y_(j_r + l) - y_(i0 + l)) (x) omega V_r xi_r
//   bond force         f_l = sum_r A_(j_r + l) omega V_r xi_r
//                          + t Y,   t the hourglass formula (hourglass.hpp) with Gx = (F_l + F_(j_r + l)) xi_r,
//                                   Y = y_(j_r + l) - y_(i0 + l)
//                      plus the i-end term P_l K_l^-1 m_xi of the point pass (f_own),
// with A = P K^-1 and F read from structure-of-arrays copies (entry a + 3 c of node j at
// soa[(a + 3 c) n + j] for A, soa[(9 + a + 3 c) n + j] for F, stride n = soa_stride(nodes)); W = 8
// (AVX-512) or 4 (AVX2), chunk_vector.hpp.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/core/field.hpp"
#include "pd/models/hourglass.hpp"
#include "pd/core/parallel.hpp"
#include "pd/laws/elastic.hpp"
#include "pd/simd/translated_families.hpp"

#include <cstdint>
#include <vector>

#ifdef PD_CHUNK_WIDTH
namespace pd::detail {

// Stride [doubles] of the structure-of-arrays copies (soa, K^-1) for n nodes: n rounded up to a
// whole 4 KiB page plus 3 cache lines. With a stride of a whole number of pages the 18 arrays
// of A and F would map onto the same L1 sets and evict each other (the bond pass read its partner
// values 1.8x slower, measured); 3 lines apart they spread over the sets.
inline std::size_t soa_stride(std::size_t n) { return (n + 511) / 512 * 512 + 24; }

// One bond of a run's template family (the family of the run's first node t, translated_families.hpp):
// what every chunk of the run uses for its bond r (64 bytes, so a bond is one cache line).
struct alignas(64) TemplateBond {
    double wxi[3];        // omega V_j xi [m^4]
    double xi[3];         // xi [m]
    double hg;            // c_hg V_j / |xi| [N/m^4] (0 without hourglass control)
    std::int64_t offset;  // j - t: bond r of node i0 + l has partner i0 + offset + l
};
// The templates of all runs: run q's bonds are bond[begin[q] .. begin[q + 1]).
struct ChunkTemplates {
    std::vector<std::int64_t> begin;
    std::vector<TemplateBond> bond;
};
template <int D>
ChunkTemplates chunk_templates(const TranslatedRuns& runs, const Bonds& b, const Field<D>& x, const std::vector<double>& wV,
                               const std::vector<double>& hg)
{
    ChunkTemplates t;
    t.begin.push_back(0);
    for (int first : runs.run_first) {
        for_family(b, static_cast<std::size_t>(first), [&](std::int64_t k, int j) {
            TemplateBond tb{};
            for (int c = 0; c < D; ++c) {
                tb.xi[c] = x.c[c][j] - x.c[c][first];
                tb.wxi[c] = wV[k] * tb.xi[c];
            }
            tb.hg = hg.empty() ? 0.0 : hg[k];
            tb.offset = j - first;
            t.bond.push_back(tb);
        });
        t.begin.push_back(static_cast<std::int64_t>(t.bond.size()));
    }
    return t;
}

// Per-node data of the chunk path: K^-1 as 9 arrays (entry e of node i at kinv[e ns + i], stride ns = soa_stride(n)), per chunk
// whether every lane has K^-1 != 0 (else the stress goes node by node), and per node whether the
// per-node kernels of an undamaged pass read its block (the nodes outside chunks and their partners).
template <class Mat>
void chunk_node_data(const TranslatedRuns& runs, const Bonds& b, const std::vector<Mat>& Kinv, std::vector<double>& kinv,
                     std::vector<std::uint8_t>& regular, std::vector<std::uint8_t>& block_read)
{
    const std::size_t n = b.nodes(), ns = soa_stride(n);
    kinv.assign(9 * ns, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (int e = 0; e < 9; ++e) kinv[e * ns + i] = Kinv[i](e % 3, e / 3);
    block_read.assign(n, 0);
    for (int i : runs.rest) {
        block_read[i] = 1;
        for_family(b, i, [&](std::int64_t, int j) { block_read[j] = 1; });
    }
    regular.assign(runs.chunk_start.size(), 1);
    for (std::size_t q = 0; q < regular.size(); ++q)
        for (int l = 0; l < chunk_width; ++l) regular[q] = regular[q] && !Kinv[runs.chunk_start[q] + l].isZero(0);
}

// N[a + 3 c][l] = sum_r (y_a(j_r + l) - y_a(i0 + l)) omega V_r xi_r,c  (F K of lane l); tb, s: the
// template bonds of the chunk's run.
inline void chunk_deformation_sums(const TemplateBond* tb, std::int64_t s, int i0, const double* const y[3],
                                   double (*N)[PD_CHUNK_WIDTH])
{
    const vchunk yi[3] = {load_chunk(y[0] + i0), load_chunk(y[1] + i0), load_chunk(y[2] + i0)};
    vchunk acc[9] = {};
    for (std::int64_t r = 0; r < s; ++r) {
        const std::int64_t j = i0 + tb[r].offset;
        for (int a = 0; a < 3; ++a) {
            const vchunk dz = load_chunk(y[a] + j) - yi[a];
            for (int c = 0; c < 3; ++c) acc[a + 3 * c] += dz * tb[r].wxi[c];
        }
    }
    for (int e = 0; e < 9; ++e) store_chunk(N[e], acc[e]);
}

// f_a(i0 + l) for the W lanes of every chunk of one run [N/m^3] (the chunks' first nodes start[0 ..
// chunks - 1]): the bond sums above plus f_own. The bonds go in blocks of `block`, each block over
// all chunks of the run, with the partial sums kept in f: the partner values of one block (21
// arrays) stay in L1 from one chunk to the next, which those of a whole family do not. Each lane
// still adds its bonds in family order, as a chunk taken alone would.
template <bool Hourglass, bool AlongBond>
inline void run_forces(const TemplateBond* tb, std::int64_t s, const int* start, int chunks, const double* const y[3],
                       const double* soa, std::size_t n, const double* const f_own[3], double* const f[3])
{
    constexpr std::int64_t block = 32;
    for (std::int64_t r0 = 0; r0 < s; r0 += block) {
        const std::int64_t r1 = r0 + block < s ? r0 + block : s;
        for (int q = 0; q < chunks; ++q) {
            const int i0 = start[q];
            const vchunk yi[3] = {load_chunk(y[0] + i0), load_chunk(y[1] + i0), load_chunk(y[2] + i0)};
            vchunk Fi[9];
            if constexpr (Hourglass)
                for (int e = 0; e < 9; ++e) Fi[e] = load_chunk(soa + (9 + e) * n + i0);
            vchunk acc[3] = {};
            if (r0 > 0)
                for (int a = 0; a < 3; ++a) acc[a] = load_chunk(f[a] + i0);
            for (std::int64_t r = r0; r < r1; ++r) {
                const std::int64_t j = i0 + tb[r].offset;
                for (int a = 0; a < 3; ++a)
                    for (int c = 0; c < 3; ++c) acc[a] += load_chunk(soa + (a + 3 * c) * n + j) * tb[r].wxi[c];
                if constexpr (Hourglass) {
                    vchunk Y[3], Gx[3];
                    for (int a = 0; a < 3; ++a) {
                        Y[a] = load_chunk(y[a] + j) - yi[a];
                        Gx[a] = vchunk{};
                        for (int c = 0; c < 3; ++c) Gx[a] += (Fi[a + 3 * c] + load_chunk(soa + (9 + a + 3 * c) * n + j)) * tb[r].xi[c];
                    }
                    const vchunk t = hourglass_scalar<3, AlongBond>(Gx, Y, tb[r].hg);
                    for (int a = 0; a < 3; ++a) acc[a] += t * Y[a];
                }
            }
            for (int a = 0; a < 3; ++a) store_chunk(f[a] + i0, r1 == s ? acc[a] + load_chunk(f_own[a] + i0) : acc[a]);
        }
    }
}

// Thermal expansion of the linear law (Correspondence's header): sigma less p_i I with
// p_i = coef (alpha (theta_i - theta_ref)) [Pa], coef = D lambda + 2 G; theta null: none.
struct ChunkThermal {
    const double* theta = nullptr;  // node temperatures [K]
    double coef = 0, alpha = 0, theta_ref = 0;  // [Pa], [1/K], [K]
};

// F, P K^-1, sigma and P = sigma per node from the chunk arrays, for the lanes of the regular chunks
// that the chunked pass did not copy (Correspondence::sync_node_matrices).
template <class Mat>
void sync_chunk_matrices(const TranslatedRuns& runs, const std::vector<std::uint8_t>& regular, const std::vector<std::uint8_t>& copied,
                         const double* soa, std::size_t n, double lambda, double G, const ChunkThermal& th, std::vector<Mat>& F,
                         std::vector<Mat>& A, std::vector<Mat>& sigma, std::vector<Mat>& P)
{
    parallel_for_items(runs.chunk_start.size(), runs.nodes, [&](std::size_t q) {
        for (int l = 0; regular[q] && l < chunk_width; ++l) {
            const std::size_t i = static_cast<std::size_t>(runs.chunk_start[q] + l);
            if (copied[i]) continue;
            for (int e = 0; e < 9; ++e) {
                F[i](e % 3, e / 3) = soa[(9 + e) * n + i];
                A[i](e % 3, e / 3) = soa[e * n + i];
            }
            laws::small_strain_stress(F[i].data(), lambda, G, sigma[i].data());  // the chunk's operations
            if (th.theta) sigma[i].diagonal().array() -= th.coef * (th.alpha * (th.theta[i] - th.theta_ref));
            P[i] = sigma[i];
        }
    });
}

// Law::linear for the W lanes of a chunk, from the deformation sums N[9][W] (column-major entries):
//   F = N K^-1,  sigma = laws::small_strain_stress(F) - p I (ChunkThermal),  A = sigma K^-1,  f_own = A m_xi,
// with K^-1 and m_xi of the lanes from structure-of-arrays copies (entry e of node i at kinv[e n + i],
// m_xi.c[c][i]). Out: F, sigma and A as [9][W], A and F into soa, f_own into its field arrays.
inline void chunk_linear_stress(int i0, const double (*N)[PD_CHUNK_WIDTH], const double* kinv, std::size_t n,
                                const double* const mxi[3], double lambda, double G, const ChunkThermal& th, double (*F)[PD_CHUNK_WIDTH],
                                double (*S)[PD_CHUNK_WIDTH], double (*A)[PD_CHUNK_WIDTH], double* soa, double* const f_own[3])
{
    vchunk Ki[9], Nv[9], Fv[9], Sv[9];
    for (int e = 0; e < 9; ++e) {
        Ki[e] = load_chunk(kinv + e * n + i0);
        Nv[e] = load_chunk(N[e]);
    }
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) Fv[a + 3 * c] = Nv[a] * Ki[3 * c] + Nv[a + 3] * Ki[1 + 3 * c] + Nv[a + 6] * Ki[2 + 3 * c];
    laws::small_strain_stress(Fv, lambda, G, Sv);
    if (th.theta) {
        const vchunk p = th.coef * (th.alpha * (load_chunk(th.theta + i0) - th.theta_ref));
        Sv[0] -= p, Sv[4] -= p, Sv[8] -= p;
    }
    vchunk fo[3] = {};
    for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
            const vchunk Av = Sv[a] * Ki[3 * c] + Sv[a + 3] * Ki[1 + 3 * c] + Sv[a + 6] * Ki[2 + 3 * c];
            fo[a] += Av * load_chunk(mxi[c] + i0);
            store_chunk(A[a + 3 * c], Av);
            store_chunk(soa + (a + 3 * c) * n + i0, Av);
        }
    for (int e = 0; e < 9; ++e) {
        store_chunk(F[e], Fv[e]);
        store_chunk(S[e], Sv[e]);
        store_chunk(soa + (9 + e) * n + i0, Fv[e]);
    }
    for (int a = 0; a < 3; ++a) store_chunk(f_own[a] + i0, fo[a]);
}

}  // namespace pd::detail
#endif
