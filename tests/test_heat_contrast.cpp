// A conductivity contrast (ConductivityContrast, heat/conductivity.hpp): node i conducts with f_i k, a
// bond with the mean of its ends' conductivities; the wrapper is linear, so implicit Euler needs no Picard
// iteration and matches the plain model where every factor is the same.
#include "pd/heat/agwai.hpp"
#include "pd/heat/conductivity.hpp"
#include "pd/heat/correspondence_heat.hpp"
#include "pd/core/lattice.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace {

constexpr double dx = 1e-3, k = 16, rho_c = 3.9e6, thickness = 1e-3;  // [m], [W/(m K)], [J/(m^3 K)], [m]

struct Plate {  // 10 x 8 points; factor contrast on x > 5 dx
    pd::Body<2> body = pd::box<2>(pd::Vec<2>{0, 0}, pd::Vec<2>{10 * dx, 8 * dx}, dx, thickness);
    pd::Bonds bonds = pd::build_bonds(body, 3.05 * dx);
    std::vector<double> factors(double contrast) const
    {
        std::vector<double> f(body.size(), 1.0);
        for (std::size_t i = 0; i < f.size(); ++i)
            if (body.x.c[0][i] > 5 * dx) f[i] = contrast;
        return f;
    }
};

TEST(ConductivityContrast, BondConductsWithTheMeanOfItsEnds)
{
    const Plate p;
    const std::vector<double> f = p.factors(1e6);
    pd::ConductivityContrast<pd::Agwai> contrast({0, thickness}, pd::Property::constant(k), p.body, p.bonds, f);
    const pd::Agwai unit({1, thickness}, p.body, p.bonds);
    const Eigen::SparseMatrix<double> A = pd::heat_operator(contrast, p.bonds), A1 = pd::heat_operator(unit, p.bonds);
    int across = 0;
    for (std::size_t i = 0; i < p.body.size(); ++i) {
        double row = 0;
        for (std::int64_t b = p.bonds.begin(i); b < p.bonds.end(i); ++b) {
            const int j = p.bonds.partner[b];
            const double expected = 0.5 * (f[i] + f[std::size_t(j)]) * k * A1.coeff(int(i), j);  // the rule of the header
            EXPECT_NEAR(A.coeff(int(i), j), expected, 1e-14 * std::abs(expected));  // a few roundings of one product
            across += f[i] != f[std::size_t(j)];
            row += A.coeff(int(i), j);
        }
        EXPECT_NEAR(A.coeff(int(i), int(i)), -row, 1e-14 * std::abs(row));  // uniform fields carry no heat
    }
    EXPECT_GT(across, 0);  // the interface is crossed by bonds
}

TEST(ConductivityContrast, ExplicitEulerConservesHeatAndKeepsTheRange)
{
    const Plate p;
    pd::ConductivityContrast<pd::Agwai> model({0, thickness}, pd::Property::constant(k), p.body, p.bonds, p.factors(1e6));
    pd::Conduction<decltype(model)> heat(model, p.bonds, std::vector<double>(p.body.size(), rho_c), {});
    std::vector<double> theta(p.body.size());
    for (std::size_t i = 0; i < theta.size(); ++i) theta[i] = 300 + 1e3 * p.body.x.c[1][i];  // 300.5..307.5 K across the interface
    const auto [lo, hi] = std::minmax_element(theta.begin(), theta.end());
    const double theta_lo = *lo, theta_hi = *hi;
    auto total = [&] {
        double E = 0;
        for (std::size_t i = 0; i < theta.size(); ++i) E += p.body.volume[i] * rho_c * theta[i];
        return E;
    };
    const double E0 = total();
    const double dt = pd::thermal_critical_step(model, p.bonds, heat, theta);  // dt_G: rho c_i / |A_ii| for Agwai
    for (int n = 0; n < 300; ++n) heat.explicit_euler(theta, dt);
    const auto [mn, mx] = std::minmax_element(theta.begin(), theta.end());
    // Each step is a convex combination of the old temperatures (weights 1 - dt |A_ii| / rho c >= 0 and
    // dt A_ij / rho c): the range can only shrink, up to the rounding of ~300 K values (1e-13).
    EXPECT_GE(*mn, theta_lo - 1e-10);
    EXPECT_LE(*mx, theta_hi + 1e-10);
    EXPECT_GT(*mx - *mn, 1e-3);  // not yet uniform: the slow half still holds a gradient
    EXPECT_NEAR(total(), E0, 1e-13 * E0);  // 300 steps, a few roundings of ~300 K each
}

TEST(ConductivityContrast, UniformFactorsAreThePlainModelUnderImplicitEuler)
{
    const Plate p;
    const double f = 7;
    pd::ConductivityContrast<pd::CorrespondenceHeat<2>> wrapped({0, 1.0, thickness}, pd::Property::constant(k), p.body, p.bonds,
                                                                std::vector<double>(p.body.size(), f));
    pd::CorrespondenceHeat<2> plain({f * k, 1.0, thickness}, p.body, p.bonds);
    static_assert(!decltype(wrapped)::nonlinear);  // no Picard iteration
    std::vector<double> t1(p.body.size()), t2;
    for (std::size_t i = 0; i < t1.size(); ++i) t1[i] = 300 + 2e3 * p.body.x.c[0][i] * p.body.x.c[0][i] / (10 * dx);
    t2 = t1;
    pd::Conduction<decltype(wrapped)> h1(wrapped, p.bonds, std::vector<double>(p.body.size(), rho_c), {});
    pd::Conduction<decltype(plain)> h2(plain, p.bonds, std::vector<double>(p.body.size(), rho_c), {});
    const double dt = 100 * pd::thermal_critical_step(plain, p.bonds, h2, t2);
    for (int n = 0; n < 20; ++n) h1.implicit_euler(t1, dt), h2.implicit_euler(t2, dt);
    double diff = 0, change = 0;
    for (std::size_t i = 0; i < t1.size(); ++i)
        diff = std::max(diff, std::abs(t1[i] - t2[i])), change = std::max(change, std::abs(t2[i] - (300 + 2e3 * p.body.x.c[0][i] * p.body.x.c[0][i] / (10 * dx))));
    EXPECT_GT(change, 1e-2);       // the field moved
    EXPECT_LE(diff, 1e-9 * 300);   // the same operator up to the rounding of f k against k times f (LU of ~1e3 rows)
}

TEST(ConductivityContrast, RefusesBadFactorsAndATemperatureDependentK)
{
    const Plate p;
    using M = pd::ConductivityContrast<pd::Agwai>;
    EXPECT_THROW(M({0, thickness}, pd::Property::constant(k), p.body, p.bonds, std::vector<double>(3, 1.0)), std::invalid_argument);
    EXPECT_THROW(M({0, thickness}, pd::Property::constant(k), p.body, p.bonds, std::vector<double>(p.body.size(), 0.0)), std::invalid_argument);
    EXPECT_THROW(M({0, thickness}, pd::Property::table({0, 1000}, {50, 30}), p.body, p.bonds, p.factors(10)), std::invalid_argument);
}

}  // namespace
