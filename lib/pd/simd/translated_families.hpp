// Translation runs of bond families (the cost of correspondence: reports/3d/model_cost.md).
// On a lattice (x fastest, build_bonds sorts a family by partner index), the nodes of one x-row
// away from the row's two ends have families that are translates of each other: node i + 1 has
// the family of node i shifted by one index. Such nodes can be taken W at a time as the W lanes of
// a vector: the partners of bond r of nodes i0 .. i0 + W - 1 are the W consecutive nodes
// j_r + 0 .. j_r + W - 1 (j_r the partner of bond r of i0), so node j's values are W contiguous
// doubles of a structure-of-arrays field (no gather), and the per-bond data (xi, omega V_j, ...)
// are those of node i0's bond r, one scalar per W bonds (no per-bond stream).
// A node t + q joins the run started at node t when, for every bond r of the family,
//   partner[begin(t + q) + r] - (t + q) == partner[begin(t) + r] - t,
//   each given per-bond array (e.g. |xi|, omega V_j) agrees to the relative tol, and each given
//   per-node array (the reference coordinates, when the kernel uses xi itself) gives the same
//   difference x_j - x_i to tol delta (default tol 1e-12: lattice coordinates differ at round-off).
// A run of length L gives floor(L / W) chunks of W nodes; its other nodes go to `rest`, as do
// nodes with an empty family. The split depends only on the bonds, so results stay independent of
// the thread count. A kernel that uses the chunks reads node i0's bond data for all W lanes, which
// changes its results only at round-off (tol). Runs assume every bond intact: use them only when
// bonds.has_damage() is false.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/parallel.hpp"

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <vector>

namespace pd {

struct TranslatedRuns {
    int width = 0;                  // W, nodes per chunk
    std::size_t nodes = 0, bonds = 0;  // sizes of the Bonds they were found on (a check for users)
    const int* partner_data = nullptr;  // and its partner array: runs fit only the very same Bonds
    std::vector<int> chunk_start;   // first node i0 of each chunk (nodes i0 .. i0 + W - 1)
    std::vector<int> chunk_run;     // run of each chunk, an index into run_first
    std::vector<int> run_first;     // first node t of each run that has chunks (its family is the template)
    std::vector<int> run_chunks;    // chunks of run p: run_chunks[p] .. run_chunks[p + 1] - 1 (consecutive)
    std::vector<int> rest;          // nodes in no chunk, ascending
    bool fits(const Bonds& b) const
    {
        return width > 0 && nodes == b.nodes() && bonds == b.size() && partner_data == b.partner.data();
    }
    std::size_t chunked_nodes() const { return chunk_start.size() * static_cast<std::size_t>(width); }
};

namespace detail {

inline bool same_within(double a, double b, double tol) { return std::abs(a - b) <= tol * std::abs(b); }

// Does the family of node i translate that of node t (header)?
inline bool translates(const Bonds& b, std::size_t t, std::size_t i, std::initializer_list<const std::vector<double>*> per_bond,
                       std::initializer_list<const std::vector<double>*> per_node, double tol)
{
    const std::int64_t bt = b.begin(t), bi = b.begin(i), s = b.end(t) - bt;
    if (b.end(i) - bi != s || s == 0) return false;
    const long shift = static_cast<long>(i) - static_cast<long>(t);
    const double dtol = tol * b.delta;
    for (std::int64_t r = 0; r < s; ++r) {
        const int jt = b.partner[bt + r], ji = b.partner[bi + r];
        if (ji - jt != shift) return false;
        for (const std::vector<double>* c : per_node)
            if (std::abs(((*c)[ji] - (*c)[i]) - ((*c)[jt] - (*c)[t])) > dtol) return false;
        for (const std::vector<double>* c : per_bond)
            if (!same_within((*c)[bi + r], (*c)[bt + r], tol)) return false;
    }
    return true;
}

}  // namespace detail

namespace detail {
// unit(u) for the n_units work units (chunks, or runs of chunks), then node(i) for every node in no
// chunk; each loop parallel when the scene has parallel_min_nodes nodes, as a loop over all nodes.
template <bool Uneven, class Unit, class Node>
bool units_then_rest(const TranslatedRuns& runs, const Bonds& b, std::size_t n_units, Unit&& unit, Node&& node)
{
    if (!runs.fits(b) || runs.chunk_start.empty()) return false;
    parallel_for_items<Uneven>(n_units, runs.nodes, [&](std::size_t u) { unit(u); });
    parallel_for_items(runs.rest.size(), runs.nodes, [&](std::size_t q) { node(static_cast<std::size_t>(runs.rest[q])); });
    return true;
}
}  // namespace detail

// The two loops of a chunked pass: chunk(q) for every chunk q, then node(i) for every node in no
// chunk. Returns false, calling nothing, when the runs do not fit these bonds or have no chunk.
template <class Chunk, class Node>
bool for_chunks_then_rest(const TranslatedRuns& runs, const Bonds& b, Chunk&& chunk, Node&& node)
{
    return detail::units_then_rest<false>(runs, b, runs.chunk_start.size(), chunk, node);
}
// The same with run(p) for every run p (all chunks of the run in one call; runs differ in length,
// so they are scheduled dynamically), then the rest.
template <class Run, class Node>
bool for_runs_then_rest(const TranslatedRuns& runs, const Bonds& b, Run&& run, Node&& node)
{
    return detail::units_then_rest<true>(runs, b, runs.run_first.size(), run, node);
}

inline TranslatedRuns find_translated_runs(const Bonds& b, int width, std::initializer_list<const std::vector<double>*> per_bond,
                                     std::initializer_list<const std::vector<double>*> per_node = {}, double tol = 1e-12)
{
    TranslatedRuns runs;
    runs.width = width;
    runs.nodes = b.nodes();
    runs.bonds = b.size();
    runs.partner_data = b.partner.data();
    const std::size_t n = b.nodes();
    for (std::size_t t = 0; t < n;) {
        std::size_t len = 1;
        while (t + len < n && detail::translates(b, t, t + len, per_bond, per_node, tol)) ++len;
        const std::size_t chunks = b.end(t) > b.begin(t) ? len / static_cast<std::size_t>(width) : 0;
        if (chunks > 0) {
            runs.run_first.push_back(static_cast<int>(t));
            runs.run_chunks.push_back(static_cast<int>(runs.chunk_start.size()));
        }
        for (std::size_t c = 0; c < chunks; ++c) {
            runs.chunk_start.push_back(static_cast<int>(t + c * width));
            runs.chunk_run.push_back(static_cast<int>(runs.run_first.size()) - 1);
        }
        for (std::size_t i = t + chunks * width; i < t + len; ++i) runs.rest.push_back(static_cast<int>(i));
        t += len;
    }
    runs.run_chunks.push_back(static_cast<int>(runs.chunk_start.size()));
    return runs;
}

}  // namespace pd
