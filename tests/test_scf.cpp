// Shear correction factor (models/scf.hpp; spec/000b sec. 1.3, V12); LPS with SCF: test_lps_scf.cpp.
// References: lattice sums over integer offsets written out in scf_fixtures.hpp, and Gauss-Legendre
// quadrature of N over a continuum ball/disc; neither calls the code under test.
#include "pd/bond_loop.hpp"
#include "pd/models/scf.hpp"

#include <gtest/gtest.h>

#include "scf_fixtures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

using namespace pd;
using namespace pd_test::scf_fixtures;
constexpr double pi = std::numbers::pi;

namespace {
// Gauss-Legendre nodes and weights on [lo, hi] (Newton on P_n; exact for degree 2n - 1).
std::vector<std::array<double, 2>> gauss(int n, double lo, double hi)
{
    std::vector<std::array<double, 2>> q;
    for (int i = 1; i <= n; ++i) {
        double z = std::cos(pi * (i - 0.25) / (n + 0.5)), dp = 0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = z;
            for (int k = 2; k <= n; ++k) { const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k; p0 = p1; p1 = p2; }
            dp = n * (z * p1 - p0) / (z * z - 1);
            const double dz = p1 / dp;
            z -= dz;
            if (std::abs(dz) < 1e-16) break;
        }
        q.push_back({0.5 * (lo + hi) + 0.5 * (hi - lo) * z, (hi - lo) / ((1 - z * z) * dp * dp)});
    }
    return q;
}
}  // namespace

// V12: bulk SCF on the cubic lattice with full volumes is 0.9008 for delta = 3 dx and 3.05 dx.
// Both horizons hold the same 122 neighbours (no |n|^2 in (9, 9.3025]), hence "m-independent";
// the exact lattice value is 118/131 = 0.900763. Tolerance 1e-5: the probe's e = |Y| - |xi| is
// nonlinear in gamma = 1e-6 (relative O(gamma)); everything else is round-off.
TEST(SCF, BulkCubicLatticeMatchesV12)
{
    const double dx = 1e-3;
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 7 * dx, 7 * dx}}, dx);
    const int mid = 3 + 3 * 7 + 3 * 49;
    const double ref = lattice_scf<3>();
    EXPECT_NEAR(ref, 118.0 / 131.0, 1e-14);
    double first = 0;
    for (double m : {3.0, 3.05}) {
        Bonds b = build_bonds(body, m * dx);
        ASSERT_EQ(b.end(mid) - b.begin(mid), 122);
        const auto scf = shear_correction_factor(b, body.x, 3);
        EXPECT_NEAR(scf[mid] / ref, 1.0, 1e-5) << "m = " << m;
        EXPECT_NEAR(scf[mid], 0.9008, 5e-5) << "m = " << m;  // the 4 digits of V12
        if (m == 3.0) first = scf[mid];
        else EXPECT_NEAR(scf[mid], first, 1e-12);
    }
}

// 2D analogue on the square lattice (delta = 3 dx, 28 neighbours): SCF = 85/82 = 1.036585.
TEST(SCF, BulkSquareLattice)
{
    const double dx = 2e-3, t = 1e-3;
    auto body = box<2>({{0, 0}}, {{7 * dx, 7 * dx}}, dx, t);
    Bonds b = build_bonds(body, 3 * dx);
    const int mid = 3 + 3 * 7;
    const auto scf = shear_correction_factor(b, body.x, 2);
    EXPECT_NEAR(lattice_scf<2>(), 85.0 / 82.0, 1e-14);
    EXPECT_NEAR(scf[mid] / (85.0 / 82.0), 1.0, 1e-5);  // O(gamma) nonlinearity of the probe
}

// Continuum: N over a full ball by product Gauss-Legendre quadrature (r, cos(polar), azimuth),
// with the exact e = |Y| - |xi| and theta from the same quadrature: N = 4 gamma^2 m / 15 in 3D
// and N = 4 gamma^2 m / 8 in 2D (the derivation in scf.hpp), for any radial omega, so the
// continuum SCF is 1. Tolerance 1e-5: O(gamma) nonlinearity; the quadrature is exact for the
// linearised polynomial integrand.
TEST(SCF, ContinuumBallAndDiscGiveOne)
{
    const double delta = 2.0, g = 1e-6;
    const std::function<double(double)> omegas[] = {[](double) { return 1.0; },
                                                    [&](double r) { return 1 - r / delta; }};
    const auto R = gauss(12, 0, delta), U = gauss(12, -1, 1), P = gauss(24, 0, 2 * pi);
    for (const auto& omega : omegas) {
        for (int dim : {3, 2}) {
            double m = 0, sth = 0, N = 0;
            for (int pass = 0; pass < 2; ++pass) {
                const double theta = pass == 1 ? dim * sth / m : 0.0;
                for (const auto& [r, wr] : R)
                    for (const auto& [u, wu] : (dim == 3 ? U : std::vector<std::array<double, 2>>{{0.0, 1.0}}))
                        for (const auto& [p, wp] : P) {
                            const double s = std::sqrt(1 - u * u);
                            const double x = r * s * std::cos(p), y = r * s * std::sin(p), z = r * u;
                            const double dV = (dim == 3 ? r * r : r) * wr * wu * wp;
                            const double X = x + g * y, Y = y + g * x;  // XY pure shear
                            const double e = std::sqrt(X * X + Y * Y + z * z) - r;
                            if (pass == 0) { m += omega(r) * r * r * dV; sth += omega(r) * r * e * dV; }
                            else N += omega(r) * std::pow(e - theta * r / dim, 2) * dV;
                        }
            }
            EXPECT_LT(std::abs(sth / m), 1e-5 * g);  // theta = O(gamma^2): zero to first order
            const double a_D = dim == 3 ? 15.0 : 8.0;
            EXPECT_NEAR(4 * g * g * m / (a_D * N), 1.0, 1e-5) << "dim " << dim;
        }
    }
}

// Surface nodes (3D box 7^3 and square 7^2, delta = 3 dx), each against its lattice sum:
// - edges and corners: theta != 0 under the probe and e_d (the omega-weighted projection of e
//   off |xi|) loses part of the shear, so N/m falls and SCF rises above the bulk value
//   (3D edge 0.97674, corner 1.97109; 2D edge 1.25, corner 2.48705);
// - a face centre is BELOW the bulk (0.81783): a continuum half-ball has the full ball's N/m by
//   reflection (SCF = 1), but the lattice counts the node's own layer z = 0 with full volume,
//   and its in-plane bonds carry the largest XY shear (with that layer halved the sum gives the
//   bulk 118/131 exactly). The first layers inside are lower still (z = 1: 0.75692).
TEST(SCF, SurfaceNodesAgainstLatticeSums)
{
    const double dx = 1e-3;
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 7 * dx, 7 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    const auto scf = shear_correction_factor(b, body.x, 3);
    const double bulk = lattice_scf<3>();
    using N3 = std::array<int, 3>;
    const struct { int node; std::function<bool(const N3&)> keep; } cases[] = {
        {3 + 3 * 7, [](const N3& n) { return n[2] >= 0; }},                                  // face
        {3 + 3 * 7 + 49, [](const N3& n) { return n[2] >= -1; }},                             // layer z = 1
        {3, [](const N3& n) { return n[1] >= 0 && n[2] >= 0; }},                             // edge
        {0, [](const N3& n) { return n[0] >= 0 && n[1] >= 0 && n[2] >= 0; }}};               // corner
    for (const auto& c : cases) EXPECT_NEAR(scf[c.node] / lattice_scf<3>(c.keep), 1.0, 1e-5) << "node " << c.node;
    EXPECT_LT(scf[3 + 3 * 7], bulk);
    EXPECT_GT(scf[3], bulk);
    EXPECT_GT(scf[0], scf[3]);

    auto body2 = box<2>({{0, 0}}, {{7 * dx, 7 * dx}}, dx, 1e-3);
    Bonds b2 = build_bonds(body2, 3 * dx);
    const auto scf2 = shear_correction_factor(b2, body2.x, 2);
    EXPECT_NEAR(scf2[3] / lattice_scf<2>([](const N3& n) { return n[1] >= 0; }), 1.0, 1e-5);                // edge
    EXPECT_NEAR(scf2[0] / lattice_scf<2>([](const N3& n) { return n[0] >= 0 && n[1] >= 0; }), 1.0, 1e-5);  // corner
    EXPECT_GT(scf2[3], lattice_scf<2>());
    EXPECT_GT(scf2[0], scf2[3]);
}

// Damage: an intact damage array changes nothing; breaking bonds of a node lowers its N (m is
// the whole family, as in LPS) and raises its SCF. Threads: per-node work, bit-identical.
TEST(SCF, DamageAndThreads)
{
    const double dx = 1e-3;
    auto body = box<3>({{0, 0, 0}}, {{14 * dx, 14 * dx, 14 * dx}}, dx);  // > parallel_min_nodes
    Bonds b = build_bonds(body, 3 * dx);
    set_threads(1);
    const auto s1 = shear_correction_factor(b, body.x, 3);
    set_threads(2);
    const auto s2 = shear_correction_factor(b, body.x, 3);
    set_threads(0);
    EXPECT_EQ(s1, s2);
    b.enable_damage();
    EXPECT_EQ(shear_correction_factor(b, body.x, 3), s1);
    const int mid = 7 + 7 * 14 + 7 * 196;
    for (std::int64_t k = b.begin(mid); k < b.end(mid); ++k)
        if (body.x.c[0][b.partner[k]] > body.x.c[0][mid]) b.break_pair(k);
    EXPECT_GT(shear_correction_factor(b, body.x, 3)[mid], s1[mid]);
    EXPECT_THROW(shear_correction_factor(b, body.x, 2), std::invalid_argument);  // dim != D
}

// A family that no probe shear stretches to first order (its only intact bonds along x: every probe
// plane XY, ZX, YZ changes their length by O(gamma^2) only) has no shear mode to correct: SCF = 1,
// as for an empty family (before the rule: SCF ~ 1/gamma^2 = 1e12, and alpha with it).
TEST(SCF, FamilyThatNoShearStretchesGetsOne)
{
    const double dx = 1e-3;
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 7 * dx, 7 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    b.enable_damage();
    const int mid = 3 + 3 * 7 + 3 * 49;
    for (std::int64_t k = b.begin(mid); k < b.end(mid); ++k) {
        const int j = b.partner[k];
        if (body.x.c[1][j] != body.x.c[1][mid] || body.x.c[2][j] != body.x.c[2][mid]) b.break_pair(k);
    }
    EXPECT_EQ(shear_correction_factor(b, body.x, 3, scf_gamma, true)[mid], 1.0);
    EXPECT_EQ(shear_correction_factor(b, body.x, 3)[mid], 1.0);
}
