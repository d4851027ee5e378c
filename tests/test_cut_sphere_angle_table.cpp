// The meteorite's geometry and load table (spec/000c sec. 4.1, 4.3):
// - cut_sphere (problems/common/cut_sphere.hpp): body and shell volumes against the closed forms
//   4/3 pi R^3 and 4/3 pi ((R + Delta)^3 - R^3) (the quadrature error of the cut cells only), the first
//   moment of the body zero (the grid is symmetric about the centre), the node classes;
// - AngleTable (pd/bc/angle_table.hpp): the table's values at its own angles, a smooth symmetric
//   load (cos phi) between them to the error of a cubic spline, zero slope at 0 and 180 deg without
//   those angles in the table, and the refusals; read_angle_table reads the CSV columns.
#include "pd/io/angle_table_file.hpp"
#include "problems/common/cut_sphere.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

using namespace pd;

namespace {
constexpr double pi = std::numbers::pi;
}

TEST(CutSphere, VolumesAreThoseOfTheSphereAndTheShell)
{
    const double R = 5e-3, dx = 0.6e-3;
    for (double shell : {dx, 0.1 * dx}) {
        const CutSphere s = cut_sphere(R, dx, shell);
        double vb = 0, vs = 0, mx = 0, my = 0, mz = 0;
        for (std::size_t i = 0; i < s.body.size(); ++i) {
            const double r = std::hypot(s.body.x.c[0][i], s.body.x.c[1][i], s.body.x.c[2][i]);
            if (s.in_shell(i)) {
                vs += s.body.volume[i];
                EXPECT_GE(r, R * (1 - 1e-12));  // a shell part's centroid lies in the shell
                EXPECT_LE(r, (R + shell) * (1 + 1e-12));
            } else {
                vb += s.body.volume[i], mx += s.body.volume[i] * s.body.x.c[0][i];
                my += s.body.volume[i] * s.body.x.c[1][i], mz += s.body.volume[i] * s.body.x.c[2][i];
                EXPECT_LT(r, R);
                EXPECT_LE(s.body.volume[i], dx * dx * dx * (1 + 1e-12));
            }
        }
        // Tolerances: the cut cells' 32 x 32 midpoint rule across the chords (its integrand has a square-root
        // edge where the sphere leaves a cell row), measured 1.5e-5 (body), 1.8e-5 and 1.9e-4 (shell of dx
        // and dx/10) and 1e-6 to 3e-6 (all with the dropped parts); each bound is 10 to 100 times that.
        const double Vb = 4 * pi * R * R * R / 3, Vs = 4 * pi * (std::pow(R + shell, 3) - R * R * R) / 3;
        EXPECT_LT(std::abs(vb - Vb) / Vb, 2e-4) << "shell " << shell;
        EXPECT_LT(std::abs(vb + vs + s.dropped_volume - Vb - Vs) / (Vb + Vs), 1e-4) << "shell " << shell;
        EXPECT_LT(std::abs(vs - Vs) / Vs, 2e-2) << "shell " << shell;
        EXPECT_LT(s.dropped_volume, 1e-3 * Vs);
        for (double m : {mx, my, mz}) EXPECT_LT(std::abs(m), 1e-12 * Vb * R);  // symmetric grid: cancels to round-off
        EXPECT_GT(s.cut_cells, 0);
        EXPECT_EQ(s.surface.size(), s.n_body);
        EXPECT_GT(s.body.size(), s.n_body);
    }
    EXPECT_THROW(cut_sphere(R, 0, dx), std::invalid_argument);
    EXPECT_THROW(cut_sphere(R, dx, -1), std::invalid_argument);
    EXPECT_THROW(cut_sphere(R, 2 * R, dx), std::invalid_argument);
}

TEST(AngleTable, InterpolatesASymmetricLoadWithACubicSpline)
{
    std::vector<double> deg, val;
    for (int k = 0; k <= 24; ++k) deg.push_back(7.5 * k), val.push_back(std::cos(7.5 * k * pi / 180));
    const AngleTable t(deg, val);
    for (std::size_t k = 0; k < deg.size(); ++k) EXPECT_NEAR(t(deg[k] * pi / 180), val[k], 1e-14);
    double worst = 0;
    for (int q = 0; q <= 1800; ++q) worst = std::max(worst, std::abs(t(q * pi / 1800) - std::cos(q * pi / 1800)));
    EXPECT_LT(worst, 2e-6);  // h^4 |f''''| / 384 with h = 7.5 deg: 7.7e-7
    EXPECT_GT(worst, 1e-9);  // and it is an interpolation, not the cosine
    // Without 0 and 180 deg in the table: still symmetric, zero slope at the axis.
    std::vector<double> d2, v2;
    for (int k = 0; k < 25; ++k) d2.push_back(3 + 7 * k), v2.push_back(std::cos((3 + 7 * k) * pi / 180));
    const AngleTable u(d2, v2);
    const double h = 1e-4;  // one-sided slopes: O(h u'') = 1e-4 for zero slope; the cosine's own slope at 3 deg is 0.05
    EXPECT_NEAR((u(h) - u(0)) / h, 0, 1e-3);
    EXPECT_NEAR((u(pi) - u(pi - h)) / h, 0, 1e-3);
    EXPECT_NEAR(u(0), 1, 1e-3);
    EXPECT_NEAR(u(-0.3), u(0.3), 1e-15);  // folded
    EXPECT_THROW(AngleTable({0}, {1}), std::invalid_argument);
    EXPECT_THROW(AngleTable({0, 10, 5}, {1, 1, 1}), std::invalid_argument);
    EXPECT_THROW(AngleTable({0, 190}, {1, 1}), std::invalid_argument);
    EXPECT_THROW(AngleTable({0, 90}, {1, NAN}), std::invalid_argument);
}

TEST(AngleTable, ReadsTheColumnsOfACsv)
{
    const auto path = pd_test::scratch_dir() / "flux.csv";
    std::ofstream(path) << "angle_deg,Q_W_m2\n0,2\n90,1\n180,0.5\n";
    const AngleTable t = read_angle_table(path, "Q_W_m2");
    EXPECT_NEAR(t(pi / 2), 1, 1e-14);
    EXPECT_THROW(read_angle_table(path, "p_Pa"), std::runtime_error);
    std::ofstream(path) << "angle_deg,Q_W_m2\n90,1\n10,2\n";
    EXPECT_THROW(read_angle_table(path, "Q_W_m2"), std::runtime_error);
}
