// Exact partial areas of 2D cells in a horizon (partial_area.hpp) and the exact-area partial volumes
// of build_bonds (bonds.hpp). References: the chord-length integral summed by a composite Simpson rule
// (no closed form, no breakpoints), areas known in closed form (whole disc, half disc, square inside),
// and the partition of the disc: the cells of a full family plus the node's own cover the horizon
// exactly, so their areas add up to pi delta^2.
#include "pd/core/bonds.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/core/partial_area.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

using namespace pd;
constexpr double pi = std::numbers::pi;

namespace {
// Area of the disc |p| <= R within [x0, x1] x [y0, y1] as the integral of the chord length inside
// the rectangle, composite Simpson on n intervals (the sqrt end-point singularity limits it to about
// n^-1.5 of R^2).
double chord_integral(double R, double x0, double x1, double y0, double y1, int n = 200000)
{
    auto chord = [&](double x) {
        if (std::abs(x) >= R) return 0.0;
        const double s = std::sqrt(R * R - x * x);
        return std::max(0.0, std::min(y1, s) - std::max(y0, -s));
    };
    const double h = (x1 - x0) / n;
    double sum = chord(x0) + chord(x1);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4 : 2) * chord(x0 + k * h);
    return sum * h / 3;
}
}  // namespace

// Tolerance 1e-14 (areas of order R^2 ~ 3): the round-off of a few closed-form terms.
TEST(PartialArea, ClosedFormCases)
{
    const double R = 1.7;
    EXPECT_NEAR(disc_rectangle_area(R, -2, 2, -2, 2), pi * R * R, 1e-14);       // whole disc
    EXPECT_NEAR(disc_rectangle_area(R, 0, 5, -5, 5), 0.5 * pi * R * R, 1e-14);  // half disc
    EXPECT_NEAR(disc_rectangle_area(R, 0, 5, 0, 5), 0.25 * pi * R * R, 1e-14);  // quarter
    EXPECT_NEAR(disc_rectangle_area(R, -0.5, 0.7, -1.0, 0.2), 1.2 * 1.2, 1e-14);  // rectangle inside
    EXPECT_EQ(disc_rectangle_area(R, 1.3, 2.0, 1.3, 2.0), 0.0);                 // corner (1.3, 1.3) outside
    EXPECT_EQ(disc_rectangle_area(R, 0.5, 0.5, 0, 1), 0.0);                     // empty rectangle
    // A side on the tangent y = R: the chord is the circle's on both sides of x = 0 (without that
    // split point the whole range was taken as lying below the circle).
    EXPECT_NEAR(disc_rectangle_area(R, -0.5, 0.5, 0.5, R), chord_integral(R, -0.5, 0.5, 0.5, R), 1e-7);
    // An edge a few ulps inside x = R: the sliver's area is ~1e-22 (asin(x/R) gave -3.7e-8 at R = 4.7).
    for (double r : {R, 4.7}) {
        const double a = disc_rectangle_area(r, std::nextafter(std::nextafter(r, 0.0), 0.0), r + 1, -0.5, 0.5);
        EXPECT_GE(a, 0.0);
        EXPECT_LT(a, 1e-15);
    }
}

// Random rectangles cutting the disc in every way (one to four corners inside, chords through one or
// two sides, across the centre): the closed form against the Simpson chord integral. Tolerance 1e-7
// of R^2: the measured Simpson error at n = 2e5 is below 1e-8.
TEST(PartialArea, MatchesTheChordIntegral)
{
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.3, 1.3), w(0.05, 1.5);
    const double R = 1.0;
    int cut = 0;
    for (int n = 0; n < 60; ++n) {
        const double x0 = u(rng), y0 = u(rng), x1 = x0 + w(rng), y1 = y0 + w(rng);
        const double a = disc_rectangle_area(R, x0, x1, y0, y1), ref = chord_integral(R, x0, x1, y0, y1);
        EXPECT_NEAR(a, ref, 1e-7) << x0 << " " << x1 << " " << y0 << " " << y1;
        cut += a > 0 && a < (x1 - x0) * (y1 - y0) - 1e-9;
    }
    EXPECT_GT(cut, 30);  // most rectangles really are cut by the circle
}

// The cells of the centre node's family and its own cell tile the disc, so sum_j beta_j V_j + V_i =
// pi delta^2 t, on the lattice's own axes and on rotated lattices (the angle given to build_bonds),
// for integer and non-integer m; beta_ij = beta_ji bit for bit. Tolerance 1e-12 of the disc: the
// round-off of about 100 closed-form areas (measured below 1.2e-15 with atan2; asin gave 2e-9), and
// cells covered by less than 1e-12 of their area are left out of a family (bonds.cpp).
TEST(PartialArea, FamilyAreasAddUpToTheDisc)
{
    const double h = 1.0, t = 0.01;
    for (double deg : {0.0, 5.0, 10.0, 30.0})
        for (double m : {1.5, 2.05, 2.5, 3.0, 3.3, 3.5, 4.7, 5.5}) {
            const double th = deg * pi / 180, c = std::cos(th), s = std::sin(th);
            Body<2> body;
            body.dx = h;
            body.measure = t;
            for (int a = -8; a <= 8; ++a)
                for (int b = -8; b <= 8; ++b) body.push({{c * a * h - s * b * h, s * a * h + c * b * h}}, h * h * t);
            const int centre = 8 * 17 + 8;
            BondOptions opt;
            opt.partial_volume = PartialVolume::exact_area;
            opt.lattice_angle = th;
            const Bonds bonds = build_bonds(body, m * h, opt);
            double area = body.volume[centre];
            bool beyond = false;
            for (std::int64_t k = bonds.begin(centre); k < bonds.end(centre); ++k) {
                area += bonds.volume[k];
                beyond |= bonds.length[k] > m * h;
            }
            EXPECT_NEAR(area, pi * m * m * h * h * t, 1e-12 * area) << deg << " deg, m = " << m;
            if (m > 1.6) {  // m = 1.5 cuts none
                EXPECT_TRUE(beyond) << "cells centred beyond delta but cut by it belong to the family";
            }
            for (std::size_t k = 0; k < bonds.size(); ++k) {
                const int i = static_cast<int>(std::upper_bound(bonds.offset.begin(), bonds.offset.end(), static_cast<std::int64_t>(k)) - bonds.offset.begin()) - 1;
                ASSERT_EQ(bonds.volume[k] / body.volume[bonds.partner[k]], bonds.volume[bonds.reverse[k]] / body.volume[i]) << k;
            }
        }
}

// Hand value: at m = 3 the cell of offset (3, 1) (centre at sqrt 10 = 3.162 > 3) is cut by the
// horizon; it joins the family with the fraction of its area inside, from the chord integral.
TEST(PartialArea, CellBeyondTheHorizonJoinsWithItsCoveredFraction)
{
    auto body = box<2>({{0, 0}}, {{13.0, 13.0}}, 1.0);
    BondOptions opt;
    opt.partial_volume = parse_partial_volume("exact-area");
    const Bonds b = build_bonds(body, 3.0, opt);
    const int centre = 6 + 6 * 13, j = (6 + 3) + (6 + 1) * 13;  // offset (3, 1)
    const std::int64_t k = std::lower_bound(b.partner.begin() + b.begin(centre), b.partner.begin() + b.end(centre), j) - b.partner.begin();
    ASSERT_LT(k, b.end(centre));
    ASSERT_EQ(b.partner[k], j);
    EXPECT_NEAR(b.volume[k] / body.volume[j], chord_integral(3.0, 2.5, 3.5, 0.5, 1.5), 1e-7);
    EXPECT_GT(b.volume[k], 0.0);
}

TEST(PartialArea, RefusesWhatItCannotDo)
{
    {  // references that count full families within delta refuse families that reach beyond it
        const auto body = box<2>({{0, 0}}, {{12.0, 12.0}}, 1.0);
        const Bonds b = build_bonds(body, 3.0, {.partial_volume = PartialVolume::exact_area, .keep = {}});
        const PMB pmb({.material = Elastic::from_E_nu(200e9, 1.0 / 3.0), .dim = 2}, b);
        EXPECT_FALSE(families_within_horizon(b));
        EXPECT_THROW(surface_correction(pmb, body, b), std::invalid_argument);
    }
    BondOptions opt;
    opt.partial_volume = PartialVolume::exact_area;
    EXPECT_THROW(build_bonds(box<3>({{0, 0, 0}}, {{4.0, 4.0, 4.0}}, 1.0), 2.0, opt), std::invalid_argument);
    opt.influence.kind = Influence::Kind::triangular;  // negative beyond delta
    EXPECT_THROW(build_bonds(box<2>({{0, 0}}, {{4.0, 4.0}}, 1.0), 2.0, opt), std::invalid_argument);
    EXPECT_THROW(parse_partial_volume("ipa"), std::invalid_argument);
}
