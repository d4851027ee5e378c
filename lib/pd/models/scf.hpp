// Shear correction factor (SCF) of LPS, per node (spec/000b sec. 1.3; thesis eq. 4.14:
// alpha(x) = SCF(x) alpha_LPS), computed as Peridigm's
// material_utilities.cxx::computeShearCorrectionFactor does:
//   1. gamma = 1e-6; the node x_i stays fixed and each partner moves by a pure shear of xi:
//        XY: u_x = gamma xi_y, u_y = gamma xi_x;  ZX: u_z = gamma xi_x, u_x = gamma xi_z;
//        YZ: u_y = gamma xi_z, u_z = gamma xi_y   (2D: XY only, the one in-plane shear mode);
//   2. per mode, theta = (D/m_i) sum_j omega |xi| e V_j with the node's own m_i, e = |Y| - |xi|,
//      and N = sum_j omega e_d^2 V_j with e_d = e - theta |xi| / D;
//   3. N_max = max over modes (the largest N gives the smallest correction);
//   4. SCF = 4 gamma^2 m_i / (a_D N_max), a_3 = 15 (Peridigm), a_2 = 8 (derived below).
// Continuum values (omega = omega(|xi|), n = xi/|xi|, e = |xi| n.eps.n to first order in gamma):
// the XY shear has eps_xy = eps_yx = gamma, so e = 2 gamma |xi| n_x n_y and theta = 0 on a full
// ball (n_x n_y is odd). Then N = 4 gamma^2 <n_x^2 n_y^2> m with <.> the mean over directions:
//   3D sphere: <n_x^2 n_y^2> = 1/15, N = 4 gamma^2 m / 15, and W_d = (alpha/2) N = 2 G gamma^2
//     with alpha = 15 G / m: the classical G eps:eps = 2 G gamma^2 (Peridigm, spec 1.3).
//   2D disc: n = (cos p, sin p), <cos^2 p sin^2 p> = (1/2 pi) int_0^2pi cos^2 sin^2 dp = 1/8,
//     N = 4 gamma^2 m / 8 = gamma^2 m / 2, and W_d = (alpha/2) N = 2 G gamma^2 with the 2D split
//     e_d = e - theta |xi|/2 and alpha = 8 G / m (lps.hpp): the classical in-plane G eps:eps.
// Hence SCF = 4 gamma^2 m / (a_D N_max) is 1 for a full continuum ball in either dimension, and
// LPS with alpha_i = SCF_i a_D G / m_i gives exactly the classical 2 G gamma^2 in the mode of N_max.
// Lattice values (tests/test_scf.cpp): bulk node of the cubic lattice, full volumes, delta = 3 dx
// (or 3.05 dx, the same 122 neighbours): SCF = 118/131 = 0.90076 (spec V12: 0.9008); square
// lattice, delta = 3 dx: SCF = 85/82 = 1.03659. Surface nodes of a cube: edges and corners rise
// above the bulk (0.97674, 1.97109; 2D edge 1.25, corner 2.48705), but a face centre falls below
// it (0.81783), a lattice effect: the node's own layer counts with full volume (halved, the face
// gives 118/131 again, as the continuum half-ball gives 1).
// Deviations from Peridigm, documented: e is evaluated cancellation-free as
// (|Y|^2 - |xi|^2)/(|Y| + |xi|) (same number in exact arithmetic); when the bonds carry a damage
// array, theta and N sum only intact bonds (Peridigm's copy ignores damage), while m_i sums the
// whole family as LPS's m_i does under its reference rule, or only the intact bonds with
// intact_m = true (LPS's default intact rule, lps.hpp). 1D has no deviatoric part (a_1 = 0): SCF = 1.
// A node whose N_max is 0 (no intact bond, or m_i = 0) gets SCF = 1, and so does a node whose N_max
// lies below scf_degenerate times the full-ball value 4 gamma^2 m_i / a_D: a family left with a few
// bonds that no probe shear stretches to first order in gamma (bonds along one line or in a plane
// normal to every probe), whose N_max is O(gamma^2) of that value or round-off; SCF would reach
// 1e12-1e43 and alpha_i with it, and the model would blow up at any step
// (problems/3d/stability_atlas.cpp, 90 % of the pairs broken).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

// Peridigm's probe shear strain [-]: small enough that e is linear in it to ~1e-6 relative.
inline constexpr double scf_gamma = 1e-6;
// N_max below this fraction of the full-ball value is a degenerate shear mode (header): a family no
// probe stretches to first order has N_max ~ gamma^2 = 1e-12 of it (or round-off), real modes far more.
inline constexpr double scf_degenerate = 1e-8;

namespace detail {

// a_D of alpha = a_D G / m: 1 / <n_x^2 n_y^2> over the unit sphere (15) or circle (8).
inline double scf_shear_constant(int dim) { return dim == 3 ? 15.0 : dim == 2 ? 8.0 : 0.0; }

// N = sum omega e_d^2 V over node i's (intact) bonds under the pure shear u_a = gamma xi_b,
// u_b = gamma xi_a, with theta from the node's weighted volume m (steps 2 of the header).
template <int D>
double scf_mode_norm(const Bonds& b, const Field<D>& x, std::size_t i, int a, int c, double gamma, double m)
{
    const Vec<D> xi_i = x[i];
    // e = |Y| - |xi| for bond k, with Y = xi + u(xi).
    auto extension = [&](std::int64_t k) {
        const Vec<D> xi = x[b.partner[k]] - xi_i;
        Vec<D> Y = xi;
        Y[a] += gamma * xi[c];
        Y[c] += gamma * xi[a];
        const double L = norm(xi), l = norm(Y);
        return (dot(Y, Y) - dot(xi, xi)) / (l + L);
    };
    double sum_theta = 0;
    for_intact_bonds(b, i, [&](std::int64_t k, int) { sum_theta += b.omega[k] * b.length[k] * extension(k) * b.volume[k]; });
    const double theta = D * sum_theta / m;  // (4.8) with the node's own m
    double N = 0;
    for_intact_bonds(b, i, [&](std::int64_t k, int) {
        const double ed = extension(k) - theta * b.length[k] / D;  // (4.9), e_d = e - theta |xi| / D
        N += b.omega[k] * ed * ed * b.volume[k];
    });
    return N;
}

}  // namespace detail

// SCF_i for every node (header steps 1-4). x: reference positions [m]; dim must equal D.
// gamma: probe shear strain [-], Peridigm's 1e-6 by default. intact_m: m_i over the intact bonds
// only (same as the whole family when the bonds carry no damage).
template <int D>
std::vector<double> shear_correction_factor(const Bonds& b, const Field<D>& x, int dim, double gamma = scf_gamma,
                                            bool intact_m = false)
{
    if (dim != D) throw std::invalid_argument("shear_correction_factor: dim " + std::to_string(dim) + " != field dimension " + std::to_string(D));
    if (x.size() != b.nodes()) throw std::invalid_argument("shear_correction_factor: positions and bonds differ in node count");
    if (!(gamma > 0)) throw std::invalid_argument("shear_correction_factor: gamma must be > 0");
    std::vector<double> scf(b.nodes(), 1.0);
    if constexpr (D >= 2) {
        // Shear planes (a, c): XY, ZX, YZ as Peridigm; 2D keeps XY only.
        constexpr int modes = D == 3 ? 3 : 1;
        static constexpr int plane[3][2] = {{0, 1}, {2, 0}, {1, 2}};
        const double a_D = detail::scf_shear_constant(D);
        parallel_for(b.nodes(), [&](std::size_t i) {
            double m = 0;  // weighted volume over the whole family or the intact bonds, as LPS
            const bool skip_broken = intact_m && b.has_damage();
            for_family(b, i, [&](std::int64_t k, int) {
                if (!skip_broken || b.intact[k]) m += b.omega[k] * b.length[k] * b.length[k] * b.volume[k];
            });
            if (!(m > 0)) return;
            double N_max = 0;
            for (int md = 0; md < modes; ++md)
                N_max = std::max(N_max, detail::scf_mode_norm<D>(b, x, i, plane[md][0], plane[md][1], gamma, m));
            const double full_ball = 4 * gamma * gamma * m / a_D;  // N_max of a full continuum ball
            if (N_max > scf_degenerate * full_ball) scf[i] = 4 * gamma * gamma * m / (a_D * N_max);  // step 4
        });
    }
    return scf;
}

}  // namespace pd
