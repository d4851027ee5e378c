// pd/io/list_option.hpp -- comma-separated lists (numbers or named choices) given as one string option.
//
//     opt.add_string("sf", "0.5", "safety factors, comma-separated");
//     opt.parse(argc, argv);
//     const std::vector<double> sf = pd::io::list_option(opt, "sf", pd::io::ListValues::positive);
//
// Items are split at every ',' (no blanks allowed around them: "0.5,0.1"); each must parse as a
// finite double (pd::io::parse_double) within the requested bound and the magnitude range of real
// options (Options::min_magnitude .. max_magnitude). A malformed or out-of-bound
// item, or an empty list, ends the program with one line naming the option and status 2
// (Options::fail, the drivers' input-error contract).
#pragma once

#include "pd/io/csv.hpp"
#include "pd/io/options.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace pd::io {

enum class ListValues {
    positive,      // every item > 0 (lengths, safety factors)
    non_negative,  // every item >= 0 (coefficients that may be switched off)
};

// The items of string option `name`, in the order given.
inline std::vector<double> list_option(const Options& opt, const std::string& name, ListValues bound)
{
    std::vector<double> v;
    std::stringstream ss(opt.get_string(name));
    const bool positive = bound == ListValues::positive;
    for (std::string item; std::getline(ss, item, ',');) {
        double x = 0;
        const bool ok = parse_double(item, x) && std::isfinite(x) && (positive ? x > 0 : x >= 0);
        if (!ok) opt.fail("option --" + name + ": '" + item + "' is not a " + (positive ? "positive number" : "number >= 0"));
        if (const std::string bad = Options::magnitude_error(x); !bad.empty()) opt.fail("option --" + name + ": '" + item + "' " + bad);
        v.push_back(x);
    }
    if (v.empty()) opt.fail("option --" + name + ": empty list");
    return v;
}

// The items of string option `name`, each one of `allowed` (e.g. --runs none,stretch,micro);
// an unknown or empty item ends the program with one line and status 2.
inline std::vector<std::string> list_choices(const Options& opt, const std::string& name, const std::vector<std::string>& allowed)
{
    std::vector<std::string> v;
    std::stringstream ss(opt.get_string(name));
    for (std::string item; std::getline(ss, item, ',');) {
        bool known = false;
        for (const auto& a : allowed) known = known || item == a;
        if (!known) {
            std::string names;
            for (const auto& a : allowed) names += (names.empty() ? "" : "|") + a;
            opt.fail("option --" + name + ": unknown item '" + item + "' (one of " + names + ")");
        }
        v.push_back(item);
    }
    if (v.empty()) opt.fail("option --" + name + ": empty list");
    return v;
}

}  // namespace pd::io
