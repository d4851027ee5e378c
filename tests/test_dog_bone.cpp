// The dog-bone specimen of problems/common/dog_bone.hpp (the Hopkinson case, spec/000c sec. 3.2): the
// kept cells' volumes plus the dropped slivers' equal the outline's exact area (gauge rectangle,
// circular fillets in closed form, grips) times the thickness; the gauge holds whole cells with a node
// row on y = 0; every node lies inside the outline; cut cells sit at their covered area's centroid.
#include "problems/common/dog_bone.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd;

namespace {
// Exact area of the outline over |x| <= X [m^2]: 4 int_0^X h(x) dx, the fillet part from
// int_0^L sqrt(R^2 - s^2) ds = (L sqrt(R^2 - L^2) + R^2 asin(L/R)) / 2.
double exact_area(const DogBoneShape& s, double X)
{
    const double R = s.fillet_radius, L = s.fillet_length();
    const double fillet = (0.5 * s.gauge_width + R) * L - 0.5 * (L * std::sqrt(R * R - L * L) + R * R * std::asin(L / R));
    return 4 * (0.25 * s.gauge_width * s.gauge_length + fillet + 0.5 * s.grip_width * (X - 0.5 * s.gauge_length - L));
}
}  // namespace

// Midpoint rule with 64 points per cell across the fillet's curvature and the two kinks of h(x): a
// relative error of order (hx/64)^2 / R^2 per cut cell, far below 1e-6 of the whole.
TEST(DogBone, VolumesAddUpToTheOutlineTimesTheThickness)
{
    for (double dx : {0.328e-3, 0.656e-3}) {
        DogBoneShape s;
        s.x_end = (std::lround(31e-3 / dx) + 0.5) * dx;  // the outermost cells end exactly at +-x_end
        const DogBone d = dog_bone(s, dx);
        double V = 0;
        for (double v : d.body.volume) V += v;
        const double exact = exact_area(s, s.x_end) * s.thickness;
        EXPECT_NEAR((V + d.dropped_volume) / exact, 1.0, 1e-6) << dx;
        EXPECT_GT(d.cut_cells, 0);
        EXPECT_LT(d.dropped_volume, 0.01 * exact);
    }
}

TEST(DogBone, GaugeOfWholeCellsWithARowOnTheAxisAndNodesInside)
{
    DogBoneShape s;
    const DogBone d = dog_bone(s, 1e-3 / 3.05);
    const long ny = std::lround(s.gauge_width / d.hy);
    EXPECT_EQ(ny % 2, 1);
    EXPECT_NEAR(ny * d.hy, s.gauge_width, 1e-15);
    EXPECT_NEAR(std::lround(s.thickness / d.hz) * d.hz, s.thickness, 1e-15);
    long on_axis = 0;
    for (std::size_t i = 0; i < d.body.size(); ++i) {
        const double x = d.body.x.c[0][i], y = d.body.x.c[1][i];
        EXPECT_LE(std::abs(y), s.half_width(x) + 1e-12) << i;
        if (std::abs(x) < 0.5 * s.gauge_length - d.hx) {  // inside the gauge: whole cells
            EXPECT_NEAR(d.body.volume[i], d.hx * d.hy * d.hz, 1e-12 * d.hx * d.hy * d.hz) << i;
            on_axis += y == 0;
        }
        if (i > 0 && d.body.x.c[2][i] == d.body.x.c[2][i - 1] && std::abs(y - d.body.x.c[1][i - 1]) < 0.5 * d.hy) {
            EXPECT_GT(x, d.body.x.c[0][i - 1]) << "x fastest, node " << i;
        }
    }
    EXPECT_GT(on_axis, 0);
}

// A cell cut by a straight grip edge: its node sits at the middle of the covered strip.
TEST(DogBone, CutCellNodeAtTheCentroidOfItsCoveredArea)
{
    DogBoneShape s;
    s.grip_width = 9.5e-3;  // the grip edge y = 4.75 mm cuts the row of cells above the gauge's
    const DogBone d = dog_bone(s, 1e-3 / 3.05, 0.0);
    bool seen = false;
    for (std::size_t i = 0; i < d.body.size(); ++i) {
        const double x = d.body.x.c[0][i], y = d.body.x.c[1][i];
        if (x < 20e-3 || y < 0) continue;
        const double row = std::round(y / d.hy), y0 = (row - 0.5) * d.hy;
        if (std::abs(y - row * d.hy) < 1e-12) continue;  // a whole cell
        if (y0 >= 0.5 * s.grip_width) continue;
        EXPECT_NEAR(y, 0.5 * (y0 + 0.5 * s.grip_width), 1e-12) << i;
        EXPECT_NEAR(d.body.volume[i], d.hx * (0.5 * s.grip_width - y0) * d.hz, 1e-9 * d.hx * d.hy * d.hz) << i;
        seen = true;
    }
    EXPECT_TRUE(seen);
}
