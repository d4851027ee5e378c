// Chunks of translated families (translated_families.hpp) and the chunk kernels of PMB, LPS and PALS
// (bond_loop.hpp, chunk_vector.hpp). The run finder is checked on lattices whose rows are known;
// the chunked forces against (a) a pair-force loop written here from the PMB formula and (b) the
// per-node code of the same model on the same bonds with damage bookkeeping on and every bond
// intact, which never takes the chunk path. (Correspondence: test_correspondence_reference.cpp.)
#include "pd/bond_loop.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/simd/translated_families.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pd;

namespace {
constexpr double dx = 1e-3;

// Lattice with x-rows of nx nodes, positions y = x + a random field of amplitude 2 % of dx plus a
// 1e-3 stretch along x.
template <int D>
Field<D> random_positions(const Body<D>& body, unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    Field<D> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int d = 0; d < D; ++d) y.c[d][i] += (d == 0 ? 1e-3 * body.x.c[0][i] : 0.0) + 0.02 * dx * U(gen);
    return y;
}

// max_i |f_i - g_i| / max_i |g_i| over all components.
template <int D>
double relative_difference(const Field<D>& f, const Field<D>& g)
{
    double diff = 0, scale = 0;
    for (int d = 0; d < D; ++d)
        for (std::size_t i = 0; i < f.size(); ++i) {
            diff = std::max(diff, std::abs(f.c[d][i] - g.c[d][i]));
            scale = std::max(scale, std::abs(g.c[d][i]));
        }
    return diff / scale;
}

// The same model built on a copy of the bonds with damage bookkeeping on (no chunks).
template <class Model, int D, class Make>
void expect_chunked_equals_per_node(const Body<D>& body, const Bonds& b, Make make, std::size_t expected_chunked)
{
    Bonds plain = b;
    plain.enable_damage();
    Model chunked = make(b), per_node = make(plain);
    EXPECT_TRUE(chunked.runs.fits(b) || expected_chunked == 0);
    EXPECT_EQ(chunked.runs.chunked_nodes(), expected_chunked);
    const Field<D> y = random_positions(body, 5);
    Field<D> f, g;
    internal_force(chunked, b, y, f);
    internal_force(per_node, plain, y, g);
    // Same terms, summed in another order, with node i0's |xi| (equal to an ulp) for the whole
    // chunk: round-off only, ~1e-15 of the largest force; 1e-12 leaves margin, and a wrong lane or
    // partner changes f by O(1).
    EXPECT_LT(relative_difference(f, g), 1e-12);
}

// Chunks of W nodes per row: `translated` nodes of each of `rows` rows have translated families.
std::size_t chunked_nodes(std::size_t rows, std::size_t translated)
{
#ifdef PD_CHUNK_WIDTH
    return rows * (translated / detail::chunk_width * detail::chunk_width);
#else
    (void)rows;
    (void)translated;
    return 0;
#endif
}
}  // namespace

// 30 x 4 x 3 lattice, delta = 3 dx: nodes 3 .. 26 of every row (24 of 30) translate node 3's family.
TEST(TranslatedRuns, RowsOfALatticeAndWhatBreaksThem)
{
    auto body = box<3>({{0, 0, 0}}, {{30 * dx, 4 * dx, 3 * dx}}, dx);
    const Bonds b = build_bonds(body, 3 * dx);
    const TranslatedRuns runs = find_translated_runs(b, 8, {&b.length}, {&body.x.c[0], &body.x.c[1], &body.x.c[2]});
    EXPECT_EQ(runs.chunked_nodes(), 12u * 24u);
    EXPECT_EQ(runs.chunked_nodes() + runs.rest.size(), body.size());
    EXPECT_TRUE(runs.fits(b));
    // Every chunk holds W translates of its first node: same family size, partners shifted by l.
    for (int i0 : runs.chunk_start)
        for (int l = 1; l < 8; ++l) {
            ASSERT_EQ(b.end(i0 + l) - b.begin(i0 + l), b.end(i0) - b.begin(i0));
            for (std::int64_t r = 0; r < b.end(i0) - b.begin(i0); ++r) ASSERT_EQ(b.partner[b.begin(i0 + l) + r], b.partner[b.begin(i0) + r] + l);
        }
    // A per-bond value that differs beyond the tolerance takes its node out of its run.
    std::vector<double> coef(b.size(), 1.0);
    coef[b.begin(runs.chunk_start[0] + 3)] = 1 + 1e-9;
    const TranslatedRuns cut = find_translated_runs(b, 8, {&coef});
    EXPECT_LT(cut.chunked_nodes(), runs.chunked_nodes());
    // Irregular positions: the bond vectors differ, no node translates another.
    Field<3> moved = body.x;
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> U(-1, 1);
    for (auto& c : moved.c) for (double& v : c) v += 1e-3 * dx * U(gen);
    EXPECT_EQ(find_translated_runs(b, 8, {}, {&moved.c[0], &moved.c[1], &moved.c[2]}).chunked_nodes(), 0u);
}

// PMB: chunked force against the pair force written out, f_i = sum_j c omega V_j s Y/|Y|.
TEST(TranslatedRuns, PMBChunkedForceEqualsPairForceFormula)
{
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 4 * dx, 3 * dx}}, dx);
    const Bonds b = build_bonds(body, 3.05 * dx);
    const PMB pmb({Elastic::from_E_nu(100e9, 0.25)}, b);
    const Field<3> y = random_positions(body, 9);
    Field<3> f, ref(body.size());
    internal_force(pmb, b, y, f);
    for (std::size_t i = 0; i < body.size(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const Vec<3> Y = y[b.partner[k]] - y[i];
            const double L = b.length[k], s = (norm(Y) - L) / L;
            ref.add(i, (pmb.c * b.omega[k] * b.volume[k] * s / norm(Y)) * Y);
        }
    EXPECT_LT(relative_difference(f, ref), 1e-12);
    expect_chunked_equals_per_node<PMB>(body, b, [](const Bonds& bb) { return PMB({Elastic::from_E_nu(100e9, 0.25)}, bb); },
                                        chunked_nodes(12, 18));
}

// LPS in 3D (both passes chunked), with SCF, and in 2D; PALS (3D only).
TEST(TranslatedRuns, LPSAndPALSChunkedForceEqualsPerNodeCode)
{
    const Elastic mat = Elastic::from_E_nu(100e9, 0.33);
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 4 * dx, 3 * dx}}, dx);
    const Bonds b = build_bonds(body, 3.05 * dx);
    expect_chunked_equals_per_node<LPS>(body, b, [&](const Bonds& bb) { return LPS({.material = mat, .dim = 3}, bb); }, chunked_nodes(12, 18));
    expect_chunked_equals_per_node<LPS>(body, b, [&](const Bonds& bb) {
        LPS lps({.material = mat, .dim = 3}, bb);
        lps.apply_shear_correction(body.x);
        return lps;
    }, chunked_nodes(12, 18));
    // PALS's w_j, s_j hold the partner's multipliers, so the partners' families must translate too:
    // nodes 6 .. 17 of a row (two horizons from its ends).
    expect_chunked_equals_per_node<PALS>(body, b, [&](const Bonds& bb) { return PALS({.material = mat}, body, bb); }, chunked_nodes(12, 12));
    auto plate = box<2>({{0, 0}}, {{40 * dx, 5 * dx}}, dx);
    const Bonds b2 = build_bonds(plate, 3.05 * dx);
    expect_chunked_equals_per_node<LPS>(plate, b2, [&](const Bonds& bb) { return LPS({.material = mat, .dim = 2}, bb); }, chunked_nodes(5, 34));
}

// Bond factors that break the translation (scale_bonds: surface correction, random modulus) must
// refresh the runs: with stale runs a chunk would apply its first node's coefficients to all lanes.
// A copy of the bonds is not the object the runs were found on: no chunks, same forces.
TEST(TranslatedRuns, ScaledBondsAndCopiedBondsKeepTheForces)
{
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 4 * dx, 3 * dx}}, dx);
    const Bonds b = build_bonds(body, 3.05 * dx);
    std::vector<double> factor(b.size());
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            factor[k] = 1 + 0.2 * std::sin(0.7 * std::min<int>(i, j) + 1.3 * std::max<int>(i, j));  // symmetric in i, j
        }
    const Field<3> y = random_positions(body, 13);
    Bonds plain = b;
    plain.enable_damage();
    auto compare = [&](auto model, auto per_node) {
        const std::size_t before = model.runs.chunked_nodes();
        model.scale_bonds(factor);
        per_node.scale_bonds(factor);
        EXPECT_LT(model.runs.chunked_nodes(), before + 1);  // refreshed: a random factor leaves few translates
        Field<3> f, g, h;
        internal_force(model, b, y, f);
        internal_force(per_node, plain, y, g);
        EXPECT_LT(relative_difference(f, g), 1e-12);
        const Bonds copy = b;  // same content, another object: the runs do not fit it
        EXPECT_FALSE(model.runs.fits(copy));
        internal_force(model, copy, y, h);
        EXPECT_LT(relative_difference(h, g), 1e-12);
    };
    const PMB::Params pp{Elastic::from_E_nu(100e9, 0.25)};
    compare(PMB(pp, b), PMB(pp, plain));
    const Elastic mat = Elastic::from_E_nu(100e9, 0.33);
    compare(LPS({.material = mat, .dim = 3}, b), LPS({.material = mat, .dim = 3}, plain));
}
