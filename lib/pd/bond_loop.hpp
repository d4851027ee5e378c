// THE bond loop: internal force density f_i = sum_j t_ij(Y) Y_ij over the intact bonds of i
// [N/m^3] for ordinary models (force along the deformed bond Y = y_j - y_i), f_i = sum_j f_ij(Y)
// for non-ordinary ones. What a model or its kernel supplies, role by role, is a named concept
// in kernel_concepts.hpp (ordinary or NonOrdinaryKernel; KernelProvider, FamilyKernel,
// NodeTermKernel, HourglassKernel, ChunkRunKernel, OrdinaryChunkKernel); each is tested at compile
// time, so an ordinary model compiles the plain loop below and a switched-off role costs nothing.
// Chunks: in undamaged scenes a chunk kernel takes the nodes of translated families W at a time
// (node j's values as contiguous vectors, per-bond data as node i0's scalars) and the other nodes
// take the per-node code; the split is fixed by the bonds, so results do not depend on the
// threads. Each lane sums its bonds in family order (not the 8 partial sums below); the results
// differ from the per-node code's at round-off only.
// Bond work (optional, for critical-micropotential damage, damage/micropotential.hpp):
// internal_force(model, bonds, y, f, &work) also integrates the work of each pair's force over the
// step, inside the force pass, for the bond k (i -> j) of the pair's lower node (j > i) only:
//   w[k] += keep_k 1/2 (g_k + f_k) . (Y_k - Y_k^old) / volume_k  [x (r_i + r_j)/2 with per-node ratios]
//   g_k   = f_k
// f_k the force density on i from bond k with both ends' states included (ordinary models: g_k =
// t_k, the bond_scalar, and f_k = t_k Y_k; non-ordinary: the D components), Y^old the positions of
// the previous pass, keep_k = intact[k]; with y_old null the pass only stores g (the first pass).
// It also sets w_max[i], the largest w of node i's bonds with j > i, so that the breaking test
// skips the nodes below w_C without reading their bonds. A NodeTermKernel then also supplies
// node_share; a HourglassKernel's hourglass part is left out when work.hourglass is false. A
// FamilyKernel takes the work as family_force<Damaged, true>(i, bonds, y, &work). Without work
// (default) the passes compile as before (template flag Out = false): no store, no branch.
// Owner computes (gather only, no atomics): bit-identical results for any number of threads.
// Broken bonds are zeroed by multiplying with intact[k]; the undamaged scene compiles a loop
// without that array (if constexpr).
// Summation order, fixed so that it depends neither on the threads nor on the vectoriser: bond
// begin(i) + l + 8 m of node i goes to partial sum l (l < lanes = 8), and the 8 partial sums are
// added pairwise at the end (lane_sums, the per-node traversal under every per-node pass). The
// 8-bond inner loop has a fixed trip count, so GCC turns it into SIMD code (y_j gathered, vsqrtpd,
// vdivpd) -- provided sqrt need not set errno, i.e. the build uses -fno-math-errno; otherwise the
// loop stays scalar, with 8 independent partial sums.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/kernel_concepts.hpp"
#include "pd/core/parallel.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/simd/translated_families.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace pd {

// Bond work of the force pass (header). One record of components + 1 doubles per bond, (g, w), so
// that the pass streams one array; it reads and writes the records of the bonds k (i -> j) with
// j > i only, each from the thread of node i (one writer per record).
struct BondWork {
    int components = 0;                  // 1 (ordinary: g = t) or D (g = f)
    double* rec = nullptr;               // per bond: g (the previous pass's on entry, this pass's on exit), w [J/m^6 in 3D]
    const double* y_old[3] = {};         // positions of the previous pass [m]; null: store g only
    const double* volume = nullptr;      // beta V_j per bond (Bonds::volume) [m^3]
    const double* ratio = nullptr;       // per node J_C(theta_ref)/J_C(theta_i), or null [-]
    double* w_max = nullptr;             // per node, out: the largest w of its bonds with j > i (lowest double: none)
    bool hourglass = true;               // f_k with the kernel's hourglass_force, if it has one (false: without)
};

namespace detail {

inline constexpr int lanes = 8;  // bonds per SIMD group: one AVX-512 or two AVX2 registers of doubles

// `lanes` partial sums of C components, reduced pairwise in a fixed order.
template <int C>
struct LaneSum {
    double s[C][lanes] = {};
    double total(int c)
    {
        for (int w = lanes / 2; w > 0; w /= 2)
            for (int l = 0; l < w; ++l) s[c][l] += s[c][l + w];
        return s[c][0];
    }
};

// Calls bond(k, l, keep) for every bond k of [kb, ke), with its lane l and keep = intact[k] as a
// double (1 when the scene has no damage), full vectors of bonds first. The intact flags of a
// vector are read as one 8-byte word, which the vectoriser can widen (a per-byte load it cannot).
template <bool Damaged, class Bond>
inline void for_lanes(std::int64_t kb, std::int64_t ke, const std::uint8_t* intact, Bond&& bond)
{
    static_assert(lanes == sizeof(std::uint64_t));
    std::int64_t k = kb;
    for (; k + lanes <= ke; k += lanes) {
        std::uint64_t flags = 0;
        if constexpr (Damaged) std::memcpy(&flags, intact + k, lanes);
        for (int l = 0; l < lanes; ++l) {
            const int byte = std::endian::native == std::endian::little ? l : lanes - 1 - l;  // byte of bond k + l
            bond(k + l, l, Damaged ? static_cast<double>((flags >> (8 * byte)) & 0xff) : 1.0);
        }
    }
    for (int l = 0; k < ke; ++k, ++l) bond(k, l, Damaged ? static_cast<double>(intact[k]) : 1.0);
}

// THE family traversal of the per-node path: C sums over the bonds of node i, bond k = begin(i) +
// l + 8 m into partial sum l, the partial sums reduced pairwise (LaneSum). term(k, j, keep, add)
// gets bond k (partner j, keep = intact[k] as a double, 1 when not Damaged) and calls add(c, v) for
// its terms, which it has multiplied by keep where the bond is to count as broken.
template <int C, bool Damaged, class Term>
inline std::array<double, C> lane_sums(const Bonds& b, std::size_t i, Term&& term)
{
    LaneSum<C> sum;
    const int* partner = b.partner.data();
    for_lanes<Damaged>(b.offset[i], b.offset[i + 1], b.intact.data(), [&](std::int64_t k, int l, double keep) {
        term(k, partner[k], keep, [&](int c, double v) { sum.s[c][l] += v; });
    });
    std::array<double, C> S;
    for (int c = 0; c < C; ++c) S[c] = sum.total(c);
    return S;
}

// True unless the kernel is a NonOrdinaryKernel.
template <class Model>
constexpr bool is_ordinary()
{
    return !NonOrdinaryKernel<Model>;
}

// Bond work of bond k (i -> j, j > i) of the force pass (header): fk = its force density times keep
// (ordinary models: fk[0] = t, the force being t Y). Returns the bond's w.
template <int D, bool Ordinary>
inline double bond_work(const BondWork& o, std::size_t i, std::int64_t k, int j, const double* Y, const double* fk, double keep)
{
    constexpr int C = Ordinary ? 1 : D;
    double* r = o.rec + (C + 1) * k;  // g[0 .. C), then w
    if (o.y_old[0]) {
        double s = 0;
        for (int a = 0; a < D; ++a) {
            const double Yo = o.y_old[a][j] - o.y_old[a][i];
            s += (Ordinary ? r[0] * Yo + fk[0] * Y[a] : r[a] + fk[a]) * (Y[a] - Yo);
        }
        double d = 0.5 * s / o.volume[k];
        if (o.ratio) d *= 0.5 * (o.ratio[i] + o.ratio[j]);
        r[C] += keep * d;
    }
    for (int c = 0; c < C; ++c) r[c] = fk[c];
    return r[C];
}

#ifdef PD_CHUNK_WIDTH
// f of the W nodes i0 + l of a chunk for an ordinary model: sum over node i0's bonds k (partners
// j + l) of t Y, with Y = y_(j + l) - y_(i0 + l) and t = model.bond_scalar(i0, k, j, |Y|) taken in
// vchunk: the W lanes at once.
// Calls bond(k, j, Y, |Y|) for the bonds k of node i0 (partners j), Y and |Y| of the W lanes of the
// chunk (lane l: node i0 + l, partner j + l) as vectors: the one chunk traversal.
template <int D, class Bond>
void for_chunk_bonds(const Bonds& b, const Field<D>& y, int i0, Bond&& bond)
{
    vchunk yi[D];
    for (int d = 0; d < D; ++d) yi[d] = load_chunk(y.c[d].data() + i0);
    for (std::int64_t k = b.offset[i0]; k < b.offset[i0 + 1]; ++k) {
        const int j = b.partner[k];
        vchunk Y[D], len2 = {};
        for (int d = 0; d < D; ++d) {
            Y[d] = load_chunk(y.c[d].data() + j) - yi[d];
            len2 += Y[d] * Y[d];
        }
        bond(k, j, Y, sqrt_chunk(len2));
    }
}

template <int D, class Model>
void ordinary_chunk(const Model& model, const Bonds& b, int i0, const Field<D>& y, Field<D>& f)
{
    vchunk acc[D] = {};
    for_chunk_bonds(b, y, i0, [&](std::int64_t k, int j, const vchunk* Y, const vchunk& ylen) {
        const vchunk t = model.bond_scalar(static_cast<std::size_t>(i0), k, j, ylen);
        for (int d = 0; d < D; ++d) acc[d] += t * Y[d];
    });
    for (int d = 0; d < D; ++d) store_chunk(f.c[d].data() + i0, acc[d]);
}
#endif

template <bool Damaged, bool Out, int D, class Model>
void bond_pass(const Model& model, const Bonds& bonds, const Field<D>& y, Field<D>& f, const BondWork* out = nullptr)
{
    static_assert(!Out || Damaged, "the bond work is for damaged scenes (micropotential)");
    if constexpr (Out)
        if (out->components != (is_ordinary<Model>() ? 1 : D)) throw std::invalid_argument("bond_pass: BondWork components do not match the model");
    const double* y0 = y.c[0].data();
    const double* y1 = D > 1 ? y.c[1].data() : nullptr;
    const double* y2 = D > 2 ? y.c[2].data() : nullptr;
    auto node = [&](std::size_t i) {
        if constexpr (FamilyKernel<Model, D>) {
            const Vec<D> fi = model.template family_force<Damaged, Out>(i, bonds, y, out);
            for (int d = 0; d < D; ++d) f.c[d][i] = fi[d];
        } else {
            double w_max = std::numeric_limits<double>::lowest();  // Out: over the bonds with j > i
            const double yi0 = y0[i], yi1 = D > 1 ? y1[i] : 0, yi2 = D > 2 ? y2[i] : 0;
            const std::array<double, D> sum = lane_sums<D, Damaged>(bonds, i, [&](std::int64_t k, int j, double keep, auto&& add) {
                const double Y0 = y0[j] - yi0;
                const double Y1 = D > 1 ? y1[j] - yi1 : 0;
                const double Y2 = D > 2 ? y2[j] - yi2 : 0;
                if constexpr (is_ordinary<Model>()) {
                    double ylen = std::sqrt(Y0 * Y0 + Y1 * Y1 + Y2 * Y2);  // |Y| [m]
                    // A broken bond is zeroed by the factor keep; lengthening it by 1 m first keeps a
                    // broken bond of zero length from giving inf * 0 = NaN (no effect on intact bonds).
                    if constexpr (Damaged) ylen += 1.0 - keep;
                    double t = model.bond_scalar(i, k, j, ylen);
                    if constexpr (Damaged) t *= keep;
                    if constexpr (Out)
                        if (static_cast<std::size_t>(j) > i) {
                            const double Yk[3] = {Y0, Y1, Y2};
                            w_max = std::max(w_max, bond_work<D, true>(*out, i, k, j, Yk, &t, keep));
                        }
                    add(0, t * Y0);
                    if constexpr (D > 1) add(1, t * Y1);
                    if constexpr (D > 2) add(2, t * Y2);
                } else {
                    Vec<D> Y;
                    Y[0] = Y0;
                    if constexpr (D > 1) Y[1] = Y1;
                    if constexpr (D > 2) Y[2] = Y2;
                    Vec<D> fk = model.bond_force(i, k, j, Y);  // must be finite for broken bonds too
                    if constexpr (Damaged) fk *= keep;
                    for (int d = 0; d < D; ++d) add(d, fk[d]);
                    if constexpr (Out)
                        if (static_cast<std::size_t>(j) > i) {
                            if constexpr (NodeTermKernel<Model>) fk += keep * model.node_share(i, k, j);
                            if constexpr (HourglassKernel<Model, D>)
                                if (!out->hourglass) fk -= keep * model.hourglass_force(i, k, j, Y);
                            w_max = std::max(w_max, bond_work<D, false>(*out, i, k, j, Y.c.data(), fk.c.data(), keep));
                        }
                }
            });
            if constexpr (NodeTermKernel<Model>) {
                const Vec<D> fn = model.node_force(i);
                for (int d = 0; d < D; ++d) f.c[d][i] = sum[d] + fn[d];
            } else {
                for (int d = 0; d < D; ++d) f.c[d][i] = sum[d];
            }
            if constexpr (Out) out->w_max[i] = w_max;
        }
    };
    // Chunks of translated families (translated_families.hpp), undamaged scenes only: W nodes per call.
    if constexpr (!Damaged && ChunkRunKernel<Model, D>) {
        if (const TranslatedRuns* runs = model.chunks(bonds))
            if (for_runs_then_rest(*runs, bonds, [&](std::size_t p) { model.run_force(static_cast<int>(p), bonds, y, f); }, node)) return;
    }
#ifdef PD_CHUNK_WIDTH
    if constexpr (!Damaged && is_ordinary<Model>() && OrdinaryChunkKernel<Model>) {
        static_assert(!NodeTermKernel<Model>, "ordinary chunk kernels have no node term");
        if (const TranslatedRuns* runs = model.chunks(bonds))
            if (for_chunks_then_rest(*runs, bonds, [&](std::size_t q) { ordinary_chunk(model, bonds, runs->chunk_start[q], y, f); }, node)) return;
    }
#endif
    parallel_for(bonds.nodes(), node);
}
}  // namespace detail

// Bookkeeping sums (energy densities): per node i, in parallel, the sum over its intact bonds k, in
// family order, of term(i, k); then finish(i, sum) gives node i's value.
template <class Term, class Finish>
std::vector<double> node_sums(const Bonds& b, Term&& term, Finish&& finish)
{
    std::vector<double> out(b.nodes(), 0.0);
    parallel_for(b.nodes(), [&](std::size_t i) {
        double sum = 0;
        for_intact_bonds(b, i, [&](std::int64_t k, int) { sum += term(i, k); });
        out[i] = finish(i, sum);
    });
    return out;
}

// No per-sum weights for stretch_sums: its one sum adds x itself.
struct Unweighted {};

// Point-pass sums over the deformed bond lengths (LPS dilatation, PALS theta and p): per node i,
//   S_c = sum over the intact bonds k of i of  w(k)[c] x(k, |Y_k|)    (c < C; Unweighted: C = 1, S = sum x)
// handed to done(i, S) as a std::array<double, C>. x is written once, generic in |Y|: double for the
// per-node path (the bond loop's lanes and order; a broken bond's x is multiplied by intact = 0),
// detail::vchunk for the chunk path (undamaged scenes, nodes of the runs' chunks, W at a time, each
// lane in family order; node i0's bonds stand for the chunk's).
template <int C, int D, class X, class W, class Done>
void stretch_sums(const Bonds& b, const Field<D>& y, const TranslatedRuns& runs, X&& x, W&& w, Done&& done)
{
    constexpr bool unweighted = std::is_same_v<std::decay_t<W>, Unweighted>;
    static_assert(!unweighted || C == 1, "stretch_sums: several sums need weights");
    const double* yc[3] = {y.c[0].data(), D > 1 ? y.c[1].data() : nullptr, D > 2 ? y.c[2].data() : nullptr};
    auto node = [&](std::size_t i, auto damaged) {
        done(i, detail::lane_sums<C, decltype(damaged)::value>(b, i, [&](std::int64_t k, int j, double keep, auto&& add) {
            const double Y0 = yc[0][j] - yc[0][i];
            const double Y1 = D > 1 ? yc[1][j] - yc[1][i] : 0;
            const double Y2 = D > 2 ? yc[2][j] - yc[2][i] : 0;
            double v = x(k, std::sqrt(Y0 * Y0 + Y1 * Y1 + Y2 * Y2));
            if constexpr (decltype(damaged)::value) v *= keep;
            if constexpr (unweighted) add(0, v);
            else {
                const std::array<double, C> wk = w(k);
                for (int c = 0; c < C; ++c) add(c, wk[c] * v);
            }
        }));
    };
    if (b.has_damage()) return parallel_for(b.nodes(), [&](std::size_t i) { node(i, std::true_type{}); });
    auto plain = [&](std::size_t i) { node(i, std::false_type{}); };
#ifdef PD_CHUNK_WIDTH
    auto chunk = [&](std::size_t q) {
        const int i0 = runs.chunk_start[q];
        detail::vchunk acc[C] = {};
        detail::for_chunk_bonds(b, y, i0, [&](std::int64_t k, int, const detail::vchunk*, const detail::vchunk& ylen) {
            const detail::vchunk v = x(k, ylen);
            if constexpr (unweighted) acc[0] += v;
            else {
                const std::array<double, C> wk = w(k);
                for (int c = 0; c < C; ++c) acc[c] += wk[c] * v;
            }
        });
        for (int l = 0; l < detail::chunk_width; ++l) {
            std::array<double, C> S;
            for (int c = 0; c < C; ++c) S[c] = acc[c][l];
            done(static_cast<std::size_t>(i0 + l), S);
        }
    };
    if (for_chunks_then_rest(runs, b, chunk, plain)) return;
#endif
    parallel_for(b.nodes(), plain);
}

// Calls pass(kernel) with the model's kernel (KernelProvider[ForBonds], kernel_concepts.hpp), or
// with the model itself when it is its own kernel.
template <class Model, class Pass>
void with_model_kernel(const Model& model, const Bonds& bonds, Pass&& pass)
{
    using P = std::remove_reference_t<Pass>;
    if constexpr (KernelProviderForBonds<Model, P>) model.with_kernel(pass, bonds);
    else if constexpr (KernelProvider<Model, P>) model.with_kernel(pass);
    else pass(model);
}

// The bond pass alone, with the model's state of its last point pass: f [N/m^3] and, when work is
// given (damaged scenes only), the bond work of the pass (header).
template <int D, class Model>
void bond_forces(const Model& model, const Bonds& bonds, const Field<D>& y, Field<D>& f, const BondWork* out = nullptr)
{
    if (f.size() != y.size()) f.resize(y.size());
    if (out && !bonds.has_damage()) throw std::invalid_argument("bond_forces: the bond work needs bonds.enable_damage()");
    auto pass = [&](const auto& kernel) {
        if (out)
            detail::bond_pass<true, true>(kernel, bonds, y, f, out);
        else if (bonds.has_damage())
            detail::bond_pass<true, false>(kernel, bonds, y, f);
        else
            detail::bond_pass<false, false>(kernel, bonds, y, f);
    };
    with_model_kernel(model, bonds, pass);
}

// The hourglass part of the internal force density [N/m^3]: the kernel's hourglass_force (a
// HourglassKernel, kernel_concepts.hpp) summed over the intact bonds of each node by the per-node pass,
// with the model's state of its last point pass, into *f (null: only whether there is one). Returns
// false, f untouched, when the model's kernel has none (no hourglass control, or C_hg = 0). The
// hourglass force is no gradient of an energy, so the energy books integrate its work from this force
// (time/verlet.hpp).
namespace detail {
// The hourglass term of kernel k alone, as a non-ordinary kernel of the per-node bond pass (its lanes).
template <class K, int D>
struct HourglassPart {
    static constexpr bool ordinary = false;
    const K& k;
    Vec<D> bond_force(std::size_t i, std::int64_t b, int j, const Vec<D>& Y) const { return k.hourglass_force(i, b, j, Y); }
};
}  // namespace detail

template <int D, class Model>
bool hourglass_forces(const Model& model, const Bonds& bonds, const Field<D>& y, Field<D>* f)
{
    bool found = false;
    with_model_kernel(model, bonds, [&](const auto& kernel) {
        using K = std::decay_t<decltype(kernel)>;
        if constexpr (HourglassKernel<K, D>) {
            found = true;
            if (!f) return;
            if constexpr (requires { model.sync_node_matrices(); }) model.sync_node_matrices();  // F of every node
            if (f->size() != y.size()) f->resize(y.size());
            const detail::HourglassPart<K, D> part{kernel};
            if (bonds.has_damage()) detail::bond_pass<true, false>(part, bonds, y, *f);
            else detail::bond_pass<false, false>(part, bonds, y, *f);
        }
    });
    return found;
}

// f: internal force density at current positions y [N/m^3]; out: optional bond work (header).
template <int D, class Model>
void internal_force(Model& model, const Bonds& bonds, const Field<D>& y, Field<D>& f, const BondWork* out = nullptr)
{
    if (f.size() != y.size()) f.resize(y.size());
    if constexpr (Model::has_point_pass) model.point_pass(bonds, y);
    bond_forces(model, bonds, y, f, out);
}

// A HistoryModel (kernel_concepts.hpp): f at y with the trial state over the step dt [s] from the
// committed history.
template <int D, class Model>
    requires HistoryModel<Model, D>
void internal_force(Model& model, const Bonds& bonds, const Field<D>& y, double dt, Field<D>& f, const BondWork* out = nullptr)
{
    if (f.size() != y.size()) f.resize(y.size());
    model.point_pass(bonds, y, dt);
    bond_forces(model, bonds, y, f, out);
}

}  // namespace pd
