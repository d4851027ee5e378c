// Sparse linear solves K du = R for the Newton-type solvers: SimplicialLDLT (sparse Cholesky, AMD
// ordering; reads the lower triangle only, so for the symmetric tangents of PMB, LPS, PALS; an
// indefinite matrix is factorised too, an exactly singular one fails), ConjugateGradient with the
// Jacobi preconditioner (symmetric positive (semi-)definite; ||K du - R|| <= cg_tol ||R||), or
// SparseLU (COLAMD ordering; any matrix, e.g. the non-symmetric tangent of correspondence), and for
// large systems SuiteSparse's supernodal CHOLMOD LL^T (symmetric positive definite) and UMFPACK LU
// (any matrix), the same factorisations with dense kernels on the supernodes / fronts.
// A factorisation is kept until the next factorise call (reuse across iterations and steps).
#pragma once
#include <Eigen/CholmodSupport>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <sstream>
#include <stdexcept>
#include <string>

namespace pd {

enum class LinearSolver { cholesky, cg, lu, cholmod, umfpack };
inline LinearSolver parse_linear_solver(const std::string& s)
{
    if (s == "cholesky") return LinearSolver::cholesky;
    if (s == "cg") return LinearSolver::cg;
    if (s == "lu") return LinearSolver::lu;
    if (s == "cholmod") return LinearSolver::cholmod;
    if (s == "umfpack") return LinearSolver::umfpack;
    throw std::invalid_argument("unknown linear solver '" + s + "' (cholesky | cg | lu | cholmod | umfpack)");
}

class SparseSolver {
public:
    bool factorise(const Eigen::SparseMatrix<double>& K, LinearSolver kind, double cg_tol, int cg_max_iter, std::string& failure)
    {
        kind_ = kind;
        if (kind_ == LinearSolver::cholesky) {
            ldlt_.compute(K);
            if (ldlt_.info() != Eigen::Success) failure = "sparse Cholesky (LDLT) failed: singular tangent";
            return ldlt_.info() == Eigen::Success;
        }
        if (kind_ == LinearSolver::lu) {
            lu_.compute(K);
            if (lu_.info() != Eigen::Success) failure = "sparse LU failed: " + lu_.lastErrorMessage();
            return lu_.info() == Eigen::Success;
        }
        if (kind_ == LinearSolver::cholmod) {
            llt_.compute(K);
            if (llt_.info() != Eigen::Success) failure = "CHOLMOD LL^T failed: tangent not positive definite";
            return llt_.info() == Eigen::Success;
        }
        if (kind_ == LinearSolver::umfpack) {  // 64-bit indices: the 32-bit version runs out of index space near 300k unknowns
            k64_ = K;  // kept: UmfPackLU refers to its matrix
            umf_.compute(k64_);
            if (umf_.info() != Eigen::Success)
                failure = "UMFPACK LU failed (status " + std::to_string(umf_.umfpackFactorizeReturncode()) +
                          (umf_.umfpackFactorizeReturncode() == UMFPACK_WARNING_singular_matrix ? ": singular tangent)" : ")");
            return umf_.info() == Eigen::Success;
        }
        cg_.setTolerance(cg_tol);
        if (cg_max_iter > 0) cg_.setMaxIterations(cg_max_iter);
        cg_.compute(K);
        if (cg_.info() != Eigen::Success) failure = "CG preconditioner setup failed";
        return cg_.info() == Eigen::Success;
    }

    bool solve(const Eigen::VectorXd& R, Eigen::VectorXd& du, std::string& failure)
    {
        if (kind_ == LinearSolver::cholesky) {
            du = ldlt_.solve(R);
            if (ldlt_.info() != Eigen::Success || !du.allFinite()) failure = "sparse Cholesky (LDLT) solve failed: singular tangent";
        } else if (kind_ == LinearSolver::lu) {
            du = lu_.solve(R);
            if (lu_.info() != Eigen::Success || !du.allFinite()) failure = "sparse LU solve failed: singular tangent";
        } else if (kind_ == LinearSolver::cholmod) {
            du = llt_.solve(R);
            if (llt_.info() != Eigen::Success || !du.allFinite()) failure = "CHOLMOD LL^T solve failed";
        } else if (kind_ == LinearSolver::umfpack) {
            du = umf_.solve(R);
            if (umf_.info() != Eigen::Success || !du.allFinite()) failure = "UMFPACK LU solve failed: singular tangent";
        } else {
            du = cg_.solve(R);
            if (cg_.info() != Eigen::Success) {
                std::ostringstream m;
                m << "CG did not converge in " << cg_.iterations() << " iterations (relative error " << cg_.error() << ")";
                failure = m.str();
            }
        }
        return failure.empty();
    }

private:
    LinearSolver kind_ = LinearSolver::cholesky;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg_;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt_;
    Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long> k64_;
    Eigen::UmfPackLU<Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>> umf_;
};

}  // namespace pd
