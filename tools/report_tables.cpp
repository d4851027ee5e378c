// tools/report_tables.cpp -- the tables of the report pages, generated from the committed CSVs.
// A page marks a generated table with two HTML comments (invisible in rendered Markdown):
//
//   <!-- table csv=jc_bar/summary.csv rows=^sigma_eq_centre_ cols=quantity:quantity,value:ours [Pa] fmt=value:%.4g -->
//   ... the table, written by this tool ...
//   <!-- end table -->
//
// Keys (space separated, no spaces inside a value):
//   csv=PATH     the CSV, relative to the page's folder (required);
//   rows=REGEX   keep the rows whose first field matches (ECMAScript, search; default all);
//   where=LIST   and whose fields match too: COLUMN=REGEX separated by ';';
//   cols=LIST    columns in order, each NAME or NAME:HEADER (underscores in HEADER become spaces;
//                default every column under its own name);
//   fmt=LIST     NAME:printf-format for numbers of that column (default %.6g; nan/inf as written);
//   scale=LIST   NAME:factor multiplying that column's numbers before formatting (e.g. Pa -> MPa).
// Usage: report_tables --check|--write PATH...  (files or folders: every *.md below them).
//   --check  regenerates every marked table in memory and exits 1 naming the first page, line and
//            table that differs from the file: a number edited by hand, or a CSV that changed or
//            lost a row, fails (the ctest `report_tables`); it also fails on a CSV below the folders
//            that lost a number (ragged rows, or an empty field in a numeric column);
//   --write  rewrites the marked tables in place from the CSVs (`make report`).
// Bad markers, missing CSVs or columns: one line naming the page and line, exit 2.
#include "pd/io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

struct Marker {
    std::string csv, rows;
    std::vector<std::pair<std::string, std::string>> where;  // (column, regex)
    std::vector<std::pair<std::string, std::string>> cols;  // (name, header)
    std::map<std::string, std::string> fmt;
    std::map<std::string, double> scale;
};

[[noreturn]] void bad(const fs::path& page, std::size_t line, const std::string& what)
{
    throw std::invalid_argument(page.string() + ":" + std::to_string(line) + ": " + what);
}

// "a:b,c" -> (a, b), (c, "").
std::vector<std::pair<std::string, std::string>> pairs(const std::string& list)
{
    std::vector<std::pair<std::string, std::string>> out;
    std::stringstream ss(list);
    for (std::string item; std::getline(ss, item, ',');) {
        const std::size_t c = item.find(':');
        out.emplace_back(item.substr(0, c), c == std::string::npos ? std::string() : item.substr(c + 1));
    }
    return out;
}

Marker parse_marker(const std::string& text, const fs::path& page, std::size_t line)
{
    Marker m;
    std::stringstream ss(text);
    for (std::string kv; ss >> kv;) {
        const std::size_t eq = kv.find('=');
        if (eq == std::string::npos) bad(page, line, "table marker: '" + kv + "' is not key=value");
        const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
        if (key == "csv") {
            m.csv = value;
        } else if (key == "rows") {
            m.rows = value;
        } else if (key == "where") {
            std::stringstream ws(value);
            for (std::string f; std::getline(ws, f, ';');) {
                const std::size_t e = f.find('=');
                if (e == std::string::npos) bad(page, line, "table marker: where '" + f + "' is not COLUMN=REGEX");
                m.where.emplace_back(f.substr(0, e), f.substr(e + 1));
            }
        } else if (key == "cols") {
            m.cols = pairs(value);
        } else if (key == "fmt") {
            for (auto& [k, v] : pairs(value)) m.fmt[k] = v;
        } else if (key == "scale") {
            for (auto& [k, v] : pairs(value))
                if (!pd::io::parse_double(v, m.scale[k])) bad(page, line, "table marker: scale of '" + k + "' is not a number");
        } else {
            bad(page, line, "table marker: unknown key '" + key + "' (csv, rows, where, cols, fmt, scale)");
        }
    }
    if (m.csv.empty()) bad(page, line, "table marker: csv= is required");
    return m;
}

std::string cell(const std::string& field, const std::string& fmt, double scale)
{
    double v = 0;
    if (!pd::io::parse_double(field, v) || !std::isfinite(v)) {  // text: a '|' would end the Markdown cell
        std::string text;
        for (char ch : field) text += ch == '|' ? std::string("\\|") : std::string(1, ch);
        return text;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt.empty() ? "%.6g" : fmt.c_str(), v * scale);
    return buf;
}

// The table of a marker, as Markdown lines.
std::vector<std::string> render(const Marker& m, const fs::path& page, std::size_t line)
{
    const fs::path csv = page.parent_path() / m.csv;
    if (!fs::exists(csv)) bad(page, line, "table marker: no file " + csv.string());
    const pd::io::CsvTable t = pd::io::read_csv(csv);
    std::vector<std::pair<std::string, std::string>> cols = m.cols;
    if (cols.empty())
        for (const std::string& h : t.header) cols.emplace_back(h, std::string());
    std::vector<std::size_t> index;
    std::string head = "|", rule = "|";
    for (auto& [name, header] : cols) {
        if (!t.has_column(name)) bad(page, line, "table marker: " + csv.string() + " has no column '" + name + "'");
        index.push_back(t.column(name));
        std::string h = header.empty() ? name : header;
        if (!header.empty())
            for (char& ch : h) ch = ch == '_' ? ' ' : ch;
        head += ' ';
        head += h;
        head += " |";
        rule += "---|";
    }
    std::vector<std::string> out{head, rule};
    const std::regex keep(m.rows.empty() ? std::string(".*") : m.rows);
    std::vector<std::pair<std::size_t, std::regex>> where;
    for (const auto& [col, re] : m.where) {
        if (!t.has_column(col)) bad(page, line, "table marker: " + csv.string() + " has no column '" + col + "'");
        where.emplace_back(t.column(col), std::regex(re));
    }
    for (const pd::io::CsvRow& r : t.rows) {
        if (!std::regex_search(r.fields.at(0), keep)) continue;
        bool pass = true;
        for (const auto& [c, re] : where) pass = pass && std::regex_search(r.fields.at(c), re);
        if (!pass) continue;
        std::string row = "|";
        for (std::size_t c = 0; c < cols.size(); ++c) {
            const std::string& name = cols[c].first;
            const auto f = m.fmt.find(name);
            const auto s = m.scale.find(name);
            row += ' ';
            row += cell(r.fields[index[c]], f == m.fmt.end() ? "" : f->second, s == m.scale.end() ? 1.0 : s->second);
            row += " |";
        }
        out.push_back(row);
    }
    if (out.size() == 2) bad(page, line, "table marker: no row of " + csv.string() + " matches rows=" + m.rows);
    return out;
}

// A committed CSV that lost a number: rows of unequal length (read_csv throws), or an empty field in
// a column whose other fields are all numbers. The ledger's own files, where an empty field means
// "none", are checked by tools/ledger.cpp instead. Returns "" or a description.
std::string damaged(const fs::path& csv)
{
    const std::string name = csv.filename().string();
    if (name.rfind("ledger", 0) == 0 || name == "spec_cases.csv") return "";
    pd::io::CsvTable t;
    try {
        t = pd::io::read_csv(csv);
    } catch (const std::exception& e) {
        return e.what();
    }
    for (std::size_t c = 0; c < t.header.size(); ++c) {
        long empty_line = 0;
        bool numeric = true;
        for (const pd::io::CsvRow& r : t.rows) {
            double v = 0;
            if (r.fields[c].empty()) empty_line = empty_line ? empty_line : r.line;
            else numeric = numeric && pd::io::parse_double(r.fields[c], v);
        }
        if (empty_line && numeric)
            return csv.string() + ":" + std::to_string(empty_line) + ": empty field in the numeric column '" + t.header[c] + "'";
    }
    return "";
}

// Regenerates the marked tables of one page; returns the new text and sets `first_diff` to a
// description of the first table that differs ("" when none).
std::string regenerate(const fs::path& page, std::string& first_diff)
{
    std::ifstream in(page);
    std::vector<std::string> lines;
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    static const std::regex open(R"(^<!-- table (.*) -->\s*$)"), close(R"(^<!-- end table -->\s*$)");
    std::vector<std::string> out;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        out.push_back(lines[i]);
        std::smatch mt;
        if (!std::regex_match(lines[i], mt, open)) continue;
        std::size_t end = i + 1;
        while (end < lines.size() && !std::regex_match(lines[end], close)) ++end;
        if (end == lines.size()) bad(page, i + 1, "table marker without <!-- end table -->");
        const std::vector<std::string> table = render(parse_marker(mt[1].str(), page, i + 1), page, i + 1);
        const std::vector<std::string> old(lines.begin() + static_cast<long>(i) + 1, lines.begin() + static_cast<long>(end));
        if (old != table && first_diff.empty()) {
            std::size_t k = 0;
            while (k < old.size() && k < table.size() && old[k] == table[k]) ++k;
            first_diff = page.string() + ":" + std::to_string(i + 2 + k) + ": generated table differs from " +
                         (k < table.size() ? "'" + table[k] + "'" : "its end") + " (from the CSV)";
        }
        out.insert(out.end(), table.begin(), table.end());
        out.push_back(lines[end]);
        i = end;
    }
    std::string text;
    for (const std::string& l : out) text += l + "\n";
    return text;
}

int run(int argc, char** argv)
{
    if (argc < 3 || (std::string(argv[1]) != "--check" && std::string(argv[1]) != "--write"))
        throw std::invalid_argument("usage: report_tables --check|--write PATH... (pages or folders of pages)");
    const bool write = std::string(argv[1]) == "--write";
    std::vector<fs::path> pages, csvs;
    for (int a = 2; a < argc; ++a) {
        if (fs::is_directory(argv[a])) {
            for (const auto& e : fs::recursive_directory_iterator(argv[a])) {
                if (e.path().extension() == ".md") pages.push_back(e.path());
                if (e.path().extension() == ".csv") csvs.push_back(e.path());
            }
        } else if (fs::exists(argv[a])) {
            pages.emplace_back(argv[a]);
        } else {
            throw std::invalid_argument(std::string("no file or folder '") + argv[a] + "'");
        }
    }
    std::sort(pages.begin(), pages.end());
    int tables = 0, differing = 0;
    for (const fs::path& page : pages) {
        std::string diff;
        const std::string text = regenerate(page, diff);
        for (std::size_t p = text.find("<!-- table "); p != std::string::npos; p = text.find("<!-- table ", p + 1)) ++tables;
        if (diff.empty()) continue;
        ++differing;
        if (write) {
            std::ofstream(page) << text;
            std::printf("report_tables: rewrote %s\n", page.string().c_str());
        } else {
            std::fprintf(stderr, "report_tables: %s\n", diff.c_str());
        }
    }
    std::sort(csvs.begin(), csvs.end());
    int broken = 0;
    for (const fs::path& csv : csvs) {
        const std::string what = damaged(csv);
        if (what.empty()) continue;
        ++broken;
        std::fprintf(stderr, "report_tables: %s\n", what.c_str());
    }
    std::printf("report_tables: %d generated tables in %zu pages, %d page(s) %s; %zu CSVs, %d damaged\n", tables, pages.size(),
                differing, write ? "rewritten" : "differ from their CSVs", csvs.size(), broken);
    return !write && (differing > 0 || broken > 0) ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "report_tables: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "report_tables: error: %s\n", e.what());
        return 2;
    }
}
