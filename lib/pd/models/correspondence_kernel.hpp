// pd/models/correspondence_kernel.hpp -- the bond kernel of the correspondence model
// (models/correspondence.hpp hands it to the bond pass through with_kernel): raw pointers to the
// model's per-node and per-bond arrays and the per-bond force formula, written once in scalar form.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/models/correspondence_chunks.hpp"
#include "pd/models/correspondence_simd.hpp"
#include "pd/models/hourglass.hpp"
#include "pd/simd/translated_families.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace pd {

// Bond kernel (bond_loop.hpp, with_kernel). The force density on i from bond k (i -> j),
//   omega V_j (P_i K_i^-1 + P_j K_j^-1) xi  +  c_hg V_j/|xi| ((2Y - (F_i + F_j) xi).Y / |Y|^2) Y,
// (second term only when Hourglass) is split: the i-end term summed over the family is
// P_i K_i^-1 m_xi (node_force, once per node); bond_force gives the rest. Branch-free plain
// arithmetic on raw arrays, so that the bond loop vectorises it. The hourglass term is the formula of
// models/hourglass.hpp (AlongBond: HourglassDirection::bond), which the AVX2 and chunk paths share.
template <int D, bool Hourglass, bool AlongBond = false>
struct CorrespondenceKernel {
    static constexpr bool ordinary = false;
    static constexpr int DD = D * D;  // entries of a D x D matrix
    const double* x[D];        // reference positions [m]
    const double* f_own[D];    // P_i K_i^-1 m_xi [N/m^3]
    const double* wV;          // omega V_j per bond [m^3]
    const double* hg;          // c_hg V_j / |xi| per bond [N/m^4] (Hourglass only)
    const double* A;           // P K^-1 per node, D x D column-major blocks [Pa/m^5]
    const double* F;           // F per node, D x D column-major blocks [-] (Hourglass only)
    const double* blk;         // per node A and F, 4-padded columns (Correspondence::blocks; 3D)
    const TranslatedRuns* runs;   // chunks of translated families (3D, AVX2/AVX-512), or null
    const double* soa;         // A and F per node as 18 arrays (chunks only)
    std::size_t soa_n;         // their stride
#ifdef PD_CHUNK_WIDTH
    const detail::ChunkTemplates* templates;
#endif
    Vec<D> node_force(std::size_t i) const
    {
        Vec<D> f;
        for (int d = 0; d < D; ++d) f[d] = f_own[d][i];
        return f;
    }
    // Bond k's part of node_force, omega V_j P_i K_i^-1 xi [N/m^3] (bond work, bond_loop.hpp).
    Vec<D> node_share(std::size_t i, std::int64_t k, int j) const
    {
        Vec<D> f;  // zero
        for (int a = 0; a < D; ++a)
            for (int c = 0; c < D; ++c) f[a] += wV[k] * A[DD * i + a + D * c] * (x[c][j] - x[c][i]);
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
        if constexpr (Hourglass) f += hourglass_force(i, k, j, Y);
        return f;
    }
    // The hourglass term of bond_force [N/m^3] (models/hourglass.hpp; bond work without it, bond_loop.hpp).
    Vec<D> hourglass_force(std::size_t i, std::int64_t k, int j, const Vec<D>& Y) const requires Hourglass
    {
        const double *Fi = F + DD * i, *Fj = F + DD * static_cast<std::size_t>(j);
        double Gx[D];  // (F_i + F_j) xi [m]
        for (int a = 0; a < D; ++a) {
            Gx[a] = 0;
            for (int c = 0; c < D; ++c) Gx[a] += (Fi[a + D * c] + Fj[a + D * c]) * (x[c][j] - x[c][i]);
        }
        return hourglass_scalar<D, AlongBond>(Gx, Y.c.data(), hg[k]) * Y;
    }
#ifdef PD_CHUNK_WIDTH
    // Chunk hook of the bond loop (bond_loop.hpp): f of the nodes of run p's chunks, undamaged.
    const TranslatedRuns* chunks(const Bonds& b) const { return runs && runs->fits(b) ? runs : nullptr; }
    void run_force(int p, const Bonds&, const Field<D>& y, Field<D>& f) const
        requires(D == 3)
    {
        const std::int64_t tb = templates->begin[p], s = templates->begin[p + 1] - tb;
        const int c0 = runs->run_chunks[p];
        const double* yc[3] = {y.c[0].data(), y.c[1].data(), y.c[2].data()};
        double* fc[3] = {f.c[0].data(), f.c[1].data(), f.c[2].data()};
        detail::run_forces<Hourglass, AlongBond>(templates->bond.data() + tb, s, runs->chunk_start.data() + c0, runs->run_chunks[p + 1] - c0, yc, soa,
                                      soa_n, f_own, fc);
    }
#endif
#ifdef PD_CORRESPONDENCE_AVX2
    // The whole f_i (bond_loop.hpp, family kernel), 3D, vectorised within the bond
    // (correspondence_simd.hpp); Out: also the bond work of the pass (bond_loop.hpp).
    template <bool Damaged, bool Out = false>
        requires(D == 3)
    Vec<D> family_force(std::size_t i, const Bonds& b, const Field<D>& y, const BondWork* out = nullptr) const
    {
        return detail::family_force_avx2<Hourglass, AlongBond, Damaged, Out>(*this, i, b, y, out);
    }
#endif
};

}  // namespace pd
