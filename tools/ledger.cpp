// tools/ledger.cpp -- the verification ledger: one row per numbered verification case of the sources.
// Inputs (under ROOT/reports):
//   spec_cases.csv    case,title: every verification case of the digests (../shared/spec/*.md: `### Vn`
//                     or `**Vn` headings; `--spec DIR` checks the list against the digests themselves);
//   ledger_cases.csv  case,code,page,csv,row,tolerance,check,reason,deviation,note,wall: how each case is
//                     verified (written by hand; it holds no measured number -- see reports/README.md).
// Outputs (generated; `--check` compares them with the committed files, `--write` rewrites them):
//   ledger.csv        case,title,code,reference,ours,error,tolerance,check,reason,wall_s,status,page,
//                     deviation,note
//                     with reference / ours / error copied verbatim from columns reference / value /
//                     rel_error of the case's CSV row, wall_s from its wall cell;
//   ledger_status.csv status,cases: the count per status;
//   check_kinds.csv   kind,checks,passed,failed: the checks of every committed run (every checks.csv
//                     below reports/, written by Case::finish) by kind (pd/io/checks.hpp); `unrecorded`:
//                     a checks.csv of a run made before the kinds were recorded (no kind column);
//   regression_bounds.csv  run,check,passed: the regression bounds among them, listed apart.
// Status, computed here and never written by hand:
//   MISSING              no code of the project runs the case (code empty);
//   REPRODUCED           a driver case whose csv row has |rel_error| <= tolerance (when a tolerance is
//                        given) and whose run passed every check matching the regex `check` (when given:
//                        checks.csv beside the csv, written by Case::finish; at least one must match,
//                        and none may be a regression bound: our own earlier output proves nothing),
//                        or unit tests (`test Suite.Name;...`) that exist in ROOT/tests (they run in make
//                        check, which fails when they do);
//   DEVIATION EXPLAINED  a driver case that misses (or has neither tolerance nor check: nothing compares
//                        it with the published value) and whose deviation column says why;
//   NOT REPRODUCED       the same without an explanation.
// The note column (partial coverage, what is left) does not change the status.
// Usage: ledger --check|--write ROOT [--spec DIR]. Exit 0 ok, 1 a generated file differs (--check),
// 2 bad input (a case without a row, a row of no case, a missing CSV, row, column, test or driver).
#include "csv_records.hpp"
#include "pd/io/csv.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using tools::records;
using tools::slurp;

namespace {

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

// The verification cases of the digests: `### V3 — title` or `**V3. title**` (file prefix before the
// first `_<letter>`: 000a_theory... -> 000a, 001_004_crackpath -> 001_004).
std::set<std::string> digest_cases(const fs::path& dir)
{
    std::set<std::string> ids;
    static const std::regex heading(R"(^(?:### |\*\*)(V[0-9]+)\b)"), prefix(R"(^([0-9_]*?[0-9a-z]*?)_[a-z])");
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".md") continue;
        std::smatch p;
        const std::string name = e.path().filename().string();
        if (!std::regex_search(name, p, prefix)) continue;
        std::ifstream in(e.path());
        std::smatch m;
        for (std::string l; std::getline(in, l);)
            if (std::regex_search(l, m, heading)) ids.insert(p[1].str() + " " + m[1].str());
    }
    return ids;
}

// Every gtest name of ROOT/tests: TEST(Suite, Name), TEST_F(...), TEST_P(...) -> "Suite.Name".
std::set<std::string> test_names(const fs::path& dir)
{
    std::set<std::string> names;
    static const std::regex test(R"(\bTEST(?:_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\))");
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (e.path().extension() != ".cpp" && e.path().extension() != ".hpp") continue;
        const std::string text = slurp(e.path());
        for (std::sregex_iterator it(text.begin(), text.end(), test), end; it != end; ++it)
            if ((*it)[2].str().rfind("DISABLED_", 0) != 0) names.insert((*it)[1].str() + "." + (*it)[2].str());  // a disabled test does not run
    }
    return names;
}

// A driver name `bar_modes_1d` is problems/1d/bar_modes.cpp; `pd_run` is problems/pd_run.cpp.
bool driver_exists(const fs::path& root, const std::string& code)
{
    static const std::regex dim(R"(^(\w+)_([123]d)$)");
    std::smatch m;
    if (std::regex_match(code, m, dim) && fs::exists(root / "problems" / m[2].str() / (m[1].str() + ".cpp"))) return true;
    return fs::exists(root / "problems" / (code + ".cpp"));
}

struct CsvCache {
    fs::path reports;
    std::map<std::string, std::vector<std::map<std::string, std::string>>> files;
    std::map<std::string, std::string> first_column;  // file -> name of its first column
    const std::vector<std::map<std::string, std::string>>& get(const std::string& rel)
    {
        auto it = files.find(rel);
        if (it == files.end()) {
            it = files.emplace(rel, records(reports / rel)).first;
            first_column[rel] = pd::io::read_csv(reports / rel).header.at(0);
        }
        return it->second;
    }
    // The row of `rel` whose first field is `key_row`.
    const std::map<std::string, std::string>& row(const std::string& rel, const std::string& key_row, const std::string& where)
    {
        for (const auto& r : get(rel))
            if (r.at(first_column.at(rel)) == key_row) return r;
        bad(where + ": " + rel + " has no row '" + key_row + "'");
    }
    const std::string& field(const std::map<std::string, std::string>& r, const std::string& col, const std::string& rel,
                             const std::string& where)
    {
        const auto it = r.find(col);
        if (it == r.end()) bad(where + ": " + rel + " has no column '" + col + "'");
        return it->second;
    }
};

// `PATH:ROW:COLUMN` or `PATH:sum(COLUMN)` -> the field, or the sum formatted shortest.
std::string wall_cell(CsvCache& csv, const std::string& addr, const std::string& where)
{
    static const std::regex sum(R"(^([^:]+):sum\((\w+)\)$)"), cell(R"(^([^:]+):([^:]+):(\w+)$)");
    std::smatch m;
    if (std::regex_match(addr, m, sum)) {
        double total = 0;
        for (const auto& r : csv.get(m[1].str())) {
            double v = 0;
            if (!pd::io::parse_double(csv.field(r, m[2].str(), m[1].str(), where), v)) bad(where + ": wall column is not numeric");
            total += v;
        }
        return pd::io::format_shortest(total);
    }
    if (std::regex_match(addr, m, cell)) return csv.field(csv.row(m[1].str(), m[2].str(), where), m[3].str(), m[1].str(), where);
    bad(where + ": wall '" + addr + "' is not PATH:ROW:COLUMN or PATH:sum(COLUMN)");
}

std::string csv_line(const std::vector<std::string>& fields);

// check_kinds.csv and regression_bounds.csv (header) from every checks.csv below ROOT/reports, in path order.
std::pair<std::string, std::string> check_tables(const fs::path& reports)
{
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(reports))
        if (e.path().filename() == "checks.csv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    std::map<std::string, std::array<long, 2>> count;  // kind -> passed, failed
    std::string bounds = csv_line({"run", "check", "passed"});
    for (const fs::path& f : files) {
        const std::string run = fs::relative(f.parent_path(), reports).generic_string();
        for (const auto& r : records(f)) {
            const auto kind_it = r.find("kind"), passed = r.find("passed"), check = r.find("check");
            if (passed == r.end() || check == r.end()) bad(f.string() + ": needs the columns check,[kind,]passed");
            const std::string kind = kind_it == r.end() ? "unrecorded" : kind_it->second;
            if (kind != "accuracy" && kind != "property" && kind != "regression_bound" && kind != "unrecorded")
                bad(f.string() + ": unknown kind '" + kind + "'");
            ++count[kind][passed->second == "1" ? 0 : 1];
            if (kind == "regression_bound") bounds += csv_line({run, check->second, passed->second});
        }
    }
    std::string kinds = csv_line({"kind", "checks", "passed", "failed"});
    for (const char* k : {"accuracy", "property", "regression_bound", "unrecorded"}) {
        const auto& c = count[k];
        kinds += csv_line({k, std::to_string(c[0] + c[1]), std::to_string(c[0]), std::to_string(c[1])});
    }
    return {kinds, bounds};
}

std::string csv_line(const std::vector<std::string>& fields)
{
    std::string line;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i) line += ',';
        line += pd::io::csv_escape(fields[i]);
    }
    line += '\n';
    return line;
}

// ledger.csv and ledger_status.csv as text.
std::pair<std::string, std::string> build(const fs::path& root, const std::set<std::string>* digests)
{
    const fs::path reports = root / "reports";
    const auto spec = records(reports / "spec_cases.csv");
    const auto cases = records(reports / "ledger_cases.csv");
    std::map<std::string, std::string> title;
    for (const auto& s : spec) title[s.at("case")] = s.at("title");
    if (digests) {
        for (const std::string& id : *digests)
            if (!title.count(id)) bad("reports/spec_cases.csv lacks case '" + id + "' of the digests");
        for (const auto& [id, t] : title)
            if (!digests->count(id)) bad("reports/spec_cases.csv has case '" + id + "', which no digest numbers");
    }
    std::map<std::string, const std::map<std::string, std::string>*> by_case;
    for (const auto& c : cases) {
        const std::string& id = c.at("case");
        if (!title.count(id)) bad("reports/ledger_cases.csv: '" + id + "' is not a case of reports/spec_cases.csv");
        if (by_case.count(id)) bad("reports/ledger_cases.csv: case '" + id + "' has two rows");
        by_case[id] = &c;
    }
    const std::set<std::string> tests = test_names(root / "tests");
    CsvCache csv{reports, {}, {}};
    std::string ledger = csv_line({"case", "title", "code", "reference", "ours", "error", "tolerance", "check", "reason", "wall_s",
                                   "status", "page", "deviation", "note"});
    std::map<std::string, int> count{{"REPRODUCED", 0}, {"DEVIATION EXPLAINED", 0}, {"NOT REPRODUCED", 0}, {"MISSING", 0}};
    for (const auto& s : spec) {
        const std::string& id = s.at("case");
        if (!by_case.count(id)) bad("reports/ledger_cases.csv has no row for case '" + id + "'");
        const auto& c = *by_case[id];
        const std::string where = "reports/ledger_cases.csv, case " + id;
        const std::string& code = c.at("code");
        std::string reference, ours, error, wall, status;
        if (code.empty()) {
            status = "MISSING";
        } else if (code.rfind("test ", 0) == 0) {
            std::stringstream names(code.substr(5));
            for (std::string n; std::getline(names, n, ';');) {
                n = std::string(pd::io::detail::trim(n));
                if (!tests.count(n)) bad(where + ": no test " + n + " in tests/");
            }
            status = "REPRODUCED";
        } else {
            if (!driver_exists(root, code)) bad(where + ": no driver " + code + " in problems/");
            if (c.at("csv").empty() || c.at("row").empty()) bad(where + ": a driver case needs csv and row");
            const auto& r = csv.row(c.at("csv"), c.at("row"), where);
            reference = csv.field(r, "reference", c.at("csv"), where);
            ours = csv.field(r, "value", c.at("csv"), where);
            error = csv.field(r, "rel_error", c.at("csv"), where);
            double e = NAN, tol = NAN;
            pd::io::parse_double(error, e);
            const bool has_tol = !c.at("tolerance").empty(), has_check = !c.at("check").empty();
            if (has_tol && !pd::io::parse_double(c.at("tolerance"), tol))
                bad(where + ": tolerance '" + c.at("tolerance") + "' is not a number");
            bool ok = (has_tol || has_check) && (!has_tol || std::abs(e) <= tol);
            if (has_check) {
                const std::string checks = (fs::path(c.at("csv")).parent_path() / "checks.csv").string();
                const std::regex which(c.at("check"));
                int matched = 0;
                for (const auto& k : csv.get(checks))
                    if (std::regex_search(csv.field(k, "check", checks, where), which)) {
                        if (k.count("kind") && k.at("kind") == "regression_bound")
                            bad(where + ": check '" + k.at("check") + "' is a regression bound; it cannot earn a status");
                        ++matched;
                        ok = ok && csv.field(k, "passed", checks, where) == "1";
                    }
                if (!matched) bad(where + ": no check of " + checks + " matches '" + c.at("check") + "'");
            }
            status = ok ? "REPRODUCED" : c.at("deviation").empty() ? "NOT REPRODUCED" : "DEVIATION EXPLAINED";
        }
        if (!c.at("wall").empty()) wall = wall_cell(csv, c.at("wall"), where);
        if (!c.at("page").empty() && !fs::exists(reports / c.at("page"))) bad(where + ": no page reports/" + c.at("page"));
        const std::string page = c.at("page").empty() ? "" : "[" + fs::path(c.at("page")).stem().string() + "](" + c.at("page") + ")";
        ++count[status];
        ledger += csv_line({id, title[id], code, reference, ours, error, c.at("tolerance"), c.at("check"), c.at("reason"), wall,
                            status, page, c.at("deviation"), c.at("note")});
    }
    std::string status = csv_line({"status", "cases"});
    for (const char* s : {"REPRODUCED", "DEVIATION EXPLAINED", "NOT REPRODUCED", "MISSING"})
        status += csv_line({s, std::to_string(count[s])});
    status += csv_line({"total", std::to_string(spec.size())});
    return {ledger, status};
}

int run(int argc, char** argv)
{
    if (argc < 3 || (std::string(argv[1]) != "--check" && std::string(argv[1]) != "--write"))
        bad("usage: ledger --check|--write ROOT [--spec DIR]");
    const bool write = std::string(argv[1]) == "--write";
    const fs::path root = argv[2];
    std::set<std::string> digests;
    const bool with_spec = argc >= 5 && std::string(argv[3]) == "--spec";
    if (argc >= 4 && !with_spec) bad(std::string("unknown argument '") + argv[3] + "' (--spec DIR)");
    if (with_spec) {
        if (!fs::is_directory(argv[4])) bad(std::string("--spec: no folder ") + argv[4]);
        digests = digest_cases(argv[4]);
    }
    const auto [ledger, status] = build(root, with_spec ? &digests : nullptr);
    const auto [kinds, bounds] = check_tables(root / "reports");
    int differ = 0;
    for (const auto& [name, text] : {std::pair{"ledger.csv", ledger}, std::pair{"ledger_status.csv", status},
                                     std::pair{"check_kinds.csv", kinds}, std::pair{"regression_bounds.csv", bounds}}) {
        const fs::path p = root / "reports" / name;
        if (fs::exists(p) && slurp(p) == text) continue;
        ++differ;
        if (write) std::ofstream(p) << text;
        std::fprintf(write ? stdout : stderr, "ledger: %s %s\n", p.string().c_str(),
                     write ? "rewritten" : "differs from what reports/ledger_cases.csv and the CSVs give (make report)");
    }
    std::printf("ledger: %s%s\n", status.c_str() + status.find('\n') + 1, with_spec ? "(cases checked against the digests)" : "");
    return !write && differ ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ledger: error: %s\n", e.what());
        return 2;
    }
}
