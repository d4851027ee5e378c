// Valid point clouds and their mutations, for the point-cloud reader's fuzz test (test_point_cloud_fuzz.cpp):
// seed clouds (1D, 2D, 3D; optional columns, comments, CRLF, quoted fields), byte- and token-level mutations
// (hostile numbers, header columns, rows) drawn from a seeded generator, and an input escaped for printing.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace pd_test::point_cloud_mutations {

// A valid cloud: nx x ny x nz lattice of spacing h; `extra` columns with their value per point.
struct Seed {
    std::string text;
    int dim;
};

inline std::string number(double v)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

inline std::vector<Seed> seeds()
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

inline const std::vector<std::string> bad_numbers{
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e308", "-1e308", "1e309", "-1e309", "-0", "0", "+0",
    "4.9e-324", "1e-320", "1e-400", "99999999999999999999", "9223372036854775807", "9223372036854775808",
    "-9223372036854775809", "9.3e18", "-9.3e18", "1e19", "", " ", "1e", "e5", ".", "-", "+", "+-1", "--1",
    "0x10", "1,5", "\"1\"", "\"1", "1\"", "1.5.5", "1e5e5", "１", "1\t", "\t1", "0.5", "2", "1", "-1",
    std::string(400, '9'), "0." + std::string(400, '0') + "1", "\"\"", "\"1,2\"", "#1", "1 2"};

inline const std::vector<std::string> bad_columns{"x",  "y",  "z",  "volume", "block", "vx",   "vy",  "vz",
                                           "ux", "fixed", "no_fail", "T0", "T_fixed", "vX", "t0", "",
                                           " ", "\"x\"", "x ", "volume\t", "\xEF\xBB\xBFx", "#x", "mass"};

inline const std::vector<std::string> inserts{",", "\"", "\n", "\r", "\r\n", "\t", " ", "#", std::string(1, '\0'),
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

inline std::string escaped(const std::string& s, std::size_t limit = 4000)
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

}  // namespace pd_test::point_cloud_mutations
