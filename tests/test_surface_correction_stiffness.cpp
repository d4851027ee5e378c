// Surface correction of PMB by the energy method (spec/002 sec. 2.4) on whole specimens: energy
// densities at every node before and after the correction, the stiffness of the spec/000b T2 bar
// and the elongation of a static 1D bar against the classical values (factors: test_surface_correction.cpp).
#include "pd/models/surface_correction.hpp"

#include <gtest/gtest.h>

#include "surface_correction_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace pd;
using namespace pd_test::surface_correction_fixtures;

namespace {
// max_i |W_a(i)/ref - 1| over all nodes.
double max_deviation(const std::vector<double>& W, double ref)
{
    double dev = 0;
    for (double w : W) dev = std::max(dev, std::abs(w / ref - 1));
    return dev;
}
}  // namespace

// 3D box 8x6x5, m = 3 (no node has a full family): energy density at EVERY node under each
// uniaxial extension, as max_i |W(i)/W_inf - 1| before and after the correction, W_inf the
// full-family value. Exactness is not expected: G_ij averages g of both ends and mixes the
// directions, so only nodes whose partners share their g (and bonds along the probe) are exact.
TEST(SurfaceCorrection, EnergyAtEveryNodeApproachesBulk3D)
{
    const double dx = 1e-3, eps = 1e-5;
    const Elastic mat = Elastic::from_E_nu(200e9, 0.25);
    auto body = box<3>({{0, 0, 0}}, {{8 * dx, 6 * dx, 5 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    PMB pmb({mat, 3}, b);
    const auto f = surface_correction(pmb, body, b);
    PMB corrected = pmb;
    apply_surface_correction(corrected, body, b, parse_surface_correction("energy"));
    for (int a = 0; a < 3; ++a) {
        const Field<3> y = uniaxial(body, a, eps);
        const double ref = f.W_inf[a] * (eps * eps) / (1e-6 * 1e-6);  // W scales with strain^2
        const auto W0 = pmb.energy_density(b, y), W1 = corrected.energy_density(b, y);
        double lo0 = 1e9, hi0 = 0, lo1 = 1e9, hi1 = 0, mean0 = 0, mean1 = 0, avg0 = 0, avg1 = 0;
        for (std::size_t i = 0; i < W0.size(); ++i) {
            const double r0 = W0[i] / ref, r1 = W1[i] / ref, n = static_cast<double>(W0.size());
            lo0 = std::min(lo0, r0), hi0 = std::max(hi0, r0), lo1 = std::min(lo1, r1), hi1 = std::max(hi1, r1);
            mean0 += std::abs(r0 - 1) / n, mean1 += std::abs(r1 - 1) / n, avg0 += r0 / n, avg1 += r1 / n;
        }
        std::printf("[ surface  ] 3D 8x6x5 m=3 axis %d: W/W_inf range [%.3f, %.3f] -> [%.3f, %.3f], "
                    "max |dev| %.3f -> %.3f, mean |dev| %.3f -> %.3f, body mean %.3f -> %.3f\n",
                    a, lo0, hi0, lo1, hi1, max_deviation(W0, ref), max_deviation(W1, ref), mean0, mean1, avg0, avg1);
        // Measured (this box): range [0.257, <=1] -> [0.737, 1.499], max |dev| 0.743 -> 0.36-0.50,
        // mean |dev| 0.44-0.52 -> 0.16-0.23, body mean 0.48-0.56 -> 0.966-1.027. Bounds with margin:
        EXPECT_LT(lo0, 0.3);   // corner node, about 1/8 of a family, before the correction
        EXPECT_GT(lo1, 0.70);  // every node, corners included, after
        EXPECT_LT(hi1, 1.55);  // over-stiffening of nodes whose partners are corner/edge nodes (step 4 mean)
        EXPECT_LT(mean1, 0.5 * mean0);
        EXPECT_NEAR(avg1, 1.0, 0.05);  // volume average: 5% (direction mixing of step 5)
    }
}

// Whole-specimen stiffness of the spec/000b T2 bar (10 x 2 x 1 mm, delta = 3.05 dx, continuum
// c = 18K/(pi delta^4)) under affine uniaxial strain eps along each axis:
// M_eff = 2 sum_i W_i V_i / (V eps^2) against the classical PMB constrained modulus
// M = lambda + 2G = 9K/5 (nu = 1/4), with the classical reference (which also removes the lattice
// quadrature error of the bulk), at dx = 0.25 mm (4 nodes thick) and 0.125 mm (8 nodes thick).
TEST(SurfaceCorrection, BarStiffnessMovesToClassical3D)
{
    const double eps = 1e-4;
    const Elastic mat = Elastic::from_E_nu(100e9, 0.25);
    const double M = 1.8 * mat.K;
    for (double dx : {0.25e-3, 0.125e-3}) {
        auto body = box<3>({{0, 0, 0}}, {{10e-3, 2e-3, 1e-3}}, dx);
        Bonds b = build_bonds(body, 3.05 * dx);
        PMB pmb({mat, 3}, b);
        PMB corrected = pmb;
        apply_surface_correction(corrected, body, b, SurfaceCorrectionMethod::energy,
                                 {.reference = SurfaceCorrectionOptions::Reference::classical, .kappa = mat.K});
        PMB untouched = pmb;
        apply_surface_correction(untouched, body, b, SurfaceCorrectionMethod::none);
        ASSERT_EQ(untouched.coef, pmb.coef);
        for (int a = 0; a < 3; ++a) {
            const Field<3> y = uniaxial(body, a, eps);
            const auto W0 = pmb.energy_density(b, y), W1 = corrected.energy_density(b, y);
            double U0 = 0, U1 = 0, V = 0;
            for (std::size_t i = 0; i < body.size(); ++i) {
                U0 += W0[i] * body.volume[i];
                U1 += W1[i] * body.volume[i];
                V += body.volume[i];
            }
            const double r0 = 2 * U0 / (V * eps * eps) / M, r1 = 2 * U1 / (V * eps * eps) / M;
            std::printf("[ surface  ] T2 bar dx=%.3f mm m=3.05 axis %d: M_eff/M before %.4f after %.4f\n", dx * 1e3, a, r0, r1);
            EXPECT_LT(std::abs(r1 - 1), std::abs(r0 - 1));
            // 15%: in a specimen 4-8 nodes thick the direction mixing of step 5 (oblique bonds take
            // a blend of G_x, G_y, G_z) leaves a residual of this order across the thickness.
            EXPECT_LT(std::abs(r1 - 1), 0.15);
        }
    }
}

// 1D static bar (40 nodes, m = 3, lattice calibration so the bulk is exact), node 0 held, axial
// force F on the last node as a body force F/V. Linearised PMB: sum_j coef_ij (u_j - u_i) + b_i = 0,
// solved densely by hand. Classical elongation F L/(E A) over L = x_39 - x_0; the soft truncated families at
// both ends lengthen the PD bar, and the correction must bring it closer (numbers printed).
TEST(SurfaceCorrection, StaticBarElongationMovesToClassical1D)
{
    const double dx = 1e-3, A = 1e-4, E = 200e9, F = 1e3;
    const int N = 40;
    auto body = box<1>({{0}}, {{N * dx}}, dx, A);
    Bonds b = build_bonds(body, 3 * dx);
    PMB pmb({Elastic::from_E_nu(E, 0.25), 1, Plane::stress, A, PMB::Params::Calibration::lattice, dx}, b);
    PMB corrected = pmb;
    apply_surface_correction(corrected, body, b, SurfaceCorrectionMethod::energy);
    const double classical = F * (N - 1) * dx / (E * A);
    auto elongation = [&](const PMB& model) {
        const int n = N - 1;  // unknowns u_1 .. u_{N-1}
        std::vector<std::vector<double>> K(n, std::vector<double>(n, 0.0));
        std::vector<double> u(n, 0.0);
        for (int i = 1; i < N; ++i)
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                const int j = b.partner[k];
                K[i - 1][i - 1] += model.coef[k];
                if (j > 0) K[i - 1][j - 1] -= model.coef[k];
            }
        u[n - 1] = F / body.volume[N - 1];
        // Gaussian elimination without pivoting: K is symmetric positive definite (uniform volumes,
        // symmetric coef, node 0 held).
        for (int p = 0; p < n; ++p)
            for (int r = p + 1; r < n; ++r) {
                const double l = K[r][p] / K[p][p];
                for (int q = p; q < n; ++q) K[r][q] -= l * K[p][q];
                u[r] -= l * u[p];
            }
        for (int p = n - 1; p >= 0; --p) {
            for (int q = p + 1; q < n; ++q) u[p] -= K[p][q] * u[q];
            u[p] /= K[p][p];
        }
        return u[n - 1];
    };
    const double e0 = elongation(pmb) / classical, e1 = elongation(corrected) / classical;
    std::printf("[ surface  ] 1D static bar N=40 m=3: elongation / classical before %.4f after %.4f\n", e0, e1);
    EXPECT_GT(e0, 1.0);  // truncated families are softer
    EXPECT_LT(std::abs(e1 - 1), std::abs(e0 - 1));
}
