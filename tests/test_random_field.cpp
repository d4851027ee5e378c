// Random material fields (lib/pd/core/random_field.hpp, spec/001_004 V5) and the per-bond critical
// stretch of CriticalStretch: reproducibility (seed, threads, order), sample moments against the
// closed-form moments of the normal and Weibull laws, the floor, bond symmetry; random modulus and
// density (modulus_factors, density_field) in an Explicit PMB run.
// Statistical tolerances: z standard errors with z = 5 (two-sided false-alarm probability
// 5.7e-7 for a fresh seed; the seeds here are fixed, so each test is deterministic).
#include "pd/damage/critical_stretch.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/pmb.hpp"
#include "pd/core/random_field.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace pd;

namespace {
constexpr double z = 5;              // standard errors allowed (header)
constexpr std::size_t n_big = 200000;

struct Moments { double mean, var; };
Moments sample_moments(const std::vector<double>& v)
{
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
    double ss = 0;
    for (double x : v) ss += (x - mean) * (x - mean);
    return {mean, ss / (v.size() - 1)};
}
}  // namespace

TEST(RandomField, SameSeedSameFieldForOneAndTwoThreadsAndAnyOrder)
{
    const RandomSpec spec = RandomSpec::normal(4e-4, 1.5e-4, 12345);
    set_threads(1);
    const std::vector<double> one = node_field(spec, 50000);
    set_threads(2);
    const std::vector<double> two = node_field(spec, 50000);
    set_threads(0);
    EXPECT_EQ(one, two);  // bitwise: each value is a pure function of (seed, id)
    for (std::size_t i = one.size(); i-- > 0;) ASSERT_EQ(spec(i), one[i]) << i;  // reverse order
}

TEST(RandomField, DifferentSeedsAndStreamsDiffer)
{
    // floor -inf: with the default floor 0 half the values of N(0, 1) would coincide at 0.
    RandomSpec a = RandomSpec::normal(0, 1, 1, -INFINITY), b = RandomSpec::normal(0, 1, 2, -INFINITY), c = a;
    c.stream = 1;
    const auto va = node_field(a, 10000), vb = node_field(b, 10000), vc = node_field(c, 10000);
    long same_ab = 0, same_ac = 0;
    for (std::size_t i = 0; i < va.size(); ++i) same_ab += va[i] == vb[i], same_ac += va[i] == vc[i];
    EXPECT_EQ(same_ab, 0);  // continuous law: a coincidence has probability ~1e-16 per node
    EXPECT_EQ(same_ac, 0);
}

TEST(RandomField, NormalMeanAndVarianceWithinStatisticalTolerance)
{
    // Concrete of spec B.4: mean 4e-4, sd 1.5e-4; floor -inf so the law is the untruncated normal.
    const double mu = 4e-4, sd = 1.5e-4;
    const auto v = node_field(RandomSpec::normal(mu, sd, 7, -INFINITY), n_big);
    const Moments m = sample_moments(v);
    EXPECT_NEAR(m.mean, mu, z * sd / std::sqrt(n_big));                             // SE of the mean
    EXPECT_NEAR(m.var, sd * sd, z * sd * sd * std::sqrt(2.0 / (n_big - 1)));        // SE of s^2 (normal)
    // Fraction below zero against Phi(-mu/sd) = 0.5 erfc(mu/(sd sqrt 2)) (spec B.2 (ii): 0.38 %).
    const double p = 0.5 * std::erfc(mu / (sd * std::sqrt(2.0)));
    const double frac = static_cast<double>(std::count_if(v.begin(), v.end(), [](double x) { return x < 0; })) / n_big;
    EXPECT_NEAR(p, 0.0038, 1e-4);                                                     // hand value Phi(-2.667)
    EXPECT_NEAR(frac, p, z * std::sqrt(p * (1 - p) / n_big));                        // binomial SE
}

TEST(RandomField, WeibullMomentsMatchClosedForm)
{
    // E[X^n] = lambda^n Gamma(1 + n/k); variance of s^2 from the central 4th moment mu4:
    // Var(s^2) ~ (mu4 - sigma^4)/N.
    const double k = 2.5, lambda = 3e-3;
    const auto v = node_field(RandomSpec::weibull(k, lambda, 99), n_big);
    auto raw = [&](int n) { return std::pow(lambda, n) * std::tgamma(1 + n / k); };
    const double mean = raw(1), var = raw(2) - mean * mean;
    const double mu4 = raw(4) - 4 * mean * raw(3) + 6 * mean * mean * raw(2) - 3 * std::pow(mean, 4);
    const Moments m = sample_moments(v);
    EXPECT_NEAR(m.mean, mean, z * std::sqrt(var / n_big));
    EXPECT_NEAR(m.var, var, z * std::sqrt((mu4 - var * var) / n_big));
    // Median lambda (ln 2)^(1/k): fraction below it is 1/2 within the binomial SE.
    const double median = lambda * std::pow(std::log(2.0), 1 / k);
    const double below = static_cast<double>(std::count_if(v.begin(), v.end(), [&](double x) { return x < median; })) / n_big;
    EXPECT_NEAR(below, 0.5, z * 0.5 / std::sqrt(n_big));
}

TEST(RandomField, FloorIsHonoured)
{
    const double floor = 1e-4;
    const auto v = node_field(RandomSpec::normal(4e-4, 1.5e-4, 3, floor), n_big);
    EXPECT_GE(*std::min_element(v.begin(), v.end()), floor);
    // P(X < floor) = Phi((floor - mu)/sd) = Phi(-2) = 0.02275 of the values sit at the floor.
    const double p = 0.5 * std::erfc(2 / std::sqrt(2.0));
    const double at = static_cast<double>(std::count(v.begin(), v.end(), floor)) / n_big;
    EXPECT_NEAR(at, p, z * std::sqrt(p * (1 - p) / n_big));
    EXPECT_THROW(RandomSpec::weibull(0, 1, 1), std::invalid_argument);
    EXPECT_THROW(RandomSpec::normal(0, -1, 1), std::invalid_argument);
}

TEST(RandomField, BondValuesSymmetricAndFollowTheRule)
{
    const Body<3> body = box<3>({0, 0, 0}, {6e-3, 5e-3, 4e-3}, 1e-3);
    const Bonds b = build_bonds(body, 2.1e-3);
    const RandomSpec spec = RandomSpec::normal(1.328e-2, 3.32e-3, 5);
    for (BondRule rule : {BondRule::min, BondRule::max, BondRule::mean, BondRule::bond}) {
        const auto s = bond_field(spec, b, rule);
        ASSERT_EQ(s.size(), b.size());
        for (std::size_t k = 0; k < b.size(); ++k) ASSERT_EQ(s[k], s[b.reverse[k]]) << k;
    }
    const auto smin = bond_field(spec, b, BondRule::min), smean = bond_field(spec, b, BondRule::mean);
    const auto smax = bond_field(spec, b, parse_bond_rule("max"));
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (auto k = b.begin(i); k < b.end(i); ++k) {
            const double si = spec(i), sj = spec(b.partner[k]);
            ASSERT_EQ(smin[k], std::min(si, sj));
            ASSERT_EQ(smax[k], std::max(si, sj));
            ASSERT_DOUBLE_EQ(smean[k], 0.5 * (si + sj));
        }
    EXPECT_THROW(parse_bond_rule("half"), std::invalid_argument);
}

TEST(RandomField, PerBondCriticalStretchBreaksExactlyTheWeakBonds)
{
    // Uniform stretch s = 1e-3 (y = 1.001 x): every bond has s = 1e-3. Bonds with s0_k below it
    // break, the others hold; a constant s0_bond equals the scalar path.
    const Body<3> body = box<3>({0, 0, 0}, {5e-3, 5e-3, 5e-3}, 1e-3);
    Field<3> y(body.size());
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < body.size(); ++i) y.c[d][i] = 1.001 * body.x.c[d][i];
    Bonds b = build_bonds(body, 2.1e-3);
    b.enable_damage();
    CriticalStretch cs;
    cs.s0_bond = bond_field(RandomSpec::normal(1e-3, 2e-4, 11), b, BondRule::bond);
    const long expected = std::count_if(cs.s0_bond.begin(), cs.s0_bond.end(), [](double s0) { return s0 < 1e-3 * (1 - 1e-9); });
    EXPECT_EQ(cs.apply(b, y), expected);
    for (std::size_t k = 0; k < b.size(); ++k) ASSERT_EQ(b.intact[k], cs.s0_bond[k] < 1e-3 * (1 - 1e-9) ? 0 : 1) << k;
    EXPECT_GT(expected, 0);
    EXPECT_LT(expected, static_cast<long>(b.size()));
    // Scalar vs constant per-bond field: same broken set.
    Bonds b1 = build_bonds(body, 2.1e-3), b2 = b1;
    b1.enable_damage(), b2.enable_damage();
    CriticalStretch scalar = CriticalStretch::uniform(0.9e-3), per_bond;
    per_bond.s0_bond.assign(b2.size(), 0.9e-3);
    EXPECT_EQ(scalar.apply(b1, y), per_bond.apply(b2, y));
    EXPECT_EQ(b1.intact, b2.intact);
    per_bond.s0_bond.pop_back();
    EXPECT_THROW(per_bond.apply(b2, y), std::invalid_argument);
}

namespace {
// Explicit PMB block (14 x 13 x 12 nodes, above parallel_min_nodes) released from a smooth
// non-uniform displacement, with modulus factors and densities from seeded normal fields; or, with
// random = false, the homogeneous block. Returns the displacement after 40 steps.
Field<3> random_material_run(int threads, bool random)
{
    set_threads(threads);
    const double dx = 1e-3, E = 200e9, rho = 7850;
    const Body<3> body = box<3>({0, 0, 0}, {14 * dx, 13 * dx, 12 * dx}, dx);
    Bonds b = build_bonds(body, 3.05 * dx);
    const Elastic mat = Elastic::from_E_nu(E, 0.25);
    PMB pmb({.material = mat, .dim = 3}, b);
    if (random) pmb.scale_bonds(modulus_factors(RandomSpec::normal(E, 0.05 * E, 11), b, BondRule::mean));
    Explicit<3, PMB> sim(body, b, pmb, rho);
    if (random) sim.rho = density_field(RandomSpec::normal(rho, 0.05 * rho, 11, 0.5 * rho), body.size());
    for (std::size_t i = 0; i < body.size(); ++i) sim.u.c[0][i] = 1e-6 * std::sin(200 * body.x.c[0][i] + 300 * body.x.c[1][i]);
    sim.start();
    // dt: 0.1 of dx / c_wave (c = sqrt(E/rho) ~ 5 km/s): far below the critical step even for the
    // field's extremes (factor <= 1.25 at 5 sd, rho >= 0.75 rho).
    const double dt = 0.1 * dx / std::sqrt(E / rho);
    for (int n = 0; n < 40; ++n) sim.step(dt);
    set_threads(0);
    return sim.u;
}
}  // namespace

// Random modulus and density: the run is bit-identical for 1 and 2 threads (fields are pure
// functions of (seed, stream, id); owner-computes force loop) and differs from the homogeneous run.
// Sample means against the requested means, z = 5 standard errors: modulus factors drawn per pair
// (rule bond: independent draws; each pair appears twice in the ordered list, so n = pairs),
// mean 1, sd 0.05; densities per node, mean 7850, sd 392.5.
TEST(RandomField, RandomModulusAndDensityRunIsThreadIndependent)
{
    const Field<3> u1 = random_material_run(1, true), u2 = random_material_run(2, true), u0 = random_material_run(1, false);
    double diff = 0, scale = 0;
    for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(u1.c[d], u2.c[d]) << "component " << d;
        for (std::size_t i = 0; i < u0.size(); ++i) {
            diff = std::max(diff, std::abs(u1.c[d][i] - u0.c[d][i]));
            scale = std::max(scale, std::abs(u0.c[d][i]));
        }
    }
    EXPECT_GT(diff, 1e-3 * scale);  // the fields change the run (5 % scatter)

    const Body<3> body = box<3>({0, 0, 0}, {20e-3, 20e-3, 20e-3}, 1e-3);
    const Bonds b = build_bonds(body, 3.05e-3);
    const Moments f = sample_moments(modulus_factors(RandomSpec::normal(200e9, 10e9, 3), b, BondRule::bond));
    EXPECT_NEAR(f.mean, 1.0, z * 0.05 / std::sqrt(b.size() / 2.0));
    const Moments r = sample_moments(density_field(RandomSpec::normal(7850, 392.5, 3, 1000), body.size()));
    EXPECT_NEAR(r.mean, 7850, z * 392.5 / std::sqrt(double(body.size())));
    EXPECT_NEAR(std::sqrt(r.var), 392.5, z * 392.5 / std::sqrt(2.0 * body.size()));  // se of sd: sd/sqrt(2n)
    EXPECT_THROW(density_field(RandomSpec::normal(7850, 392.5, 3), 10), std::invalid_argument);  // floor 0
}
