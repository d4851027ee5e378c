// pd/core/variable_horizon.hpp -- bond families when every node has its own horizon delta_i and
// cell side h_i (refined grids, spec/002 sec. 2.5-2.6, 4.6): H(i) = {j : |xi| <= delta_i}.
// Two couplings of the bond-based forces, each a per-bond micromodulus on ordinary families, so that
// the force traversal is the one of uniform grids (PMB::scale_bonds):
//   source  "scaling PD" (spec/002 eq. 3.1b): node i sums over H(i) only, every bond with c(delta_i).
//           The lists are not symmetric where delta_i != delta_j: j in H(i) but i not in H(j) is a
//           lost bond, whose force on i has no reaction on j (ghost forces). reverse[k] = -1 there.
//   dual    dual-horizon PD (Ren et al.; spec/002 eqs. 2.24-2.25, 3.1c): the pair (i, j) interacts
//           when j in H(i) or i in H(j); each horizon that holds the pair contributes half of its
//           own micromodulus, c_ij = (c(delta_i) a_ij + c(delta_j) a_ji) / 2, with a_ij the
//           fraction of j's cell inside i's horizon (0 when j is not in H(i)). c_ij = c_ji, so the
//           pair forces are equal and opposite: the internal forces sum to zero (no ghost force).
//           With one delta everywhere c_ij = c a_ij: the usual family.
// Partial volumes: a_ij = partner_share (bonds.hpp) with delta_i and h_j: 1 (none), PA-PDLAMMPS's
// linear rule, or (2D) the exact area of j's square cell (lattice axes along x) inside the disc of
// radius delta_i. The families hold the full volumes V_j; a_ij enters through the factors.
// Influence function 1 only (the source's choice, spec/002 sec. 2.3).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/neighbors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

enum class HorizonCoupling { source, dual };

struct HorizonFamilies {
    Bonds bonds;                  // delta = the largest delta_i; volume = full V_j
    std::vector<double> delta;    // delta_i per node [m]
    std::vector<double> share;    // a_ij per bond k = (i -> j): j's cell fraction inside H(i) [-] (0: j outside it)
    HorizonCoupling coupling = HorizonCoupling::dual;
};

// The families of a body whose node i has horizon delta[i] and cell side h[i] (h is used by the
// partial volumes only). Throws std::invalid_argument for sizes that differ, non-positive values,
// exact areas outside 2D, or duplicate points.
template <int D>
HorizonFamilies build_variable_horizon_bonds(const Body<D>& body, const std::vector<double>& delta, const std::vector<double>& h,
                                             HorizonCoupling coupling, PartialVolume pv = PartialVolume::none)
{
    const std::size_t n = body.size();
    if (delta.size() != n || h.size() != n) throw std::invalid_argument("variable horizon: one delta and one h per node expected");
    if (pv == PartialVolume::exact_area && D != 2) throw std::invalid_argument("exact-area partial volumes are for 2D only");
    double reach = 0;  // the farthest a partner can be, over all nodes [m]
    for (std::size_t i = 0; i < n; ++i) {
        if (!(delta[i] > 0) || !(h[i] > 0)) throw std::invalid_argument("variable horizon: delta and h must be positive (node " + std::to_string(i) + ")");
        reach = std::max(reach, delta[i] + (pv == PartialVolume::exact_area ? h[i] * std::sqrt(0.5) : 0.0));
    }
    HorizonFamilies f;
    f.delta = delta, f.coupling = coupling;
    Bonds& b = f.bonds;
    b.offset.assign(n + 1, 0);
    b.delta = n > 0 ? *std::max_element(delta.begin(), delta.end()) : 0.0;
    if (n == 0) return f;
    auto share = [&](std::size_t i, int j, double r) { return partner_share<D>(body.x[j] - body.x[i], r, delta[i], h[j], pv); };
    const NeighborLists near = neighbor_lists(body.x, reach * (1 + 1e-6), [&](int i, int j) {
        const double r = norm(body.x[j] - body.x[i]);
        return share(i, j, r) > 0 || (coupling == HorizonCoupling::dual && share(j, i, r) > 0);
    });
    for (std::size_t i = 0; i < n; ++i) {
        for (std::int64_t q = near.offset[i]; q < near.offset[i + 1]; ++q) {
            const int j = near.partner[q];
            const double r = norm(body.x[j] - body.x[i]);
            if (r == 0) throw std::invalid_argument("duplicate points " + std::to_string(i) + " and " + std::to_string(j));
            b.partner.push_back(j), b.length.push_back(r), b.omega.push_back(1.0), b.volume.push_back(body.volume[j]);
            f.share.push_back(share(i, j, r));
        }
        b.offset[i + 1] = static_cast<std::int64_t>(b.partner.size());
    }
    index_reverse_bonds(b, coupling == HorizonCoupling::dual);  // the plain variable horizon's lost bonds: -1
    return f;
}

// The micromodulus of every bond relative to c(bonds.delta), for PMB::scale_bonds (header):
// source c(delta_i) a_ij, dual (c(delta_i) a_ij + c(delta_j) a_ji)/2, each over c(bonds.delta).
// c_of_delta(delta) is the model's micromodulus for a uniform horizon delta (e.g. PMB::micromodulus).
template <class Micromodulus>
std::vector<double> horizon_factors(const HorizonFamilies& f, Micromodulus&& c_of_delta)
{
    const Bonds& b = f.bonds;
    std::vector<double> c(f.delta.size());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = c_of_delta(f.delta[i]);
    const double c_ref = c_of_delta(b.delta);
    std::vector<double> factor(b.size());
    for (std::size_t i = 0; i < c.size(); ++i)
        for_family(b, i, [&](std::int64_t k, int j) {
            const double own = c[i] * f.share[k];
            factor[k] = f.coupling == HorizonCoupling::source ? own / c_ref : 0.5 * (own + c[j] * f.share[b.reverse[k]]) / c_ref;
        });
    return factor;
}

}  // namespace pd
