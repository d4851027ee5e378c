// The Lame point laws of laws/elastic.hpp against hand values: uniaxial stretch F = diag(1 + e, 1, 1)
// gives eps_xx = e, E_xx = e + e^2/2 and sigma_xx = (lambda + 2G) e, sigma_yy = sigma_zz = lambda e; a
// simple shear F = I + g e_x (x) e_y gives eps_xy = g/2, E_xy = g/2, E_yy = g^2/2 and sigma_xy = G g.
// Tolerances: round-off only (a few operations each): 1e-15 on strains of order 1e-2, 1e-12 G on
// stresses of order 1e-2 G.
#include "pd/laws/elastic.hpp"

#include <gtest/gtest.h>

using namespace pd::laws;

TEST(LawsElastic, LameFormUnderUniaxialStretchAndSimpleShear)
{
    const double lambda = 80e9, G = 50e9, e = 1e-2, g = 3e-2;
    Mat3 F = Mat3::Identity();
    F(0, 0) = 1 + e;
    const Mat3 s = lame_stress(small_strain(F), lambda, G);
    EXPECT_NEAR(s(0, 0), (lambda + 2 * G) * e, 1e-12 * G);
    EXPECT_NEAR(s(1, 1), lambda * e, 1e-12 * G);
    EXPECT_NEAR(s(2, 2), lambda * e, 1e-12 * G);
    EXPECT_NEAR(green_lagrange(F)(0, 0), e + e * e / 2, 1e-15);

    Eigen::Matrix2d S = Eigen::Matrix2d::Identity();  // 2D, the same templates
    S(0, 1) = g;
    const Eigen::Matrix2d eps = small_strain(S), E = green_lagrange(S);
    EXPECT_NEAR(eps(0, 1), g / 2, 1e-15);
    EXPECT_NEAR(eps(1, 0), g / 2, 1e-15);
    EXPECT_NEAR(E(0, 1), g / 2, 1e-15);
    EXPECT_NEAR(E(1, 1), g * g / 2, 1e-15);
    EXPECT_NEAR(lame_stress(eps, lambda, G)(0, 1), G * g, 1e-12 * G);
    EXPECT_NEAR(lame_stress(eps, lambda, G)(0, 0), 0.0, 1e-12 * G);
}
