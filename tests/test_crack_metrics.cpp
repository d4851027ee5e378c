// Crack metrics (lib/pd/damage/crack_metrics.hpp) on synthetic damage fields whose answers are
// known by construction: a straight crack at 30 degrees, a Y branch at a known point with known
// branch angles, tip histories of known speed, a crack centreline with known offsets, and level
// curves of linear fields (marching squares is exact for a linear field).
#include "problems/common/crack/crack_metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

using namespace pd;
using namespace pd::crack;
namespace {

constexpr double pi = std::numbers::pi;
constexpr double h = 1e-3;  // lattice spacing [m]

// Lattice x = i h (i = 0..nx-1), y = (j + 0.5) h (j = -ny..ny-1): the line y = 0 runs between two
// node rows, as the pre-crack of the glass plate does.
Field<2> lattice(long nx, long ny)
{
    Field<2> x;
    for (long j = -ny; j < ny; ++j)
        for (long i = 0; i < nx; ++i) x.c[0].push_back(i * h), x.c[1].push_back((j + 0.5) * h);
    return x;
}

double segment_distance(const Vec<2>& p, const Vec<2>& a, const Vec<2>& b)
{
    const Vec<2> ab = b - a;
    const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    return norm(p - (a + t * ab));
}

// phi = 0.5 on the nodes within w of any of the segments, 0 elsewhere.
std::vector<double> band(const Field<2>& x, const std::vector<std::pair<Vec<2>, Vec<2>>>& segs, double w)
{
    std::vector<double> phi(x.size(), 0.0);
    for (std::size_t i = 0; i < x.size(); ++i)
        for (const auto& [a, b] : segs)
            if (segment_distance(x[i], a, b) <= w) phi[i] = 0.5;
    return phi;
}

Vec<2> v2(double a, double b) { return Vec<2>{{a, b}}; }

}  // namespace

// Crack from the origin at 30 degrees, 60 mm long, band half-width 0.8 h. Tip: the farthest band
// node projects between L - h (a 1.6 h wide band holds a node in every h of its length) and
// L + 0.8 h (the band's end cap). Angle: the band's node set is symmetric about the line up to
// lattice aliasing, whose effect on the axis is below 0.5 degree for L = 60 h (measured 0.03).
TEST(CrackMetrics, StraightCrackTipAndAngle)
{
    const Field<2> x = lattice(100, 50);
    const double a = pi / 6, L = 60 * h;
    const Vec<2> d = v2(std::cos(a), std::sin(a));
    const std::vector<double> phi = band(x, {{v2(0, 0), L * d}}, 0.8 * h);
    const Tip tip = tip_along(x, phi, v2(0, 0), d);
    ASSERT_GE(tip.node, 0);
    EXPECT_GE(tip.advance, L - h);
    EXPECT_LE(tip.advance, L + 0.8 * h);
    const Tip far = tip_farthest(x, phi, v2(0, 0));
    EXPECT_LE(far.advance, L + 0.8 * h);
    EXPECT_GE(far.advance, tip.advance);
    EXPECT_NEAR(principal_angle(damaged_points(x, phi)) * 180 / pi, 30.0, 0.5);
    // Points exactly on a line at -68 degrees: the axis is exact (round-off 1e-12).
    std::vector<Vec<2>> line;
    for (int k = 0; k < 20; ++k) line.push_back(v2(k * std::cos(-68 * pi / 180), k * std::sin(-68 * pi / 180)));
    EXPECT_NEAR(principal_angle(line) * 180 / pi, -68.0, 1e-12);
    // A mask excluding the crack leaves no tip; below-threshold damage is no tip either.
    EXPECT_EQ(tip_along(x, phi, v2(0, 0), d, tip_threshold, Mask(x.size(), 0)).node, -1);
    EXPECT_EQ(tip_along(x, std::vector<double>(x.size(), 0.3), v2(0, 0), d).node, -1);
}

// Stem y = 0 from x = 0 to 40 mm, branches at +-15 degrees from (40 mm, 0), 40 mm long, band
// half-width 0.75 h (two node rows along the stem). The branch point is found within 2 h: each
// bin's cluster centre lies within h/2 of its line, and an error e in the centre offsets moves
// the intersection of two lines at +-15 degrees by e / (2 tan 15) = 0.93 h for e = h/2. Branch
// angles within 3 degrees: centre errors of h/2 over the 10-bin (10 h) fit. (Measured: point
// (40.05, 0.00) mm, angles +-15.09 degrees.)
TEST(CrackMetrics, YBranchPointAndAngles)
{
    const Field<2> x = lattice(100, 30);
    const double b = 15 * pi / 180, xb = 40 * h;
    const Vec<2> P = v2(xb, 0);
    const auto segs = std::vector<std::pair<Vec<2>, Vec<2>>>{
        {v2(0, 0), P}, {P, P + 40 * h * v2(std::cos(b), std::sin(b))}, {P, P + 40 * h * v2(std::cos(b), -std::sin(b))}};
    const std::vector<double> phi = band(x, segs, 0.75 * h);
    const Branching br = find_branching(x, phi, v2(0, 0), v2(1, 0), h, 0.0);
    ASSERT_TRUE(br.found);
    EXPECT_NEAR(br.point[0], xb, 2 * h);
    EXPECT_NEAR(br.point[1], 0.0, 2 * h);
    EXPECT_NEAR(br.angle_upper * 180 / pi, 15.0, 3.0);
    EXPECT_NEAR(br.angle_lower * 180 / pi, -15.0, 3.0);
    EXPECT_GT(br.s_split, br.s);  // the split is seen downstream of the branch point

    // A straight crack has no branch; nor has one with a side crack shorter than `confirm` bins
    // (a 3-node arrested crack 4 h above the main one).
    const std::vector<double> straight = band(x, {{v2(0, 0), v2(80 * h, 0)}}, 0.75 * h);
    EXPECT_FALSE(find_branching(x, straight, v2(0, 0), v2(1, 0), h, 0.0).found);
    std::vector<double> side = straight;
    for (std::size_t i = 0; i < x.size(); ++i)
        if (std::abs(x.c[1][i] - 4.5 * h) < 1e-9 && x.c[0][i] > 29.5 * h && x.c[0][i] < 32.5 * h) side[i] = 0.5;
    EXPECT_FALSE(find_branching(x, side, v2(0, 0), v2(1, 0), h, 0.0).found);
}

// Tip at rest at 50 mm until t0 = 6 us, then moving at v = 1000 m/s along x; samples every 50 ns.
TEST(CrackMetrics, TipHistorySpeedAndInitiation)
{
    const double dt = 50e-9, t0 = 6e-6, v = 1000, window = 2e-6;
    TipHistory exact, stepped;
    for (int l = 0; l <= 600; ++l) {
        const double t = l * dt, a = 0.05 + v * std::max(0.0, t - t0);
        exact.push(t, Tip{0, v2(a, 0), a});
        const double q = h * std::floor(a / h + 1e-9);  // quantised to the lattice (1e-9: round-off at node positions)
        stepped.push(t, Tip{0, v2(q, 0), q});
    }
    // Initiation: the first sample with advance >= 50 mm + 0.99 h is at 6.99 us -> sample 7.00 us.
    EXPECT_NEAR(exact.initiation_time(0.99 * h), 7.0e-6, 1e-12);
    // Crossing 60 mm at t0 + 10 mm / v = 16 us (linear between samples: exact up to round-off).
    EXPECT_NEAR(exact.time_at_advance(0.06), 16e-6, 1e-15);
    EXPECT_TRUE(std::isnan(exact.time_at_advance(1.0)));
    // Windows that lie wholly after t0 give v to round-off (1e-9 relative).
    for (const SpeedSample& s : exact.speed(window))
        if (s.t - window / 2 >= t0) {
            EXPECT_NEAR(s.v, v, 1e-9 * v);
        }
    EXPECT_NEAR(exact.max_speed(window), v, 1e-9 * v);
    EXPECT_NEAR(exact.mean_speed(window, t0, 30e-6), v, 1e-9 * v);
    // Quantised tip: each window end is off by less than h, so |V - v| < h / window = 500 m/s, and
    // the mean over 24 us (24 mm of advance) is off by less than h / 24 us = 42 m/s.
    for (const SpeedSample& s : stepped.speed(window))
        if (s.t - window / 2 >= t0) {
            EXPECT_LT(std::abs(s.v - v), h / window);
        }
    EXPECT_LT(std::abs(stepped.mean_speed(window, t0, 30e-6) - v), h / 24e-6);
}

// Centreline offsets by construction (origin 0, reference line y = 0, bins of width h at x = i h).
TEST(CrackMetrics, PathDeviationFromReferenceLine)
{
    const Field<2> x = lattice(100, 20);
    std::vector<double> phi(x.size(), 0.0);
    // Damaged rows y = 2.5 h and 3.5 h for x < 50 h (centre 3 h), 9.5 h and 10.5 h beyond (10 h).
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double xi = x.c[0][i] / h, yj = x.c[1][i] / h;
        const bool left = xi < 49.5 && (std::abs(yj - 2.5) < 1e-9 || std::abs(yj - 3.5) < 1e-9);
        const bool right = xi > 49.5 && (std::abs(yj - 9.5) < 1e-9 || std::abs(yj - 10.5) < 1e-9);
        if (left || right) phi[i] = 0.4;
    }
    const PathDeviation dev = path_deviation(x, phi, v2(0, 0), v2(1, 0), h, 0, 99 * h);
    ASSERT_EQ(dev.s.size(), 100u);
    // RMS = sqrt((50 * 3^2 + 50 * 10^2) / 100) h = sqrt(54.5) h; max 10 h (round-off 1e-12 h).
    EXPECT_NEAR(dev.rms, std::sqrt(54.5) * h, 1e-12 * h);
    EXPECT_NEAR(dev.max, 10 * h, 1e-12 * h);
    // Nodes (i h, (i/2 + 0.5) h) for even i: centreline n = s/2 + h/2, slope angle atan(1/2).
    std::vector<double> tilt(x.size(), 0.0);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const long xi = std::lround(x.c[0][i] / h);
        if (xi % 2 == 0 && xi <= 38 && std::abs(x.c[1][i] / h - (xi / 2 + 0.5)) < 1e-9) tilt[i] = 0.5;
    }
    const PathDeviation t = path_deviation(x, tilt, v2(0, 0), v2(1, 0), h, 0, 99 * h);
    EXPECT_EQ(t.s.size(), 20u);
    EXPECT_NEAR(t.angle, std::atan(0.5), 1e-12);
    EXPECT_NEAR(t.max, 19.5 * h, 1e-12 * h);
}

// Marching squares on a linear field f = (x + 2 y) / h: the level 10.3 is the line from
// (0, 5.15 h) to (10 h, 0.15 h) across [0, 10 h]^2; linear interpolation on the cell edges is
// exact for a linear field, so every end point lies on it and the segments add up to its length
// sqrt(10^2 + 5^2) h (round-off 1e-12).
TEST(CrackMetrics, LevelCurveOfLinearFieldIsExact)
{
    Field<2> x;
    std::vector<double> f;
    for (int j = 0; j <= 10; ++j)
        for (int i = 0; i <= 10; ++i) x.c[0].push_back(i * h), x.c[1].push_back(j * h), f.push_back(i + 2.0 * j);
    const std::vector<Segment> segs = level_curve(lattice_scalar(x, f, h), 10.3);
    ASSERT_FALSE(segs.empty());
    double length = 0;
    for (const Segment& s : segs) {
        EXPECT_NEAR((s.a[0] + 2 * s.a[1]) / h, 10.3, 1e-12);
        EXPECT_NEAR((s.b[0] + 2 * s.b[1]) / h, 10.3, 1e-12);
        length += norm(s.b - s.a);
    }
    EXPECT_NEAR(length, std::sqrt(125.0) * h, 1e-12);

    // The same lattice rotated by 20 degrees (and shifted): the curve of the rotated field is the
    // rotated curve, so end points satisfy the field's equation in the lattice frame.
    const double a = 20 * pi / 180, c = std::cos(a), s = std::sin(a);
    Field<2> r;
    for (std::size_t q = 0; q < x.size(); ++q) {
        r.c[0].push_back(0.3 + c * x.c[0][q] - s * x.c[1][q]);
        r.c[1].push_back(-0.1 + s * x.c[0][q] + c * x.c[1][q]);
    }
    double rotated_length = 0;
    for (const Segment& g : level_curve(lattice_scalar(r, f, h, a), 10.3)) {
        for (const Vec<2>& p : {g.a, g.b}) {
            const double X = c * (p[0] - 0.3) + s * (p[1] + 0.1), Y = -s * (p[0] - 0.3) + c * (p[1] + 0.1);
            EXPECT_NEAR((X + 2 * Y) / h, 10.3, 1e-9);  // 1e-9: rotation round-off on 0.3 m offsets / h
        }
        rotated_length += norm(g.b - g.a);
    }
    EXPECT_NEAR(rotated_length, std::sqrt(125.0) * h, 1e-9 * h * 100);
    // A node off the lattice is rejected.
    r.c[0][5] += 0.3 * h;
    EXPECT_THROW(lattice_scalar(r, f, h, a), std::invalid_argument);
}

// Saddle cell f = (1, 0, 1, 0) counter-clockwise from (0, 0), level 0.5: the cell mean 0.5 counts
// as high, so the high corners (0, 0) and (h, h) connect and the curve cuts off the low corners
// (h, 0) and (0, h): two segments joining the edge midpoints around each of them.
TEST(CrackMetrics, LevelCurveSaddleUsesCellMean)
{
    Field<2> x;
    for (const auto& [i, j] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}})
        x.c[0].push_back(i * h), x.c[1].push_back(j * h);
    const std::vector<Segment> segs = level_curve(lattice_scalar(x, {1, 0, 1, 0}, h), 0.5);
    ASSERT_EQ(segs.size(), 2u);
    for (const Segment& s : segs) {
        const Vec<2> mid = 0.5 * (s.a + s.b);
        const double to_low = std::min(norm(mid - v2(h, 0)), norm(mid - v2(0, h)));
        EXPECT_NEAR(to_low, std::sqrt(2.0) / 4 * h, 1e-15);  // midpoint of (h/2, 0)-(h, h/2) is h sqrt(2)/4 from (h, 0)
    }
}
