// Quasi-static Newton-Raphson (solve/newton.hpp) against closed forms: the affine field of a 1D
// LPS bar and of a 3D PMB / LPS / PALS / correspondence block whose outer layers (2 delta thick) carry the affine
// displacement (spec/000b V12: an affine map is an exact discrete equilibrium when every free node
// and its partners have complete families), quadratic convergence on a finite stretch, load
// stepping, and the reports of failed solves.
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/solve/newton.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

using namespace pd;

namespace {
// Prescribes u = H x (all components) on the nodes within `layer` of the box faces; others start at 0.
template <int D>
Boundary<D> affine_frame(const Body<D>& body, const double (&H)[D][D], const Vec<D>& lo, const Vec<D>& hi, double layer)
{
    Boundary<D> bc;
    for (std::size_t i = 0; i < body.size(); ++i) {
        bool outer = false;
        for (int d = 0; d < D; ++d) outer = outer || body.x.c[d][i] < lo[d] + layer || body.x.c[d][i] > hi[d] - layer;
        if (!outer) continue;
        for (int d = 0; d < D; ++d) {
            double g = 0;
            for (int e = 0; e < D; ++e) g += H[d][e] * body.x.c[e][i];
            bc.prescribe({Prescribed::Kind::displacement, {static_cast<int>(i)}, d, TimeFunction::constant(g)});
        }
    }
    return bc;
}
template <int D>
double affine_error(const Body<D>& body, const Field<D>& u, const double (&H)[D][D])
{
    double err = 0, scale = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int d = 0; d < D; ++d) {
            double g = 0;
            for (int e = 0; e < D; ++e) g += H[d][e] * body.x.c[e][i];
            err = std::max(err, std::abs(u.c[d][i] - g));
            scale = std::max(scale, std::abs(g));
        }
    return err / scale;
}
void print(const char* name, const NewtonResult& r)
{
    std::printf("[ newton ] %s: %s, %d iterations, %d tangents, residuals", name, r.message.c_str(), r.iterations, r.tangents);
    for (double h : r.history) std::printf(" %.2e", h);
    std::printf("\n");
}
}  // namespace

// 1D LPS bar, L = 1 m, dx = 2 cm, delta = 3 dx, grips 2 delta thick with u = eps x. 1D bonds do not
// rotate, so the problem is linear: one Newton step, then a residual at round-off. Tolerance: the
// displacement error is K^-1 times the residual, cond(K) ~ (L/dx)^2 = 2500 times the tolerance 1e-11 (round-off
// floor of the relative residual here: ~1e-12).
TEST(Newton, LPSBarAffineFieldIn1D)
{
    const double dx = 0.02, delta = 3 * dx, eps = 1e-3;
    const Body<1> body = box<1>({{0}}, {{1.0}}, dx, 1e-4);
    const Bonds bonds = build_bonds(body, delta);
    LPS lps({Elastic::from_E_nu(200e9, 0.25), 1}, bonds);
    const double H[1][1] = {{eps}};
    const Boundary<1> bc = affine_frame<1>(body, H, {{0}}, {{1.0}}, 2 * delta);
    Newton<1, LPS> newton(body, bonds, lps);
    Field<1> u(body.size());
    const NewtonResult r = newton.solve(u, bc, 0, {.tol = 1e-11});
    print("1D LPS affine", r);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.iterations, 1);
    EXPECT_LT(affine_error(body, u, H), 2500 * 1e-11);
}

// 3D block 16 x 16 x 16 dx (4^3 free nodes), delta = 3.05 dx, frame of 2 delta carrying a general affine map H
// (stretch, shear, rotation-free). PMB (analytic tangent, Cholesky) and LPS (coloured FD tangent,
// CG). Geometrically nonlinear: a few Newton steps. Tolerance as above with cond ~ 16^2 < 100 x 1e-10.
TEST(Newton, AffineFieldIn3DPMBandLPS)
{
    const double dx = 1e-3;
    const Vec<3> lo{{0, 0, 0}}, hi{{16 * dx, 16 * dx, 16 * dx}};
    const Body<3> body = box<3>(lo, hi, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    const double H[3][3] = {{2e-3, 5e-4, 0}, {5e-4, -1e-3, 3e-4}, {0, 3e-4, 1e-3}};
    const Boundary<3> bc = affine_frame<3>(body, H, lo, hi, 2 * 3.05 * dx);
    const Elastic mat = Elastic::from_E_nu(100e9, 0.25);
    PMB pmb({.material = mat, .dim = 3}, bonds);
    LPS lps({.material = mat, .dim = 3}, bonds);
    Field<3> u(body.size());
    const NewtonResult rp = Newton<3, PMB>(body, bonds, pmb).solve(u, bc, 0, {.tol = 1e-10});
    print("3D PMB affine (Cholesky)", rp);
    ASSERT_TRUE(rp.converged) << rp.message;
    const double ep = affine_error(body, u, H);
    Field<3> u2(body.size());
    const NewtonResult rl = Newton<3, LPS>(body, bonds, lps).solve(u2, bc, 0, {.tol = 1e-10, .linear = LinearSolver::cg});
    print("3D LPS affine (CG)", rl);
    ASSERT_TRUE(rl.converged) << rl.message;
    const double el = affine_error(body, u2, H);
    std::printf("[ newton ] max |u - H x| / max |H x|: PMB %.3e, LPS %.3e\n", ep, el);
    EXPECT_LT(ep, 100 * 1e-10);
    EXPECT_LT(el, 100 * 1e-10);
}

// The same block and frame for PALS (coloured FD tangent, Cholesky: its tangent is symmetric) and
// correspondence (linear law, Littlewood C_hg = 0.02; FD tangent, sparse LU: the tangent is not
// symmetric, solve/linear_solver.hpp). Each free node (2 delta inside) and its partners (delta
// inside) have full, point-symmetric families, which under an affine map carry the same state: PALS
// the same force state per bond direction, correspondence the same P K^-1 (F is exact for an affine
// map, the hourglass term vanishes), so the pair forces of xi and -xi cancel and u = H x is the
// discrete equilibrium. Tolerance as above: the residual tolerance 1e-10 times cond ~ 16^2 < 100.
TEST(Newton, AffineFieldIn3DPALSandCorrespondence)
{
    const double dx = 1e-3;
    const Vec<3> lo{{0, 0, 0}}, hi{{16 * dx, 16 * dx, 16 * dx}};
    const Body<3> body = box<3>(lo, hi, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    const double H[3][3] = {{2e-3, 5e-4, 0}, {5e-4, -1e-3, 3e-4}, {0, 3e-4, 1e-3}};
    const Boundary<3> bc = affine_frame<3>(body, H, lo, hi, 2 * 3.05 * dx);
    const Elastic mat = Elastic::from_E_nu(100e9, 0.25);
    PALS pals({.material = mat}, body, bonds);
    Correspondence<3> corr({.material = mat, .C_hg = 0.02}, body, bonds);
    Field<3> u(body.size());
    const NewtonResult rp = Newton<3, PALS>(body, bonds, pals).solve(u, bc, 0, {.tol = 1e-10});
    print("3D PALS affine (Cholesky)", rp);
    ASSERT_TRUE(rp.converged) << rp.message;
    const double ep = affine_error(body, u, H);
    Field<3> u2(body.size());
    const NewtonResult rc = Newton<3, Correspondence<3>>(body, bonds, corr).solve(u2, bc, 0, {.tol = 1e-10, .linear = LinearSolver::lu});
    print("3D correspondence affine (LU)", rc);
    ASSERT_TRUE(rc.converged) << rc.message;
    const double ec = affine_error(body, u2, H);
    std::printf("[ newton ] max |u - H x| / max |H x|: PALS %.3e, correspondence %.3e\n", ep, ec);
    EXPECT_LT(ep, 100 * 1e-10);
    EXPECT_LT(ec, 100 * 1e-10);
}

// Finite stretch (10 %) of a PMB block held at both ends (all components): geometric terms make
// the problem nonlinear; with the exact tangent the residual falls quadratically,
// r_(k+1) <= C r_k^2, until round-off. Checked on the iterations with r_k < 1e-2 (asymptotic
// range) and r_(k+1) > 1e-13 (above round-off): log r_(k+1) / log r_k >= 1.8.
TEST(Newton, QuadraticConvergenceOnFiniteStretch)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{0, 0, 0}}, {{12 * dx, 4 * dx, 4 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 2.05 * dx);
    PMB pmb({.material = Elastic::from_E_nu(100e9, 0.25), .dim = 3}, bonds);
    Boundary<3> bc;
    NodeSet left = select<3>(body, [&](const Vec<3>& p) { return p[0] < 2 * dx; }, "left");
    NodeSet right = select<3>(body, [&](const Vec<3>& p) { return p[0] > 10 * dx; }, "right");
    bc.fix(left);
    bc.fix(right);
    bc.prescribe({Prescribed::Kind::displacement, right, 0, TimeFunction::constant(0.1 * 12 * dx)});
    std::ostringstream log;
    Field<3> u(body.size());
    const NewtonResult r = Newton<3, PMB>(body, bonds, pmb).solve(u, bc, 0, {.tol = 1e-13, .log = &log});
    print("3D PMB 10 % stretch", r);
    ASSERT_TRUE(r.converged) << r.message;
    int checked = 0;
    for (std::size_t k = 0; k + 1 < r.history.size(); ++k)
        if (r.history[k] < 1e-2 && r.history[k + 1] > 1e-13) {
            EXPECT_GE(std::log(r.history[k + 1]) / std::log(r.history[k]), 1.8) << "iteration " << k;
            ++checked;
        }
    EXPECT_GE(checked, 1);
    EXPECT_NE(log.str().find("newton it 1 residual"), std::string::npos);
    // Modified Newton (tangent kept) converges too, only linearly: more iterations, fewer tangents.
    Field<3> um(body.size());
    const NewtonResult rm = Newton<3, PMB>(body, bonds, pmb).solve(um, bc, 0, {.tol = 1e-10, .max_iter = 60, .reuse_tangent = true, .reuse_ratio = 0.5});
    print("3D PMB 10 % stretch, modified", rm);
    ASSERT_TRUE(rm.converged) << rm.message;
    EXPECT_LT(rm.tangents, rm.iterations);
}

// Load stepping: the 1D PMB bar (clamp delta thick, end traction p = 100 MPa ramped) is linear, so
// the field at level t is t times the final one; tolerance 1e-9 sits above the round-off floor
// 1e-16 L / (strain dx) = 1e-11 (dynamic_relaxation.hpp); the field error is at most cond(K) ~ 2500
// times it. And a solve that cannot finish reports it.
TEST(Newton, LoadStepsAndFailureReports)
{
    const double dx = 0.02, delta = 3 * dx;
    const Body<1> body = box<1>({{0}}, {{1.0}}, dx, 1e-4);
    const Bonds bonds = build_bonds(body, delta);
    PMB pmb({.material = Elastic::from_E_nu(200e9, 0.25), .dim = 1, .measure = 1e-4}, bonds);
    Boundary<1> bc;
    bc.fix(select<1>(body, [&](const Vec<1>& p) { return p[0] < delta; }, "clamp"));
    bc.traction(select<1>(body, [&](const Vec<1>& p) { return p[0] > 1.0 - dx; }, "end"), {{1e8}}, dx, TimeFunction::ramp(1.0, 1.0));
    Newton<1, PMB> newton(body, bonds, pmb);
    Field<1> u(body.size());
    const auto rs = newton.solve_steps(u, bc, {0.25, 0.5, 1.0}, {.tol = 1e-9});
    ASSERT_EQ(rs.size(), 3u);
    for (const auto& r : rs) EXPECT_TRUE(r.converged) << r.message;
    for (const auto& r : rs) print("load step", r);
    EXPECT_NEAR(newton.reaction()[0], -1e8 * 1e-4, 1e-8 * 1e4);  // reaction balances p A = 10 kN
    Field<1> half(body.size());
    newton.solve(half, bc, 0.5, {.tol = 1e-9});
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_NEAR(half.c[0][i], 0.5 * u.c[0][i], 2500 * 1e-9 * std::abs(u.c[0].back()));
    // max_iter = 0 with a non-zero residual: not converged, with a message.
    Field<1> z(body.size());
    const NewtonResult r0 = newton.solve(z, bc, 1.0, {.tol = 1e-12, .max_iter = 0});
    EXPECT_FALSE(r0.converged);
    EXPECT_NE(r0.message.find("not converged"), std::string::npos);
    // Unsupported body: no constraint, a net body force, Cholesky of a singular tangent.
    Boundary<1> free;
    free.body_force({{1e3}});
    Field<1> uf(body.size());
    const NewtonResult rf = newton.solve(uf, free, 0, {.tol = 1e-12, .max_iter = 5});
    print("unsupported bar", rf);
    EXPECT_FALSE(rf.converged);
    EXPECT_FALSE(rf.message.empty());
}
