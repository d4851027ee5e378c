// Correspondence heat conduction with hourglass suppression (spec/000b sec. 3.4-3.5, V11, V12).
// Tolerances: 1e-9 relative for gradients and the assembled operator (a 3x3 inverse and ~120-term
// sums: round-off of a few hundred ulps); 1e-8 for the quadratic-field Q, whose terms are ~(x/dx)^2
// larger than the result and cancel (x up to 16 dx).
#include "pd/heat/conduction.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include "heat_fixtures.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <random>

namespace {

using pd_test::cube;

// Is node i at least two horizons (plus a cell) from every face of the n^D cube? Its family and its
// neighbours' families are then complete and symmetric.
template <int D>
bool deep_interior(const pd::Body<D>& b, std::size_t i, int n, double dx, double delta)
{
    for (int d = 0; d < D; ++d)
        if (b.x.c[d][i] < 2 * delta + dx || b.x.c[d][i] > n * dx - 2 * delta - dx) return false;
    return true;
}

template <int D>
void polynomial_fields(double m, double measure)
{
    const int n = 16;
    const double dx = 1e-3, k = 40;
    const auto body = cube<D>(n, dx, measure);
    const auto bonds = pd::build_bonds(body, m * dx);
    for (double C : {0.0, 1.0}) {
        pd::CorrespondenceHeat<D> model({k, C, measure}, body, bonds);
        std::vector<double> lin(body.size()), quad(body.size()), Q;
        for (std::size_t i = 0; i < body.size(); ++i) {
            lin[i] = 3 + 200 * body.x.c[0][i] - (D > 1 ? 70 * body.x.c[D - 1][i] : 0);
            quad[i] = 0.5 * body.x.c[0][i] * body.x.c[0][i];
        }
        pd::heat_flow(model, bonds, lin, Q);
        for (std::size_t i = 0; i < body.size(); ++i) {
            // The gradient is exact at every node, surface nodes included (any family spanning D dims).
            EXPECT_NEAR(model.g[i](0), 200, 1e-9 * 200) << "D " << D << " node " << i;
            if (deep_interior(body, i, n, dx, m * dx)) {
                EXPECT_NEAR(Q[i], 0, 1e-9 * k * 200 / dx);
            }
        }
        pd::heat_flow(model, bonds, quad, Q);
        for (std::size_t i = 0; i < body.size(); ++i)
            if (deep_interior(body, i, n, dx, m * dx)) {
                EXPECT_NEAR(Q[i], k, 1e-8 * k) << "D " << D << " C_hg " << C;
            }
    }
}

}  // namespace

TEST(CorrespondenceHeat, LinearFieldsExactAndQuadraticGivesKLaplacian)
{
    polynomial_fields<1>(3.0, 1e-4);
    polynomial_fields<2>(3.05, 1e-3);
    polynomial_fields<3>(3.05, 1);
}

TEST(CorrespondenceHeat, AlternatingModeIsZeroEnergyWithoutSuppressionAndDiffusesWithIt)
{
    // theta_j = (-1)^j: theta_j - theta_i is even in xi, so g = 0 and Q = 0 without suppression
    // (spec 3.5: the zero-energy mode). The stabilising sign of the suppression cools hot nodes.
    const double dx = 1e-3, A = 1e-4;
    const auto body = cube<1>(40, dx, A);
    const auto bonds = pd::build_bonds(body, 3 * dx);
    std::vector<double> theta(body.size()), Q;
    for (std::size_t i = 0; i < body.size(); ++i) theta[i] = i % 2 ? 1.0 : -1.0;
    pd::CorrespondenceHeat<1> off({50, 0, A}, body, bonds), on({50, 1, A}, body, bonds);
    pd::heat_flow(off, bonds, theta, Q);
    for (std::size_t i = 6; i + 6 < body.size(); ++i) EXPECT_NEAR(Q[i], 0, 1e-6);
    pd::heat_flow(on, bonds, theta, Q);
    for (std::size_t i = 6; i + 6 < body.size(); ++i) EXPECT_LT(Q[i] * theta[i], -1e3);
}

TEST(CorrespondenceHeat, AssembledOperatorEqualsTheHeatLoopColumnByColumn)
{
    // Q = A theta: the exact matrix of add_operator against heat_flow on unit vectors (2D, with damage).
    const double dx = 1e-3, s = 1e-3;
    const auto body = cube<2>(7, dx, s);
    auto bonds = pd::build_bonds(body, 3.05 * dx);
    bonds.enable_damage();
    std::mt19937 rng(7);
    for (std::size_t i = 0; i < bonds.nodes(); ++i)
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k)
            if (int(i) < bonds.partner[k] && rng() % 7 == 0) bonds.intact[k] = bonds.intact[bonds.reverse[k]] = 0;
    pd::CorrespondenceHeat<2> model({50, 0.3, s}, body, bonds);
    const Eigen::MatrixXd A = Eigen::MatrixXd(pd::heat_operator(model, bonds));
    std::vector<double> e(body.size(), 0.0), Q;
    for (std::size_t c = 0; c < body.size(); ++c) {
        e[c] = 1;
        pd::heat_flow(model, bonds, e, Q);
        e[c] = 0;
        for (std::size_t r = 0; r < body.size(); ++r) EXPECT_NEAR(A(r, c), Q[r], 1e-9 * A.cwiseAbs().maxCoeff());
    }
}
