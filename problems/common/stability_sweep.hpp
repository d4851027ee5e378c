// problems/common/stability_sweep.hpp -- empirical stability limit of an explicit run: a sweep over time-step
// factors (dt = factor * dt_crit), then a search for the threshold factor, stability.csv and an
// aligned print.
//
// The driver supplies run(factor) -> StabilityPoint (one short run, e.g. with pd::Explicit catching
// pd::Unstable). Threshold search: the lowest unstable factor of the sweep, or, when every sweep
// factor is stable, the factor doubled until a run is unstable (at most max_factor); when every
// sweep factor is unstable, the factor halved until a run is stable (at least min_factor; default
// 0: no search downwards); then bisection between the highest stable and the lowest unstable factor
// until the bracket is below rel_tol of it. The threshold is the bracket midpoint (NaN if nothing up
// to max_factor is unstable, or nothing down to min_factor is stable). This assumes one threshold
// (stable below, unstable above), as von Neumann analysis predicts for velocity Verlet on a linear system.
//
//     auto result = pd::io::stability_sweep({0.5, 0.7, 0.9, 1.1, 1.3}, run, 8.0, 0.005);
//     pd::io::print_stability(std::cout, "lps", result.points);
//     pd::io::write_stability_csv(out / "stability.csv", {{"lps", result}});
#pragma once

#include "pd/io/csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace pd::io {

struct StabilityPoint {
    double dt_factor = 0;       // dt / dt_crit [-]
    double dt_s = 0;            // time step [s]
    double dt_crit_s = 0;       // critical-step estimate the factor refers to [s]
    double energy_growth = 0;   // max mechanical energy over the run / initial [-]
    bool stable = true;         // no instability detected within the run
    long unstable_step = -1;    // step at which the guard fired (-1 if stable)
    std::string kind = "sweep";  // "sweep" or "search" (threshold search)
};

struct StabilityResult {
    std::vector<StabilityPoint> points;  // in the order run
    double threshold = std::numeric_limits<double>::quiet_NaN();  // limit factor [-] (see header)
};

inline StabilityResult stability_sweep(const std::vector<double>& factors,
                                       const std::function<StabilityPoint(double)>& run,
                                       double max_factor, double rel_tol, double min_factor = 0)
{
    StabilityResult r;
    double lo = 0, hi = std::numeric_limits<double>::infinity();  // highest stable, lowest unstable
    auto record = [&](double f, const char* kind) {
        r.points.push_back(run(f));
        r.points.back().kind = kind;
        if (r.points.back().stable) lo = std::max(lo, f);
        else hi = std::min(hi, f);
    };
    for (double f : factors) record(f, "sweep");
    while (!std::isfinite(hi) && lo > 0 && 2 * lo <= max_factor) record(2 * lo, "search");
    while (lo == 0 && std::isfinite(hi) && min_factor > 0 && hi / 2 >= min_factor) record(hi / 2, "search");
    if (!std::isfinite(hi) || lo == 0 || lo > hi) return r;
    while (hi - lo > rel_tol * hi) record(0.5 * (lo + hi), "search");
    r.threshold = 0.5 * (lo + hi);
    return r;
}

// For a scheme meant to be stable at any step (implicit Euler, CVODE, Newmark): the factors run in
// order until one is unstable. The threshold is the largest factor stable with every smaller one, a
// lower bound of the limit (nothing is bracketed unless a run failed: `bracketed`).
inline StabilityResult stability_ladder(const std::vector<double>& factors, const std::function<StabilityPoint(double)>& run,
                                        bool& bracketed)
{
    StabilityResult r;
    r.threshold = 0;
    bracketed = false;
    for (double f : factors) {
        r.points.push_back(run(f));
        r.points.back().kind = "ladder";
        if (!r.points.back().stable) {
            bracketed = true;
            break;
        }
        r.threshold = f;
    }
    return r;
}

// Aligned table of the points, one per line, with a label column.
inline void print_stability(std::ostream& os, const std::string& label, const std::vector<StabilityPoint>& pts)
{
    char line[200];
    std::snprintf(line, sizeof line, "%-8s %-6s %9s %11s %11s %13s %6s %8s\n", "label", "kind", "dt_factor", "dt_s",
                  "dt_crit_s", "energy_growth", "stable", "step");
    os << line;
    for (const auto& p : pts) {
        std::snprintf(line, sizeof line, "%-8s %-6s %9.4f %11.4e %11.4e %13.4g %6s %8ld\n", label.c_str(),
                      p.kind.c_str(), p.dt_factor, p.dt_s, p.dt_crit_s, p.energy_growth, p.stable ? "yes" : "no",
                      p.unstable_step);
        os << line;
    }
}

// stability.csv: label,kind,dt_factor,dt_s,dt_crit_s,energy_growth,stable,unstable_step.
inline void write_stability_csv(const std::filesystem::path& path,
                                const std::vector<std::pair<std::string, StabilityResult>>& results)
{
    CsvWriter csv(path, {"label", "kind", "dt_factor", "dt_s", "dt_crit_s", "energy_growth", "stable", "unstable_step"});
    for (const auto& [label, res] : results)
        for (const auto& p : res.points)
            csv.row({label, p.kind, p.dt_factor, p.dt_s, p.dt_crit_s, p.energy_growth, int(p.stable), p.unstable_step});
}

}  // namespace pd::io
