// pd/core/refinement.hpp -- multi-level grids of cell-centred nodes (spec/002 sec. 4.4-4.6): the
// node tree of adaptive grid refinement, Method B (cell splitting).
//   split(nodes): each listed active node (a cell of side h centred at x) becomes 2^D children at the
//     centres of its sub-cells, x +- h/4 per axis, side h/2, volume V/2^D (they sum to the parent's),
//     level + 1; the parent is kept in the tree, inactive (the source's volume := 0 and negative
//     level, written here as a flag). The children's horizon follows the refinement type (sec. 3.3):
//     delta (delta halves, m kept), m (delta kept, m doubles) or delta_m (delta = m_level h_child).
//   visibility_zone(nodes): the nodes to split so that no coarser node sees the given ones (sec. 4.5,
//     Alg. A.3): the given active nodes and every active node of the same level within their horizon.
//   refine_nested(inside, levels, rule): `levels` splits of a region, nested so that no node sees a
//     node two levels finer: level l splits the active level l-1 nodes with inside(x, s), s the sum of
//     the horizons of levels 0 .. l-2 (the caller's region shrunk by s); m_level(l) for delta_m.
//   ancestor(node): the level-0 node it descends from (the triggers work on level-0 ids, V6f).
//   interface_horizon(m): the interface nodes of the refined region take delta = m d_min, d_min the
//     distance to the nearest coarser node (sec. 4.6, the fix of the partial cells PA-PDLAMMPS drops;
//     V6e: 3 sqrt(2) h at d_min = sqrt(2) h). Interface nodes: the first row of refined nodes, those
//     with a coarser node nearer than 2 h (Method A's at h or sqrt(2) h; Method B's sub-cells on the
//     near side of a parent cell at the interface at sqrt(10)/2 h; those on its far side, at
//     sqrt(26)/2 h, are not). So m d_min stays between the source's 3 h and 4.24 h (Method A) or is
//     3 sqrt(10)/2 h = 4.74 h (Method B, m = 3).
//   body(): the active nodes as a Body (ids(): their node numbers), with h and delta per active node.
// Node numbers never change: children are appended.
#pragma once
#include "pd/core/lattice.hpp"

#include <cmath>
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
    std::vector<int> level, parent;    // level (0: the initial grid), parent node (-1 at level 0)
    std::vector<int> first_child;      // the first of its 2^D children (-1: not split)
    std::vector<std::uint8_t> active;  // 1: a node of the computation; 0: split
    double measure = 1;                // 2D thickness / 1D cross-section (as Body)

    static constexpr int children = 1 << D;

    RefinedGrid() = default;
    // The initial grid: the nodes of a lattice body (spacing body.dx > 0), all with horizon delta.
    RefinedGrid(const Body<D>& body, double delta0) : measure(body.measure)
    {
        if (!(body.dx > 0)) throw std::invalid_argument("RefinedGrid: the initial body must be a lattice (dx > 0)");
        if (!(delta0 > 0)) throw std::invalid_argument("RefinedGrid: the horizon must be positive");
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
            const double dc = rule == Refinement::delta ? delta[p] / 2 : rule == Refinement::m ? delta[p] : m_level * hc;
            first_child[p] = static_cast<int>(size());
            const Vec<D> xp = x[p];
            const double vp = volume[p];
            const int lp = level[p];
            for (int c = 0; c < children; ++c) {
                Vec<D> xc = xp;
                for (int d = 0; d < D; ++d) xc[d] += ((c >> d) & 1 ? 0.25 : -0.25) * h[p];
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

    // The nodes to split around `nodes` (header), each once, ascending.
    std::vector<int> visibility_zone(const std::vector<int>& nodes) const
    {
        std::vector<std::uint8_t> pick(size(), 0);
        for (int q : nodes) {
            if (q < 0 || q >= static_cast<int>(size()) || !active[q])
                throw std::invalid_argument("RefinedGrid::visibility_zone: node " + std::to_string(q) + " is not an active node");
            for (std::size_t i = 0; i < size(); ++i)
                if (active[i] && level[i] == level[q] && norm(x[i] - x[q]) <= delta[q] * (1 + 1e-10)) pick[i] = 1;
        }
        std::vector<int> zone;
        for (std::size_t i = 0; i < size(); ++i)
            if (pick[i]) zone.push_back(static_cast<int>(i));
        return zone;
    }

    int ancestor(int node) const
    {
        while (parent.at(node) >= 0) node = parent[node];
        return node;
    }

    // The interface horizon (header); returns how many nodes it changed.
    int interface_horizon(double m)
    {
        int changed = 0;
        for (std::size_t i = 0; i < size(); ++i) {
            if (!active[i] || level[i] == 0) continue;
            double d_min = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j < size(); ++j)
                if (active[j] && level[j] < level[i]) d_min = std::min(d_min, norm(x[j] - x[i]));
            if (d_min < 2 * h[i]) delta[i] = m * d_min, ++changed;
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
        volume.push_back(v), h.push_back(side), delta.push_back(hor), level.push_back(lev), parent.push_back(par);
        first_child.push_back(-1), active.push_back(1);
    }
    std::vector<double> gather(const std::vector<double>& a) const
    {
        std::vector<double> out;
        for (int i : ids()) out.push_back(a[i]);
        return out;
    }
};

}  // namespace pd
