// Surface correction of LPS by the energy method (models/surface_correction.hpp): the reference
// is the classical uniaxial-strain energy, written here from K and G; after the correction the
// worst energy density under the uniaxial extensions is closer to it; the corrected model (omega
// V_j scaled by a symmetric G_ij, m_i kept) balances its pair forces. It is not variational (m_i
// kept): the test measures how far its force is from the gradient of its energy.
#include "pd/bond_loop.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/surface_correction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace pd;

namespace {
constexpr double dx = 1e-3;
const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

// y = x + eps x_a e_a (uniaxial strain along a).
Field<3> uniaxial(const Body<3>& body, int a, double eps)
{
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) y.c[a][i] += eps * body.x.c[a][i];
    return y;
}

// max_i |W_a(i)/ref - 1| over all nodes and the three axes.
double worst_energy_error(LPS lps, const Body<3>& body, const Bonds& b, double eps, double ref)
{
    double worst = 0;
    for (int a = 0; a < 3; ++a) {
        const Field<3> y = uniaxial(body, a, eps);
        lps.point_pass(b, y);
        for (double W : lps.energy_density(b, y)) worst = std::max(worst, std::abs(W / ref - 1));
    }
    return worst;
}

double total_energy(LPS& lps, const Body<3>& body, const Bonds& b, const Field<3>& y)
{
    lps.point_pass(b, y);
    const std::vector<double> W = lps.energy_density(b, y);
    double sum = 0;
    for (std::size_t i = 0; i < W.size(); ++i) sum += W[i] * body.volume[i];
    return sum;
}
}  // namespace

// 3D box 8 x 6 x 5, m = 3 (no node has a full family): the reference is (K + 4G/3)/2 eps^2, the
// factors are symmetric, and the worst energy density over all nodes and axes moves towards it.
TEST(LPSSurfaceCorrection, EnergyAtEveryNodeApproachesClassicalUniaxialStrain)
{
    auto body = box<3>({{0, 0, 0}}, {{8 * dx, 6 * dx, 5 * dx}}, dx);
    const Bonds b = build_bonds(body, 3 * dx);
    const LPS plain({.material = steel, .dim = 3}, b);
    const SurfaceCorrectionOptions opt{.zeta = 1e-6, .reference = SurfaceCorrectionOptions::Reference::classical};
    const SurfaceFactors<3> sf = surface_correction(plain, body, b, opt);
    const double W_ref = 0.5 * (steel.K + 4 * steel.G / 3) * opt.zeta * opt.zeta;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(sf.W_inf[a] / W_ref, 1.0, 1e-14);
    for (std::size_t k = 0; k < b.size(); ++k) ASSERT_EQ(sf.G[k], sf.G[b.reverse[k]]);
    LPS corrected = plain;
    apply_surface_correction(corrected, body, b, SurfaceCorrectionMethod::energy, opt);
    const double before = worst_energy_error(plain, body, b, opt.zeta, W_ref);
    const double after = worst_energy_error(corrected, body, b, opt.zeta, W_ref);
    std::printf("max |W/W_ref - 1|: %.3f before, %.3f after the correction\n", before, after);
    EXPECT_GT(before, 0.2);      // truncated families are far off (measured 0.33)
    EXPECT_LT(after, 0.9 * before);  // measured 0.27: G_ij averages both ends and mixes directions, not exact
}

// Corrected model under a random deformation: sum_i f_i V_i = 0 (pair forces balance, G symmetric).
// f_i V_i against -dE/dy_i (E = sum_i W_i V_i, central differences) is printed, not asserted: with
// m_i kept the force is not the gradient of W (LPS::scale_bonds); the uncorrected model is, to 1e-5.
TEST(LPSSurfaceCorrection, CorrectedModelBalancesItsPairForces)
{
    auto body = box<3>({{0, 0, 0}}, {{7 * dx, 5 * dx, 4 * dx}}, dx);
    const Bonds b = build_bonds(body, 3 * dx);
    LPS models[2] = {LPS({.material = steel, .dim = 3}, b), LPS({.material = steel, .dim = 3}, b)};
    apply_surface_correction(models[1], body, b, SurfaceCorrectionMethod::energy, {.reference = SurfaceCorrectionOptions::Reference::classical});
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> U(-1, 1);
    Field<3> y = body.x;
    for (auto& c : y.c) for (double& v : c) v += 1e-3 * dx * U(gen);
    for (int corrected : {0, 1}) {
        LPS& m = models[corrected];
        Field<3> f;
        internal_force(m, b, y, f);
        double net[3] = {}, scale = 0;
        for (std::size_t i = 0; i < body.size(); ++i)
            for (int d = 0; d < 3; ++d) {
                net[d] += f.c[d][i] * body.volume[i];
                scale = std::max(scale, std::abs(f.c[d][i] * body.volume[i]));
            }
        for (int d = 0; d < 3; ++d) EXPECT_LT(std::abs(net[d]), 1e-12 * scale * body.size()) << "component " << d;
        // Central differences, h = 1e-6 dx: truncation and round-off ~1e-7 of f V.
        const double h = 1e-6 * dx;
        double worst = 0;
        for (std::size_t i : {std::size_t{0}, body.size() / 2, body.size() - 1})
            for (int d = 0; d < 3; ++d) {
                Field<3> yp = y, ym = y;
                yp.c[d][i] += h;
                ym.c[d][i] -= h;
                const double dE = (total_energy(m, body, b, yp) - total_energy(m, body, b, ym)) / (2 * h);
                worst = std::max(worst, std::abs(-dE / (f.c[d][i] * body.volume[i]) - 1));
            }
        std::printf("%s: max |(-dE/dy) / (f V) - 1| = %.2e\n", corrected ? "corrected" : "uncorrected", worst);
        if (!corrected) {
            EXPECT_LT(worst, 1e-5);  // the plain LPS is variational (measured 6e-9; corrected 0.42)
        }
    }
}
