// Error against run time for the adaptive-refinement drivers (spec/002 sec. 11, issue "the point of
// the thesis"): every run of a case (uniform grids and the adaptive one) with its nodes, wall time and
// quantities of interest, each against one reference (the published value the fine grid should give),
// in work_precision.csv; and the summary rows every adaptive driver reports: nodes_final,
// wall_adaptive, wall_adaptive_updates (refinement, bonds, transfer: apart from stepping),
// wall_uniform_fine and speedup_vs_uniform_fine, with the uniform fine run's quantities beside the
// adaptive run's.
#pragma once
#include "pd/io/case.hpp"
#include "pd/io/csv.hpp"
#include "pd/time/adaptive_refinement.hpp"

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace pd::crack {

struct WorkPoint {
    std::string run;               // "uniform" or "adaptive"
    double dx = 0;                 // spacing (adaptive: the coarse one) [m]
    double nodes = 0;              // final node count
    double wall = 0;               // [s]
    std::vector<double> values;    // the quantities of interest, in the order of the names
};

struct Quantity {
    std::string stem, suffix;      // name stem and unit suffix: t_branch + s -> t_branch_s, t_branch_adaptive_s
    std::string unit;              // SI unit of the summary (s, m/s)
    double reference;              // published value for the fine grid (nan: none)
    double published_adaptive;     // published value of the adaptive run (nan: none)
    std::string name(const std::string& run = "") const { return stem + (run.empty() ? "" : "_" + run) + "_" + suffix; }
};

// work_precision.csv: run, dx_m, nodes, wall_s, then <name> and <name>_error per quantity.
inline void write_work_precision(const std::filesystem::path& path, const std::vector<Quantity>& q, const std::vector<WorkPoint>& runs)
{
    std::vector<std::string> cols{"run", "dx_m", "nodes", "wall_s"};
    for (const Quantity& x : q) cols.push_back(x.name()), cols.push_back(x.name() + "_error");
    io::CsvWriter csv(path, cols);
    for (const WorkPoint& r : runs) {
        std::vector<io::CsvCell> cells{r.run, r.dx, r.nodes, r.wall};
        for (std::size_t k = 0; k < q.size(); ++k) cells.push_back(r.values[k]), cells.push_back(io::relative_error(r.values[k], q[k].reference));
        csv.row(cells);
    }
}

// The summary rows (header): the adaptive run's quantities against the published adaptive values,
// the uniform fine run's against the published fine values (fine: nullptr when it was not run), and
// the costs. published_nodes / published_speedup: the source's (nan: none).
inline std::vector<io::SummaryRow> adaptive_rows(const std::vector<Quantity>& q, const WorkPoint& adaptive, const WorkPoint* fine,
                                                 const AdaptiveStats& st, double published_nodes, double published_speedup)
{
    using io::relative_error;
    const double nan = std::nan("");
    std::vector<io::SummaryRow> rows{{"nodes_final", adaptive.nodes, published_nodes, relative_error(adaptive.nodes, published_nodes), "-"}};
    for (std::size_t k = 0; k < q.size(); ++k) {
        rows.push_back({q[k].name("adaptive"), adaptive.values[k], q[k].published_adaptive, relative_error(adaptive.values[k], q[k].published_adaptive),
                        q[k].unit});
        const double v = fine ? fine->values[k] : nan;
        rows.push_back({q[k].name("uniform_fine"), v, q[k].reference, relative_error(v, q[k].reference), q[k].unit});
    }
    const double wall_fine = fine ? fine->wall : nan;
    rows.push_back({"wall_adaptive", adaptive.wall, nan, nan, "s"});
    rows.push_back({"wall_adaptive_updates", st.wall_update, nan, nan, "s"});
    rows.push_back({"grid_updates", static_cast<double>(st.updates), nan, nan, "-"});
    rows.push_back({"wall_uniform_fine", wall_fine, nan, nan, "s"});
    rows.push_back({"speedup_vs_uniform_fine", wall_fine / adaptive.wall, published_speedup,
                    relative_error(wall_fine / adaptive.wall, published_speedup), "-"});
    return rows;
}

// Both for a case: work_precision.csv in the run's folder (the uniform runs, then the adaptive one) and
// the summary rows, the uniform fine run being the uniform run at dx_fine (the adaptive run's finest
// spacing), if any.
inline void report_work_precision(io::Case& run, const std::vector<Quantity>& q, std::vector<WorkPoint> uniform, const WorkPoint& adaptive,
                                  double dx_fine, const AdaptiveStats& st, double published_nodes, double published_speedup)
{
    std::size_t fine = uniform.size();
    for (std::size_t k = 0; k < uniform.size(); ++k)
        if (std::abs(uniform[k].dx - dx_fine) < 1e-9 * dx_fine) fine = k;
    run.summary_observed(adaptive_rows(q, adaptive, fine < uniform.size() ? &uniform[fine] : nullptr, st, published_nodes, published_speedup));
    uniform.push_back(adaptive);
    write_work_precision(run.file("work_precision.csv"), q, uniform);
}

// The options of an adaptive run, shared by the drivers: --adaptive, --levels, --t-start, --triggers,
// --energy-fraction, --energy-every, --zone-margin (time/adaptive_refinement.hpp), each with the case's default.
struct AdaptiveCli {
    bool& on;
    int& levels;
    double& t_start;
    std::string& triggers;
    double& energy_fraction;
    int& energy_every;
    double& zone_margin;

    AdaptiveCli(io::Options& opt, double t_start_default, const std::string& triggers_default, const std::string& source)
        : on(opt.add_flag("adaptive", "also run adaptive refinement from the first (coarse) grid (" + source + ")")),
          levels(opt.add_int("levels", 1, "adaptive: refinement levels")),
          t_start(opt.add("t-start", t_start_default, "adaptive: time the triggers start (" + source + ")", "s")),
          triggers(opt.add_string("triggers", triggers_default, "adaptive: triggers (" + source + ")", {"energy", "damage", "both"})),
          energy_fraction(opt.add("energy-fraction", 0.7, "adaptive: energy trigger W >= this x W_max")),
          energy_every(opt.add_int("energy-every", 1, "adaptive: steps between energy-trigger checks")),
          zone_margin(opt.add("zone-margin", 0, "adaptive: cells added to each refinement zone (ours; 0: the source's zone)"))
    {
        opt.require_at_least("zone-margin", 0);
        opt.require_at_least("levels", 1);
        opt.require_at_least("energy-every", 1);
        opt.require_range("energy-fraction", 0, 1, false, true);
    }
    // After parsing: an adaptive run has no checkpoints.
    void validate(io::Options& opt) const
    {
        if (on && (opt.get_int("checkpoint-every") > 0 || opt.get_flag("resume")))
            opt.fail("option --adaptive: the adaptive run has no checkpoints (drop --checkpoint-every / --resume)");
    }
    AdaptiveOptions options(Refinement rule, double interface_m, PartialVolume pv) const
    {
        return {.levels = levels, .rule = rule, .m_level = {}, .t_start = t_start, .energy_fraction = triggers == "damage" ? 0.0 : energy_fraction,
                .energy_every = energy_every, .damage_trigger = triggers != "energy", .interface_m = interface_m, .zone_margin = zone_margin, .partial_volume = pv};
    }
};

}  // namespace pd::crack
