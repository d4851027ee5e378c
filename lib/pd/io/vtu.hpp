// pd/io/vtu.hpp -- VTU (VTK XML UnstructuredGrid, ASCII) files of points for ParaView, and the
// .pvd collection that makes a time series of them.
//
// The nodes are written as VTK_VERTEX cells (type 1), one per point, with named point data:
// scalars (1 component) and vectors (always 3 components in the file; data given with D = 1, 2
// or 3 components is padded with zeros). Values are written in the shortest decimal form that
// reads back to the same double. Format: VTK file formats, "XML File Formats" (Kitware, VTK 9
// documentation), UnstructuredGrid and Collection (.pvd) sections.
//
//     pd::io::VtuWriter w(out / "state_0010.vtu");
//     w.points(x, y);                         // 2D: z = 0
//     w.scalar("damage", phi);
//     w.vector("displacement_m", ux, uy);     // padded to (ux, uy, 0)
//     w.time(t);                              // optional TimeValue field data [s]
//     w.write();
//     pvd.add(t, out / "state_0010.vtu");     // PvdWriter pvd(out / "state.pvd");
//
// Sizes are checked when the data are given (std::invalid_argument); file errors throw
// std::runtime_error. The writer keeps a copy of the data until write().
#pragma once

#include <cstddef>
#include <filesystem>
#include <limits>
#include <span>
#include <string>
#include <vector>

namespace pd::io {

class VtuWriter {
public:
    explicit VtuWriter(std::filesystem::path path);

    // Positions [m]: x has N entries; y and z have N entries or are empty (then zeros).
    void points(const std::vector<double>& x, const std::vector<double>& y = {},
                const std::vector<double>& z = {});
    // Positions stored point by point, D = 1, 2 or 3 values per point: xyz[i * D + c].
    void points_interleaved(std::span<const double> xyz, int D);

    // Point data (after points()). Names must be unique; put the unit in the name (u_m, T_K).
    void scalar(const std::string& name, const std::vector<double>& v);
    // Vector from component arrays: vy and vz have N entries or are empty (then zeros).
    void vector(const std::string& name, const std::vector<double>& vx,
                const std::vector<double>& vy = {}, const std::vector<double>& vz = {});
    // Vector stored point by point, D = 1, 2 or 3 components: v[i * D + c]; padded to 3.
    void vector_interleaved(const std::string& name, std::span<const double> v, int D);

    // Optional simulation time [s], written as the TimeValue field data that ParaView reads.
    void time(double t_s) { time_s_ = t_s; }

    // Creates the parent folders and writes the file (complete, or throws std::runtime_error).
    void write() const;

    std::size_t size() const { return n_; }  // number of points
    const std::filesystem::path& path() const { return path_; }

private:
    struct Array {
        std::string name;
        int components;            // 1 or 3
        std::vector<double> data;  // data[i * components + c]
    };
    void check_new_array(const std::string& name, std::size_t n) const;

    std::filesystem::path path_;
    std::size_t n_ = 0;
    bool have_points_ = false;
    std::vector<double> xyz_;  // xyz_[3 * i + c] [m]
    std::vector<Array> arrays_;
    double time_s_ = std::numeric_limits<double>::quiet_NaN();  // NaN: not written
};

// A ParaView collection (.pvd) of VTU files with their times. The file is written at
// construction (empty collection) and rewritten completely on every add(), through a temporary
// file and a rename, so that it is a valid file at every moment of a run.
class PvdWriter {
public:
    explicit PvdWriter(std::filesystem::path path);

    // vtu_path is the VTU path as given to VtuWriter (same working folder as the .pvd path); the
    // .pvd stores it relative to its own folder so the output folder can be moved as a whole.
    void add(double time_s, const std::filesystem::path& vtu_path);

    std::size_t size() const { return entries_.size(); }
    const std::filesystem::path& path() const { return path_; }

private:
    struct Entry {
        double time_s;
        std::string file;  // relative to the .pvd folder, generic format ('/')
    };
    void rewrite() const;

    std::filesystem::path path_;
    std::vector<Entry> entries_;
};

}  // namespace pd::io
