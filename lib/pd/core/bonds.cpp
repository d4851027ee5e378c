// CSR bond families (bonds.hpp) from the neighbour search of neighbors.hpp.
#include "pd/core/bonds.hpp"
#include "pd/core/errors.hpp"
#include "pd/core/neighbors.hpp"
#include "pd/core/partial_area.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace pd {

PartialVolume parse_partial_volume(const std::string& name)
{
    if (name == "none") return PartialVolume::none;
    if (name == "pa-pdlammps") return PartialVolume::pa_pdlammps;
    if (name == "exact-area") return PartialVolume::exact_area;
    throw std::invalid_argument("unknown partial-volume option '" + name + "' (none, pa-pdlammps, exact-area)");
}

template <int D>
Bonds build_bonds(const Body<D>& body, double delta, const BondOptions& opt)
{
    if (!(delta > 0)) throw std::invalid_argument("horizon delta must be positive");
    const std::size_t n = body.size();
    Bonds b;
    b.delta = delta;
    b.influence = opt.influence;
    b.offset.assign(n + 1, 0);
    if (n == 0) return b;
    const bool exact = opt.partial_volume == PartialVolume::exact_area;
    if (opt.partial_volume != PartialVolume::none && !(body.dx > 0))
        throw std::invalid_argument("partial volumes need a lattice spacing (dx > 0)");
    if (exact && D != 2) throw std::invalid_argument("exact-area partial volumes are for 2D lattices only");
    if (exact && opt.influence.kind != Influence::Kind::one && opt.influence.kind != Influence::Kind::inv_xi)
        throw std::invalid_argument("exact-area partial volumes need an influence function defined beyond delta (one, inv_xi)");
    // Families that cannot fit are refused before the search: about n x (horizon / mean node volume)
    // bonds of ~64 bytes each (the bond arrays and a model's per-bond data).
    double volume = 0;
    for (double v : body.volume) volume += v;
    const double horizon = horizon_moment(Influence{}, 0, delta, D, body.measure);  // its volume [m^3]
    double family = horizon / (volume / static_cast<double>(n));
    if (!(family <= static_cast<double>(n - 1))) family = static_cast<double>(n - 1);  // also NaN (zero volumes)
    char what[160];
    std::snprintf(what, sizeof what, "the horizon delta = %g m: about %.3g bonds (%zu nodes, %.3g per family)", delta,
                  static_cast<double>(n) * family, n, family);
    require_memory(static_cast<double>(n) * family * 64.0, what);
    // Search reach: delta, or (exact-area) the farthest cell corner the horizon can touch.
    const double reach = (exact ? delta + body.dx * std::sqrt(0.5) : delta) * (1 + horizon_roundoff);

    // 1. Candidates by cell lists (neighbors.hpp), cells a little wider than the search reach. With
    // side exactly delta, lattice points at exactly delta (integer m) sit on cell faces and
    // round-off in (x - lo)/side can put two neighbours two cells apart (bond lost).
    const double cell = reach * (1 + 1e-6);  // 1e-6 >> horizon_roundoff and index round-off
    const NeighborLists near = neighbor_lists(body.x, cell, [&](int i, int j) {
        return norm(body.x[j] - body.x[i]) <= reach && (!opt.keep || opt.keep(i, j));
    });

    // 2. Families, sorted by partner index for locality.
    const double h = body.dx;
    const double ca = std::cos(opt.lattice_angle), sa = std::sin(opt.lattice_angle);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec<D> xi = body.x[i];
        for (std::int64_t q = near.offset[i]; q < near.offset[i + 1]; ++q) {
            const int j = near.partner[q];
            const double r = norm(body.x[j] - xi);
            if (r == 0) throw std::invalid_argument("duplicate points " + std::to_string(i) + " and " + std::to_string(j));
            Vec<D> e = body.x[j] - xi;
            if constexpr (D == 2)
                if (exact) e = Vec<2>{{ca * e[0] + sa * e[1], -sa * e[0] + ca * e[1]}};  // in the lattice's axes
            const double beta = partner_share<D>(e, r, delta, h, opt.partial_volume);
            if (!(beta > 0)) continue;
            b.partner.push_back(j);
            b.length.push_back(r);
            b.omega.push_back(opt.influence(r, delta));
            b.volume.push_back(beta * body.volume[j]);
        }
        b.offset[i + 1] = static_cast<std::int64_t>(b.partner.size());
    }

    index_reverse_bonds(b, true);  // 3.
    return b;
}

void index_reverse_bonds(Bonds& b, bool symmetric)
{
    // One merge pass: visiting i in ascending order, the bonds j -> l (l < j) of a family sorted by
    // partner are met in the order of l, so a cursor per family finds each twin in O(1).
    b.reverse.assign(b.size(), -1);
    std::vector<std::int64_t> next(b.offset.begin(), b.offset.end() - 1);
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for_family(b, i, [&](std::int64_t k, int j) {
            if (j <= static_cast<int>(i)) return;
            std::int64_t p = next[j];
            while (p < b.offset[j + 1] && b.partner[p] < static_cast<int>(i)) ++p;  // j -> l without a twin
            if (p < b.offset[j + 1] && b.partner[p] == static_cast<int>(i)) b.reverse[k] = p, b.reverse[p] = k, next[j] = p + 1;
        });
    if (symmetric && std::find(b.reverse.begin(), b.reverse.end(), std::int64_t{-1}) != b.reverse.end())
        throw std::logic_error("bond family is not symmetric (keep filter must be symmetric)");
}

std::vector<std::array<long, 3>> full_family_offsets(double delta, double dx, int dim)
{
    const double reach = delta * (1 + horizon_roundoff);
    const long M = static_cast<long>(std::floor(reach / dx));
    std::vector<std::array<long, 3>> offsets;
    for (long a = -M; a <= M; ++a)
        for (long b = (dim > 1 ? -M : 0); b <= (dim > 1 ? M : 0); ++b)
            for (long c = (dim > 2 ? -M : 0); c <= (dim > 2 ? M : 0); ++c) {
                const long n2 = a * a + b * b + c * c;
                if (n2 > 0 && dx * std::sqrt(double(n2)) <= reach) offsets.push_back({a, b, c});
            }
    return offsets;
}

template Bonds build_bonds<1>(const Body<1>&, double, const BondOptions&);
template Bonds build_bonds<2>(const Body<2>&, double, const BondOptions&);
template Bonds build_bonds<3>(const Body<3>&, double, const BondOptions&);

}  // namespace pd
