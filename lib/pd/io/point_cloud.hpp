// pd/io/point_cloud.hpp -- reader of a user's point cloud (the discretisation of build/bin/pd_run),
// the CSV counterpart of Peridigm's text-file discretisation ("x y z block volume").
//
// Columns, by name, in any order (header line first; blank lines and '#' comments skipped):
//   x, y, z, volume       required: reference position [m], nodal volume [m^3] (> 0)
//   block                 optional integer, passed through (default 1)
//   vx, vy, vz            optional initial velocity [m/s] (absent = 0)
//   ux, uy, uz            optional initial displacement [m] (absent = 0)
//   fixed                 optional 0/1: 1 = the point is held at its initial displacement
//   no_fail               optional 0/1: 1 = the bonds of the point never break (with bond breaking)
//   T0                    optional initial temperature [K or C] (absent: NaN, the run's --T0)
//   T_fixed               optional held temperature [same unit]; an empty field = free (NaN)
// Any other column is an error (a misspelt "vX" must not be ignored silently).
// With dim < 3 the coordinates beyond dim must be the same for every point (they are ignored by
// the physics and written back unchanged), and u, v beyond dim must be 0. A fixed point must have
// zero initial velocity. Two points at the same position are an error.
// Every error throws PointCloudError with ONE line "<file>:<line>: column '<c>': <what>" (the
// line and column parts are left out when they do not apply, e.g. an unreadable file).
#pragma once

#include "pd/core/lattice.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::io {

struct PointCloudError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

struct PointCloud {
    std::filesystem::path path;
    std::array<std::vector<double>, 3> x;  // reference positions x, y, z [m]
    std::vector<double> volume;            // nodal volumes [m^3]
    std::array<std::vector<double>, 3> u;  // initial displacement [m]
    std::array<std::vector<double>, 3> v;  // initial velocity [m/s]
    std::vector<long> block;               // block id (1 when the column is absent)
    std::vector<std::uint8_t> fixed;       // 1 = held
    std::vector<std::uint8_t> no_fail;     // 1 = bonds of the point never break
    std::vector<double> T0;                // initial temperature [K or C]; NaN = not given
    std::vector<double> T_fixed;           // held temperature [K or C]; NaN = free
    std::vector<long> line;                // 1-based line of each point in the file
    std::vector<std::string> columns;      // header as read

    std::size_t size() const { return volume.size(); }
    bool has_column(const std::string& name) const;
    long blocks() const;                   // number of distinct block ids
    long fixed_count() const;
    long no_fail_count() const;
};

// Reads and validates a point cloud for a `dim`-dimensional run (dim = 1, 2 or 3; see header).
PointCloud read_point_cloud(const std::filesystem::path& path, int dim);

// The first D coordinates and the volumes as a Body; dx is the lattice spacing (0: none) and
// measure the 2D thickness [m] or 1D cross-section [m^2] implied by the volumes.
template <int D>
Body<D> to_body(const PointCloud& pc, double dx, double measure)
{
    Body<D> body;
    body.dx = dx;
    body.measure = measure;
    for (std::size_t i = 0; i < pc.size(); ++i) {
        Vec<D> p;
        for (int d = 0; d < D; ++d) p[d] = pc.x[d][i];
        body.push(p, pc.volume[i]);
    }
    return body;
}

}  // namespace pd::io
