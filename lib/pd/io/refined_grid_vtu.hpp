// pd/io/refined_grid_vtu.hpp -- the active nodes of a multi-level grid (core/refinement.hpp) as a VTU
// file for ParaView, so that a user sees where a grid was refined: point arrays `level`, `cell_side_m`,
// `horizon_m`, and any per-active-node scalars of the caller (e.g. a displacement component).
#pragma once
#include "pd/core/refinement.hpp"
#include "pd/io/vtu.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd::io {

template <int D>
void write_refined_grid_vtu(const std::filesystem::path& file, const RefinedGrid<D>& g,
                            const std::vector<std::pair<std::string, std::vector<double>>>& extra = {})
{
    const std::vector<int> ids = g.ids();
    std::vector<double> c[3], level;
    for (int i : ids) {
        for (int d = 0; d < D; ++d) c[d].push_back(g.x.c[d][i]);
        level.push_back(g.level[i]);
    }
    VtuWriter w(file);
    w.points(c[0], c[1], c[2]);
    w.scalar("level", level);
    w.scalar("cell_side_m", g.active_h());
    w.scalar("horizon_m", g.active_delta());
    for (const auto& [name, v] : extra) {
        if (v.size() != ids.size()) throw std::invalid_argument("write_refined_grid_vtu: '" + name + "' needs one value per active node");
        w.scalar(name, v);
    }
    w.write();
}

}  // namespace pd::io
