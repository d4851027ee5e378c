// The optimised correspondence force (lane sums, i-end term once per node, vectorised bond kernel
// with the hourglass term compiled in) against a straightforward evaluation written here from the
// textbook formulas (spec/000b sec. 1.5, 1.6, erratum 1 and 4), with plain loops over the bonds:
//   K_i = sum omega xi (x) xi V_j,  F_i = (sum omega Y (x) xi V_j) K_i^-1,  P_i from the law,
//   f_i = sum_j [omega V_j (P_i K_i^-1 + P_j K_j^-1) xi
//               + C_hg c V_j/|xi| ((2Y - (F_i + F_j) xi).Y/|Y|^2) Y],   c = 18 K/(pi delta^4),
// over intact bonds only (HourglassDirection::bond, Peridigm's form: |Y| in place of |Y|^2). It calls nothing of the model: the reference uses Eigen, the bonds and
// the positions, so an error in the restructured sums or in the kernel split shows up here.
#include "pd/bond_loop.hpp"
#include "pd/models/correspondence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

using namespace pd;

namespace {
using M3 = Eigen::Matrix3d;
using V3 = Eigen::Vector3d;

constexpr double dx = 1e-3;        // lattice spacing [m]
constexpr double m_ratio = 3.05;   // delta / dx

enum class RefLaw { linear, svk };

// Textbook force density [N/m^3] at every node; scale[i] = sum of the magnitudes of the bond terms
// of node i (the size round-off is relative to).
std::vector<V3> reference_force(const Body<3>& body, const Bonds& b, const Field<3>& y, const Elastic& mat, RefLaw law,
                                double C_hg, HourglassDirection dir, std::vector<double>& scale)
{
    const std::size_t n = body.size();
    const double lambda = mat.K - 2 * mat.G / 3;
    const double c = 18 * mat.K / (std::numbers::pi * std::pow(b.delta, 4));  // PMB micromodulus, 3D
    auto xi_of = [&](std::size_t i, int j) { return V3(body.x.c[0][j] - body.x.c[0][i], body.x.c[1][j] - body.x.c[1][i], body.x.c[2][j] - body.x.c[2][i]); };
    auto Y_of = [&](std::size_t i, int j) { return V3(y.c[0][j] - y.c[0][i], y.c[1][j] - y.c[1][i], y.c[2][j] - y.c[2][i]); };
    auto intact = [&](std::int64_t k) { return !b.has_damage() || b.intact[k]; };
    std::vector<M3> F(n), A(n);
    for (std::size_t i = 0; i < n; ++i) {
        M3 K = M3::Zero(), N = M3::Zero();
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const V3 xi = xi_of(i, b.partner[k]);
            K += b.omega[k] * b.volume[k] * xi * xi.transpose();
            N += b.omega[k] * b.volume[k] * Y_of(i, b.partner[k]) * xi.transpose();
        }
        const M3 Kinv = K.inverse();
        F[i] = N * Kinv;
        M3 P;
        if (law == RefLaw::linear) {
            const M3 eps = 0.5 * (F[i] + F[i].transpose()) - M3::Identity();
            P = lambda * eps.trace() * M3::Identity() + 2 * mat.G * eps;
        } else {
            const M3 E = 0.5 * (F[i].transpose() * F[i] - M3::Identity());
            P = F[i] * (lambda * E.trace() * M3::Identity() + 2 * mat.G * E);
        }
        A[i] = P * Kinv;
    }
    std::vector<V3> f(n, V3::Zero());
    scale.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const int j = b.partner[k];
            const V3 xi = xi_of(i, j), Y = Y_of(i, j);
            const V3 elastic = b.omega[k] * b.volume[k] * (A[i] * xi + A[j] * xi);
            const double den = dir == HourglassDirection::unit ? Y.squaredNorm() : Y.norm();
            const V3 hourglass = C_hg * c * b.volume[k] / xi.norm() * (2 * Y - F[i] * xi - F[j] * xi).dot(Y) / den * Y;
            f[i] += elastic + hourglass;
            scale[i] += b.omega[k] * b.volume[k] * ((A[i] * xi).norm() + (A[j] * xi).norm()) + hourglass.norm()
                        + C_hg * c * b.volume[k] / xi.norm() * 2 * Y.squaredNorm() / den * Y.norm();
        }
    return f;
}

// Random non-affine deformation of the lattice: finite affine part plus nodal noise (2 % of dx), so
// the hourglass term is not zero.
// max |g - f| over all nodes and components, relative to max |f|.
double relative_max_difference(const Field<3>& g, const Field<3>& f)
{
    double diff = 0, scale = 0;
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < f.size(); ++i) {
            diff = std::max(diff, std::abs(g.c[d][i] - f.c[d][i]));
            scale = std::max(scale, std::abs(f.c[d][i]));
        }
    return diff / scale;
}

Field<3> random_deformation(const Body<3>& body, unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    M3 G;
    for (int a = 0; a < 3; ++a) for (int c = 0; c < 3; ++c) G(a, c) = (a == c) + 0.05 * U(gen);
    Field<3> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) {
        const V3 x(body.x.c[0][i], body.x.c[1][i], body.x.c[2][i]);
        const V3 yi = G * x;
        for (int d = 0; d < 3; ++d) y.c[d][i] = yi(d) + 2e-5 * U(gen);  // noise [m]
    }
    return y;
}

// The model's force against the textbook one, C_hg = 0.02, linear and Saint Venant-Kirchhoff laws,
// both hourglass directions. Tolerance: the two evaluations sum the same ~100 terms per node in
// different orders and groupings (lane or chunk sums, i-end term factored out), each term with
// relative round-off ~1e-15, so they agree to ~1e-14 of the sum of term magnitudes; 1e-12 leaves
// margin and is far below any formula error (a wrong sign or a missing term changes f by O(1) of that
// scale). The hourglass part must stand well above that bound for the comparison to test it: 1e-3 of
// the scale along Y/|Y|; along Y it is |Y| ~ 1e-3 m times smaller in SI, so 1e-6 (still 1e6 times
// the tolerance).
void expect_textbook_force(const Body<3>& body, const Bonds& b, const Field<3>& y)
{
    const Elastic steel = Elastic::from_E_nu(200e9, 0.3);
    using C3 = Correspondence<3>;
    for (HourglassDirection dir : {HourglassDirection::unit, HourglassDirection::bond})
        for (RefLaw law : {RefLaw::linear, RefLaw::svk}) {
            const C3::Law model_law = law == RefLaw::linear ? C3::Law::linear : C3::Law::saint_venant_kirchhoff;
            C3 model({.material = steel, .law = model_law, .C_hg = 0.02, .hourglass_direction = dir}, body, b);
            Field<3> f;
            internal_force(model, b, y, f);
            std::vector<double> scale;
            const std::vector<V3> ref = reference_force(body, b, y, steel, law, 0.02, dir, scale);
            double worst = 0, hg_part = 0;
            for (std::size_t i = 0; i < body.size(); ++i)
                for (int d = 0; d < 3; ++d) {
                    ASSERT_TRUE(std::isfinite(f.c[d][i]));
                    worst = std::max(worst, std::abs(f.c[d][i] - ref[i](d)) / scale[i]);
                }
            // The hourglass term matters in this deformation: without it the force changes (header).
            C3 plain({steel, model_law}, body, b);
            Field<3> f0;
            internal_force(plain, b, y, f0);
            double worst0 = 0;
            std::vector<double> scale0;
            const std::vector<V3> ref0 = reference_force(body, b, y, steel, law, 0, dir, scale0);
            for (std::size_t i = 0; i < body.size(); ++i)
                for (int d = 0; d < 3; ++d) {
                    hg_part = std::max(hg_part, std::abs(f.c[d][i] - f0.c[d][i]) / scale[i]);
                    worst0 = std::max(worst0, std::abs(f0.c[d][i] - ref0[i](d)) / scale0[i]);
                }
            std::printf("direction %d, law %d: max abs(f - f_ref)/scale = %.2e (C_hg = 0: %.2e), max hourglass part/scale = %.2e\n",
                        int(dir), int(law), worst, worst0, hg_part);
            EXPECT_LT(worst, 1e-12) << "direction " << int(dir) << ", law " << int(law);
            EXPECT_LT(worst0, 1e-12) << "law " << int(law);
            EXPECT_GT(hg_part, dir == HourglassDirection::unit ? 1e-3 : 1e-6) << "direction " << int(dir) << ", law " << int(law);
        }
}
}  // namespace

// Every 7th bond pair broken (the per-node code with damage).
TEST(CorrespondenceReference, OptimisedForceEqualsTextbookFormulaWithDamageAndHourglass)
{
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 6 * dx, 5 * dx}}, dx);
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(k);
    expect_textbook_force(body, b, random_deformation(body, 17));
}

// Undamaged lattice with x-rows of 24 nodes: the nodes 3 .. 20 of a row have translated families,
// so the chunk kernels (translated_families.hpp, correspondence_chunks.hpp) take most nodes and the
// per-node code the rest; both must give the textbook force.
TEST(CorrespondenceReference, ChunkedForceEqualsTextbookFormula)
{
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 5 * dx, 4 * dx}}, dx);
    const Bonds b = build_bonds(body, m_ratio * dx);
    const Correspondence<3> probe({Elastic::from_E_nu(200e9, 0.3)}, body, b);
#ifdef PD_CHUNK_WIDTH
    // 5 x 4 rows of 18 translated nodes each: 16 of them in chunks of 8 (AVX-512) or 4 (AVX2).
    const std::size_t rows = 5 * 4, per_row = 18 / detail::chunk_width * detail::chunk_width;
    EXPECT_EQ(probe.runs.chunked_nodes(), rows * per_row);
    EXPECT_EQ(probe.runs.rest.size(), body.size() - rows * per_row);
#else
    EXPECT_EQ(probe.runs.chunked_nodes(), 0u);
#endif
    expect_textbook_force(body, b, random_deformation(body, 23));
}

// The bond pass alone after damage bookkeeping is switched on (bond_loop.hpp bond_forces: the state
// of the last point pass): the per-node kernels then read every node's block, also those the chunk
// path wrote. With every bond intact the force must be the undamaged one.
TEST(CorrespondenceReference, BondPassAfterEnablingDamageUsesTheChunkedPointPass)
{
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 5 * dx, 4 * dx}}, dx);
    Bonds b = build_bonds(body, m_ratio * dx);
    Correspondence<3> model({Elastic::from_E_nu(200e9, 0.3), Correspondence<3>::Law::linear, 0.02}, body, b);
    const Field<3> y = random_deformation(body, 29);
    Field<3> f, g;
    internal_force(model, b, y, f);  // undamaged: chunks
    b.enable_damage();
    bond_forces(model, b, y, g);     // damaged path, no point pass
    EXPECT_LT(relative_max_difference(g, f), 1e-12);  // round-off of the two summation orders
}

// Params::node_matrices = false: the chunked point pass leaves F, sigma, P and P K^-1 of chunk
// nodes in its own arrays. The forces must not change, sync_node_matrices must give the values the
// default pass stores (the same operations, so equal to round-off), and everything that reads
// them (the public bond_force, from parallel code too, energy_density, a damaged bond pass) must
// see the current values. Each reader follows a lean pass at a new deformation, so that matrices
// left from an earlier sync are stale; 24 x 10 x 10 nodes, above parallel_min_nodes.
TEST(CorrespondenceReference, NodeMatricesOffGivesTheSameForcesAndMatrices)
{
    using C3 = Correspondence<3>;
    auto body = box<3>({{0, 0, 0}}, {{24 * dx, 10 * dx, 10 * dx}}, dx);
    ASSERT_GE(static_cast<long>(body.size()), parallel_min_nodes);
    Bonds b = build_bonds(body, m_ratio * dx);
    C3::Params p{Elastic::from_E_nu(200e9, 0.3), C3::Law::linear, 0.02};
    C3 full(p, body, b);
    p.node_matrices = false;
    C3 lean(p, body, b);
    Field<3> f_full, f_lean;
    auto both_at = [&](const Field<3>& y) {  // point and bond pass of both models; forces equal
        internal_force(full, b, y, f_full);
        internal_force(lean, b, y, f_lean);
        for (int d = 0; d < 3; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) ASSERT_EQ(f_lean.c[d][i], f_full.c[d][i]) << "node " << i;
    };
    const Field<3> y1 = random_deformation(body, 31), y2 = random_deformation(body, 37), y3 = random_deformation(body, 41);
    both_at(y1);
#ifdef PD_CHUNK_WIDTH
    ASSERT_TRUE(lean.matrices_partial);
    std::size_t i0 = 0;  // a chunk node whose matrices the pass skipped (not read by a per-node kernel)
    for (int s : lean.runs.chunk_start)
        for (int l = 0; l < detail::chunk_width; ++l)
            if (!lean.block_read[s + l]) i0 = static_cast<std::size_t>(s + l);
    ASSERT_FALSE(lean.block_read[i0]);
    EXPECT_TRUE(lean.F[i0].isIdentity(0)) << "not skipped: the test would prove nothing";
    // The public per-bond force (bond loops of wrappers) fills them in first, from parallel code too.
    Field<3> fb_full(body.size()), fb_lean(body.size());
    parallel_for(body.size(), [&](std::size_t i) {
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            const Vec<3> Y{y1.c[0][j] - y1.c[0][i], y1.c[1][j] - y1.c[1][i], y1.c[2][j] - y1.c[2][i]};
            const Vec<3> a = full.bond_force(i, k, j, Y), c = lean.bond_force(i, k, j, Y);
            for (int d = 0; d < 3; ++d) { fb_full.c[d][i] += a[d]; fb_lean.c[d][i] += c[d]; }
        }
    });
    EXPECT_FALSE(lean.matrices_partial);
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < body.size(); ++i) ASSERT_EQ(fb_lean.c[d][i], fb_full.c[d][i]) << "node " << i;
#endif
    both_at(y2);  // the matrices now hold y1's values
    const std::vector<double> W_full = full.energy_density(b, y2), W_lean = lean.energy_density(b, y2);  // syncs
    double scale = 0;
    for (std::size_t i = 0; i < body.size(); ++i) scale = std::max(scale, full.sigma[i].cwiseAbs().maxCoeff());
    // sigma: the sync repeats the chunk's operations (laws::small_strain_stress), equal unless the compiler
    // contracts a multiply-add differently in the scalar and the vector code, i.e. to one rounding
    // of |sigma| (1e-15 of its largest entry); W = 1/2 sigma : eps follows it (relative 1e-14, and
    // an absolute 1e-300 for a node with W = 0).
    for (std::size_t i = 0; i < body.size(); ++i) {
        ASSERT_EQ(lean.F[i], full.F[i]) << "node " << i;
        ASSERT_EQ(lean.PKinv[i], full.PKinv[i]) << "node " << i;
        ASSERT_LE((lean.sigma[i] - full.sigma[i]).cwiseAbs().maxCoeff(), 1e-15 * scale) << "node " << i;
        ASSERT_EQ(lean.P[i], lean.sigma[i]) << "node " << i;
        ASSERT_NEAR(W_lean[i], W_full[i], 1e-14 * std::abs(W_full[i]) + 1e-300) << "node " << i;
    }
    // A damaged bond pass right after a lean point pass completes the per-node blocks from them.
    both_at(y3);  // the matrices now hold y2's values
    b.enable_damage();
    Field<3> g;
    bond_forces(lean, b, y3, g);
    EXPECT_LT(relative_max_difference(g, f_full), 1e-12);  // round-off of the two summation orders
}
