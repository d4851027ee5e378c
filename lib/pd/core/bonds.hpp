// Bond families in CSR form (offsets, partners) with structure-of-arrays per-bond data, the
// reverse-bond index (bond j->i of bond i->j in O(1)); the neighbours come from neighbors.hpp.
// A family holds every j != i with |x_j - x_i| <= delta (boundary included).
// Partial volumes (spec/002 sec. 3.2): `none` uses the full V_j; `pa-pdlammps` scales V_j by
//   beta = 1 for |xi| <= delta - h/2,  beta = (delta + h/2 - |xi|)/h for delta - h/2 < |xi| <= delta,
// with h the lattice spacing (the partial-area rule of PDLAMMPS). `exact-area` (2D lattices only)
// scales V_j by the exact fraction of j's square cell (side h, axes rotated by lattice_angle) inside
// the horizon (partial_area.hpp), and so also holds the j with |xi| > delta whose cell the horizon
// cuts (|xi| < delta + h/sqrt 2): the areas of IPA-Hybrid (spec/002 sec. 3.2), with the integration
// point left at the node (IPA-Hybrid moves it to the centroid of the covered part). The areas of a
// full family add up to pi delta^2 (to 1e-12). Influence functions must be defined beyond delta
// (one, inv_xi).
#pragma once
#include "pd/core/influence.hpp"
#include "pd/core/lattice.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace pd {

enum class PartialVolume { none, pa_pdlammps, exact_area };
PartialVolume parse_partial_volume(const std::string& name);  // "none" | "pa-pdlammps" | "exact-area"; throws otherwise

struct Bonds {
    double delta = 0;                 // horizon [m]
    Influence influence{};            // omega(|xi|) the families were built with (`omega` holds its values)
    std::vector<std::int64_t> offset;  // family of i is [offset[i], offset[i+1])
    std::vector<int> partner;         // j of bond k, ascending within a family
    std::vector<double> length;       // reference length |xi| [m]
    std::vector<double> omega;        // influence omega(|xi|) [-]
    std::vector<double> volume;       // beta V_j, partner volume seen from i [m^3]
    std::vector<std::int64_t> reverse;  // index of bond j->i
    std::vector<std::uint8_t> intact;   // 1 intact, 0 broken; empty when the scene has no damage
    bool damage = false;                // enable_damage() was called (so also for a body without bonds)

    std::size_t nodes() const { return offset.empty() ? 0 : offset.size() - 1; }
    std::size_t size() const { return partner.size(); }  // ordered pairs i->j
    std::int64_t begin(std::size_t i) const { return offset[i]; }
    std::int64_t end(std::size_t i) const { return offset[i + 1]; }
    bool has_damage() const { return damage; }
    // Breaks both halves of bond k's pair; returns how many of them were intact (0, 1 or 2).
    int break_pair(std::int64_t k)
    {
        std::uint8_t& back = intact[reverse[k]];
        const int was = intact[k] + back;
        intact[k] = 0;
        back = 0;
        return was;
    }
    void enable_damage()
    {
        intact.assign(size(), 1);
        damage = true;
    }
};

// The family traversals in family order, for set-up and bookkeeping that need no vector path (the
// force, dilatation and heat passes take bond_loop.hpp's lane_sums): bond(k, j) for every bond k of
// node i (partner j), k ascending; for_intact_bonds skips the broken ones, for_family visits them
// too (set-up at the reference, histories kept on broken bonds, damage bookkeeping).
template <class Bond>
inline void for_family(const Bonds& b, std::size_t i, Bond&& bond)
{
    for (std::int64_t k = b.begin(i); k < b.end(i); ++k) bond(k, b.partner[k]);
}
template <class Bond>
inline void for_intact_bonds(const Bonds& b, std::size_t i, Bond&& bond)
{
    const bool damaged = b.has_damage();
    for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
        if (!damaged || b.intact[k]) bond(k, b.partner[k]);
}

struct BondOptions {
    Influence influence{};
    PartialVolume partial_volume = PartialVolume::none;
    double lattice_angle = 0;  // exact-area: rotation of the 2D lattice's axes from x [rad]
    // Optional filter: a bond i->j is created only when keep(i, j) is true (pre-cracks as cut
    // bonds). It must be symmetric in i and j, and safe to call from several threads at once.
    std::function<bool(int i, int j)> keep;
};

// Relative tolerance on |xi| <= delta: lattice coordinates are computed in floating point, so a
// neighbour at exactly delta (e.g. delta = 3 dx) can come out an ulp beyond it.
inline constexpr double horizon_roundoff = 1e-10;

template <int D>
Bonds build_bonds(const Body<D>& body, double delta, const BondOptions& opt = {});

// True when no bond is longer than delta (with the roundoff rule); false for exact-area families,
// which also hold the cells the horizon cuts beyond delta.
inline bool families_within_horizon(const Bonds& b)
{
    for (double L : b.length)
        if (L > b.delta * (1 + horizon_roundoff)) return false;
    return true;
}

// Integer offsets n != 0 of the full family of a simple-cubic lattice of spacing dx in `dim`
// dimensions (|n| dx <= delta with the roundoff rule of build_bonds); unused components are 0.
std::vector<std::array<long, 3>> full_family_offsets(double delta, double dx, int dim);

}  // namespace pd
