// pd/io/state_output.hpp -- the per-step outputs of a point-cloud run (problems/pd_run.cpp):
// `state_step<NNNN>.csv` (node_id,x,y,z[,ux,uy,uz,vx,vy,vz][,damage][,ep][,T,Q_W_m3]; reference x,y,z as read, u and
// v zero beyond the dimension, 17 significant digits) and `state_step<NNNN>.vtu` with a .pvd series, plus
// the parser of the step list "0,100,400".
#pragma once
#include "pd/core/field.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/io/vtu.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::io {

// "0,100,400" -> sorted unique steps in [0, steps]; "" -> {steps}; "none" -> {}. Throws
// std::invalid_argument naming --output-steps otherwise.
inline std::vector<long> parse_output_steps(const std::string& text, long steps)
{
    if (text == "none") return {};
    if (text.empty()) return {steps};
    std::vector<long> list;
    std::size_t begin = 0;
    while (begin <= text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string item = text.substr(begin, comma - begin);
        long s = 0;
        const auto r = std::from_chars(item.data(), item.data() + item.size(), s);
        if (item.empty() || r.ec != std::errc() || r.ptr != item.data() + item.size())
            throw std::invalid_argument("option --output-steps expects step numbers separated by commas, got '" + text + "'");
        if (s < 0) throw std::invalid_argument("option --output-steps: step " + item + " is negative");
        if (s > steps) throw std::invalid_argument("option --output-steps: step " + item + " is beyond --steps " + std::to_string(steps));
        list.push_back(s);
        begin = comma + 1;
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    return list;
}

inline std::filesystem::path step_file(const std::filesystem::path& out, long n, const char* ext)
{
    char name[64];
    std::snprintf(name, sizeof name, "state_step%04ld.%s", n, ext);
    return out / name;
}

// The fields of one state: motion (u, v) when mechanics runs, temperature T and heat-flow density
// Q when heat conduction runs (null = not part of the run: the columns are left out).
template <int D>
struct StateFields {
    const Field<D>* u = nullptr;             // displacement [m]
    const Field<D>* v = nullptr;             // velocity [m/s]
    const std::vector<double>* T = nullptr;  // temperature [K or C, the unit of the input]
    const std::vector<double>* Q = nullptr;  // heat-flow density into the node [W/m^3]
    const std::vector<double>* damage = nullptr;  // point damage phi (critical_stretch.hpp) [-]; with u only
    const std::vector<double>* ep = nullptr;      // equivalent plastic strain (models/plastic_points.hpp) [-]; with u only
};

template <int D>
void write_state(const std::filesystem::path& out, long n, const PointCloud& pc, const StateFields<D>& s)
{
    std::vector<std::string> header{"node_id", "x", "y", "z"};
    if (s.u) header.insert(header.end(), {"ux", "uy", "uz", "vx", "vy", "vz"});
    if (s.u && s.damage) header.push_back("damage");
    if (s.u && s.ep) header.push_back("ep");
    if (s.T) header.insert(header.end(), {"T", "Q_W_m3"});
    CsvWriter csv(step_file(out, n, "csv"), header, false);
    for (std::size_t i = 0; i < pc.size(); ++i) {
        std::vector<CsvCell> row{i, pc.x[0][i], pc.x[1][i], pc.x[2][i]};
        if (s.u) {
            for (int d = 0; d < 3; ++d) row.emplace_back(d < D ? s.u->c[d][i] : 0.0);
            for (int d = 0; d < 3; ++d) row.emplace_back(d < D ? s.v->c[d][i] : 0.0);
            if (s.damage) row.emplace_back((*s.damage)[i]);
            if (s.ep) row.emplace_back((*s.ep)[i]);
        }
        if (s.T) {
            row.emplace_back((*s.T)[i]);
            row.emplace_back((*s.Q)[i]);
        }
        csv.row(row);
    }
    csv.flush();
}

template <int D>
void write_state_vtu(const std::filesystem::path& out, long n, double t, const PointCloud& pc, const StateFields<D>& s,
                     PvdWriter& pvd)
{
    const std::vector<double> zero;  // components beyond D: padded with zeros by the writer
    auto comp = [&](const Field<D>& f, int d) -> const std::vector<double>& { return d < D ? f.c[d] : zero; };
    VtuWriter w(step_file(out, n, "vtu"));
    w.points(pc.x[0], pc.x[1], pc.x[2]);
    if (s.u) {
        w.vector("displacement_m", comp(*s.u, 0), comp(*s.u, 1), comp(*s.u, 2));
        w.vector("velocity_m_per_s", comp(*s.v, 0), comp(*s.v, 1), comp(*s.v, 2));
        if (s.damage) w.scalar("damage", *s.damage);
        if (s.ep) w.scalar("plastic_strain", *s.ep);
    }
    if (s.T) {
        w.scalar("T", *s.T);
        w.scalar("Q_W_m3", *s.Q);
    }
    w.scalar("block", std::vector<double>(pc.block.begin(), pc.block.end()));
    w.scalar("fixed", std::vector<double>(pc.fixed.begin(), pc.fixed.end()));
    w.time(t);
    w.write();
    pvd.add(t, w.path());
}

}  // namespace pd::io
