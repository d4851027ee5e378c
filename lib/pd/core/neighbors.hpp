// pd/core/neighbors.hpp -- neighbour search by cell lists, shared by the bond families (bonds.cpp) and
// the contact lists (bc/contact.hpp). Points are binned into cubic cells of side `cell` (>= the search
// reach) over their bounding box; the candidates of point i are the points of the 3^D cells around
// its own, and accept(i, j) (the caller's distance rule, exact or strict, plus any filter) keeps a
// candidate. Every list is sorted by partner index, so the result depends neither on the binning
// nor on the threads. Occupied cells only are stored (sorted keys, binary search), so a cloud whose
// fragments fly apart costs no empty cells: O(N log N) for bounded density. accept runs on several
// threads at once (OpenMP), so it must not write shared state. CellBins is the binning alone, for
// searches around other points than the binned ones (the windowed updates of adaptive refinement).
#pragma once
#include "pd/core/field.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {

// Neighbour lists in CSR form: the partners of i are partner[offset[i] .. offset[i+1]), ascending.
struct NeighborLists {
    std::vector<std::int64_t> offset{0};
    std::vector<int> partner;
};

// Points binned into cubic cells of side `cell` (see header): near(p, visit) calls visit(j) for every
// point j of the 3^D cells around p's cell (candidates within `cell` of p, and more), in cell order;
// near(p, radius, visit) those of the (2 ceil(radius/cell) + 1)^D cells around it.
template <int D>
class CellBins {
public:
    CellBins(const Field<D>& x, double cell) : cell_(cell)
    {
        if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("neighbour search: the cell side must be positive and finite");
        const std::size_t n = x.size();
        if (n == 0) return;
        for (int d = 0; d < D; ++d) lo_[d] = *std::min_element(x.c[d].begin(), x.c[d].end());
        std::vector<Coord> coord(n);
        for (std::size_t i = 0; i < n; ++i) coord[i] = cell_of(x[i], static_cast<long>(i));
        sorted_.resize(n);
        for (std::size_t i = 0; i < n; ++i) sorted_[i] = static_cast<int>(i);
        std::stable_sort(sorted_.begin(), sorted_.end(), [&](int a, int b) { return before(coord[a], coord[b]); });
        for (std::size_t q = 0; q < n; ++q)
            if (q == 0 || before(keys_.back(), coord[sorted_[q]])) keys_.push_back(coord[sorted_[q]]), start_.push_back(static_cast<std::int64_t>(q));
        start_.push_back(static_cast<std::int64_t>(n));
    }

    template <class Visit>
    void near(const Vec<D>& p, Visit&& visit) const { near(p, cell_, visit); }

    // The points of the cells within `radius` of p's cell (every point within radius of p, and more).
    template <class Visit>
    void near(const Vec<D>& p, double radius, Visit&& visit) const
    {
        if (keys_.empty()) return;
        const Coord home = cell_of(p, -1);
        const long reach = std::max(1L, static_cast<long>(std::ceil(radius / cell_))), side = 2 * reach + 1;
        long nb = 1;
        for (int d = 0; d < D; ++d) nb *= side;
        for (long s = 0; s < nb; ++s) {
            Coord c = home;
            long rest = s;
            for (int d = 0; d < D; ++d, rest /= side) c[d] += rest % side - reach;
            const auto it = std::lower_bound(keys_.begin(), keys_.end(), c, before);
            if (it == keys_.end() || before(c, *it)) continue;
            const std::size_t cq = static_cast<std::size_t>(it - keys_.begin());
            for (std::int64_t q = start_[cq]; q < start_[cq + 1]; ++q) visit(sorted_[q]);
        }
    }

private:
    using Coord = std::array<std::int64_t, D>;
    double cell_;
    Vec<D> lo_{};
    std::vector<int> sorted_;            // points sorted by cell (lexicographic, z slowest)
    std::vector<Coord> keys_;            // occupied cells, ascending
    std::vector<std::int64_t> start_;    // their first position in sorted_

    static bool before(const Coord& a, const Coord& b)
    {
        for (int d = D - 1; d >= 0; --d)
            if (a[d] != b[d]) return a[d] < b[d];
        return false;
    }
    Coord cell_of(const Vec<D>& p, long point) const  // point: its index for the message (-1: a query)
    {
        Coord c;
        for (int d = 0; d < D; ++d) {
            const double k = std::floor((p[d] - lo_[d]) / cell_);
            if (!(k < 4e18 && k > -4e18))  // NaN too, or a cloud spread over more cells than an index holds: an input error
                throw std::invalid_argument("neighbour search: point " + (point >= 0 ? std::to_string(point) + " (0-based)" : std::string("queried")) +
                                            " has a non-finite coordinate or lies more than 4e18 horizons from the others");
            c[d] = static_cast<std::int64_t>(k);
        }
        return c;
    }
};

template <int D, class Accept>
NeighborLists neighbor_lists(const Field<D>& x, double cell, Accept&& accept)
{
    const CellBins<D> bins(x, cell);
    const std::size_t n = x.size();
    NeighborLists out;
    out.offset.assign(n + 1, 0);
    std::vector<std::vector<int>> lists(n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(n); ++i) {
        bins.near(x[i], [&](int j) {
            if (j != i && accept(static_cast<int>(i), j)) lists[i].push_back(j);
        });
        std::sort(lists[i].begin(), lists[i].end());
    }
    for (std::size_t i = 0; i < n; ++i) out.offset[i + 1] = out.offset[i] + static_cast<std::int64_t>(lists[i].size());
    out.partner.resize(out.offset[n]);
    for (std::size_t i = 0; i < n; ++i) std::copy(lists[i].begin(), lists[i].end(), out.partner.begin() + out.offset[i]);
    return out;
}

}  // namespace pd
