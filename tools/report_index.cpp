// tools/report_index.cpp -- reports/index.html: the verification ledger, then per case its plots,
// drawn from the committed CSVs by tools/svg_plot.hpp (one self-contained file, no network).
// Inputs (under ROOT/reports): ledger.csv (tools/ledger.cpp) and plots.csv, one row per chart:
//   case     the ledger case it illustrates (e.g. `000b V1`)
//   title    the chart's title
//   csv      the data, relative to reports/
//   x        the x column
//   y        the y columns, `COL[:LABEL]` separated by `;` (one series each)
//   group    optional column whose values split every y column into series (e.g. model, integrator)
//   where    optional filters `COL=REGEX` separated by `;` (rows whose COL matches, ECMAScript search)
//   xlabel, ylabel  axis labels with the unit in brackets, e.g. `dx [m]`, `E1 [-]` (required)
//   xscale, yscale  lin or log
//   style    line (lines and markers, default), points, or curve (lines only: long histories);
//            `+rate` adds the observed rate of the finest pair (the two smallest x) to each legend
//            entry, the slope of log y against log x
// Usage: report_index --check|--write ROOT. --write writes reports/index.html; --check regenerates it
// in memory and exits 1 when it differs from the file, or when the page is not well-formed (tags
// balanced), lacks a case of the ledger, or has a chart whose axis labels carry no unit; 2 on bad
// input (a missing CSV or column, a label without unit, an unknown case).
#include "csv_records.hpp"
#include "pd/io/csv.hpp"
#include "svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using tools::Record;
using tools::records;

namespace {

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

std::vector<std::string> split(const std::string& s, char sep)
{
    std::vector<std::string> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, sep);)
        if (!item.empty()) out.push_back(item);
    return out;
}

std::string anchor(const std::string& id)
{
    std::string a = "case-";
    for (char ch : id) a += ch == ' ' ? '-' : ch;
    return a;
}

// A number of the ledger as the README shows it (%.5g); text as it is.
std::string shown(const std::string& field, const char* fmt = "%.5g")
{
    double v = 0;
    if (field.empty() || !pd::io::parse_double(field, v) || !std::isfinite(v)) return svg::escape(field);
    return svg::num(v, fmt);
}

bool has_unit(const std::string& label) { return std::regex_search(label, std::regex(R"(\[[^\]]+\]\s*$)")); }

// One chart of plots.csv as SVG.
std::string chart(const fs::path& reports, const Record& p, const std::string& where_row)
{
    for (const char* k : {"xlabel", "ylabel"})
        if (!has_unit(p.at(k))) bad(where_row + ": " + k + " '" + p.at(k) + "' has no unit in brackets");
    const std::vector<Record> data = records(reports / p.at("csv"));
    auto need = [&](const std::string& col) {
        if (!data.empty() && !data[0].count(col)) bad(where_row + ": " + p.at("csv") + " has no column '" + col + "'");
    };
    need(p.at("x"));
    std::vector<std::pair<std::string, std::regex>> filters;
    for (const std::string& f : split(p.at("where"), ';')) {
        const std::size_t eq = f.find('=');
        if (eq == std::string::npos) bad(where_row + ": where '" + f + "' is not COL=REGEX");
        need(f.substr(0, eq));
        filters.emplace_back(f.substr(0, eq), std::regex(f.substr(eq + 1)));
    }
    if (!p.at("group").empty()) need(p.at("group"));
    const std::string style = p.at("style");
    svg::Chart c{.title = p.at("title"), .xlabel = p.at("xlabel"), .ylabel = p.at("ylabel"), .xlog = p.at("xscale") == "log",
                 .ylog = p.at("yscale") == "log", .series = {}};
    for (const std::string& yspec : split(p.at("y"), ';')) {
        const std::size_t colon = yspec.find(':');
        const std::string col = yspec.substr(0, colon), label = colon == std::string::npos ? col : yspec.substr(colon + 1);
        need(col);
        std::map<std::string, std::size_t> index;  // group value -> series, in order of appearance
        for (const Record& r : data) {
            bool keep = true;
            for (const auto& [fc, re] : filters) keep = keep && std::regex_search(r.at(fc), re);
            if (!keep) continue;
            const std::string g = p.at("group").empty() ? "" : r.at(p.at("group"));
            if (!index.count(g)) {
                index[g] = c.series.size();
                const bool one_y = split(p.at("y"), ';').size() == 1;
                const std::string name = g.empty() ? label : one_y ? g : g + " " + label;
                c.series.push_back({name, {}, style.rfind("points", 0) != 0, style.rfind("curve", 0) != 0});
            }
            double x = NAN, y = NAN;
            pd::io::parse_double(r.at(p.at("x")), x);
            pd::io::parse_double(r.at(col), y);
            c.series[index[g]].points.emplace_back(x, y);
        }
    }
    if (c.series.empty()) bad(where_row + ": no row of " + p.at("csv") + " passes the filters");
    if (style.find("+rate") != std::string::npos)
        for (svg::Series& s : c.series) {
            std::vector<std::pair<double, double>> pts;
            for (const auto& [x, y] : s.points)
                if (x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y)) pts.emplace_back(x, y);
            std::sort(pts.begin(), pts.end());
            if (pts.size() >= 2 && pts[1].first > pts[0].first)
                s.name += " (rate " + svg::num(std::log(pts[1].second / pts[0].second) / std::log(pts[1].first / pts[0].first), "%.2f") + ")";
        }
    return c.render();
}

std::string page(const fs::path& root)
{
    const fs::path reports = root / "reports";
    const std::vector<Record> ledger = records(reports / "ledger.csv"), plots = records(reports / "plots.csv");
    std::map<std::string, std::vector<std::size_t>> by_case;
    for (std::size_t k = 0; k < plots.size(); ++k) by_case[plots[k].at("case")].push_back(k);
    std::map<std::string, int> count;
    for (const Record& r : ledger) ++count[r.at("status")];
    for (const auto& [id, ks] : by_case) {
        bool known = false;
        for (const Record& r : ledger) known = known || r.at("case") == id;
        if (!known) bad("reports/plots.csv: case '" + id + "' is not in reports/ledger.csv");
    }
    std::string h =
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>pd: verification ledger</title>\n<style>\n"
        "body { font-family: sans-serif; margin: 2em; max-width: 1250px; }\n"
        "table { border-collapse: collapse; font-size: 12px; }\n"
        "td, th { border: 1px solid #ccc; padding: 2px 6px; text-align: left; vertical-align: top; }\n"
        ".REPRODUCED { background: #d7f5d7; } .DEVIATION { background: #fff1c2; } .NOT { background: #f9d0d0; } .MISSING { background: #e4e4e4; }\n"
        "section { border-top: 1px solid #999; margin-top: 1.5em; } svg { margin: 4px; border: 1px solid #eee; }\n"
        "</style>\n</head>\n<body>\n<h1>Verification ledger</h1>\n"
        "<p>One row per numbered verification case of the sources, generated from the committed CSVs by tools/ledger.cpp "
        "and tools/report_index.cpp (see reports/README.md for how the status is computed). Reference: the published value "
        "where the source gives one, else the independent reference the case's page names.</p>\n<p>";
    for (const char* s : {"REPRODUCED", "DEVIATION EXPLAINED", "NOT REPRODUCED", "MISSING"})
        h += "<span class=\"" + split(s, ' ')[0] + "\">" + s + ": " + std::to_string(count[s]) + "</span> &#160; ";
    h += "(" + std::to_string(ledger.size()) + " cases)</p>\n<table>\n<tr><th>case</th><th>title</th><th>code</th><th>reference</th>"
         "<th>ours</th><th>error</th><th>tolerance</th><th>wall [s]</th><th>status</th></tr>\n";
    for (const Record& r : ledger)
        h += "<tr><td><a href=\"#" + anchor(r.at("case")) + "\">" + svg::escape(r.at("case")) + "</a></td><td>" + svg::escape(r.at("title")) +
             "</td><td>" + svg::escape(r.at("code").substr(0, 60)) + (r.at("code").size() > 60 ? "..." : "") + "</td><td>" +
             shown(r.at("reference")) + "</td><td>" + shown(r.at("ours")) + "</td><td>" + shown(r.at("error"), "%.2g") + "</td><td>" +
             shown(r.at("tolerance")) + "</td><td>" + shown(r.at("wall_s"), "%.3g") + "</td><td class=\"" + split(r.at("status"), ' ')[0] +
             "\">" + r.at("status") + "</td></tr>\n";
    h += "</table>\n";
    for (const Record& r : ledger) {
        const std::string id = r.at("case");
        h += "<section id=\"" + anchor(id) + "\">\n<h2>" + svg::escape(id) + ": " + svg::escape(r.at("title")) + "</h2>\n";
        h += "<p><span class=\"" + split(r.at("status"), ' ')[0] + "\">" + r.at("status") + "</span>";
        if (!r.at("code").empty()) h += " &#8212; " + svg::escape(r.at("code"));
        static const std::regex link(R"(^\[([^\]]*)\]\(([^)]*)\)$)");
        std::smatch m;
        if (std::regex_match(r.at("page"), m, link)) h += " &#8212; page <a href=\"" + m[2].str() + "\">" + svg::escape(m[1].str()) + "</a>";
        h += "</p>\n";
        for (const char* k : {"reason", "deviation", "note"})
            if (!r.at(k).empty()) h += "<p><b>" + std::string(k) + ":</b> " + svg::escape(r.at(k)) + "</p>\n";
        for (std::size_t k : by_case[id]) h += chart(reports, plots[k], "reports/plots.csv, row " + std::to_string(k + 1));
        h += "</section>\n";
    }
    return h + "</body>\n</html>\n";
}

// Well-formedness of the generated page: every tag closed in order (void tags written as <x/>).
std::string malformed(const std::string& html)
{
    // A scan, not a regex: libstdc++'s regex recurses once per character of a match, and an SVG path's
    // attribute is thousands of characters long (a stack overflow under AddressSanitizer).
    std::vector<std::string> open;
    auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
    auto alnum = [&](char c) { return letter(c) || (c >= '0' && c <= '9'); };
    for (std::size_t at = html.find('<'); at != std::string::npos; at = html.find('<', at + 1)) {
        std::size_t k = at + 1;
        const bool closing = k < html.size() && html[k] == '/';
        if (closing) ++k;
        if (k >= html.size() || !letter(html[k])) continue;  // not a tag (<!DOCTYPE, <!--, a lone '<')
        const std::size_t name_end = std::find_if_not(html.begin() + k, html.end(), alnum) - html.begin();
        const std::size_t gt = html.find('>', name_end);
        if (gt == std::string::npos) return "<" + html.substr(k, name_end - k) + " has no '>'";
        const std::string name = html.substr(k, name_end - k);
        if (html[gt - 1] == '/') continue;  // <x/>
        if (!closing) {
            open.push_back(name);
        } else {
            if (open.empty() || open.back() != name) return "</" + name + "> closes " + (open.empty() ? "nothing" : "<" + open.back() + ">");
            open.pop_back();
        }
    }
    return open.empty() ? "" : "<" + open.back() + "> is never closed";
}

std::string invalid(const std::string& html, const fs::path& root)
{
    if (const std::string m = malformed(html); !m.empty()) return "not well-formed: " + m;
    for (const Record& r : records(root / "reports" / "ledger.csv"))
        if (html.find("<section id=\"" + anchor(r.at("case")) + "\">") == std::string::npos) return "no section for case " + r.at("case");
    static const std::regex label(R"(<text class="(x|y)label"[^>]*>([^<]*)</text>)");
    std::size_t charts = 0, labels = 0;
    for (std::size_t p = html.find("<svg "); p != std::string::npos; p = html.find("<svg ", p + 1)) ++charts;
    for (std::sregex_iterator it(html.begin(), html.end(), label), end; it != end; ++it) {
        if (!has_unit((*it)[2].str())) return "axis label '" + (*it)[2].str() + "' has no unit";
        ++labels;
    }
    if (labels != 2 * charts) return std::to_string(charts) + " charts but " + std::to_string(labels) + " axis labels";
    return "";
}

int run(int argc, char** argv)
{
    if (argc != 3 || (std::string(argv[1]) != "--check" && std::string(argv[1]) != "--write"))
        bad("usage: report_index --check|--write ROOT");
    const fs::path root = argv[2], out = root / "reports" / "index.html";
    const std::string html = page(root);
    if (const std::string why = invalid(html, root); !why.empty()) {
        std::fprintf(stderr, "report_index: the generated page is %s\n", why.c_str());
        return 1;
    }
    const std::string old = tools::slurp(out);
    const std::size_t charts = [&] {
        std::size_t n = 0;
        for (std::size_t p = html.find("<svg "); p != std::string::npos; p = html.find("<svg ", p + 1)) ++n;
        return n;
    }();
    if (old == html) {
        std::printf("report_index: %s is up to date (%zu charts)\n", out.string().c_str(), charts);
        return 0;
    }
    if (std::string(argv[1]) == "--check") {
        std::fprintf(stderr, "report_index: %s differs from what the CSVs give (make report)\n", out.string().c_str());
        return 1;
    }
    std::ofstream(out) << html;
    std::printf("report_index: wrote %s (%zu charts)\n", out.string().c_str(), charts);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "report_index: error: %s\n", e.what());
        return 2;
    }
}
