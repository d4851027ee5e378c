// pd/io/checks.hpp -- the `--check` list of a problem driver: one printed line per documented
// tolerance ("check: <what> ok|FAILED") and the overall verdict.
//
//     pd::io::Checks check;
//     check(rate > 0.9 && rate < 1.1, "first-order convergence");
//     return opt.get_flag("check") && !check.passed() ? 1 : 0;
#pragma once

#include <cstdio>
#include <string>

namespace pd::io {

class Checks {
public:
    void operator()(bool ok, const std::string& what)
    {
        std::printf("check: %-72s %s\n", what.c_str(), ok ? "ok" : "FAILED");
        passed_ = passed_ && ok;
    }
    bool passed() const { return passed_; }

private:
    bool passed_ = true;
};

}  // namespace pd::io
