// pd/io/vtu.cpp -- ASCII VTU (points as VTK_VERTEX cells, point data) and .pvd collection writers.
// Layout follows the VTK "XML File Formats" documentation (UnstructuredGrid, Collection).
#include "pd/io/vtu.hpp"

#include "pd/io/csv.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace pd::io {

namespace {

constexpr int vtk_vertex = 1;  // VTK cell type id of a single point (vtkCellType.h: VTK_VERTEX)

std::string xml_escape(const std::string& s)
{
    std::string r;
    for (char c : s) {
        switch (c) {
        case '&': r += "&amp;"; break;
        case '<': r += "&lt;"; break;
        case '>': r += "&gt;"; break;
        case '"': r += "&quot;"; break;
        default: r += c;
        }
    }
    return r;
}

// Values of a DataArray, `per_line` values on each line.
void append_values(std::string& s, const std::vector<double>& v, std::size_t per_line)
{
    for (std::size_t k = 0; k < v.size(); ++k) {
        s += (k % per_line == 0) ? "\n          " : " ";
        s += format_shortest(v[k]);
    }
    s += "\n        ";
}

// Pads component arrays (vy, vz possibly empty) into xyz[3 i + c]; checks sizes.
std::vector<double> pack3(const std::string& what, const std::vector<double>& a, const std::vector<double>& b,
                          const std::vector<double>& c)
{
    const std::size_t n = a.size();
    if ((!b.empty() && b.size() != n) || (!c.empty() && c.size() != n))
        throw std::invalid_argument("VtuWriter: components of " + what + " differ in size");
    std::vector<double> out(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
        out[3 * i] = a[i];
        if (!b.empty()) out[3 * i + 1] = b[i];
        if (!c.empty()) out[3 * i + 2] = c[i];
    }
    return out;
}

std::vector<double> pad3(const std::string& what, std::span<const double> v, int D)
{
    if (D < 1 || D > 3) throw std::invalid_argument("VtuWriter: " + what + " must have 1, 2 or 3 components");
    if (v.size() % static_cast<std::size_t>(D) != 0)
        throw std::invalid_argument("VtuWriter: size of " + what + " is not a multiple of " + std::to_string(D));
    const std::size_t n = v.size() / D;
    std::vector<double> out(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
        for (int c = 0; c < D; ++c) out[3 * i + c] = v[i * D + c];
    return out;
}

void write_file(const std::filesystem::path& path, const std::string& text)
{
    ensure_parent_dir(path);
    PendingFile file(path);  // csv.hpp: under path.part until complete
    std::ofstream out(file.part(), std::ios::out | std::ios::trunc | std::ios::binary);
    if (!out) throw std::runtime_error("cannot open " + path.string() + " for writing");
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("write error on " + path.string());
    out.close();
    if (!file.publish()) throw std::runtime_error("cannot rename " + file.part().string() + " to " + path.string());
}

}  // namespace

VtuWriter::VtuWriter(std::filesystem::path path) : path_(std::move(path)) {}

void VtuWriter::points(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& z)
{
    xyz_ = pack3("points", x, y, z);
    n_ = x.size();
    have_points_ = true;
    arrays_.clear();
}

void VtuWriter::points_interleaved(std::span<const double> xyz, int D)
{
    xyz_ = pad3("points", xyz, D);
    n_ = xyz_.size() / 3;
    have_points_ = true;
    arrays_.clear();
}

void VtuWriter::check_new_array(const std::string& name, std::size_t n) const
{
    if (!have_points_) throw std::logic_error("VtuWriter: points() must come before array '" + name + "'");
    if (name.empty()) throw std::invalid_argument("VtuWriter: empty array name");
    for (const auto& a : arrays_)
        if (a.name == name) throw std::invalid_argument("VtuWriter: array '" + name + "' given twice");
    if (n != n_)
        throw std::invalid_argument("VtuWriter: array '" + name + "' has " + std::to_string(n) + " values for " +
                                    std::to_string(n_) + " points");
}

void VtuWriter::scalar(const std::string& name, const std::vector<double>& v)
{
    check_new_array(name, v.size());
    arrays_.push_back({name, 1, v});
}

void VtuWriter::vector(const std::string& name, const std::vector<double>& vx, const std::vector<double>& vy,
                       const std::vector<double>& vz)
{
    check_new_array(name, vx.size());
    arrays_.push_back({name, 3, pack3(name, vx, vy, vz)});
}

void VtuWriter::vector_interleaved(const std::string& name, std::span<const double> v, int D)
{
    std::vector<double> padded = pad3(name, v, D);
    check_new_array(name, padded.size() / 3);
    arrays_.push_back({name, 3, std::move(padded)});
}

void VtuWriter::write() const
{
    if (!have_points_) throw std::logic_error("VtuWriter: write() without points() for " + path_.string());
    const std::string n = std::to_string(n_);
    std::string s;
    s += "<?xml version=\"1.0\"?>\n";
    s += "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n";
    s += "  <UnstructuredGrid>\n";
    if (!std::isnan(time_s_)) {
        s += "    <FieldData>\n";
        s += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">";
        s += format_shortest(time_s_) + "</DataArray>\n";
        s += "    </FieldData>\n";
    }
    s += "    <Piece NumberOfPoints=\"" + n + "\" NumberOfCells=\"" + n + "\">\n";
    s += "      <PointData>\n";
    for (const auto& a : arrays_) {
        s += "        <DataArray type=\"Float64\" Name=\"" + xml_escape(a.name) + "\" NumberOfComponents=\"" +
             std::to_string(a.components) + "\" format=\"ascii\">";
        append_values(s, a.data, a.components == 1 ? 6 : 3);
        s += "</DataArray>\n";
    }
    s += "      </PointData>\n";
    s += "      <Points>\n";
    s += "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">";
    append_values(s, xyz_, 3);
    s += "</DataArray>\n";
    s += "      </Points>\n";
    s += "      <Cells>\n";
    std::vector<std::string> cells(3);  // connectivity, offsets, types
    for (std::size_t i = 0; i < n_; ++i) {
        const char* sep = (i % 10 == 0) ? "\n          " : " ";
        cells[0] += sep + std::to_string(i);
        cells[1] += sep + std::to_string(i + 1);
        cells[2] += sep + std::to_string(vtk_vertex);
    }
    const char* heads[3] = {"type=\"Int64\" Name=\"connectivity\"", "type=\"Int64\" Name=\"offsets\"",
                            "type=\"UInt8\" Name=\"types\""};
    for (int k = 0; k < 3; ++k)
        s += std::string("        <DataArray ") + heads[k] + " format=\"ascii\">" + cells[k] + "\n        </DataArray>\n";
    s += "      </Cells>\n";
    s += "    </Piece>\n";
    s += "  </UnstructuredGrid>\n";
    s += "</VTKFile>\n";
    write_file(path_, s);
}

PvdWriter::PvdWriter(std::filesystem::path path) : path_(std::move(path)) { rewrite(); }

void PvdWriter::add(double time_s, const std::filesystem::path& vtu_path)
{
    namespace fs = std::filesystem;
    const fs::path dir = path_.parent_path().empty() ? fs::path(".") : path_.parent_path();
    const fs::path rel = fs::absolute(vtu_path).lexically_normal().lexically_proximate(
        fs::absolute(dir).lexically_normal());
    entries_.push_back({time_s, rel.generic_string()});
    rewrite();
}

void PvdWriter::rewrite() const
{
    std::string s;
    s += "<?xml version=\"1.0\"?>\n";
    s += "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n";
    s += "  <Collection>\n";
    for (const auto& e : entries_)
        s += "    <DataSet timestep=\"" + format_shortest(e.time_s) + "\" group=\"\" part=\"0\" file=\"" +
             xml_escape(e.file) + "\"/>\n";
    s += "  </Collection>\n";
    s += "</VTKFile>\n";
    write_file(path_, s);  // under state.pvd.part, then renamed: readers never see a half-written collection
}

}  // namespace pd::io
