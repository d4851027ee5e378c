// The micropotential of a thermally expanding body (damage/micropotential.hpp, set_thermal_expansion;
// spec/000c sec. 2.3 [CODE]: the thermal bond velocity alpha dtheta/dt xi is subtracted before the work
// is taken). Closed form for PMB: a pair force c s_mech per unit volume of each end along the bond and
// the mechanical displacement increment ds_mech xi give, with the trapezoidal rule on a linear
// law, exactly w = c s_mech^2 |xi| / 2 (c = 18 K / (pi delta^4), omega = 1):
// - a body held at y = x while its temperature rises: s_mech = -alpha dtheta, so w = c (alpha dtheta)^2 |xi|/2
//   (the stored compression energy; without the correction w would stay 0);
// - a body stretched by s on top of its free thermal expansion, y = (1 + eps + s) x with both ramped:
//   w = c s^2 |xi| / 2 (without the correction the force would also work along the thermal part).
// Correspondence: the body held at y = x and heated gets the same w, bond by bond, as
// the isothermal body compressed to y = (1 - eps) x (the same stress and the same mechanical
// increments; the isothermal work integral is checked against closed forms in test_micropotential_work.cpp).
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/pmb.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

using namespace pd;

namespace {
constexpr double dx = 1e-3, delta = 3 * dx, alpha = 1.2e-5, theta_ref = 293.15, heat = 400;  // [m], [m], [1/K], [K], [K]
const Elastic mat = Elastic::from_E_nu(200e9, 0.25);
constexpr int steps = 20;

Body<3> block() { return box<3>({{0, 0, 0}}, {{6 * dx, 5 * dx, 4 * dx}}, dx); }

Field<3> scaled(const Body<3>& body, double s)
{
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v *= s;
    return y;
}

// Passes 0 .. steps of the rule on model at y(n) with the temperatures theta(n) (uniform).
template <class Model, class Y>
void run(Model& model, Bonds& b, CriticalMicropotential<3>& mp, std::vector<double>& theta, Y&& y_of, double dtheta_end)
{
    for (int n = 0; n <= steps; ++n) {
        std::fill(theta.begin(), theta.end(), theta_ref + dtheta_end * n / steps);
        const Field<3> y = y_of(n);
        mp.apply(b);
        Field<3> f;
        internal_force(model, b, y, f, mp.template bond_work<Model>(b));
        mp.accumulate(model, b, y);
    }
}
// Bounds 1e-9 of w below: the trapezoidal rule is exact for the linear PMB law, so only round-off remains.
// A PMB block with thermal expansion from theta, and a micropotential rule that never breaks.
struct ThermalPMB {
    Body<3> body = block();
    Bonds b = [&] {
        Bonds bonds = build_bonds(body, delta);
        bonds.enable_damage();
        return bonds;
    }();
    std::vector<double> theta = std::vector<double>(body.size(), theta_ref);
    PMB model{PMB::Params{.material = mat, .dim = 3}, b};
    CriticalMicropotential<3> mp;
    ThermalPMB()
    {
        const ThermalExpansion t{alpha, theta_ref, &theta};
        model.set_thermal_expansion(t);
        mp.w_c = 1e300;
        mp.set_thermal_expansion(t, body.x);
    }
};
}  // namespace

TEST(MicropotentialThermal, HeatedClampedPMBStoresItsCompressionEnergy)
{
    ThermalPMB p;
    auto& [body, b, theta, model, mp] = p;
    run(model, b, mp, theta, [&](int) { return body.x; }, heat);
    const double c = 18 * mat.K / (std::numbers::pi * std::pow(delta, 4)), eps = alpha * heat;
    for (std::size_t k = 0; k < b.size(); ++k) {
        const double w = c * eps * eps * b.length[k] / 2;
        ASSERT_NEAR(mp.work(b, k), w, 1e-9 * w) << k;
    }
}

// Only the nodes with x < 2.5 dx heat: a pair's mechanical stretch is minus the mean of its two ends'
// thermal strains (PMB), so w = c ((eps_i + eps_j)/2)^2 |xi| / 2: a hot pair, a mixed pair at a quarter
// of it (the correction of a pair whose lower node stays cold), a cold pair 0.
TEST(MicropotentialThermal, PartlyHeatedClampedPMBStoresEachPairsMeanThermalStrainEnergy)
{
    ThermalPMB p;
    auto& [body, b, theta, model, mp] = p;
    auto hot = [&](std::size_t i) { return body.x.c[0][i] < 2.5 * dx; };
    for (int n = 0; n <= steps; ++n) {
        for (std::size_t i = 0; i < body.size(); ++i) theta[i] = theta_ref + (hot(i) ? heat * n / steps : 0.0);
        mp.apply(b);
        Field<3> f;
        internal_force(model, b, body.x, f, mp.bond_work<PMB>(b));
        mp.accumulate(model, b, body.x);
    }
    const double c = 18 * mat.K / (std::numbers::pi * std::pow(delta, 4));
    int mixed = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        for_family(b, i, [&](std::int64_t k, int j) {
            const double eps = 0.5 * alpha * heat * (double(hot(i)) + double(hot(j))), w = c * eps * eps * b.length[k] / 2;
            mixed += hot(i) != hot(j);
            ASSERT_NEAR(mp.work(b, k), w, 1e-9 * c * alpha * heat * alpha * heat * b.length[k]) << k;
        });
    EXPECT_GT(mixed, 0);
}

// The thermal part changes w outside the force pass: the breaking test must see the corrected w.
TEST(MicropotentialThermal, HeatedClampedPMBBreaksItsLongestBondsWhenTheyReachCritical)
{
    ThermalPMB p;
    auto& [body, b, theta, model, mp] = p;
    run(model, b, mp, theta, [&](int) { return body.x; }, heat);
    double longest = 0, second = 0;
    for (double L : b.length) longest = std::max(longest, L);
    for (double L : b.length)
        if (L < longest * (1 - 1e-9)) second = std::max(second, L);
    const double c = 18 * mat.K / (std::numbers::pi * std::pow(delta, 4)), eps = alpha * heat;
    mp.w_c = c * eps * eps * 0.5 * (longest + second) / 2;  // between the two longest bonds' w
    EXPECT_GT(mp.apply(b), 0);
    for (std::size_t k = 0; k < b.size(); ++k) EXPECT_EQ(b.intact[k] == 0, b.length[k] > longest * (1 - 1e-9)) << k;
}

TEST(MicropotentialThermal, StretchOnTopOfFreeExpansionWorksOnlyAlongTheMechanicalPart)
{
    ThermalPMB p;
    auto& [body, b, theta, model, mp] = p;
    const double eps = alpha * heat, s_end = 2e-3;
    run(model, b, mp, theta, [&](int n) { return scaled(body, 1 + (eps + s_end) * n / steps); }, heat);
    const double c = 18 * mat.K / (std::numbers::pi * std::pow(delta, 4));
    for (std::size_t k = 0; k < b.size(); ++k) {
        const double w = c * s_end * s_end * b.length[k] / 2;
        ASSERT_NEAR(mp.work(b, k), w, 1e-9 * w) << k;
    }
}

TEST(MicropotentialThermal, HeatedClampedCorrespondenceMatchesTheMechanicallyCompressedBody)
{
    const Body<3> body = block();
    const double eps = alpha * heat;
    std::vector<double> theta(body.size(), theta_ref), iso_theta(body.size(), theta_ref);
    Bonds bt = build_bonds(body, delta), bm = build_bonds(body, delta);
    bt.enable_damage(), bm.enable_damage();
    Correspondence<3> heated({.material = mat, .C_hg = 0.02}, body, bt), compressed({.material = mat, .C_hg = 0.02}, body, bm);
    const ThermalExpansion t{alpha, theta_ref, &theta};
    heated.set_thermal_expansion(t);
    CriticalMicropotential<3> mp_t, mp_m;
    mp_t.w_c = mp_m.w_c = 1e300;
    mp_t.set_thermal_expansion(t, body.x);
    run(heated, bt, mp_t, theta, [&](int) { return body.x; }, heat);
    run(compressed, bm, mp_m, iso_theta, [&](int n) { return scaled(body, 1 - eps * n / steps); }, 0.0);
    double w_max = 0;
    for (std::size_t k = 0; k < bt.size(); ++k) w_max = std::max(w_max, mp_m.work(bm, k));
    ASSERT_GT(w_max, 0);
    // The two differ only through |Y| in the hourglass term and round-off: 1e-6 of the largest w.
    for (std::size_t k = 0; k < bt.size(); ++k) ASSERT_NEAR(mp_t.work(bt, k), mp_m.work(bm, k), 1e-6 * w_max) << k;
}
