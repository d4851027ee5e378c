// pd/io/checks.hpp -- the `--check` list of a problem driver: one printed line per documented
// tolerance ("check: <what> ok|FAILED") and the overall verdict. Each check has a kind:
//   accuracy          against an independent reference (closed form, classical or SUNDIALS solution,
//                     published value, another code), with a tolerance argued from the numerics;
//   property          a qualitative property or invariant (stable, the crack runs, a trend, a
//                     conservation law, a solver converged);
//   regression_bound  a bound taken from this code's own earlier output, with no independent
//                     justification: it catches a change, it does not show accuracy. It is printed and
//                     recorded as such, reported apart from the others (reports/README.md), and never
//                     earns a ledger status.
//
//     pd::io::Checks check;
//     check(rate > 0.9 && rate < 1.1, "first-order convergence");
//     check(err < 0.541, "E rel_error below the recorded 0.49 + 10 %", pd::io::CheckKind::regression_bound);
//     return opt.get_flag("check") && !check.passed() ? 1 : 0;
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace pd::io {

enum class CheckKind { accuracy, property, regression_bound };

inline const char* kind_name(CheckKind k)
{
    return k == CheckKind::accuracy ? "accuracy" : k == CheckKind::property ? "property" : "regression_bound";
}

struct CheckRecord {
    std::string what;
    CheckKind kind = CheckKind::accuracy;
    bool ok = false;
};

class Checks {
public:
    void operator()(bool ok, const std::string& what, CheckKind kind = CheckKind::accuracy)
    {
        const std::string label = kind == CheckKind::regression_bound ? "check (regression bound): " : "check: ";
        std::printf("%s%-*s %s\n", label.c_str(), static_cast<int>(79 - label.size()), what.c_str(), ok ? "ok" : "FAILED");
        list_.push_back({what, kind, ok});
    }
    bool passed() const
    {
        return std::all_of(list_.begin(), list_.end(), [](const CheckRecord& c) { return c.ok; });
    }
    // Every check so far, in order. Case::finish writes them to checks.csv.
    const std::vector<CheckRecord>& list() const { return list_; }

private:
    std::vector<CheckRecord> list_;
};

}  // namespace pd::io
