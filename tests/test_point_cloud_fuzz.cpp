// Deterministic mutation fuzzing of the point-cloud reader (pd/io/point_cloud.hpp): valid clouds
// (1D, 2D, 3D; optional block, u, v, fixed, no_fail, T0, T_fixed columns; comments, blank lines,
// quoted fields) are mutated at the byte level (delete, insert, duplicate, swap, truncate, BOM, CR,
// CRLF, NUL, tabs, long lines) and at the token level (a number replaced by nan, inf, 1e308, -0,
// out-of-range integers, empty text, ...; header columns repeated, dropped, unknown; extra commas;
// rows repeated, swapped, dropped). Every input must either read into a PointCloud whose sizes
// agree and whose values are finite, with positive volumes, or throw PointCloudError with ONE line
// that starts with the file name. Any other exception, or a crash, fails; the input is printed
// escaped (after a crash it is left in the scratch file named on stderr).
#include <gtest/gtest.h>

#include "pd/io/point_cloud.hpp"

#include "scratch_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

// A valid cloud: nx x ny x nz lattice of spacing h; `extra` columns with their value per point.
struct Seed {
    std::string text;
    int dim;
};

std::string number(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::vector<Seed> seeds()
{
    std::vector<Seed> s;
    {  // 3D, every optional column, a fixed point at rest and a free T_fixed field
        std::string t = "x,y,z,volume,block,vx,vy,vz,ux,uy,uz,fixed,no_fail,T0,T_fixed\n";
        for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 3; ++i) {
                    const bool fixed = i == 0;
                    t += number(i * 1e-3) + "," + number(j * 1e-3) + "," + number(k * 1e-3) + ",1e-9," +
                         std::to_string(1 + k) + "," + (fixed ? "0,0,0" : "1.5,-2,0.25") + ",0,1e-6,-1e-6," +
                         (fixed ? "1" : "0") + "," + (j ? "1" : "0") + ",293.15," + (i == 2 ? "400" : "") + "\n";
                }
        s.push_back({t, 3});
    }
    {  // 2D, common z, displacements, comment and blank lines, CRLF line ends, quoted fields
        std::string t = "# a 2D plate\r\nx,y,z,volume,ux,uy\r\n\r\n";
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                t += number(i * 0.5) + "," + number(j * 0.5) + ",0.1,\"0.25\"," + number(1e-4 * i) + ",0\r\n";
        s.push_back({t, 2});
    }
    {  // 1D, columns in another order, T0, blanks around fields
        std::string t = "volume, x ,y,z,T0,block\n";
        for (int i = 0; i < 5; ++i) t += "1e-6, " + number(i * 1e-3) + " ,0,0,20," + std::to_string(-i) + "\n";
        t += "# trailing comment\n";
        s.push_back({t, 1});
    }
    {  // 3D minimal, scientific notation and leading '+'
        std::string t = "x,y,z,volume\n";
        for (int i = 0; i < 4; ++i) t += "+" + number(i * 2.5e-3) + ",1E-3,-2e-3,1.5625e-8\n";
        s.push_back({t, 3});
    }
    {  // 2D with velocities and no_fail, fixed
        std::string t = "x,y,z,volume,vx,vy,fixed,no_fail\n";
        for (int i = 0; i < 4; ++i) t += number(i * 1.0) + "," + number(i % 2 * 1.0) + ",0,1," + (i ? "3,4,0," : "0,0,1,") + "1\n";
        s.push_back({t, 2});
    }
    return s;
}

const std::vector<std::string> bad_numbers{
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308", "1e309", "-1e309", "-0", "0", "+0",
    "4.9e-324", "1e-320", "1e-400", "99999999999999999999", "9223372036854775807", "9223372036854775808",
    "-9223372036854775809", "9.3e18", "-9.3e18", "1e19", "", " ", "1e", "e5", ".", "-", "+", "+-1", "--1",
    "0x10", "1,5", "\"1\"", "\"1", "1\"", "1.5.5", "1e5e5", "１", "1\t", "\t1", "0.5", "2", "1", "-1",
    std::string(400, '9'), "0." + std::string(400, '0') + "1", "\"\"", "\"1,2\"", "#1", "1 2"};

const std::vector<std::string> bad_columns{"x",  "y",  "z",  "volume", "block", "vx",   "vy",  "vz",
                                           "ux", "fixed", "no_fail", "T0", "T_fixed", "vX", "t0", "",
                                           " ", "\"x\"", "x ", "volume\t", "\xEF\xBB\xBFx", "#x", "mass"};

const std::vector<std::string> inserts{",", "\"", "\n", "\r", "\r\n", "\t", " ", "#", std::string(1, '\0'),
                                       "\xEF\xBB\xBF", "e", "-", "+", ".", "0", "1", "9", "\xFF", "\xC3\xA9",
                                       ",,", "\n\n", "\"\"", "\\"};

struct Mutator {
    std::mt19937_64 rng;
    std::size_t pick(std::size_t n) { return n ? std::uniform_int_distribution<std::size_t>(0, n - 1)(rng) : 0; }
    template <class V>
    const auto& any(const V& v) { return v[pick(v.size())]; }

    // Spans of the numbers-or-names between separators (',' and line ends).
    static std::vector<std::pair<std::size_t, std::size_t>> tokens(const std::string& s)
    {
        std::vector<std::pair<std::size_t, std::size_t>> t;
        std::size_t b = 0;
        for (std::size_t i = 0; i <= s.size(); ++i)
            if (i == s.size() || s[i] == ',' || s[i] == '\n' || s[i] == '\r') {
                if (i > b) t.emplace_back(b, i - b);
                b = i + 1;
            }
        return t;
    }
    // Line spans [begin, end) without the '\n'.
    static std::vector<std::pair<std::size_t, std::size_t>> lines(const std::string& s)
    {
        std::vector<std::pair<std::size_t, std::size_t>> l;
        std::size_t b = 0;
        for (std::size_t i = 0; i <= s.size(); ++i)
            if (i == s.size() || s[i] == '\n') {
                if (i > b || i < s.size()) l.emplace_back(b, i);
                b = i + 1;
            }
        return l;
    }

    void mutate(std::string& s)
    {
        const auto ls = lines(s);
        switch (pick(20)) {
        case 0: if (!s.empty()) { const std::size_t p = pick(s.size()); s.erase(p, 1 + pick(std::min<std::size_t>(8, s.size() - p))); } break;
        case 1: s.insert(pick(s.size() + 1), any(inserts)); break;
        case 2: s.insert(pick(s.size() + 1), 1, static_cast<char>(pick(256))); break;
        case 3: if (!s.empty()) { const std::size_t p = pick(s.size()), n = 1 + pick(std::min<std::size_t>(16, s.size() - p)); s.insert(p, s.substr(p, n)); } break;
        case 4: if (s.size() > 1) std::swap(s[pick(s.size())], s[pick(s.size())]); break;
        case 5: s.resize(pick(s.size() + 1)); break;
        case 6: s.insert(pick(2) ? 0 : pick(s.size() + 1), "\xEF\xBB\xBF"); break;
        case 7: {  // every line end CRLF, or CR
            const std::string to = pick(2) ? "\r\n" : "\r";
            std::string o;
            for (char c : s) o += c == '\n' ? to : std::string(1, c);
            s = o;
        } break;
        case 8: s.insert(pick(s.size() + 1), std::string(1 + pick(3), '\0')); break;
        case 9: {  // a very long line: many digits, commas or blanks
            const std::string fill = any(std::vector<std::string>{"9", ",", " ", "\t", "x"});
            std::string block;
            for (std::size_t k = 0, n = 1000 + pick(100000); k < n; ++k) block += fill;
            s.insert(pick(s.size() + 1), block);
        } break;
        case 10: case 11: case 12: {  // a token replaced by a hostile number
            const auto t = tokens(s);
            if (!t.empty()) { const auto [b, n] = any(t); s.replace(b, n, any(bad_numbers)); }
        } break;
        case 13: {  // a header column repeated, renamed or added (first non-comment line)
            for (const auto& [b, e] : ls) {
                if (e == b || s[b] == '#') continue;
                const std::string name = any(bad_columns);
                if (pick(2)) s.insert(e, "," + name);
                else s.insert(b, name + ",");
                break;
            }
        } break;
        case 14: {  // a header column dropped
            const auto t = tokens(s);
            if (!t.empty()) { const auto [b, n] = t[pick(std::min<std::size_t>(t.size(), 8))]; s.erase(b, n + (b + n < s.size())); }
        } break;
        case 15: if (!ls.empty()) { const auto [b, e] = any(ls); s.insert(e, std::string(1 + pick(3), ',')); } break;
        case 16: if (!ls.empty()) { const auto [b, e] = any(ls); s.insert(e < s.size() ? e + 1 : e, (e < s.size() ? "" : "\n") + s.substr(b, e - b) + "\n"); } break;
        case 17: if (!ls.empty()) { const auto [b, e] = any(ls); s.erase(b, e - b + (e < s.size())); } break;
        case 18: if (ls.size() > 1) {  // two lines swapped
            auto v = ls;
            const std::size_t i = pick(v.size()), j = pick(v.size());
            std::vector<std::string> text;
            for (const auto& [b, e] : v) text.push_back(s.substr(b, e - b));
            std::swap(text[i], text[j]);
            std::string o;
            for (std::size_t k = 0; k < text.size(); ++k) o += text[k] + (k + 1 < text.size() || s.ends_with('\n') ? "\n" : "");
            s = o;
        } break;
        case 19: if (!s.empty()) { const std::size_t p = pick(s.size()); if (s[p] == ',') s[p] = pick(2) ? '\t' : ';'; else s.insert(p, "\t"); } break;
        }
    }
};

std::string escaped(const std::string& s, std::size_t limit = 4000)
{
    std::string o;
    for (std::size_t i = 0; i < s.size() && o.size() < limit; ++i) {
        const unsigned char c = s[i];
        if (c == '\n') o += "\\n\n";
        else if (c == '\r') o += "\\r";
        else if (c == '\t') o += "\\t";
        else if (c == '\\') o += "\\\\";
        else if (c < 32 || c >= 127) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            o += buf;
        } else o += static_cast<char>(c);
    }
    if (o.size() >= limit) o += "... (" + std::to_string(s.size()) + " bytes)";
    return o;
}

// What is wrong with a cloud the reader accepted ("" = nothing).
std::string check_cloud(const pd::io::PointCloud& pc, int dim)
{
    const std::size_t n = pc.size();
    if (n == 0) return "no points";
    for (int d = 0; d < 3; ++d)
        if (pc.x[d].size() != n || pc.u[d].size() != n || pc.v[d].size() != n) return "sizes differ (x, u, v)";
    if (pc.block.size() != n || pc.fixed.size() != n || pc.no_fail.size() != n || pc.T0.size() != n ||
        pc.T_fixed.size() != n || pc.line.size() != n)
        return "sizes differ (block, fixed, no_fail, T0, T_fixed, line)";
    std::set<std::array<double, 3>> at;
    for (std::size_t i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d) {
            if (!std::isfinite(pc.x[d][i]) || !std::isfinite(pc.u[d][i]) || !std::isfinite(pc.v[d][i]))
                return "non-finite x, u or v at point " + std::to_string(i);
            if (d >= dim && (pc.x[d][i] != pc.x[d][0] || pc.u[d][i] != 0 || pc.v[d][i] != 0))
                return "coordinate, u or v beyond dim varies at point " + std::to_string(i);
            if (pc.fixed[i] && pc.v[d][i] != 0) return "fixed point with a velocity at point " + std::to_string(i);
        }
        if (!std::isfinite(pc.volume[i]) || !(pc.volume[i] > 0)) return "volume not finite and > 0 at point " + std::to_string(i);
        if (pc.has_column("T0") != std::isfinite(pc.T0[i])) return "T0 finite iff the column is given, point " + std::to_string(i);
        if (std::isinf(pc.T_fixed[i])) return "infinite T_fixed at point " + std::to_string(i);
        if (pc.fixed[i] > 1 || pc.no_fail[i] > 1) return "fixed / no_fail not 0 or 1 at point " + std::to_string(i);
        if (i > 0 && pc.line[i] <= pc.line[i - 1]) return "line numbers not increasing";
        if (!at.insert({pc.x[0][i], pc.x[1][i], pc.x[2][i]}).second) return "duplicate point " + std::to_string(i);
    }
    return "";
}

// The file of the running case, named on stderr if the reader crashes.
char crash_note[512];
extern "C" void on_crash(int sig)
{
    ssize_t ignored = write(2, crash_note, std::strlen(crash_note));
    (void)ignored;
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

TEST(PointCloudFuzz, MutatedCloudsReadOrFailWithOneLine)
{
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path file = pd_test::scratch_dir() / "cloud.csv";
    std::snprintf(crash_note, sizeof crash_note, "PointCloudFuzz: the reader crashed; the input is %s\n", file.c_str());
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS}) std::signal(sig, on_crash);

    const std::vector<Seed> base = seeds();
    for (const Seed& s : base) {  // the seeds themselves are valid
        std::ofstream(file, std::ios::binary) << s.text;
        EXPECT_NO_THROW({ EXPECT_EQ(check_cloud(pd::io::read_point_cloud(file, s.dim), s.dim), "") << s.text; }) << s.text;
    }

    Mutator mut{std::mt19937_64{20240611}};
    constexpr int cases = 4000;
    int accepted = 0, rejected = 0, failures = 0;
    std::size_t longest_message = 0;
    // Not failures, reported: messages that echo control bytes (NUL, CR, ...) or run very long.
    int control_messages = 0, long_messages = 0;
    std::string control_example, long_example;
    for (int k = 0; k < cases; ++k) {
        const Seed& seed = base[mut.pick(base.size())];
        std::string text = seed.text;
        for (std::size_t m = 0, n = 1 + mut.pick(3); m < n; ++m) mut.mutate(text);
        const int dim = mut.pick(4) == 0 ? 1 + static_cast<int>(mut.pick(3)) : seed.dim;
        std::ofstream(file, std::ios::binary | std::ios::trunc) << text;

        std::string problem;
        try {
            const pd::io::PointCloud pc = pd::io::read_point_cloud(file, dim);
            problem = check_cloud(pc, dim);
            ++accepted;
        } catch (const pd::io::PointCloudError& e) {
            const std::string msg = e.what();
            longest_message = std::max(longest_message, msg.size());
            if (std::any_of(msg.begin(), msg.end(), [](char c) { return static_cast<unsigned char>(c) < 32 && c != '\t'; }) &&
                control_messages++ == 0)
                control_example = escaped(msg, 300);
            if (msg.size() > 1000 && long_messages++ == 0) long_example = escaped(msg, 300);
            if (msg.find('\n') != std::string::npos) problem = "message of more than one line: " + escaped(msg, 600);
            else if (!msg.starts_with(file.string())) problem = "message does not start with the file name: " + escaped(msg, 600);
            ++rejected;
        } catch (const std::exception& e) {
            problem = std::string("exception other than PointCloudError: ") + typeid(e).name() + ": " + e.what();
        } catch (...) {
            problem = "non-standard exception";
        }
        if (!problem.empty() && ++failures <= 20)
            ADD_FAILURE() << "case " << k << " (dim " << dim << "): " << problem << "\ninput (escaped):\n" << escaped(text);
    }
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS}) std::signal(sig, SIG_DFL);
    EXPECT_EQ(failures, 0);
    EXPECT_GT(accepted, cases / 50);  // the mutations leave some clouds valid: the acceptance branch is exercised
    EXPECT_GT(rejected, cases / 2);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << cases << " mutated clouds: " << accepted << " read, " << rejected << " rejected (longest message "
              << longest_message << " characters); wall " << wall << " s\n";
    if (control_messages) std::cout << control_messages << " messages hold control bytes, e.g. " << control_example << "\n";
    if (long_messages) std::cout << long_messages << " messages are longer than 1000 characters, e.g. " << long_example << "\n";
    fs::remove_all(file.parent_path());
}
