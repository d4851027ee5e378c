// pd/core/refinement.hpp -- multi-level grids of cell-centred nodes (spec/002 sec. 4.4-4.6): the
// node tree of adaptive grid refinement, Method B (cell splitting).
//   split(nodes): each listed active node (a cell of side h centred at x) becomes 2^D children at the
//     centres of its sub-cells, x +- h/4 along each lattice axis (rotated by `angle` in 2D), side h/2, volume V/2^D (they sum to the parent's),
//     level + 1; the parent is kept in the tree, inactive (the source's volume := 0 and negative
//     level, written here as a flag). The children's horizon follows the refinement type (sec. 3.3):
//     delta (delta halves, m kept), m (delta kept, m doubles) or delta_m (delta = m_level h_child).
//   visibility_zone(nodes): the nodes to split so that no coarser node sees the given ones (sec. 4.5,
//     Alg. A.3): the given active nodes and every active node of the same level within their horizon.
//   refine_nested(inside, levels, rule): `levels` splits of a region, nested so that no node sees a
//     node two levels finer: level l splits the active level l-1 nodes with inside(x, s), s the sum of
//     the horizons of levels 0 .. l-2 (the caller's region shrunk by s); m_level(l) for delta_m.
//   refine_around(ids, levels, rule): Alg. A.3 of the triggers, around level-0 nodes `ids`: level l
//     splits the active level l-1 nodes within their horizon of the level l-1 descendants of ids (so
//     no coarser node sees one of them, sec. 4.5); nodes split before are left as they are. Returns
//     how many nodes it split (0: the zone was refined already). margin > 0 widens each zone by that
//     many cells of its level (a look-ahead of ours: fewer, larger updates; 0 is the source's rule).
//   needs_refinement(ids, levels): whether refine_around without margin would split anything.
//   ancestor(node): the level-0 node it descends from (the triggers work on level-0 ids, V6f).
//   interface_horizon(m): the interface nodes of the refined region take delta = m d_min, d_min the
//     distance to the nearest coarser node (sec. 4.6, the fix of the partial cells PA-PDLAMMPS drops;
//     V6e: 3 sqrt(2) h at d_min = sqrt(2) h). Interface nodes: the first row of refined nodes, those
//     with a coarser node nearer than 2 h (Method A's at h or sqrt(2) h; Method B's sub-cells on the
//     near side of a parent cell at the interface at sqrt(10)/2 h; those on its far side, at
//     sqrt(26)/2 h, are not). So m d_min stays between the source's 3 h and 4.24 h (Method A) or is
//     3 sqrt(10)/2 h = 4.74 h (Method B, m = 3).
//     Every other refined node takes back its nominal horizon (the refinement rule's, kept in
//     `nominal`, from which children are made), so the rule can be applied again after more splits.
//   body(): the active nodes as a Body (ids(): their node numbers), with h and delta per active node.
// Node numbers never change: children are appended. Searches use cell lists (neighbors.hpp): O(N).
#pragma once
#include "pd/core/lattice.hpp"
#include "pd/core/neighbors.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

enum class Refinement { delta, m, delta_m };

template <int D>
struct RefinedGrid {
    Field<D> x;                        // cell centres [m]
    std::vector<double> volume, h;     // cell volume [m^3] (its measure included), side [m]
    std::vector<double> delta;         // horizon [m]
    std::vector<double> nominal;       // horizon of the refinement rule (delta but at interfaces) [m]
    std::vector<int> level, parent;    // level (0: the initial grid), parent node (-1 at level 0)
    std::vector<int> first_child;      // the first of its 2^D children (-1: not split)
    std::vector<std::uint8_t> active;  // 1: a node of the computation; 0: split
    double measure = 1;                // 2D thickness / 1D cross-section (as Body)
    double angle = 0;                  // 2D: rotation of the lattice axes from x [rad] (0: axis-aligned cells)

    static constexpr int children = 1 << D;

    RefinedGrid() = default;
    // The initial grid: the nodes of a lattice body (spacing body.dx > 0), all with horizon delta.
    // angle (2D only): the lattice's axes are rotated by it from x and y [rad]; children follow them.
    RefinedGrid(const Body<D>& body, double delta0, double lattice_angle = 0) : measure(body.measure), angle(lattice_angle)
    {
        if (!(body.dx > 0)) throw std::invalid_argument("RefinedGrid: the initial body must be a lattice (dx > 0)");
        if (!(delta0 > 0)) throw std::invalid_argument("RefinedGrid: the horizon must be positive");
        if (D != 2 && angle != 0) throw std::invalid_argument("RefinedGrid: a rotated lattice is 2D only");
        for (std::size_t i = 0; i < body.size(); ++i) add(body.x[i], body.volume[i], body.dx, delta0, 0, -1);
    }

    std::size_t size() const { return volume.size(); }  // every node, split ones included

    // Method B (header). delta_m needs m_level > 0. Throws for an inactive or unknown node.
    void split(const std::vector<int>& nodes, Refinement rule, double m_level = 0)
    {
        if (rule == Refinement::delta_m && !(m_level > 0)) throw std::invalid_argument("RefinedGrid::split: delta_m needs m_level > 0");
        for (int p : nodes) {
            if (p < 0 || p >= static_cast<int>(size()) || !active[p])
                throw std::invalid_argument("RefinedGrid::split: node " + std::to_string(p) + " is not an active node");
            const double hc = h[p] / 2;
            const double dc = rule == Refinement::delta ? nominal[p] / 2 : rule == Refinement::m ? nominal[p] : m_level * hc;
            first_child[p] = static_cast<int>(size());
            const Vec<D> xp = x[p];
            const double vp = volume[p];
            const int lp = level[p];
            for (int c = 0; c < children; ++c) {
                Vec<D> off{};  // the sub-cell centre in the lattice's axes
                for (int d = 0; d < D; ++d) off[d] = ((c >> d) & 1 ? 0.25 : -0.25) * h[p];
                if constexpr (D == 2) off = Vec<D>{{std::cos(angle) * off[0] - std::sin(angle) * off[1], std::sin(angle) * off[0] + std::cos(angle) * off[1]}};
                const Vec<D> xc = xp + off;
                add(xc, vp / children, hc, dc, lp + 1, p);
            }
            active[p] = 0;
        }
    }

    // The nested refinement of a region (header). inside(x, s) [m]: x lies in the region shrunk by s.
    template <class Inside>
    void refine_nested(Inside&& inside, int levels, Refinement rule, const std::function<double(int)>& m_level = {})
    {
        double shrink = 0;  // the horizons of levels 0 .. l-2 together [m]
        for (int l = 1; l <= levels; ++l) {
            if (l >= 2)
                for (std::size_t i = 0; i < size(); ++i)
                    if (level[i] == l - 2) {
                        shrink += delta[i];
                        break;
                    }
            std::vector<int> nodes;
            for (std::size_t i = 0; i < size(); ++i)
                if (active[i] && level[i] == l - 1 && inside(x[i], shrink)) nodes.push_back(static_cast<int>(i));
            split(nodes, rule, rule == Refinement::delta_m ? m_level(l) : 0.0);
        }
    }

    // True when refine_around(ids, levels) with no margin would split a node (its zones are not all
    // split yet); nothing is split.
    bool needs_refinement(const std::vector<int>& ids, int levels) const
    {
        std::vector<int> nodes(ids);
        for (int l = 1; l <= levels && !nodes.empty(); ++l) {
            for (int i : same_level_within(nodes))
                if (active[i]) return true;
            std::vector<int> next;
            for (int q : nodes)
                for (int c = 0; c < children; ++c) next.push_back(first_child[q] + c);
            nodes = std::move(next);
        }
        return false;
    }

    // The nodes to split around `nodes` (header), each once, ascending.
    std::vector<int> visibility_zone(const std::vector<int>& nodes) const
    {
        for (int q : nodes)
            if (q < 0 || q >= static_cast<int>(size()) || !active[q])
                throw std::invalid_argument("RefinedGrid::visibility_zone: node " + std::to_string(q) + " is not an active node");
        std::vector<int> zone;
        for (int i : same_level_within(nodes))
            if (active[i]) zone.push_back(i);
        return zone;
    }

    // Alg. A.3 around level-0 nodes (header); m_level(l) for delta_m.
    int refine_around(const std::vector<int>& ids, int levels, Refinement rule, const std::function<double(int)>& m_level = {},
                      double margin = 0)
    {
        std::vector<int> nodes;  // the level l-1 descendants of ids
        for (int q : ids) {
            if (q < 0 || q >= static_cast<int>(size()) || level[q] != 0)
                throw std::invalid_argument("RefinedGrid::refine_around: node " + std::to_string(q) + " is not a level-0 node");
            nodes.push_back(q);
        }
        int split_count = 0;
        for (int l = 1; l <= levels && !nodes.empty(); ++l) {
            std::vector<int> zone;  // its active nodes
            for (int i : same_level_within(nodes, margin))
                if (active[i]) zone.push_back(i);
            split(zone, rule, rule == Refinement::delta_m ? m_level(l) : 0.0);
            split_count += static_cast<int>(zone.size());
            std::vector<int> next;
            for (int q : nodes)
                if (first_child[q] >= 0)
                    for (int c = 0; c < children; ++c) next.push_back(first_child[q] + c);
            nodes = std::move(next);
        }
        return split_count;
    }

    int ancestor(int node) const
    {
        while (parent.at(node) >= 0) node = parent[node];
        return node;
    }

    // The interface horizon (header); returns how many nodes it gave the interface horizon.
    int interface_horizon(double m)
    {
        double reach = 0;  // 2 h of the coarsest refined node [m]
        for (std::size_t i = 0; i < size(); ++i)
            if (active[i] && level[i] > 0) reach = std::max(reach, 2 * h[i]);
        if (reach == 0) return 0;
        Field<D> act;  // the active nodes, binned
        const std::vector<int> index = ids();
        for (int i : index)
            for (int d = 0; d < D; ++d) act.c[d].push_back(x.c[d][i]);
        const CellBins<D> bins(act, reach);
        int changed = 0;
        for (std::size_t i = 0; i < size(); ++i) {
            if (!active[i] || level[i] == 0) continue;
            double d_min = std::numeric_limits<double>::infinity();
            bins.near(x[i], [&](int s) {
                if (level[index[s]] < level[i]) d_min = std::min(d_min, norm(x[index[s]] - x[i]));
            });
            delta[i] = d_min < 2 * h[i] ? m * d_min : nominal[i];
            changed += d_min < 2 * h[i];
        }
        return changed;
    }

    std::vector<int> ids() const
    {
        std::vector<int> id;
        for (std::size_t i = 0; i < size(); ++i)
            if (active[i]) id.push_back(static_cast<int>(i));
        return id;
    }
    Body<D> body() const  // dx = 0: the spacing varies (active_h() gives it per node)
    {
        Body<D> b;
        b.measure = measure;
        for (int i : ids()) b.push(x[i], volume[i]);
        return b;
    }
    std::vector<double> active_h() const { return gather(h); }
    std::vector<double> active_delta() const { return gather(delta); }

private:
    void add(const Vec<D>& p, double v, double side, double hor, int lev, int par)
    {
        for (int d = 0; d < D; ++d) x.c[d].push_back(p[d]);
        volume.push_back(v), h.push_back(side), delta.push_back(hor), nominal.push_back(hor), level.push_back(lev), parent.push_back(par);
        first_child.push_back(-1), active.push_back(1);
    }
    // The nodes (active or split) of the level of each given node within its nominal horizon plus
    // margin cells, ascending.
    std::vector<int> same_level_within(const std::vector<int>& nodes, double margin = 0) const
    {
        std::vector<std::uint8_t> pick(size(), 0), levels;
        double reach = 0;
        for (int q : nodes) {
            pick[q] = 1, reach = std::max(reach, nominal[q] + margin * h[q]);
            if (static_cast<std::size_t>(level[q]) >= levels.size()) levels.resize(level[q] + 1, 0);
            levels[level[q]] = 1;
        }
        if (!nodes.empty()) {
            Field<D> near_x;  // the nodes of the given nodes' levels, binned
            std::vector<int> index;
            for (std::size_t i = 0; i < size(); ++i)
                if (static_cast<std::size_t>(level[i]) < levels.size() && levels[level[i]]) {
                    for (int d = 0; d < D; ++d) near_x.c[d].push_back(x.c[d][i]);
                    index.push_back(static_cast<int>(i));
                }
            const CellBins<D> bins(near_x, reach * (1 + 1e-10));
            for (int q : nodes)
                bins.near(x[q], [&](int s) {
                    const int j = index[s];
                    if (level[j] == level[q] && norm(x[j] - x[q]) <= (nominal[q] + margin * h[q]) * (1 + 1e-10)) pick[j] = 1;
                });
        }
        std::vector<int> out;
        for (std::size_t i = 0; i < size(); ++i)
            if (pick[i]) out.push_back(static_cast<int>(i));
        return out;
    }
    std::vector<double> gather(const std::vector<double>& a) const
    {
        std::vector<double> out;
        for (int i : ids()) out.push_back(a[i]);
        return out;
    }
};

}  // namespace pd
