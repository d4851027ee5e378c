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

// spec/000a eq. 2.82: under a uniform stretch F = diag(l, 1, 1) the Lagrangian flux is k diag(1/l, l, l) g,
// so Q of theta = x^2/2 is k/l and of theta = y^2/2 is k l in the interior; a rigid rotation changes
// nothing (det R R^-1 R^-T = I, to round-off); the assembled operator is the point pass's at that F.
TEST(CorrespondenceHeat, DeformationEntersThroughTheLagrangianConductivity)
{
    const int n = 16;
    const double dx = 1e-3, k = 40, m = 3.05, l = 1.25;
    const auto body = cube<3>(n, dx, 1);
    const auto bonds = pd::build_bonds(body, m * dx);
    using Mat = pd::CorrespondenceHeat<3>::Mat;
    std::vector<Mat> F(body.size(), Mat::Identity());
    for (Mat& f : F) f(0, 0) = l;
    pd::CorrespondenceHeat<3> model({k, 0.5, 1}, body, bonds);
    model.set_deformation(&F);
    std::vector<double> qx(body.size()), qy(body.size()), Q;
    for (std::size_t i = 0; i < body.size(); ++i) qx[i] = 0.5 * std::pow(body.x.c[0][i], 2), qy[i] = 0.5 * std::pow(body.x.c[1][i], 2);
    int interior = 0;
    pd::heat_flow(model, bonds, qx, Q);
    for (std::size_t i = 0; i < body.size(); ++i)
        if (deep_interior(body, i, n, dx, m * dx)) {
            EXPECT_NEAR(Q[i], k / l, 1e-8 * k);
            ++interior;
        }
    EXPECT_GT(interior, 0);
    pd::heat_flow(model, bonds, qy, Q);
    for (std::size_t i = 0; i < body.size(); ++i)
        if (deep_interior(body, i, n, dx, m * dx)) {
            EXPECT_NEAR(Q[i], k * l, 1e-8 * k);
        }
    // A rotation by 0.7 rad about z: the same Q as undeformed.
    const Mat Rz = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    std::vector<Mat> R(body.size(), Rz);
    std::vector<double> Q0;
    pd::CorrespondenceHeat<3> plain({k, 0.5, 1}, body, bonds);
    pd::heat_flow(plain, bonds, qy, Q0);
    model.set_deformation(&R);
    pd::heat_flow(model, bonds, qy, Q);
    // det R R^-1 R^-T = I to round-off; the sums' terms reach k (n dx / dx)^2 = k n^2 (header): 1e-10 of that.
    for (std::size_t r = 0; r < body.size(); ++r) EXPECT_NEAR(Q[r], Q0[r], 1e-10 * k * n * n);
    std::vector<Mat> few(3, Mat::Identity());
    EXPECT_THROW(model.set_deformation(&few), std::invalid_argument);
    // The assembled operator at a different F per node against the point pass (a 6^3 cube).
    const auto small = cube<3>(6, dx, 1);
    const auto sb = pd::build_bonds(small, m * dx);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-0.2, 0.2);
    std::vector<Mat> Fs(small.size());
    std::vector<double> th(small.size());
    for (std::size_t i = 0; i < small.size(); ++i) {
        Fs[i] = Mat::Identity();
        for (int a = 0; a < 3; ++a) for (int c = 0; c < 3; ++c) Fs[i](a, c) += u(rng);
        th[i] = 300 + 1e3 * u(rng);
    }
    pd::CorrespondenceHeat<3> sm({k, 0.5, 1}, small, sb);
    sm.set_deformation(&Fs);
    pd::heat_flow(sm, sb, th, Q);
    const auto A = pd::heat_operator(sm, sb);
    const Eigen::VectorXd AQ = A * Eigen::Map<const Eigen::VectorXd>(th.data(), long(th.size()));
    double scale = 0;
    for (double q : Q) scale = std::max(scale, std::abs(q));
    for (std::size_t r = 0; r < small.size(); ++r) EXPECT_NEAR(AQ(long(r)), Q[r], 1e-9 * scale);
}
