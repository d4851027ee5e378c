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

// What a windowed update reuses (adaptive refinement, time/adaptive_refinement.hpp): the families of
// the previous node set, prev_index[i] the previous index of node i (-1: a new node), and affected[i]
// = 1 for the nodes whose family may have changed (those within the largest reach of a node that
// appeared, disappeared or changed its horizon). Every other node keeps its previous family, with its
// partners renumbered (the renumbering must keep their order, as removing and appending nodes does)
// and its bonds' lengths, volumes and shares copied: the same families as a full build, at the cost
// of the affected nodes' searches.
struct FamilyReuse {
    const HorizonFamilies* prev = nullptr;
    std::vector<int> prev_index;
    std::vector<std::uint8_t> affected;
};

// The families of a body whose node i has horizon delta[i] and cell side h[i] (h is used by the
// partial volumes only); with `reuse`, a windowed update (above). Throws std::invalid_argument for
// sizes that differ, non-positive values, exact areas outside 2D, or duplicate points.
template <int D>
HorizonFamilies build_variable_horizon_bonds(const Body<D>& body, const std::vector<double>& delta, const std::vector<double>& h,
                                             HorizonCoupling coupling, PartialVolume pv = PartialVolume::none, const FamilyReuse* reuse = nullptr)
{
    const std::size_t n = body.size();
    if (delta.size() != n || h.size() != n) throw std::invalid_argument("variable horizon: one delta and one h per node expected");
    if (pv == PartialVolume::exact_area && D != 2) throw std::invalid_argument("exact-area partial volumes are for 2D only");
    if (reuse && (!reuse->prev || reuse->prev_index.size() != n || reuse->affected.size() != n))
        throw std::invalid_argument("variable horizon: a reuse needs the previous families and one index and flag per node");
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
    // The searched families (every node without reuse): each node searches its own reach, so a fine
    // node does not scan a coarse node's horizon (the cells have the smallest reach); a dual family
    // adds the nodes whose horizon holds it (the transpose of the searched lists, and of the kept
    // families that hold an affected node).
    std::vector<double> own(n);
    for (std::size_t i = 0; i < n; ++i) own[i] = (delta[i] + (pv == PartialVolume::exact_area ? h[i] * std::sqrt(0.5) : 0.0)) * (1 + 1e-6);
    const CellBins<D> bins(body.x, *std::min_element(own.begin(), own.end()));
    auto searched = [&](std::size_t i) { return !reuse || reuse->affected[i]; };
    std::vector<std::vector<int>> found(n);
#pragma omp parallel for schedule(dynamic, 64)
    for (long i = 0; i < static_cast<long>(n); ++i) {
        if (!searched(i)) continue;
        bins.near(body.x[i], own[i], [&](int j) {
            if (j != i && share(i, j, norm(body.x[j] - body.x[i])) > 0) found[i].push_back(j);
        });
    }
    std::vector<int> next_index;  // previous index -> index here
    if (reuse) {
        next_index.assign(reuse->prev->delta.size(), -1);
        for (std::size_t i = 0; i < n; ++i)
            if (reuse->prev_index[i] >= 0) next_index[reuse->prev_index[i]] = static_cast<int>(i);
    }
    if (coupling == HorizonCoupling::dual) {
        std::vector<std::vector<int>> held(n);  // held[i]: the nodes whose horizon holds i
        for (std::size_t j = 0; j < n; ++j) {
            if (searched(j)) {
                for (int i : found[j]) held[i].push_back(static_cast<int>(j));
                continue;
            }
            const Bonds& p = reuse->prev->bonds;
            for (std::int64_t k = p.begin(reuse->prev_index[j]); k < p.end(reuse->prev_index[j]); ++k) {
                const int i = next_index[p.partner[k]];
                if (i >= 0 && searched(i)) held[i].push_back(static_cast<int>(j));
            }
        }
        for (std::size_t i = 0; i < n; ++i) found[i].insert(found[i].end(), held[i].begin(), held[i].end());
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (long i = 0; i < static_cast<long>(n); ++i) {
        std::sort(found[i].begin(), found[i].end());
        found[i].erase(std::unique(found[i].begin(), found[i].end()), found[i].end());
    }
    for (std::size_t i = 0; i < n; ++i) {  // the offsets, then every family in place
        const bool kept = reuse && !reuse->affected[i];
        if (kept && reuse->prev_index[i] < 0) throw std::logic_error("variable horizon: a new node must be affected");
        const std::int64_t size = kept ? reuse->prev->bonds.end(reuse->prev_index[i]) - reuse->prev->bonds.begin(reuse->prev_index[i])
                                       : static_cast<std::int64_t>(found[i].size());
        b.offset[i + 1] = b.offset[i] + size;
    }
    const std::size_t m = static_cast<std::size_t>(b.offset[n]);
    b.partner.resize(m), b.length.resize(m), b.omega.assign(m, 1.0), b.volume.resize(m), f.share.resize(m);
    long lost = -1, duplicate = -1;  // a node whose kept family lost a partner; one with a duplicate point (thrown after the loop)
#pragma omp parallel for schedule(dynamic, 64) reduction(max : lost, duplicate)
    for (long i = 0; i < static_cast<long>(n); ++i) {
        std::int64_t k = b.offset[i];
        if (reuse && !reuse->affected[i]) {
            const HorizonFamilies& p = *reuse->prev;
            const std::int64_t first = p.bonds.begin(reuse->prev_index[i]), last = p.bonds.end(reuse->prev_index[i]);
            for (std::int64_t q = first; q < last; ++q, ++k) {
                b.partner[k] = next_index[p.bonds.partner[q]];
                if (b.partner[k] < 0) lost = i;
            }
            std::copy(p.bonds.length.begin() + first, p.bonds.length.begin() + last, b.length.begin() + b.offset[i]);
            std::copy(p.bonds.volume.begin() + first, p.bonds.volume.begin() + last, b.volume.begin() + b.offset[i]);
            std::copy(p.share.begin() + first, p.share.begin() + last, f.share.begin() + b.offset[i]);
            continue;
        }
        for (int j : found[i]) {
            const double r = norm(body.x[j] - body.x[i]);
            if (r == 0) duplicate = i;
            b.partner[k] = j, b.length[k] = r, b.volume[k] = body.volume[j], f.share[k] = share(i, j, r), ++k;
        }
    }
    if (lost >= 0) throw std::logic_error("variable horizon: the kept family of node " + std::to_string(lost) + " lost a partner; mark it affected");
    if (duplicate >= 0) throw std::invalid_argument("variable horizon: node " + std::to_string(duplicate) + " has a duplicate point");
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


// The critical stretch of every bond of dual families (CriticalStretch::s0_bond), symmetric: each
// horizon that holds the pair contributes its half of c_ij with its own critical stretch, and the pair
// breaks when its micropotential reaches the sum of the halves' critical ones (spec/002 sec. 4.6: s0
// per horizon, eq. 2.15): c_ij s0_ij^2 = (c(delta_i) a_ij s0(delta_i)^2 + c(delta_j) a_ji s0(delta_j)^2) / 2.
// With one delta everywhere s0_ij = s0(delta). Throws for source families (their lost bonds have no pair).
template <class Micromodulus, class CriticalStretchOf>
std::vector<double> pair_critical_stretch(const HorizonFamilies& f, Micromodulus&& c_of_delta, CriticalStretchOf&& s0_of_delta)
{
    if (f.coupling != HorizonCoupling::dual) throw std::invalid_argument("pair_critical_stretch: dual-horizon families expected");
    const Bonds& b = f.bonds;
    std::vector<double> c(f.delta.size()), s0(f.delta.size());
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = c_of_delta(f.delta[i]), s0[i] = s0_of_delta(f.delta[i]);
    std::vector<double> out(b.size());
    for (std::size_t i = 0; i < c.size(); ++i)
        for_family(b, i, [&](std::int64_t k, int j) {
            const double wi = c[i] * f.share[k], wj = c[j] * f.share[b.reverse[k]];
            const double ei = wi * s0[i] * s0[i], ej = wj * s0[j] * s0[j];  // summed in a fixed order: s0_ij == s0_ji bit for bit
            out[k] = std::sqrt((std::min(ei, ej) + std::max(ei, ej)) / (std::min(wi, wj) + std::max(wi, wj)));
        });
    return out;
}

}  // namespace pd
