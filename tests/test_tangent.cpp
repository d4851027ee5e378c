// Tangent stiffness (solve/tangent.hpp) against a dense, uncoloured central-difference tangent
// written here (one dof perturbed at a time; it calls only internal_force, never the code under
// test): PMB's analytic tangent, the coloured tangent of LPS, PALS and correspondence, symmetry
// of the variational models, validity and count of the colourings on a cubic lattice.
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/solve/tangent.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <set>

using namespace pd;

namespace {
constexpr double E = 100e9, nu = 0.3, dx = 1e-3;  // [Pa], [-], [m]

// 6 x 5 x 4 block, delta = 2.05 dx (small, so a dense matrix is cheap; still has interior nodes).
struct Block {
    Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 5 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.05 * dx);
    Field<3> y;
    // A smooth non-affine deformation of a few per cent (geometric terms matter).
    Block() : y(body.size())
    {
        for (std::size_t i = 0; i < body.size(); ++i) {
            const double X = body.x.c[0][i], Y = body.x.c[1][i], Z = body.x.c[2][i];
            y.c[0][i] = X + 0.03 * X + 0.02 * Y * Y / dx * 0.1 + 0.01 * Z;
            y.c[1][i] = Y - 0.01 * Y + 0.02 * std::sin(X / (3 * dx)) * dx;
            y.c[2][i] = Z + 0.015 * X * Y / (6 * dx) - 0.01 * Z;
        }
    }
};

// Dense reference: K(:, (a,d)) = -V_i (f(y + h e_ad) - f(y - h e_ad)) / (h_+ + h_-), all dofs.
template <class Model>
Eigen::MatrixXd dense_fd(Model& model, const Body<3>& body, const Bonds& bonds, const Field<3>& y, double h)
{
    const std::size_t n = body.size();
    Eigen::MatrixXd K(3 * n, 3 * n);
    Field<3> yp = y, fp, fm;
    for (std::size_t a = 0; a < n; ++a)
        for (int d = 0; d < 3; ++d) {
            yp.c[d][a] = y.c[d][a] + h;
            const double hp = yp.c[d][a] - y.c[d][a];
            internal_force(model, bonds, yp, fp);
            yp.c[d][a] = y.c[d][a] - h;
            const double hm = y.c[d][a] - yp.c[d][a];
            internal_force(model, bonds, yp, fm);
            yp.c[d][a] = y.c[d][a];
            for (std::size_t i = 0; i < n; ++i)
                for (int e = 0; e < 3; ++e) K(3 * i + e, 3 * a + d) = -body.volume[i] * (fp.c[e][i] - fm.c[e][i]) / (hp + hm);
        }
    return K;
}

template <class Model>
double coloured_vs_dense(Model& model, const Block& b, int reach)
{
    const DofMap dofs = DofMap::all(3 * b.body.size());
    const double h = tangent_step(b.bonds, b.y);
    const Eigen::MatrixXd Kc = Eigen::MatrixXd(tangent_fd(model, b.body, b.bonds, b.y, dofs, colour_bond_graph(b.bonds, reach), h));
    const Eigen::MatrixXd Kd = dense_fd(model, b.body, b.bonds, b.y, h);
    return (Kc - Kd).cwiseAbs().maxCoeff() / Kd.cwiseAbs().maxCoeff();
}
double asymmetry(const Eigen::MatrixXd& K) { return (K - K.transpose()).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff(); }
}  // namespace

// Analytic PMB tangent vs the dense central difference. Tolerance 1e-6: the difference's truncation
// error (h/L)^2 ~ 1e-9 and rounding ~1e-9 (tangent.hpp) are far below it, while a missing geometric
// term (L/|Y| n n^T vs I, ~3 % here) or a wrong sign is far above.
TEST(Tangent, PMBAnalyticEqualsDenseFiniteDifference)
{
    Block b;
    PMB pmb({.material = Elastic::from_E_nu(E, 0.25), .dim = 3}, b.bonds);
    const Eigen::MatrixXd Ka = Eigen::MatrixXd(tangent_pmb(pmb, b.body, b.bonds, b.y, DofMap::all(3 * b.body.size())));
    const Eigen::MatrixXd Kd = dense_fd(pmb, b.body, b.bonds, b.y, tangent_step(b.bonds, b.y));
    const double err = (Ka - Kd).cwiseAbs().maxCoeff() / Kd.cwiseAbs().maxCoeff();
    std::printf("[ tangent ] PMB analytic vs dense FD: %.3e\n", err);
    EXPECT_LT(err, 1e-6);
    EXPECT_LT(asymmetry(Ka), 1e-14);  // V_i c V_j / L both ways: round-off only
}

// The coloured tangent perturbs many nodes at once, but each row sees only one of them, and that
// row's force is computed from exactly the same numbers as in the dense sweep: equal to round-off
// (in fact bit for bit). With reach 1 (the bond-based distance) a state-based row sees two perturbed
// nodes: the test of the reach-2 derivation.
TEST(Tangent, ColouredEqualsDenseForStateBasedModels)
{
    Block b;
    const Elastic mat = Elastic::from_E_nu(E, nu);
    LPS lps({.material = mat, .dim = 3}, b.bonds);
    PALS pals({.material = mat}, b.body, b.bonds);
    Correspondence<3> corr({.material = mat, .C_hg = 0.02}, b.body, b.bonds);
    const double e_lps = coloured_vs_dense(lps, b, 2), e_pals = coloured_vs_dense(pals, b, 2), e_corr = coloured_vs_dense(corr, b, 2);
    const double e_lps_r1 = coloured_vs_dense(lps, b, 1);
    std::printf("[ tangent ] coloured vs dense: LPS %.3e, PALS %.3e, correspondence %.3e; LPS with reach 1: %.3e\n", e_lps,
                e_pals, e_corr, e_lps_r1);
    EXPECT_LT(e_lps, 1e-13);
    EXPECT_LT(e_pals, 1e-13);
    EXPECT_LT(e_corr, 1e-13);
    EXPECT_GT(e_lps_r1, 1e-3);
    static_assert(tangent_reach<PMB>() == 1 && tangent_reach<LPS>() == 2 && tangent_reach<PALS>() == 2 &&
                  tangent_reach<Correspondence<3>>() == 2);
}

// Variational models: K is a Hessian, symmetric up to the difference error (1e-6, as above).
TEST(Tangent, SymmetricForVariationalModels)
{
    Block b;
    const Elastic mat = Elastic::from_E_nu(E, nu);
    LPS lps({.material = mat, .dim = 3}, b.bonds);
    PALS pals({.material = mat}, b.body, b.bonds);
    const DofMap dofs = DofMap::all(3 * b.body.size());
    const Colouring col = colour_bond_graph(b.bonds, 2);
    const double a_lps = asymmetry(Eigen::MatrixXd(tangent_fd(lps, b.body, b.bonds, b.y, dofs, col)));
    const double a_pals = asymmetry(Eigen::MatrixXd(tangent_fd(pals, b.body, b.bonds, b.y, dofs, col)));
    std::printf("[ tangent ] asymmetry: LPS %.3e, PALS %.3e\n", a_lps, a_pals);
    EXPECT_LT(a_lps, 1e-6);
    EXPECT_LT(a_pals, 1e-6);
}

// A colouring is valid when no reach set holds two nodes of one colour; checked here by brute force
// over the reach sets recomputed from the partner lists. Counts on the 20^3 cubic lattice with
// delta = 3.05 dx (reported in tangent.hpp); lower bounds: a family (123 nodes) is a clique at
// reach 1, and the 2-hop ball of a node (every pair within 4 hops) at reach 2.
TEST(Tangent, ColouringOfCubicLatticeIsValid)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{20 * dx, 20 * dx, 20 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    for (int reach : {1, 2}) {
        const Colouring c = colour_bond_graph(bonds, reach);
        const std::size_t centre = 10 * 400 + 10 * 20 + 10;  // interior node
        std::set<int> ball{static_cast<int>(centre)};
        for (int hop = 0; hop < reach; ++hop) {
            std::set<int> grown = ball;
            for (int i : ball)
                for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k) grown.insert(bonds.partner[k]);
            ball = grown;
        }
        std::printf("[ tangent ] cubic lattice 20^3, delta = 3.05 dx, reach %d: %d colours (reach set %zu nodes)\n", reach,
                    c.count, ball.size());
        EXPECT_EQ(ball.size(), static_cast<std::size_t>(c.offset[centre + 1] - c.offset[centre]));
        EXPECT_GE(c.count, static_cast<int>(ball.size()));
        bool valid = true;
        for (std::size_t i = 0; i < body.size() && valid; ++i) {
            std::set<int> seen;
            for (std::int64_t q = c.offset[i]; q < c.offset[i + 1]; ++q) valid = valid && seen.insert(c.colour[c.rows[q]]).second;
        }
        EXPECT_TRUE(valid);
    }
}
