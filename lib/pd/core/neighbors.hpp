// pd/core/neighbors.hpp -- neighbour search by cell lists, shared by the bond families (bonds.cpp) and
// the contact lists (bc/contact.hpp). Points are binned into cubic cells of side `cell` (>= the search
// reach) over their bounding box; the candidates of point i are the points of the 3^D cells around
// its own, and accept(i, j) (the caller's distance rule, exact or strict, plus any filter) keeps a
// candidate. Every list is sorted by partner index, so the result depends neither on the binning
// nor on the threads. Occupied cells only are stored (sorted keys, binary search), so a cloud whose
// fragments fly apart costs no empty cells: O(N log N) for bounded density. accept runs on several
// threads at once (OpenMP), so it must not write shared state.
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

template <int D, class Accept>
NeighborLists neighbor_lists(const Field<D>& x, double cell, Accept&& accept)
{
    if (!(cell > 0) || !std::isfinite(cell)) throw std::invalid_argument("neighbour search: the cell side must be positive and finite");
    const std::size_t n = x.size();
    NeighborLists out;
    out.offset.assign(n + 1, 0);
    if (n == 0) return out;
    Vec<D> lo;
    for (int d = 0; d < D; ++d) lo[d] = *std::min_element(x.c[d].begin(), x.c[d].end());
    // Cell coordinates of every point, and the points sorted by cell (lexicographic, z slowest).
    using Coord = std::array<std::int64_t, D>;
    std::vector<Coord> coord(n);
    for (std::size_t i = 0; i < n; ++i)
        for (int d = 0; d < D; ++d) {
            const double c = std::floor((x.c[d][i] - lo[d]) / cell);
            if (!(c < 4e18))  // NaN too, or a cloud spread over more cells than an index holds: an input error
                throw std::invalid_argument("neighbour search: point " + std::to_string(i) +
                                            " (0-based) has a non-finite coordinate or lies more than 4e18 horizons from the others");
            coord[i][d] = static_cast<std::int64_t>(c);
        }
    auto before = [](const Coord& a, const Coord& b) {
        for (int d = D - 1; d >= 0; --d)
            if (a[d] != b[d]) return a[d] < b[d];
        return false;
    };
    std::vector<int> sorted(n);
    for (std::size_t i = 0; i < n; ++i) sorted[i] = static_cast<int>(i);
    std::stable_sort(sorted.begin(), sorted.end(), [&](int a, int b) { return before(coord[a], coord[b]); });
    std::vector<Coord> keys;             // occupied cells, ascending
    std::vector<std::int64_t> start;     // their first position in sorted
    for (std::size_t q = 0; q < n; ++q)
        if (q == 0 || before(keys.back(), coord[sorted[q]])) keys.push_back(coord[sorted[q]]), start.push_back(static_cast<std::int64_t>(q));
    start.push_back(static_cast<std::int64_t>(n));

    std::vector<std::vector<int>> lists(n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < static_cast<long>(n); ++i) {
        long nb = 1;
        for (int d = 0; d < D; ++d) nb *= 3;
        for (long s = 0; s < nb; ++s) {
            Coord c = coord[i];
            long rest = s;
            for (int d = 0; d < D; ++d, rest /= 3) c[d] += rest % 3 - 1;
            const auto it = std::lower_bound(keys.begin(), keys.end(), c, before);
            if (it == keys.end() || before(c, *it)) continue;
            const std::size_t cq = static_cast<std::size_t>(it - keys.begin());
            for (std::int64_t q = start[cq]; q < start[cq + 1]; ++q) {
                const int j = sorted[q];
                if (j != i && accept(static_cast<int>(i), j)) lists[i].push_back(j);
            }
        }
        std::sort(lists[i].begin(), lists[i].end());
    }
    for (std::size_t i = 0; i < n; ++i) out.offset[i + 1] = out.offset[i] + static_cast<std::int64_t>(lists[i].size());
    out.partner.resize(out.offset[n]);
    for (std::size_t i = 0; i < n; ++i) std::copy(lists[i].begin(), lists[i].end(), out.partner.begin() + out.offset[i]);
    return out;
}

}  // namespace pd
