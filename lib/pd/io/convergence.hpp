// pd/io/convergence.hpp -- convergence table of a refinement study: error and wall time per
// discretisation, observed order of convergence, aligned print and convergence.csv.
//
// Observed rate between consecutive rows k-1, k (h = dx, the grid spacing):
//     rate_k = log(e_k / e_{k-1}) / log(h_k / h_{k-1})
// so that error = C h^p gives rate = p. The rate is NaN (printed "-", written "nan") for the first
// row, when the label columns change from the previous row (a new study or model starts), and when
// it is undefined (an error <= 0 or NaN, equal spacings).
//
//     pd::io::ConvergenceTable table({"model"});
//     table.add({.dx_m = dx, .delta_m = 3 * dx, .m = 3, .nodes = n, .bonds = nb,
//                .error = e, .wall_s = timer.seconds(), .labels = {"lps"}});
//     table.print(std::cout);
//     table.write_csv(out / "convergence.csv");
//
// convergence.csv columns (DESIGN.md, "CSV contract"):
//     <label columns...>,dx_m,delta_m,m,nodes,bonds,error,rate,wall_s,<extra columns...>
#pragma once

#include "pd/io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::io {

struct ConvergenceRow {
    double dx_m = std::numeric_limits<double>::quiet_NaN();     // grid spacing [m]
    double delta_m = std::numeric_limits<double>::quiet_NaN();  // horizon [m]
    double m = std::numeric_limits<double>::quiet_NaN();        // horizon ratio delta / dx [-]
    long long nodes = 0;                                        // number of nodes [-]
    long long bonds = 0;                                        // number of bonds [-]
    double error = std::numeric_limits<double>::quiet_NaN();    // error measure (driver-defined) [-]
    double wall_s = std::numeric_limits<double>::quiet_NaN();   // wall time of the run [s]
    std::vector<std::string> labels = {};                       // one per label column
    std::vector<double> extras = {};                            // one per extra column
};

class ConvergenceTable {
public:
    // label_columns: text columns in front (e.g. {"model"}, {"study"} with values delta|m).
    // extra_columns: numeric columns after wall_s (unit in the name, e.g. "f1_Hz").
    explicit ConvergenceTable(std::vector<std::string> label_columns = {},
                              std::vector<std::string> extra_columns = {})
        : labels_(std::move(label_columns)), extras_(std::move(extra_columns))
    {
    }

    // Throws std::invalid_argument when the number of labels or extras does not match the columns.
    void add(ConvergenceRow row)
    {
        if (row.labels.size() != labels_.size() || row.extras.size() != extras_.size())
            throw std::invalid_argument("ConvergenceTable: row has " + std::to_string(row.labels.size()) +
                                        " labels and " + std::to_string(row.extras.size()) + " extras, table has " +
                                        std::to_string(labels_.size()) + " and " + std::to_string(extras_.size()));
        rows_.push_back(std::move(row));
    }

    std::size_t size() const { return rows_.size(); }
    const ConvergenceRow& row(std::size_t k) const { return rows_.at(k); }

    // Observed rate of row k against row k-1 (see the file header); NaN when undefined.
    double rate(std::size_t k) const
    {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        if (k == 0 || k >= rows_.size() || rows_[k].labels != rows_[k - 1].labels) return nan;
        const ConvergenceRow& a = rows_[k - 1];
        const ConvergenceRow& b = rows_[k];
        if (!(a.error > 0.0 && b.error > 0.0 && a.dx_m > 0.0 && b.dx_m > 0.0) || a.dx_m == b.dx_m) return nan;
        return std::log(b.error / a.error) / std::log(b.dx_m / a.dx_m);
    }

    // Aligned table with a header line; rate NaN printed as "-".
    void print(std::ostream& os) const
    {
        std::vector<std::vector<std::string>> cells{header()};
        for (std::size_t k = 0; k < rows_.size(); ++k) {
            const ConvergenceRow& r = rows_[k];
            std::vector<std::string> line = r.labels;
            for (const std::string& s : {fmt("%.4g", r.dx_m), fmt("%.4g", r.delta_m), fmt("%.4g", r.m),
                                         std::to_string(r.nodes), std::to_string(r.bonds), fmt("%.3e", r.error),
                                         std::isnan(rate(k)) ? std::string("-") : fmt("%.2f", rate(k)),
                                         fmt("%.3g", r.wall_s)})
                line.push_back(s);
            for (double x : r.extras) line.push_back(fmt("%.6g", x));
            cells.push_back(std::move(line));
        }
        std::vector<std::size_t> width(cells[0].size(), 0);
        for (const auto& line : cells)
            for (std::size_t c = 0; c < line.size(); ++c) width[c] = std::max(width[c], line[c].size());
        for (const auto& line : cells) {
            std::string text;
            for (std::size_t c = 0; c < line.size(); ++c) {
                const std::string pad(width[c] - line[c].size(), ' ');
                const bool is_label = c < labels_.size();  // text left-aligned, numbers right-aligned
                text += (c ? "  " : "") + (is_label ? line[c] + pad : pad + line[c]);
            }
            const auto end = text.find_last_not_of(' ');
            os << text.substr(0, end + 1) << '\n';
        }
    }

    // Writes convergence.csv (17 significant digits; rate NaN written "nan"); creates folders.
    void write_csv(const std::filesystem::path& path) const
    {
        CsvWriter csv(path, header(), false);
        for (std::size_t k = 0; k < rows_.size(); ++k) {
            const ConvergenceRow& r = rows_[k];
            std::vector<CsvCell> line(r.labels.begin(), r.labels.end());
            for (const CsvCell& c : {CsvCell(r.dx_m), CsvCell(r.delta_m), CsvCell(r.m), CsvCell(r.nodes),
                                     CsvCell(r.bonds), CsvCell(r.error), CsvCell(rate(k)), CsvCell(r.wall_s)})
                line.push_back(c);
            line.insert(line.end(), r.extras.begin(), r.extras.end());
            csv.row(line);
        }
        csv.flush();
    }

    std::vector<std::string> header() const
    {
        std::vector<std::string> h = labels_;
        for (const char* c : {"dx_m", "delta_m", "m", "nodes", "bonds", "error", "rate", "wall_s"}) h.push_back(c);
        h.insert(h.end(), extras_.begin(), extras_.end());
        return h;
    }

private:
    static std::string fmt(const char* format, double v)
    {
        char buf[64];
        std::snprintf(buf, sizeof buf, format, v);
        return buf;
    }

    std::vector<std::string> labels_;
    std::vector<std::string> extras_;
    std::vector<ConvergenceRow> rows_;
};

}  // namespace pd::io
