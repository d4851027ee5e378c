// pd/io/checks.hpp -- the `--check` list of a problem driver: one printed line per documented
// tolerance ("check: <what> ok|FAILED") and the overall verdict.
//
//     pd::io::Checks check;
//     check(rate > 0.9 && rate < 1.1, "first-order convergence");
//     return opt.get_flag("check") && !check.passed() ? 1 : 0;
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace pd::io {

class Checks {
public:
    void operator()(bool ok, const std::string& what)
    {
        std::printf("check: %-72s %s\n", what.c_str(), ok ? "ok" : "FAILED");
        list_.emplace_back(what, ok);
    }
    bool passed() const
    {
        return std::all_of(list_.begin(), list_.end(), [](const auto& c) { return c.second; });
    }
    // Every check so far, in order: (what, ok). Case::finish writes them to checks.csv.
    const std::vector<std::pair<std::string, bool>>& list() const { return list_; }

private:
    std::vector<std::pair<std::string, bool>> list_;
};

}  // namespace pd::io
