// pd/io/point_cloud.cpp -- point-cloud CSV reader and its validation (see point_cloud.hpp).
#include "pd/io/point_cloud.hpp"

#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <set>
#include <system_error>

namespace pd::io {

namespace {

const std::array<const char*, 3> coord_names{"x", "y", "z"};
const std::array<const char*, 3> u_names{"ux", "uy", "uz"};
const std::array<const char*, 3> v_names{"vx", "vy", "vz"};
const std::vector<std::string> allowed_columns{"x", "y", "z", "volume", "block", "vx", "vy", "vz",
                                               "ux", "uy", "uz", "fixed", "no_fail", "T0", "T_fixed"};

// A field as quoted in a message: control bytes as \xHH, cut after 40 characters.
std::string shown(const std::string& text)
{
    std::string s;
    for (std::size_t q = 0; q < text.size() && q < 40; ++q) {
        const unsigned char c = static_cast<unsigned char>(text[q]);
        if (c < 0x20 || c == 0x7f) {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", c);
            s += hex;
        } else {
            s += text[q];
        }
    }
    return text.size() > 40 ? s + "..." : s;
}

[[noreturn]] void fail_at(const std::filesystem::path& p, long line, const std::string& column, const std::string& what)
{
    std::string msg = p.string();
    if (line > 0) msg += ":" + std::to_string(line);
    if (!column.empty()) msg += ": column '" + shown(column) + "'";
    throw PointCloudError(msg + ": " + what);
}

}  // namespace

bool PointCloud::has_column(const std::string& name) const
{
    return std::find(columns.begin(), columns.end(), name) != columns.end();
}

long PointCloud::blocks() const { return static_cast<long>(std::set<long>(block.begin(), block.end()).size()); }

long PointCloud::fixed_count() const { return std::count(fixed.begin(), fixed.end(), std::uint8_t{1}); }

long PointCloud::no_fail_count() const { return std::count(no_fail.begin(), no_fail.end(), std::uint8_t{1}); }

PointCloud read_point_cloud(const std::filesystem::path& path, int dim)
{
    if (dim < 1 || dim > 3) throw std::invalid_argument("read_point_cloud: dim must be 1, 2 or 3");
    // 1. The file itself: present, a regular file, not empty, readable.
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail_at(path, 0, "", "no such file");
    if (!std::filesystem::is_regular_file(path, ec)) fail_at(path, 0, "", "not a regular file");
    if (std::filesystem::file_size(path, ec) == 0) fail_at(path, 0, "", "empty file (expected the header x,y,z,volume)");
    CsvTable t;
    try {
        t = read_csv(path);
    } catch (const std::runtime_error& e) {
        throw PointCloudError(e.what());  // already "<file>[:<line>]: <what>"
    }

    // 2. Header: known names, no repeats, the four required columns.
    PointCloud pc;
    pc.path = path;
    pc.columns = t.header;
    for (std::size_t c = 0; c < t.header.size(); ++c) {
        const std::string& name = t.header[c];
        if (name.empty()) fail_at(path, t.header_line, "", "empty column name in the header (a trailing comma?)");
        if (std::find(allowed_columns.begin(), allowed_columns.end(), name) == allowed_columns.end())
            fail_at(path, t.header_line, name, "unknown column (allowed: x,y,z,volume,block,vx,vy,vz,ux,uy,uz,fixed,no_fail,T0,T_fixed)");
        if (std::find(t.header.begin(), t.header.begin() + c, name) != t.header.begin() + c)
            fail_at(path, t.header_line, name, "column given twice");
    }
    for (const char* req : {"x", "y", "z", "volume"})
        if (!t.has_column(req)) fail_at(path, t.header_line, req, "required column missing (header must name x,y,z,volume)");
    if (t.rows.empty()) fail_at(path, t.header_line, "", "no points after the header");

    // 3. Values: finite numbers, positive volumes, integer blocks, 0/1 fixed and no_fail flags.
    const std::size_t n = t.rows.size();
    auto value = [&](std::size_t r, const std::string& name) {
        const std::size_t c = t.column(name);
        const std::string& text = t.rows[r].fields[c];
        double v = 0;
        if (!parse_double(text, v)) fail_at(path, t.rows[r].line, name, "'" + shown(text) + "' is not a number");
        if (!std::isfinite(v)) fail_at(path, t.rows[r].line, name, "'" + shown(text) + "' is not a finite number");
        if (const std::string m = Options::magnitude_error(v); !m.empty()) fail_at(path, t.rows[r].line, name, shown(text) + " " + m);
        return v;
    };
    auto column_or_zero = [&](const std::string& name, std::vector<double>& out) {
        out.assign(n, 0.0);
        if (t.has_column(name))
            for (std::size_t r = 0; r < n; ++r) out[r] = value(r, name);
    };
    for (int d = 0; d < 3; ++d) {
        column_or_zero(coord_names[d], pc.x[d]);
        column_or_zero(u_names[d], pc.u[d]);
        column_or_zero(v_names[d], pc.v[d]);
    }
    column_or_zero("volume", pc.volume);
    const double none = std::numeric_limits<double>::quiet_NaN();
    pc.T0.assign(n, none);
    pc.T_fixed.assign(n, none);
    for (std::size_t r = 0; r < n; ++r) {
        if (t.has_column("T0")) pc.T0[r] = value(r, "T0");
        if (t.has_column("T_fixed") && !t.rows[r].fields[t.column("T_fixed")].empty()) pc.T_fixed[r] = value(r, "T_fixed");
    }
    pc.block.assign(n, 1);
    pc.fixed.assign(n, 0);
    pc.no_fail.assign(n, 0);
    pc.line.resize(n);
    for (std::size_t r = 0; r < n; ++r) {
        const long line = t.rows[r].line;
        pc.line[r] = line;
        if (!(pc.volume[r] > 0)) fail_at(path, line, "volume", "must be positive, got " + t.rows[r].fields[t.column("volume")]);
        if (t.has_column("block")) {
            const double b = value(r, "block");
            const double long_range = 9.0e18;  // |b| below LONG_MAX (2^63 ~ 9.22e18) converts exactly
            if (b != std::floor(b) || std::abs(b) > long_range)
                fail_at(path, line, "block", "must be an integer, got " + t.rows[r].fields[t.column("block")]);
            pc.block[r] = static_cast<long>(b);
        }
        if (t.has_column("fixed")) {
            const double f = value(r, "fixed");
            if (f != 0 && f != 1) fail_at(path, line, "fixed", "must be 0 or 1, got " + t.rows[r].fields[t.column("fixed")]);
            pc.fixed[r] = f == 1;
        }
        if (t.has_column("no_fail")) {
            const double f = value(r, "no_fail");
            if (f != 0 && f != 1) fail_at(path, line, "no_fail", "must be 0 or 1, got " + t.rows[r].fields[t.column("no_fail")]);
            pc.no_fail[r] = f == 1;
        }
        for (int d = 0; d < 3; ++d)
            if (pc.fixed[r] && pc.v[d][r] != 0)
                fail_at(path, line, v_names[d], "a fixed point (fixed = 1) must have zero initial velocity");
    }

    // 4. Dimensions beyond dim: one common coordinate, no motion.
    const std::string dim_text = std::to_string(dim) + "D";
    for (int d = dim; d < 3; ++d)
        for (std::size_t r = 0; r < n; ++r) {
            const long line = pc.line[r];
            if (pc.x[d][r] != pc.x[d][0])
                fail_at(path, line, coord_names[d],
                        format_shortest(pc.x[d][r]) + " differs from " + format_shortest(pc.x[d][0]) + " on line " +
                            std::to_string(pc.line[0]) + "; a " + dim_text + " cloud needs one common " +
                            coord_names[d] + " (it is ignored)");
            if (pc.u[d][r] != 0) fail_at(path, line, u_names[d], "must be 0 in a " + dim_text + " run");
            if (pc.v[d][r] != 0) fail_at(path, line, v_names[d], "must be 0 in a " + dim_text + " run");
        }

    // 5. Duplicate positions: sort lexicographically, compare neighbours.
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    auto pos = [&](std::size_t i) { return std::array<double, 3>{pc.x[0][i], pc.x[1][i], pc.x[2][i]}; };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return pos(a) != pos(b) ? pos(a) < pos(b) : a < b;
    });
    for (std::size_t k = 1; k < n; ++k)
        if (pos(order[k]) == pos(order[k - 1])) {
            const std::size_t first = std::min(order[k], order[k - 1]), second = std::max(order[k], order[k - 1]);
            fail_at(path, pc.line[second], "",
                    "duplicate point (" + format_shortest(pc.x[0][second]) + ", " + format_shortest(pc.x[1][second]) +
                        ", " + format_shortest(pc.x[2][second]) + ") already on line " + std::to_string(pc.line[first]));
        }
    return pc;
}

}  // namespace pd::io
