// The sparse direct and iterative solves of solve/linear_solver.hpp against Eigen's dense LU of the
// same matrix (an independent factorisation): a 1D stiffness-like SPD matrix and an unsymmetric one.
#include "pd/solve/linear_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <vector>

namespace {
// Tridiagonal 2, -1 (+ skew * (j - i) off the diagonal), n x n: SPD for skew = 0.
Eigen::SparseMatrix<double> matrix(int n, double skew)
{
    std::vector<Eigen::Triplet<double>> t;
    for (int i = 0; i < n; ++i) {
        t.emplace_back(i, i, 2.0);
        if (i + 1 < n) t.emplace_back(i, i + 1, -1.0 + skew), t.emplace_back(i + 1, i, -1.0 - skew);
    }
    Eigen::SparseMatrix<double> K(n, n);
    K.setFromTriplets(t.begin(), t.end());
    return K;
}
}  // namespace

TEST(LinearSolver, EveryKindSolvesAsTheDenseLU)
{
    const int n = 200;
    const Eigen::VectorXd R = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    for (const double skew : {0.0, 0.3}) {
        const Eigen::SparseMatrix<double> K = matrix(n, skew);
        const Eigen::VectorXd ref = Eigen::MatrixXd(K).partialPivLu().solve(R);
        std::vector<pd::LinearSolver> kinds{pd::LinearSolver::lu, pd::LinearSolver::umfpack};
        if (skew == 0) kinds.insert(kinds.end(), {pd::LinearSolver::cholesky, pd::LinearSolver::cholmod, pd::LinearSolver::cg});
        for (const pd::LinearSolver kind : kinds) {
            pd::SparseSolver solver;
            std::string failure;
            Eigen::VectorXd u;
            ASSERT_TRUE(solver.factorise(K, kind, 1e-13, 10 * n, failure) && solver.solve(R, u, failure)) << failure;
            // Condition number ~ n^2 = 4e4: direct solves agree to ~1e-11; CG stops at a residual of 1e-13.
            EXPECT_LT((u - ref).norm(), 1e-9 * ref.norm()) << static_cast<int>(kind) << " skew " << skew;
        }
    }
    EXPECT_EQ(pd::parse_linear_solver("cholmod"), pd::LinearSolver::cholmod);
    EXPECT_EQ(pd::parse_linear_solver("umfpack"), pd::LinearSolver::umfpack);
    EXPECT_THROW(pd::parse_linear_solver("pardiso"), std::invalid_argument);
}

TEST(LinearSolver, CholmodRefusesAMatrixThatIsNotPositiveDefinite)
{
    Eigen::SparseMatrix<double> K = matrix(20, 0.0);
    K.coeffRef(5, 5) = -3.0;
    pd::SparseSolver solver;
    std::string failure;
    EXPECT_FALSE(solver.factorise(K, pd::LinearSolver::cholmod, 0, 0, failure));
    EXPECT_FALSE(failure.empty());
}
