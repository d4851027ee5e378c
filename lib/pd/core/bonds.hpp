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
#include "pd/core/partial_area.hpp"

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

// The share beta of a partner's cell (side h) in the horizon delta of a node (header), the partner at
// offset e (in the lattice's axes for exact_area), r = |e|; 0: the partner is no family member.
// build_bonds and the per-node horizons (variable_horizon.hpp) both take it.
template <int D>
inline double partner_share(const Vec<D>& e, double r, double delta, double h, PartialVolume pv)
{
    if constexpr (D == 2)
        if (pv == PartialVolume::exact_area) {
            if (r <= delta - h * std::sqrt(0.5)) return 1.0;  // cells nearer lie wholly inside
            // folded (the area is symmetric) so that beta_ij == beta_ji
            const double a = cell_fraction_in_horizon(Vec<2>{{std::abs(e[0]), std::abs(e[1])}}, delta, h);
            return a > 1e-12 ? a : 0.0;  // corner outside, or inside by round-off only
        }
    if (r > delta * (1 + horizon_roundoff)) return 0.0;
    if (pv == PartialVolume::pa_pdlammps && r > delta - h / 2) return std::min(1.0, (delta + h / 2 - r) / h);  // spec/002 sec. 3.2
    return 1.0;
}

// The reverse-bond index of families sorted by partner (j -> i by binary search). symmetric: every
// bond has its twin, else std::logic_error; otherwise a bond without one gets reverse = -1.
void index_reverse_bonds(Bonds& b, bool symmetric);

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
