// pd/io/csv.hpp -- CSV output (writer, summary.csv) and a small CSV reader.
//
// Writer: CsvWriter creates the parent folders, writes the header, and writes each row as soon as
// it is given, flushed by default, so that the rows written before a crash or abort survive.
// Doubles are written with 17 significant digits (as printf "%.17g"), which reads back to the
// same double bit for bit; integers as integers; text fields are quoted only when they contain a
// comma, a quote, a line break or surrounding blanks (RFC 4180 quoting, "" for a quote).
// Non-finite values are written `nan`, `inf`, `-inf`.
//
//     pd::io::CsvWriter csv(out / "history.csv", {"t_s", "u_m", "step"});
//     csv.row({t, u, step});
//
// Summary (DESIGN.md, "CSV contract"): write_summary writes `quantity,value,reference,rel_error,
// unit`, one row per headline result; an absent reference or error is written `nan`.
//
// Reader: read_csv returns the header and the rows as text with their line numbers (1-based), for
// point clouds and tables. It tolerates a UTF-8 byte-order mark, CRLF and CR line ends and blanks
// around fields, skips blank lines
// and lines starting with '#', understands quoted fields (on one line), and rejects rows whose
// field count differs from the header's. Errors throw std::runtime_error("<path>:<line>: ...").
#pragma once

#include "pd/core/state_archive.hpp"

#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <concepts>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace pd::io {

// ---------------------------------------------------------------- number formatting and parsing

namespace detail {
inline std::string non_finite(double v) { return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"); }
}  // namespace detail

// 17 significant digits, as "%.17g" (locale independent): enough to read back the same double.
inline std::string format_double(double v)
{
    if (!std::isfinite(v)) return detail::non_finite(v);
    std::array<char, 64> buf{};
    const int digits = 17;  // max_digits10 of IEEE double: round trip guaranteed
    auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v, std::chars_format::general, digits);
    return std::string(buf.data(), res.ptr);
}

// Shortest decimal form that reads back to the same double ("0.1" rather than "0.10000000000000001").
inline std::string format_shortest(double v)
{
    if (!std::isfinite(v)) return detail::non_finite(v);
    std::array<char, 64> buf{};
    auto res = std::to_chars(buf.data(), buf.data() + buf.size(), v);
    return std::string(buf.data(), res.ptr);
}

// Parses the whole of `text` as a double (a leading '+' is allowed, blanks are not).
// Returns false if `text` is not exactly one number. Out-of-range values become +-inf or 0.
inline bool parse_double(std::string_view text, double& out)
{
    if (!text.empty() && text.front() == '+') {
        text.remove_prefix(1);
        if (!text.empty() && text.front() == '-') return false;  // "+-1"
    }
    if (text.empty()) return false;
    const char* end = text.data() + text.size();
    const auto res = std::from_chars(text.data(), end, out);
    if (res.ptr != end) return false;
    if (res.ec == std::errc::result_out_of_range) {  // from_chars leaves `out` unset: strtod gives +-inf or 0
        const std::string copy(text);
        out = std::strtod(copy.c_str(), nullptr);
        return true;
    }
    return res.ec == std::errc();
}

// Quotes a CSV field if it needs it (comma, quote, CR/LF, leading/trailing blank, leading '#').
inline std::string csv_escape(std::string_view field)
{
    const bool blank_edge = !field.empty() && (field.front() == ' ' || field.front() == '\t' ||
                                               field.back() == ' ' || field.back() == '\t');
    const bool needs = blank_edge || field.find_first_of(",\"\r\n") != std::string_view::npos ||
                       (!field.empty() && field.front() == '#');
    if (!needs) return std::string(field);
    std::string q = "\"";
    for (char c : field) {
        if (c == '"') q += '"';
        q += c;
    }
    return q + '"';
}

// Creates the parent folder of `path` (and its parents); throws std::runtime_error on failure.
inline void ensure_parent_dir(const std::filesystem::path& path)
{
    const auto dir = path.parent_path();
    if (dir.empty()) return;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) throw std::runtime_error("cannot create folder " + dir.string() + ": " + ec.message());
}

// ------------------------------------------------------------------------------------- writer

// One CSV field: a number or a text, formatted on construction.
class CsvCell {
public:
    CsvCell(double v) : text_(format_double(v)) {}
    CsvCell(float v) : text_(format_double(v)) {}
    template <std::integral T>
    CsvCell(T v) : text_(std::to_string(v)) {}
    CsvCell(const char* s) : text_(csv_escape(s)) {}
    CsvCell(std::string_view s) : text_(csv_escape(s)) {}
    CsvCell(const std::string& s) : text_(csv_escape(s)) {}
    const std::string& text() const { return text_; }  // as written to the file

private:
    std::string text_;
};

// The output manifest: the names of the files a run writes into its output folder, one per line in
// <out>/.pd_files (recorded when a PendingFile opens, so a killed run's ".part" files are listed too).
// begin(out) first removes what the previous run's manifest lists (each file and its ".part"), so
// that a folder never mixes two runs, and nothing else: files the suite did not write stay.
// resume(out) keeps them and goes on listing: a run restarted from a checkpoint continues the run
// whose files these are (pd_run --restart).
class OutputManifest {
public:
    static constexpr const char* name = ".pd_files";
    static void begin(const std::filesystem::path& out)
    {
        namespace fs = std::filesystem;
        const std::lock_guard<std::mutex> lock(mutex());
        const fs::path list = out / name;
        std::ifstream in(list);
        for (std::string line; std::getline(in, line);) {
            const fs::path rel(line);
            if (line.empty() || rel.is_absolute() || line.find("..") != std::string::npos) continue;  // only names below out
            std::error_code ec;
            fs::remove(out / rel, ec);
            fs::remove(out / (line + ".part"), ec);
        }
        in.close();
        if (!std::ofstream(list, std::ios::trunc)) throw std::runtime_error("cannot write " + list.string());
        dir() = out;
    }
    static void resume(const std::filesystem::path& out)
    {
        const std::lock_guard<std::mutex> lock(mutex());
        if (!std::ofstream(out / name, std::ios::app)) throw std::runtime_error("cannot write " + (out / name).string());
        dir() = out;
    }
    // Lists `file` when it lies below the folder of begin() (no-op before begin, or for files elsewhere).
    static void record(const std::filesystem::path& file) noexcept
    {
        const std::lock_guard<std::mutex> lock(mutex());
        if (dir().empty()) return;
        const std::filesystem::path rel = file.lexically_normal().lexically_relative(dir().lexically_normal());
        if (rel.empty() || *rel.begin() == "..") return;
        std::ofstream(dir() / name, std::ios::app) << rel.generic_string() << '\n';
    }

private:
    static std::mutex& mutex()
    {
        static std::mutex m;
        return m;
    }
    static std::filesystem::path& dir()
    {
        static std::filesystem::path d;
        return d;
    }
};

// Set when a run stops to be resumed (io/checkpoints.hpp, pd::Interrupted): a file still open
// while the stop unwinds is not complete, so it keeps its ".part" name (the resumed run rewrites it).
inline std::atomic<bool>& stopping_to_resume()
{
    static std::atomic<bool> flag{false};
    return flag;
}

// A file written under a temporary name (`path` + ".part") that takes its own name only when it is
// complete: at close(), or when the writer is destroyed (also while an exception unwinds, e.g. an
// unstable run, so the rows written so far are kept; but not while a run stops to be resumed). A
// run that is killed leaves the ".part" file, never a cut file under the final name.
class PendingFile {
public:
    PendingFile() = default;
    explicit PendingFile(const std::filesystem::path& path) : path_(path), part_(path)
    {
        part_ += ".part";
        OutputManifest::record(path_);
    }
    PendingFile(PendingFile&& o) noexcept : path_(std::move(o.path_)), part_(std::move(o.part_)) { o.part_.clear(); }
    PendingFile& operator=(PendingFile&& o) noexcept
    {
        publish();
        path_ = std::move(o.path_), part_ = std::move(o.part_);
        o.part_.clear();
        return *this;
    }
    ~PendingFile()
    {
        if (std::uncaught_exceptions() == 0 || !stopping_to_resume()) publish();
    }
    const std::filesystem::path& part() const { return part_; }
    // Renames the temporary file into place (once); false if that failed.
    bool publish() noexcept
    {
        if (part_.empty()) return true;
        std::error_code ec;
        std::filesystem::rename(part_, path_, ec);
        part_.clear();
        return !ec;
    }

private:
    std::filesystem::path path_, part_;
};

class CsvWriter {
public:
    // Creates parent folders, opens `path`.part and writes the header; the file takes its name
    // `path` at close() or destruction (PendingFile).
    // flush_each_row = false buffers rows (faster for very long files); flush() then on demand.
    CsvWriter(const std::filesystem::path& path, std::vector<std::string> columns,
              bool flush_each_row = true)
        : path_(path), columns_(std::move(columns)), flush_each_row_(flush_each_row), file_(path)
    {
        if (columns_.empty()) throw std::invalid_argument("CsvWriter: no columns for " + path_.string());
        ensure_parent_dir(path_);
        out_.open(file_.part(), std::ios::out | std::ios::trunc);
        if (!out_) throw std::runtime_error("cannot open " + path_.string() + " for writing");
        std::vector<CsvCell> head(columns_.begin(), columns_.end());
        write_line(head.data(), head.size());
    }

    // Mixed row: csv.row({"f1_Hz", f, 1234, err}); numbers get 17 digits, integers stay integers.
    void row(std::initializer_list<CsvCell> cells) { write_line(cells.begin(), cells.size()); }
    void row(const std::vector<CsvCell>& cells) { write_line(cells.data(), cells.size()); }
    void row(const std::vector<double>& values)
    {
        std::vector<CsvCell> cells(values.begin(), values.end());
        write_line(cells.data(), cells.size());
    }
    void row_strings(const std::vector<std::string>& fields)
    {
        std::vector<CsvCell> cells(fields.begin(), fields.end());
        write_line(cells.data(), cells.size());
    }

    void flush()
    {
        out_.flush();
        if (!out_) throw std::runtime_error("write error on " + path_.string());
    }
    // Flushes, closes and renames the file into place; the writer takes no rows after it.
    void close()
    {
        flush();
        out_.close();
        if (!file_.publish()) throw std::runtime_error("cannot rename " + file_.part().string() + " to " + path_.string());
    }

    // A checkpoint of the file so far (core/state_archive.hpp, entry "csv.<file name>"): saving
    // stores the text written; loading writes that text back in place of this writer's, so that the
    // rows a resumed run adds follow those of the run it continues.
    void state(StateArchive& ar)
    {
        const std::string entry = "csv." + path_.filename().string();
        std::string text;
        long rows = static_cast<long>(rows_);
        if (ar.saving()) {
            flush();
            std::ifstream in(file_.part(), std::ios::binary);
            text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
            if (!in && !in.eof()) throw std::runtime_error("cannot read back " + file_.part().string());
        }
        ar(entry, text), ar(entry + ".rows", rows);
        if (ar.saving()) return;
        out_.close();
        out_.open(file_.part(), std::ios::out | std::ios::trunc | std::ios::binary);
        out_ << text;
        flush();
        rows_ = static_cast<std::size_t>(rows), has_header_ = true;
    }

    const std::filesystem::path& path() const { return path_; }
    const std::vector<std::string>& columns() const { return columns_; }
    std::size_t rows() const { return rows_; }  // data rows written (header excluded)

private:
    void write_line(const CsvCell* cells, std::size_t n)
    {
        if (n != columns_.size())
            throw std::invalid_argument("CsvWriter: row of " + std::to_string(n) + " fields for " +
                                        std::to_string(columns_.size()) + " columns in " + path_.string());
        std::string line;
        for (std::size_t k = 0; k < n; ++k) {
            if (k) line += ',';
            line += cells[k].text();
        }
        line += '\n';
        out_ << line;
        if (static_cast<bool>(out_) && has_header_) ++rows_;
        has_header_ = true;
        if (flush_each_row_) flush();
        if (!out_) throw std::runtime_error("write error on " + path_.string());
    }

    std::filesystem::path path_;
    std::vector<std::string> columns_;
    bool flush_each_row_;
    bool has_header_ = false;
    std::size_t rows_ = 0;
    PendingFile file_;    // declared before out_: the stream is closed before the rename
    std::ofstream out_;
};

// ------------------------------------------------------------------------------------ summary

// One headline result of a case. reference / rel_error NaN = no reference available.
struct SummaryRow {
    std::string quantity;                                           // name, unit-suffixed (f1_Hz)
    double value = std::numeric_limits<double>::quiet_NaN();        // ours [unit]
    double reference = std::numeric_limits<double>::quiet_NaN();    // published / analytic [unit]
    double rel_error = std::numeric_limits<double>::quiet_NaN();    // |value - reference| / |reference|
    std::string unit;                                               // SI unit, "-" if none
    // false: a quantity this run does not measure (the published value is listed for comparison,
    // or a feature the run did not show, e.g. no second peak); its value is written as nan. A
    // measured value must be finite (Case::finish ends a run with a non-finite one with status 3).
    bool measured = true;
};

// A row for a quantity that this run does not measure (value nan, kept in the table so that the
// published reference stays beside the measured rows).
inline SummaryRow not_measured(std::string quantity, double reference, std::string unit)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {std::move(quantity), nan, reference, nan, std::move(unit), false};
}

// |value - reference| / |reference|; NaN when the reference is NaN or zero (undefined).
inline double relative_error(double value, double reference)
{
    if (std::isnan(reference) || reference == 0.0) return std::numeric_limits<double>::quiet_NaN();
    return std::abs(value - reference) / std::abs(reference);
}

// Writes summary.csv: header exactly `quantity,value,reference,rel_error,unit`.
inline void write_summary(const std::filesystem::path& path, const std::vector<SummaryRow>& rows)
{
    CsvWriter csv(path, {"quantity", "value", "reference", "rel_error", "unit"});
    for (const auto& r : rows) csv.row({r.quantity, r.value, r.reference, r.rel_error, r.unit});
    csv.close();
}

// Prints the summary rows as the drivers' table on stdout: quantity column name_width wide,
// value and reference with `digits` significant digits.
inline void print_summary(const std::vector<SummaryRow>& rows, int name_width, int digits = 6)
{
    std::printf("\n%-*s %14s %14s %10s  %s\n", name_width, "quantity", "value", "reference", "rel_error", "unit");
    for (const auto& r : rows)
        if (r.measured)
            std::printf("%-*s %14.*g %14.*g %10.3e  %s\n", name_width, r.quantity.c_str(), digits, r.value, digits, r.reference, r.rel_error,
                        r.unit.c_str());
        else
            std::printf("%-*s %14s %14.*g %10s  %s\n", name_width, r.quantity.c_str(), "not measured", digits, r.reference, "", r.unit.c_str());
}

// ------------------------------------------------------------------------------------- reader

struct CsvRow {
    long line = 0;                    // 1-based line number in the file
    std::vector<std::string> fields;  // unquoted, blanks around unquoted fields removed
};

struct CsvTable {
    std::filesystem::path path;
    long header_line = 0;
    std::vector<std::string> header;
    std::vector<CsvRow> rows;

    bool has_column(std::string_view name) const { return find(name) < header.size(); }
    // Index of a column; throws std::runtime_error naming the file and the column if absent.
    std::size_t column(std::string_view name) const
    {
        const std::size_t k = find(name);
        if (k == header.size())
            throw std::runtime_error(path.string() + ":" + std::to_string(header_line) +
                                     ": no column '" + std::string(name) + "'");
        return k;
    }
    // Field (row r, column c) as a double; throws std::runtime_error with file, line and column.
    double number(std::size_t r, std::size_t c) const
    {
        double v = 0.0;
        if (!parse_double(rows.at(r).fields.at(c), v))
            throw std::runtime_error(path.string() + ":" + std::to_string(rows[r].line) + ": column '" +
                                     header[c] + "': '" + rows[r].fields[c] + "' is not a number");
        return v;
    }
    // A whole column as doubles.
    std::vector<double> numbers(std::string_view name) const
    {
        const std::size_t c = column(name);
        std::vector<double> v(rows.size());
        for (std::size_t r = 0; r < rows.size(); ++r) v[r] = number(r, c);
        return v;
    }

private:
    std::size_t find(std::string_view name) const
    {
        std::size_t k = 0;
        while (k < header.size() && header[k] != name) ++k;
        return k;
    }
};

namespace detail {

inline std::string_view trim(std::string_view s)
{
    const auto b = s.find_first_not_of(" \t");
    if (b == std::string_view::npos) return {};
    const auto e = s.find_last_not_of(" \t");
    return s.substr(b, e - b + 1);
}

// Splits one line into fields; returns false on an unterminated quote or text after a closing quote.
inline bool split_csv_line(std::string_view line, std::vector<std::string>& fields)
{
    fields.clear();
    std::size_t i = 0;
    while (true) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        std::string field;
        if (i < line.size() && line[i] == '"') {
            ++i;
            bool closed = false;
            while (i < line.size()) {
                if (line[i] == '"') {
                    if (i + 1 < line.size() && line[i + 1] == '"') { field += '"'; i += 2; continue; }
                    closed = true;
                    ++i;
                    break;
                }
                field += line[i++];
            }
            if (!closed) return false;
            while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
            if (i < line.size() && line[i] != ',') return false;
        } else {
            const auto comma = line.find(',', i);
            const auto end = comma == std::string_view::npos ? line.size() : comma;
            field = std::string(trim(line.substr(i, end - i)));
            i = end;
        }
        fields.push_back(std::move(field));
        if (i >= line.size()) return true;
        ++i;  // skip the comma
    }
}

}  // namespace detail

// Reads a CSV file (see the file header for what is tolerated). Throws std::runtime_error.
inline CsvTable read_csv(const std::filesystem::path& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open " + path.string() + " for reading");
    std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    if (text.starts_with("\xEF\xBB\xBF")) text.erase(0, 3);  // the UTF-8 byte-order mark of spreadsheet "CSV UTF-8"
    for (std::size_t i = 0; i < text.size(); ++i)                // CR-only line ends (classic Mac) become LF
        if (text[i] == '\r' && (i + 1 == text.size() || text[i + 1] != '\n')) text[i] = '\n';
    std::istringstream in(text);
    CsvTable t;
    t.path = path;
    std::string line;
    std::vector<std::string> fields;
    bool have_header = false;
    for (long number = 1; std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const auto body = detail::trim(line);
        if (body.empty() || body.front() == '#') continue;
        const std::string where = path.string() + ":" + std::to_string(number) + ": ";
        if (!detail::split_csv_line(line, fields))
            throw std::runtime_error(where + "malformed quoted field");
        if (!have_header) {
            t.header = fields;
            t.header_line = number;
            have_header = true;
            continue;
        }
        if (fields.size() != t.header.size())
            throw std::runtime_error(where + "expected " + std::to_string(t.header.size()) + " fields, found " +
                                     std::to_string(fields.size()) +
                                     (fields.size() == t.header.size() + 1 && detail::trim(fields.back()).empty() ? " (a trailing comma?)" : ""));
        t.rows.push_back({number, fields});
    }
    if (!have_header) throw std::runtime_error(path.string() + ": no header line");
    return t;
}

}  // namespace pd::io
