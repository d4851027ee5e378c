// Seed 001 boundary volume weights (spec/001_004 A.2 step 5, V4): intersection areas against hand
// values, the weights of straight grid-aligned edges by hand, and the area conservation
// |sum_i weight_i dx^2 - A| / A with and without the correction on convex, concave and holed
// shapes. Reference areas: the shoelace formula written here (not the library's signed_area).
#include "pd/core/polygon_weights.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

using namespace pd;

namespace {

constexpr double pi = std::numbers::pi;
constexpr double mm = 1e-3;  // [m]

double shoelace(const Ring& r)  // independent reference: |sum (x_k y_k+1 - x_k+1 y_k)| / 2 [m^2]
{
    double s = 0;
    for (std::size_t k = 0; k < r.size(); ++k) s += r[k][0] * r[(k + 1) % r.size()][1] - r[(k + 1) % r.size()][0] * r[k][1];
    return std::abs(s) / 2;
}
double reference_area(const Polygon& p)
{
    double a = shoelace(p.outer);
    for (const Ring& h : p.holes) a -= shoelace(h);
    return a;
}
Ring rotate(Ring r, const Vec<2>& c, double deg)
{
    const double t = deg * pi / 180, co = std::cos(t), si = std::sin(t);
    for (Vec<2>& p : r) {
        const Vec<2> d = p - c;
        p = c + Vec<2>{{co * d[0] - si * d[1], si * d[0] + co * d[1]}};
    }
    return r;
}
Ring rectangle(double x0, double y0, double w, double h) { return {{{x0, y0}}, {{x0 + w, y0}}, {{x0 + w, y0 + h}}, {{x0, y0 + h}}}; }
Ring circle(const Vec<2>& c, double R, int n, bool cw = false)
{
    Ring r;
    for (int k = 0; k < n; ++k) {
        const double t = (cw ? -2 : 2) * pi * k / n;
        r.push_back(c + Vec<2>{{R * std::cos(t), R * std::sin(t)}});
    }
    return r;
}
Ring star8(const Vec<2>& c, double h)  // square of half-side h as an 8-point star-shaped ring
{
    Ring r;
    for (auto [a, b] : {std::pair{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}})
        r.push_back(c + Vec<2>{{a * h, b * h}});
    return r;
}

struct AreaErrors {
    double uncorrected, corrected, shared;  // relative errors: rules none, seed001, shared_quarters
    std::size_t nodes;
};
AreaErrors area_errors(const Polygon& shape, double dx)
{
    const double A = reference_area(shape);
    double sum0 = 0, sum1 = 0;
    double sum2 = 0;
    for (double v : polygon_body(shape, dx, 1.0, WeightRule::none).body.volume) sum0 += v;
    const PolygonBody pb = polygon_body(shape, dx, 1.0, WeightRule::seed001);
    for (double v : pb.body.volume) sum1 += v;
    for (double v : polygon_body(shape, dx, 1.0, WeightRule::shared_quarters).body.volume) sum2 += v;
    return {std::abs(sum0 - A) / A, std::abs(sum1 - A) / A, std::abs(sum2 - A) / A, pb.body.size()};
}

}  // namespace

// Hand values: triangle (0.5,0.5),(1.5,0.5),(0.5,1.5) over the unit square keeps [0.5,1]^2 = 0.25
// (x + y <= 2 holds there); the triangle (0,0),(2,0),(0,2) contains the whole unit square -> 1.
TEST(PolygonWeights, ConvexTriangleOverlapHandValues)
{
    const Ring sq = rectangle(0, 0, 1, 1);
    EXPECT_NEAR(convex_triangle_overlap(sq, {{0.5, 0.5}}, {{1.5, 0.5}}, {{0.5, 1.5}}), 0.25, 1e-15);
    EXPECT_NEAR(convex_triangle_overlap(sq, {{0, 0}}, {{0, 2}}, {{2, 0}}), 1.0, 1e-15);  // clockwise triangle
    EXPECT_NEAR(convex_triangle_overlap(sq, {{2, 2}}, {{3, 2}}, {{2, 3}}), 0.0, 1e-15);
}

// Zone [-0.75, 1.25]^2 (area 4) about (0.25, 0.25):
// - plate [-3,3]^2 with hole [0,2]^2: the hole takes [0,1.25]^2 = 1.5625 -> 2.4375; the same hole as
//   a slit ring (outer, then the hole traversed clockwise, joined by a doubled segment) -> 2.4375;
// - L-shape [-2,2]^2 minus the quadrant x > 0.5, y > 0.5: the zone loses [0.5,1.25]^2 = 0.5625 -> 3.4375.
// Tolerance 1e-12: sums of a few hundred clipped triangles of size 1.
TEST(PolygonWeights, StarOverlapConcaveHoleAndSlitHandValues)
{
    const Vec<2> c{{0.25, 0.25}};
    const Ring zone = star8(c, 1.0);
    Polygon holed{rectangle(-3, -3, 6, 6), {rectangle(0, 0, 2, 2)}};
    EXPECT_NEAR(star_shape_overlap(c, zone, holed), 2.4375, 1e-12);
    Polygon slit{{{{-3, -3}}, {{3, -3}}, {{3, 3}}, {{-3, 3}}, {{-3, -3}}, {{0, 0}}, {{0, 2}}, {{2, 2}}, {{2, 0}}, {{0, 0}}}, {}};
    EXPECT_NEAR(star_shape_overlap(c, zone, slit), 2.4375, 1e-12);
    Polygon L{{{{-2, -2}}, {{2, -2}}, {{2, 0.5}}, {{0.5, 0.5}}, {{0.5, 2}}, {{-2, 2}}}, {}};
    EXPECT_NEAR(star_shape_overlap(c, zone, L), 3.4375, 1e-12);
    EXPECT_NEAR(star_shape_overlap(c, star8(c, 0.5), L), 0.9375, 1e-12);  // zone [-0.25,0.75]^2 loses [0.5,0.75]^2
}

// Mixed zone (radii 0.5 or 1 per direction, as the method builds them) against a rotated L with a
// triangular hole; reference: midpoint rule on a 2000 x 2000 sampling of the zone's box with the
// even-odd tests Polygon::contains and an independent point-in-star test (fan triangles by signs).
// Tolerance 2e-3 relative: the sampling's boundary error ~ perimeter x cell / area ~ 1e-3.
TEST(PolygonWeights, StarOverlapAgreesWithPointSampling)
{
    const Vec<2> c{{0.3, -0.1}};
    const int radius_half[8] = {1, 0, 1, 1, 0, 0, 1, 0};  // 1 = halved toward an object node
    const int dir[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    Ring zone;
    for (int k = 0; k < 8; ++k) zone.push_back(c + Vec<2>{{dir[k][0] * (radius_half[k] ? 0.5 : 1.0), dir[k][1] * (radius_half[k] ? 0.5 : 1.0)}});
    const Polygon shape{rotate({{{-2, -2}}, {{2, -2}}, {{2, 0.2}}, {{0.4, 0.2}}, {{0.4, 2}}, {{-2, 2}}}, {{0, 0}}, 17),
                        {{{{-0.2, -0.9}}, {{0.6, -0.5}}, {{-0.1, -0.3}}}}};
    auto in_star = [&](const Vec<2>& p) {
        for (int k = 0; k < 8; ++k) {
            const Vec<2>& a = zone[k];
            const Vec<2>& b = zone[(k + 1) % 8];
            const double s1 = (a[0] - c[0]) * (p[1] - c[1]) - (a[1] - c[1]) * (p[0] - c[0]);
            const double s2 = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
            const double s3 = (c[0] - b[0]) * (p[1] - b[1]) - (c[1] - b[1]) * (p[0] - b[0]);
            if (s1 >= 0 && s2 >= 0 && s3 >= 0) return true;
        }
        return false;
    };
    const int n = 2000;
    const double h = 2.0 / n;
    double sampled = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const Vec<2> p{{c[0] - 1 + (a + 0.5) * h, c[1] - 1 + (b + 0.5) * h}};
            if (in_star(p) && shape.contains(p)) sampled += h * h;
        }
    const double exact = star_shape_overlap(c, zone, shape);
    EXPECT_GT(sampled, 0.5);  // the case really overlaps the hole and the notch partly
    EXPECT_NEAR(exact / sampled, 1.0, 2e-3);
}

// Grid-aligned plate 10 x 4 cells: every boundary node has weight 9/8, interior nodes 1.
// Hand value, side node (neighbours W, E, S, SW, SE present; shape edge at y = dx/2): the zone is
// the halved square below y = 0 (dx^2/2) plus, for 0 <= y <= dx/2, the strip between the edges
// (-dx/2, 0)-(-dx, dx) and (dx/2, 0)-(dx, dx) of width dx + y: int (dx + y) dy = 5/8 dx^2 -> 9/8.
// Corner node (W, S, SW present): fan triangles 6 x 1/8 + 2 x 3/16 = 9/8 as well.
// The zones of two side nodes overlap by dx^2/8 (the source says they do not): the method adds
// mass along straight edges that the half-cell lattice already tiles exactly.
TEST(PolygonWeights, AlignedRectangleBoundaryWeightsAreNineEighths)
{
    const double dx = 1 * mm;
    const PolygonBody pb = polygon_body(Polygon{rectangle(0, 0, 10 * mm, 4 * mm), {}}, dx, 1.0);
    ASSERT_EQ(pb.body.size(), 40u);
    int edges = 0;
    for (std::size_t i = 0; i < pb.body.size(); ++i) {
        edges += pb.edge[i];
        EXPECT_NEAR(pb.weight[i], pb.edge[i] ? 9.0 / 8 : 1.0, 1e-12) << "node " << i;  // round-off of a few clips
    }
    EXPECT_EQ(edges, 2 * 10 + 2 * 2);
}

// Shared quarters by hand: square [0, 2.25]^2 (dx = 1, here in mm), nodes (0.5|1.5, 0.5|1.5); the
// strips 2 < x < 2.25 and 2 < y < 2.25 lie in empty cells. Node (1.5, 0.5): own cell 1; quarter
// [2,2.5]x[0,0.5] (claimant itself only) 0.125; [2,2.5]x[0.5,1] and [2,2.5]x[1,1.5] (claimants it
// and (1.5, 1.5)) 0.125/2 each -> 1.25; likewise (0.5, 1.5). Node (1.5, 1.5): 1 + 2 x 0.25 + the
// corner [2,2.25]^2 alone 0.0625 -> 1.5625. Sum 1 + 2.5 + 1.5625 = 5.0625 = 2.25^2.
TEST(PolygonWeights, SharedQuartersHandValues)
{
    const PolygonBody pb = polygon_body(Polygon{rectangle(0, 0, 2.25 * mm, 2.25 * mm), {}}, 1 * mm, 1.0, WeightRule::shared_quarters);
    ASSERT_EQ(pb.body.size(), 4u);
    const double expected[4] = {1.0, 1.25, 1.25, 1.5625};  // nodes x fastest
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(pb.weight[i], expected[i], 1e-12) << "node " << i;  // round-off of a few clips
    EXPECT_EQ(parse_weight_rule("shared-quarters"), WeightRule::shared_quarters);
    EXPECT_THROW(parse_weight_rule("voronoi"), std::invalid_argument);
}

// V4 area conservation at dx = 2, 1, 0.5 mm (10-120 cells across). The measured errors are printed;
// the assertions (at dx = 1 mm) state what holds with a margin (reports/2d/seed001_preprocessing.md).
TEST(PolygonWeights, AreaConservationWithAndWithoutCorrection)
{
    struct Case {
        const char* name;
        Polygon shape;
    };
    const Vec<2> c{{50 * mm, 50 * mm}};
    Ring comb{{{0, 0}}, {{60 * mm, 0}}, {{60 * mm, 30 * mm}}};  // 5 slots 1.3 mm wide, 20 mm deep
    for (int k = 4; k >= 0; --k) {
        const double x = (6 + 11 * k) * mm;
        comb.insert(comb.end(), {{{x + 1.3 * mm, 30 * mm}}, {{x + 1.3 * mm, 10 * mm}}, {{x, 10 * mm}}, {{x, 30 * mm}}});
    }
    comb.push_back({{0, 30 * mm}});
    const Case cases[] = {
        {"rectangle 100x40 aligned", {rectangle(0, 0, 100 * mm, 40 * mm), {}}},
        {"rectangle 60x30 rot 20", {rotate(rectangle(20 * mm, 35 * mm, 60 * mm, 30 * mm), c, 20), {}}},
        {"disk R 20 (256-gon)", {circle({{30.3 * mm, 29.7 * mm}}, 20 * mm, 256), {}}},
        {"L 60 arm 25 rot 25", {rotate({{{0, 0}}, {{60 * mm, 0}}, {{60 * mm, 25 * mm}}, {{25 * mm, 25 * mm}}, {{25 * mm, 60 * mm}}, {{0, 60 * mm}}}, c, 25), {}}},
        {"plate 80x50 hole R 10", {rectangle(0, 0, 80 * mm, 50 * mm), {circle({{40.2 * mm, 25.3 * mm}}, 10 * mm, 128, true)}}},
        {"comb 60x30, 1.3 mm slots", {comb, {}}},
    };
    for (double dx : {2 * mm, 1 * mm, 0.5 * mm})
        for (const Case& k : cases) {
            const AreaErrors e = area_errors(k.shape, dx);
            std::printf("  dx %.1f mm  %-26s nodes %6zu  err none %.3e  seed001 %.3e  shared-quarters %.3e\n", dx / mm, k.name, e.nodes,
                        e.uncorrected, e.corrected, e.shared);
            if (dx != 1 * mm) continue;
            // Measured (dx = 1 mm): the seed's correction does NOT cut the error 10x as the source
            // claims; it raises it on every shape (0.7-2.1 %; 1.15x the uncorrected error on the disk
            // and the comb, 16-19x on the rotated rectangle, L and holed plate), because each
            // boundary zone overlaps its neighbours' (dx^2/8 per node on straight edges). Shared
            // quarters: measured <= 4e-5 (convex corners of the rotated rectangle lose quarters
            // without claimant), asserted < 1e-4.
            EXPECT_GT(e.corrected, e.uncorrected) << k.name;
            EXPECT_GT(e.corrected, 6.5e-3) << k.name;
            EXPECT_LT(e.shared, 1e-4) << k.name;
        }
    // Aligned 100 x 40 plate: the half-cell lattice tiles it exactly (error 0 up to round-off
    // 1e-12), and 276 boundary nodes of weight 9/8 add 276/8 dx^2 over 4000 dx^2 = 8.625e-3.
    const AreaErrors plate = area_errors(cases[0].shape, 1 * mm);
    EXPECT_LT(plate.uncorrected, 1e-12);
    EXPECT_NEAR(plate.corrected, 276.0 / 8 / 4000, 1e-12);
    EXPECT_LT(plate.shared, 1e-12);
}
