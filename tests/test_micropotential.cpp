// Critical-micropotential damage (damage/micropotential.hpp) against spec/000c V8, V9 and closed forms:
// w_C constants, the integral identity (8.14)-(8.15) by independent quadrature, the lattice sum of
// the energy to cut a plane, the PMB break strain under uniform stretch (closed form, delta^{-1/2}
// scaling, both criteria), temperature-scaled J_C, the singular-node rule and the Explicit
// integration of w. The work integral of every model and the breaking test: test_micropotential_work.cpp.
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/time/verlet.hpp"

#include "damage_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace pd;
using namespace pd_test;

namespace {
const double pi = std::numbers::pi;
const Elastic si3n4 = Elastic::from_E_nu(310e9, 0.29);
constexpr double Jc_si3n4 = 109.94;  // [J/m^2], 000c sec. 2.6
}  // namespace

// spec/000c V8 (printed to 4 digits: tolerance 1.2e-4 relative, half a unit in the last digit).
TEST(Micropotential, CriticalValuesOfSpecV8)
{
    EXPECT_NEAR(w_critical(Jc_si3n4, 0.75e-3) / 4.424e14, 1.0, 1.2e-4);
    EXPECT_NEAR(w_critical(179288.86, 1e-3) / 2.283e17, 1.0, 2.2e-4);
    EXPECT_NEAR(w_critical(179288.86, 0.5e-3) / 3.652e18, 1.0, 1.4e-4);
    EXPECT_NEAR(w_critical(179288.86, 0.83e-3) / 4.810e17, 1.0, 1.1e-4);
}

// (8.14): J_C = w int_0^d int_0^2pi int_z^d int_0^acos(z/xi) xi^2 sin(phi) dphi dxi dtheta dz with w
// constant, by midpoint quadrature of the xi-z double integral after the phi and theta integrals
// (2 pi xi^2 (1 - z/xi)); 2D: int_0^d int_z^d 2 xi acos(z/xi) dxi dz. w_critical must invert it.
// Tolerance: midpoint error of 800 x 800 cells, O(h^2) = 1e-6 in 3D (smooth integrand, 1e-5 bound);
// O(h^1.5) = 4e-5 in 2D, where acos(z/xi) has a sqrt edge at xi = z (measured 2.7e-5; 1e-4 bound).
TEST(Micropotential, ConstantIntegrandIdentity)
{
    const double delta = 0.75e-3;
    const int n = 800;
    double I3 = 0, I2 = 0;
    for (int a = 0; a < n; ++a)
        for (int c = 0; c < n; ++c) {
            const double z = (a + 0.5) * delta / n, xi = (c + 0.5) * delta / n, cell = (delta / n) * (delta / n);
            if (xi <= z) continue;
            I3 += 2 * pi * xi * xi * (1 - z / xi) * cell;
            I2 += 2 * xi * std::acos(z / xi) * cell;
        }
    EXPECT_NEAR(I3 / (pi * std::pow(delta, 4) / 4), 1.0, 1e-5);
    EXPECT_NEAR(w_critical(Jc_si3n4, delta, 3) * I3 / Jc_si3n4, 1.0, 1e-5);
    EXPECT_NEAR(w_critical(Jc_si3n4, delta, 2) * I2 / Jc_si3n4, 1.0, 1e-4);
}

// Energy to cut all bonds crossing a plane between node layers of an infinite cubic lattice, with
// every bond at w_C: per unit area, w_C dx^6 / dx^2 times sum over offsets n (n_x > 0, |n| <= m) of n_x
// (an offset crosses the plane n_x times per column). It tends to J_C as m grows. Tolerance: the
// lattice-point count of a ball has a surface error O(1/m); 0.5/m is the envelope measured over
// m = 2.05 ... 20.05 (largest 0.485/m at m = 4.05); at m = 20.05 the error is 0.22 %.
TEST(Micropotential, PlaneCutEnergyConvergesToJc)
{
    for (double m : {2.05, 3.05, 4.05, 6.05, 10.05, 20.05}) {
        const double dx = 1e-4, delta = m * dx;
        const int M = static_cast<int>(m) + 1;
        double sum = 0;
        for (int a = 1; a <= M; ++a)
            for (int b = -M; b <= M; ++b)
                for (int c = -M; c <= M; ++c)
                    if (a * a + b * b + c * c <= m * m) sum += a;
        const double energy = w_critical(Jc_si3n4, delta) * std::pow(dx, 4) * sum;  // [J/m^2]
        EXPECT_LT(std::abs(energy / Jc_si3n4 - 1), 0.5 / m) << "m = " << m;
        if (m > 20) {
            EXPECT_LT(std::abs(energy / Jc_si3n4 - 1), 0.005);
        }
    }
}

namespace {
// Quasi-static isotropic stretch y = (1 + s) x of a PMB cube (delta = 3.05 h, longest bond 3 h),
// s raised by ds per step; returns the s at which the first bond breaks under micropotential
// (ratio = J_C(theta_ref)/J_C(theta) on every node) or, with s0 > 0, under critical stretch.
double first_break_strain(double h, double ds, double ratio = 1, double s0 = 0)
{
    auto body = box<3>({{0, 0, 0}}, {{4 * h, 4 * h, 4 * h}}, h);
    Bonds b = build_bonds(body, 3.05 * h);
    b.enable_damage();
    PMB pmb({si3n4, 3}, b);
    CriticalMicropotential<3> mp;
    mp.w_c = w_critical(Jc_si3n4, b.delta);
    if (ratio != 1) mp.jc_ratio.assign(body.size(), ratio);
    CriticalStretch cs = CriticalStretch::uniform(s0);
    Field<3> y = body.x, f;
    for (int n = 0; n < 100000; ++n) {
        const double s = n * ds;
        for (int d = 0; d < 3; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) y.c[d][i] = (1 + s) * body.x.c[d][i];
        const long broke = s0 > 0 ? cs.apply(b, y) : mp.apply(b);
        if (broke > 0) {
            if (s0 == 0)  // micropotential: only the longest bonds go first
                for (std::size_t k = 0; k < b.size(); ++k)
                    if (!b.intact[k]) {
                        EXPECT_NEAR(b.length[k], 3 * h, 1e-9 * h);
                    }
            return s0 > 0 ? s : s - ds;  // micropotential: w of the previous step reached w_C
        }
        if (s0 > 0) continue;
        internal_force(pmb, b, y, f);
        mp.accumulate(pmb, b, y);
    }
    return -1;
}
}  // namespace

// PMB: w = c s^2 |xi| / 2 exactly (force linear in s, trapezoidal rule exact), c = 18K/(pi delta^4),
// so the longest bond (|xi| = 3h) breaks at s*^2 = 2 w_C/(c 3h) = 4 J_C delta^4/(pi delta^4 ... ) =
// 4 J_C / (9 K 3h). Tolerance: one strain step ds (the break is detected at the first step past s*).
// Doubling delta (same m) scales s* by 2^{-1/2} for both criteria (000c sec. 2.3 [DERIVED], V8).
TEST(Micropotential, UniformStretchBreakStrainAndDeltaScaling)
{
    const double h = 0.25e-3, ds = 1e-6;
    const double s_star = std::sqrt(4 * Jc_si3n4 / (9 * si3n4.K * 3 * h));  // closed form above
    const double s1 = first_break_strain(h, ds);
    EXPECT_GE(s1, s_star - 1e-12);
    EXPECT_LT(s1, s_star + ds);
    const double s2 = first_break_strain(2 * h, ds);
    EXPECT_NEAR(s2 / s1, 1 / std::sqrt(2.0), 2 * ds / s2);
    const double c1 = first_break_strain(h, ds, 1, s0_pmb_3d(Jc_si3n4, si3n4.K, 3.05 * h));
    const double c2 = first_break_strain(2 * h, ds, 1, s0_pmb_3d(Jc_si3n4, si3n4.K, 6.1 * h));
    EXPECT_NEAR(c2 / c1, 1 / std::sqrt(2.0), 2 * ds / c2);
}

// V9: at constant theta with J_C(theta) = J_C(theta_ref)/2 (ratio 2) the bond breaks when its
// unscaled w reaches 4 J_C(theta)/(pi delta^4), i.e. at s* / sqrt(2). Tolerance: one step ds.
TEST(Micropotential, TemperatureScaledJcBreaksAtItsOwnCriticalValue)
{
    const double h = 0.25e-3, ds = 1e-6;
    const double s_theta = std::sqrt(4 * (Jc_si3n4 / 2) / (9 * si3n4.K * 3 * h));
    const double s = first_break_strain(h, ds, 2.0);
    EXPECT_GE(s, s_theta - 1e-12);
    EXPECT_LT(s, s_theta + ds);
}

// Singular-node rule (000c sec. 2.5): a correspondence node left with two bonds (K singular in 3D)
// is detached: the next apply breaks those two bonds and their reverses; no-fail nodes are spared.
TEST(Micropotential, SingularCorrespondenceNodeIsDetached)
{
    const auto body = block<3>();
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    const int lonely = 40;
    int kept = 0;
    for (std::int64_t k = b.begin(lonely); k < b.end(lonely); ++k)
        if (kept < 2) ++kept;
        else b.break_pair(k);
    auto model = make_corr<3>(0.0)(body, b);
    CriticalMicropotential<3> mp;
    mp.w_c = 1e300;
    const Field<3> y = deformed(body, 5);
    Field<3> f;
    internal_force(model, b, y, f);
    mp.accumulate(model, b, y);
    ASSERT_EQ(mp.detached_nodes, 1);
    EXPECT_EQ(mp.detached[lonely], 1);
    EXPECT_EQ(mp.apply(b), 4);
    for (std::int64_t k = b.begin(lonely); k < b.end(lonely); ++k) EXPECT_EQ(b.intact[k], 0);
}

// Explicit integrates w through the `micropotential` member: a PMB block released from a random
// deformation; w stays equal to its closed form c (s^2 - s_0^2) |xi|/2 (s_0 the initial stretch) up to the time-discretisation error
// of the trapezoidal work integral (O(dt^2); bound 1e-3 of the largest w; measured 4.0e-6).
TEST(Micropotential, ExplicitAccumulatesTheBondEnergy)
{
    const auto body = block<3>();
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    ExplicitPMBMicropotential run(body, b, 1e300);
    Explicit<3, PMB>& ex = run.ex;
    const Field<3> y0 = deformed(body, 9);
    ex.u = y0;
    for (int d = 0; d < 3; ++d) for (std::size_t i = 0; i < body.size(); ++i) ex.u.c[d][i] -= body.x.c[d][i];
    ex.start();
    for (int n = 0; n < 200; ++n) ex.step(2e-8);
    const Field<3>& y = ex.positions();
    double wmax = 0, err = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const double L = b.length[k], s = (norm(y[b.partner[k]] - y[i]) - L) / L;
            const double s0 = (norm(y0[b.partner[k]] - y0[i]) - L) / L;
            const double w_ref = 0.5 * run.pmb.c * (s * s - s0 * s0) * L;
            wmax = std::max(wmax, std::abs(w_ref));
            err = std::max(err, std::abs(run.mp.work(b, k) - w_ref));
        }
    EXPECT_GT(wmax, 0.0);
    EXPECT_LT(err, 1e-3 * wmax);
}
