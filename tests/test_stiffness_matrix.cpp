// tests/test_stiffness_matrix.cpp -- problems/common/analysis/stiffness_matrix.hpp: the finite-difference
// stiffness of a small PMB cube against the pair-spring matrix written out independently
// (reference/pmb_pair_stiffness.hpp), the rigid modes (orthonormal, annihilated by K) and the
// spectrum counts (6 zero modes in 3D, none negative, symmetric K).
#include "problems/common/analysis/stiffness_matrix.hpp"
#include "pd/models/pmb.hpp"
#include "reference/pmb_pair_stiffness.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace pd;

namespace {

// 4 x 4 x 4 cube, dx = 1 mm, delta = 3.05 dx, E = 200 GPa, nu = 1/4 (PMB), step h = 1e-5 dx: the
// forces are smooth in u, so the central-difference truncation is O(h^2 / dx^2) ~ 1e-10 and the
// round-off ~ 1e-16 / 1e-5 = 1e-11 of the entries: 1e-8 leaves two decades.
constexpr double dx = 1e-3, m = 3.05, h_rel = 1e-5, fd_tol = 1e-8;

struct Cube {
    Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, m * dx);
    Elastic mat = Elastic::from_E_nu(200e9, 0.25);
    PMB model{{.material = mat, .dim = 3}, bonds};
};

TEST(StiffnessMatrix, FiniteDifferencePMBMatchesPairSprings)
{
    Cube c;
    const Eigen::MatrixXd K = fd_stiffness(c.model, c.body, c.bonds, h_rel * dx);
    const double delta = m * dx, cm = 18 * c.mat.K / (std::numbers::pi * std::pow(delta, 4));  // spec/000b V12
    const Eigen::MatrixXd Ka = ref::pmb_pair_stiffness(c.body.x.c, c.body.volume, delta, cm);
    ASSERT_EQ(K.rows(), 3 * 64);
    EXPECT_LT((K - Ka).norm() / Ka.norm(), fd_tol);
}

TEST(StiffnessMatrix, RigidModesAreOrthonormalAndAnnihilated)
{
    Cube c;
    const Eigen::MatrixXd R = rigid_modes(c.body);
    ASSERT_EQ(R.cols(), 6);
    EXPECT_LT((R.transpose() * R - Eigen::MatrixXd::Identity(6, 6)).norm(), 1e-12);  // QR round-off
    const Eigen::MatrixXd K = fd_stiffness(c.model, c.body, c.bonds, h_rel * dx);
    const StiffnessSpectrum s = stiffness_spectrum(K, c.body, 1e-8);
    EXPECT_EQ(s.rigid, 6);
    EXPECT_EQ(s.zero, 6);      // PMB has no zero-energy mode beyond the rigid ones
    EXPECT_EQ(s.negative, 0);  // stable at the reference configuration
    EXPECT_LT(s.rigid_residual, fd_tol);
    EXPECT_LT(s.asymmetry, fd_tol);  // pair springs: K symmetric up to the difference error
    EXPECT_EQ(s.lambda.size(), 3 * 64);
    for (int k = 1; k < s.lambda.size(); ++k) EXPECT_LE(s.lambda(k - 1), s.lambda(k));  // ascending
}

// 2D: 3 rigid modes (2 translations, 1 rotation), orthonormal.
TEST(StiffnessMatrix, RigidModes2D)
{
    const Body<2> sq = box<2>({{0, 0}}, {{5 * dx, 5 * dx}}, dx, dx);
    const Eigen::MatrixXd R = rigid_modes(sq);
    ASSERT_EQ(R.cols(), 3);
    EXPECT_LT((R.transpose() * R - Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-12);
}

}  // namespace
