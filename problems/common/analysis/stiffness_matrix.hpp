// problems/common/analysis/stiffness_matrix.hpp -- dense stiffness matrix of a small patch by finite differences
// of the nodal internal forces, its rigid-body modes and its spectrum (zero-energy mode studies,
// problems/3d/hourglass_modes.cpp; seeds: spec/000a sec. 2.7-2.8).
//
// Stiffness (dof D i + d): K(D j + e, D i + d) = -d(f_j,e V_j)/du_i,d [N/m], by central differences
// about the reference configuration with step h [m]; the divisor is the exact difference
// (x + h) - (x - h) of the perturbed coordinates as stored (no rounding of 2h).
// Cost: 2 D N internal-force evaluations and a D N x D N dense matrix: patches of ~10^3 nodes.
// Rigid modes: D translations and D(D-1)/2 infinitesimal rotations about the centroid (rotation in
// the plane (a, b): u_a = -r_b, u_b = r_a), orthonormalised (Householder QR).
// Spectrum: eigenvalues of the symmetric part (K + K^T)/2 (Eigen::SelfAdjointEigenSolver, ascending),
// asymmetry ||K - K^T||_F / ||K||_F, the counts of |lambda| < zero_tol lambda_max and of
// lambda < -zero_tol lambda_max, and the rigid-mode residual ||K R||_F / (lambda_max ||R||_F).
#pragma once

#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace pd {

// K = -d(f V)/du by central differences of step h [m] (see the file header).
template <int D, class Model>
Eigen::MatrixXd fd_stiffness(Model& model, const Body<D>& body, const Bonds& bonds, double h)
{
    const int N = static_cast<int>(body.size());
    Eigen::MatrixXd K(D * N, D * N);
    Field<D> y = body.x, fp, fm;
    for (int b = 0; b < D * N; ++b) {
        const int i = b / D, d = b % D;
        const double x = body.x.c[d][i], xp = x + h, xm = x - h;
        y.c[d][i] = xp;
        internal_force(model, bonds, y, fp);
        y.c[d][i] = xm;
        internal_force(model, bonds, y, fm);
        y.c[d][i] = x;
        for (int j = 0; j < N; ++j)
            for (int e = 0; e < D; ++e) K(D * j + e, b) = -(fp.c[e][j] - fm.c[e][j]) * body.volume[j] / (xp - xm);
    }
    return K;
}

// Orthonormal rigid modes of the body, one per column (3D: 6, 2D: 3).
template <int D>
Eigen::MatrixXd rigid_modes(const Body<D>& body)
{
    using Mat = Eigen::MatrixXd;
    const int N = static_cast<int>(body.size()), nr = D == 3 ? 6 : 3;
    Mat R = Mat::Zero(D * N, nr);
    Vec<D> c{};
    for (int i = 0; i < N; ++i) c += body.x[i] * (1.0 / N);
    const int axes[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    for (int i = 0; i < N; ++i) {
        const Vec<D> r = body.x[i] - c;
        for (int d = 0; d < D; ++d) R(D * i + d, d) = 1;
        for (int q = 0; q < nr - D; ++q) {  // rotation in the plane (a, b): u_a = -r_b, u_b = r_a
            R(D * i + axes[q][0], D + q) = -r[axes[q][1]];
            R(D * i + axes[q][1], D + q) = r[axes[q][0]];
        }
    }
    return Eigen::HouseholderQR<Mat>(R).householderQ() * Mat::Identity(D * N, nr);
}

struct StiffnessSpectrum {
    Eigen::VectorXd lambda;   // eigenvalues of (K + K^T)/2, ascending [N/m]
    Eigen::MatrixXd vectors;  // eigenvectors, columns in the order of lambda
    double lambda_max = 0;    // max |lambda| [N/m]
    double asymmetry = 0;     // ||K - K^T||_F / ||K||_F
    double rigid_residual = 0;  // ||K R||_F / (lambda_max ||R||_F), R = rigid_modes(body)
    int rigid = 0;            // number of rigid modes (3D 6, 2D 3)
    int zero = 0;             // |lambda| < zero_tol lambda_max (the rigid modes included)
    int negative = 0;         // lambda < -zero_tol lambda_max
};

// Spectrum of K on `body` (see the file header); zero_tol relative to lambda_max.
template <int D>
StiffnessSpectrum stiffness_spectrum(const Eigen::MatrixXd& K, const Body<D>& body, double zero_tol)
{
    StiffnessSpectrum s;
    s.rigid = D == 3 ? 6 : 3;
    const Eigen::MatrixXd S = 0.5 * (K + K.transpose());
    s.asymmetry = (K - K.transpose()).norm() / K.norm();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
    s.lambda = eig.eigenvalues();
    s.vectors = eig.eigenvectors();
    s.lambda_max = s.lambda.cwiseAbs().maxCoeff();
    for (double l : s.lambda) {
        s.zero += std::abs(l) < zero_tol * s.lambda_max;
        s.negative += l < -zero_tol * s.lambda_max;
    }
    const Eigen::MatrixXd R = rigid_modes(body);
    s.rigid_residual = (K * R).norm() / (s.lambda_max * R.norm());
    return s;
}

}  // namespace pd
