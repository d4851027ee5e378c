// Random modulus and density (spec/001_004 B.2 wires only the critical stretch s_c), from
// the seeded fields of random_field.hpp. The PMB micromodulus is proportional to E at fixed nu
// (pmb.hpp: c = 2 D^2 kappa / M_1, kappa proportional to E), so a modulus field enters as per-bond
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
#include "pd/core/random_field.hpp"

#include <stdexcept>
#include <vector>

namespace pd {

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
