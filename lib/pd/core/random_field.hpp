// Seeded random material fields per node or per bond (spec/001_004 B.2, V5): critical stretch,
// modulus or density drawn from a normal or Weibull distribution.
// Reproducibility: the value of node (or bond) `id` is a pure function of (seed, stream, id):
//   h = mix64(seed, stream, id) (SplitMix64 finaliser, a counter-based hash),
//   u = (h >> 11 + 1/2) 2^-53  in (0, 1),
//   value = max(floor, F^-1(u)),
// with F^-1 the inverse CDF from GSL: normal  mean + gsl_cdf_gaussian_Pinv(u, sd);
//                                     Weibull gsl_cdf_weibull_Pinv(u, scale, shape),
//                                     F(x) = 1 - exp(-(x/scale)^shape).
// So the field does not depend on the thread count, the evaluation order or the domain split,
// unlike the source's patch (std::default_random_engine reseeded per rank, spec B.2 (i)).
// Bond values from node values (the source keeps one value per node and lets half-bond i->j use
// s_c(i), one-sided; spec B.2). Our owner-computes loop needs a bond and its reverse to break
// together (momentum balance), so the rule here is symmetric:
//   min   s_k = min(s_i, s_j)  (the pair fails when its weaker half would fail in the source)
//   max   s_k = max(s_i, s_j)  (the pair keeps its whole force until the stronger half would fail; the
//         source's half-bonds keep half of it from the weaker to the stronger, so min and max bracket them)
//   mean  s_k = (s_i + s_j)/2
//   bond  an independent draw per unordered pair, id = (min(i,j), max(i,j)).
// The floor guards against non-physical values: an unbounded normal gives s_c < 0 with
// probability Phi(-mean/sd) (0.38 % for concrete, spec B.2 (ii)); such a draw is raised to floor.
// Random modulus and density (spec/001_004 B.2 wires only the critical stretch s_c) from these
// fields: the PMB micromodulus is proportional to E at fixed nu (pmb.hpp: c = 2 D^2 kappa / M_1,
// kappa proportional to E), so a modulus field enters as per-bond
// factors f_k = E_k / E_mean for PMB::scale_bonds; the bond rule makes f symmetric (f_k equal on
// a bond and its reverse), so the pair forces stay equal and opposite. A density field is
// Explicit's per-node rho (time/verlet.hpp). Usage:
//   pmb.scale_bonds(modulus_factors(RandomSpec::normal(E, sd_E, seed), bonds, BondRule::mean));
//   sim.rho = density_field(RandomSpec::normal(rho, sd_rho, seed, rho_floor), body.size());
// Both are pure functions of (seed, stream, id), so a run is the same for any thread count
// (tests/test_random_field.cpp). Take the time step from the stiffest bond and the lightest node
// (e.g. the field's extremes), not from the means.
#pragma once
#include "pd/core/bonds.hpp"

#include <gsl/gsl_cdf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

// SplitMix64 finaliser (Steele, Lea, Flood 2014): a bijective 64-bit mixer with full avalanche.
inline std::uint64_t mix64(std::uint64_t z)
{
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// Uniform number in the open interval (0, 1) for (seed, stream, id); 53 random bits.
inline double hashed_uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t id)
{
    const std::uint64_t h = mix64(mix64(mix64(seed) ^ stream) ^ id);
    return (static_cast<double>(h >> 11) + 0.5) * 0x1.0p-53;
}

struct RandomSpec {
    enum class Kind { normal, weibull } kind = Kind::normal;
    double mean = 0, sd = 0;        // normal: mean and standard deviation [unit of the field]
    double shape = 0, scale = 0;    // Weibull: shape k [-] and scale lambda [unit of the field]
    double floor = 0;               // values below are raised to it [unit of the field]
    std::uint64_t seed = 1;
    std::uint64_t stream = 0;       // separates fields drawn with one seed (e.g. s0 vs E)

    static RandomSpec normal(double mean, double sd, std::uint64_t seed, double floor = 0)
    {
        if (!(sd >= 0)) throw std::invalid_argument("random field: standard deviation must be >= 0");
        RandomSpec r;
        r.kind = Kind::normal, r.mean = mean, r.sd = sd, r.seed = seed, r.floor = floor;
        return r;
    }
    static RandomSpec weibull(double shape, double scale, std::uint64_t seed, double floor = 0)
    {
        if (!(shape > 0) || !(scale > 0)) throw std::invalid_argument("random field: Weibull shape and scale must be > 0");
        RandomSpec r;
        r.kind = Kind::weibull, r.shape = shape, r.scale = scale, r.seed = seed, r.floor = floor;
        return r;
    }

    // The value of entity `id` (inverse-CDF transform of the hashed uniform, then the floor).
    double operator()(std::uint64_t id) const
    {
        const double u = hashed_uniform(seed, stream, id);
        const double x = kind == Kind::normal ? mean + (sd > 0 ? gsl_cdf_gaussian_Pinv(u, sd) : 0.0)
                                              : gsl_cdf_weibull_Pinv(u, scale, shape);
        return std::max(floor, x);
    }
};

// One value per node: v_i = spec(i).
inline std::vector<double> node_field(const RandomSpec& spec, std::size_t nodes)
{
    std::vector<double> v(nodes);
    const long n = static_cast<long>(nodes);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) v[i] = spec(static_cast<std::uint64_t>(i));
    return v;
}

enum class BondRule { min, max, mean, bond };
inline BondRule parse_bond_rule(const std::string& s)
{
    if (s == "min") return BondRule::min;
    if (s == "max") return BondRule::max;
    if (s == "mean") return BondRule::mean;
    if (s == "bond") return BondRule::bond;
    throw std::invalid_argument("bond rule must be min, max, mean or bond");
}

// Per-bond values (CSR order of b), symmetric: value[k] == value[reverse[k]] (header rules).
inline std::vector<double> bond_field(const RandomSpec& spec, const Bonds& b, BondRule rule)
{
    std::vector<double> node;
    if (rule != BondRule::bond) node = node_field(spec, b.nodes());
    std::vector<double> s(b.size());
    const long n = static_cast<long>(b.nodes());
    const std::uint64_t N = b.nodes();
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i)
        for_family(b, i, [&](std::int64_t k, int partner) {
            const std::uint64_t j = static_cast<std::uint64_t>(partner);
            const std::uint64_t lo = std::min<std::uint64_t>(i, j), hi = std::max<std::uint64_t>(i, j);
            switch (rule) {
            case BondRule::min: s[k] = std::min(node[i], node[j]); break;
            case BondRule::max: s[k] = std::max(node[i], node[j]); break;
            case BondRule::mean: s[k] = 0.5 * (node[i] + node[j]); break;
            case BondRule::bond: s[k] = spec(lo * N + hi); break;  // unordered pair id
            }
        });
    return s;
}

// Stream of the density field: independent of a modulus (stream 0) or s_c field drawn with the same seed.
inline constexpr std::uint64_t density_stream = 2;

// Per-bond modulus factors E_k / E_mean, E_k drawn by `rule` from a normal spec of mean E_mean > 0.
inline std::vector<double> modulus_factors(const RandomSpec& spec, const Bonds& b, BondRule rule)
{
    if (spec.kind != RandomSpec::Kind::normal || !(spec.mean > 0))
        throw std::invalid_argument("modulus_factors: a normal field with mean > 0 is expected");
    std::vector<double> f = bond_field(spec, b, rule);
    for (double& x : f) x /= spec.mean;
    return f;
}

// Per-node density [kg/m^3] from `spec` on the density stream (so one seed can drive E and rho).
// spec.floor must be > 0: a normal draw can be <= 0, and Explicit divides by rho.
inline std::vector<double> density_field(RandomSpec spec, std::size_t nodes)
{
    if (!(spec.floor > 0)) throw std::invalid_argument("density_field: the floor must be > 0 (a density)");
    spec.stream = density_stream;
    return node_field(spec, nodes);
}

}  // namespace pd
