// problems/3d/heat_stability_atlas.cpp -- where the heat integrators break, model by model, on stiff and
// extreme scenes, against the thermal step the project chooses (issue 22).
// Case: the free cube of stability_atlas_3d (default 6^3, dx = 1 mm, delta = 3.05 dx), adiabatic, 316L-like
// k = 16 W/(m K), rho c = 3.9e6 J/(m^3 K), random temperatures 300 +- 1 K, changed along one axis at a time:
// m = delta/dx, point jitter, broken pairs, a near-duplicate point, partial volumes, a conductivity and a
// heat-capacity contrast across the mid-plane x = L/2 (1 to 1e6), and for correspondence heat its
// suppression coefficient C_hg. Models: Agwai (bond-based, spec/000b sec. 3.3), correspondence heat with
// C_hg = 0 and 1 (sec. 3.4-3.5). Integrators: explicit Euler, implicit Euler, CVODE BDF (rtol = atol 1e-8).
// Per cell (problems/common/heat_stability_atlas.hpp), as factors of the project's estimate dt_G (the
// Gershgorin step of spec/000b eq. 3.20, pd_run's thermal step is 0.5 dt_G): explicit Euler's exact limit
// from the eigenvalues of the assembled operator (the reference), the measured largest stable step
// (bisection; a ladder 1 ... 1e4 for the implicit schemes), and the maximum-principle overshoot.
// Checked: measured = exact limit within --rel-tol + 2 % (explicit Euler); the default step stable, and the
// implicit schemes stable up to the ladder's top, in every cell whose operator has no growing mode;
// Agwai keeps the maximum principle at the default step (a convex combination: overshoot at round-off).
// Run: heat_stability_atlas_3d [--models agwai,...] [--integrators explicit,implicit,cvode] [--axes ...]
//      [--n 6] [--steps 600] [--quick] [--check] [--out DIR]
// Writes: stability.csv (one row per cell), runs.csv (every run), summary.csv, params.csv.
#include "problems/common/heat_stability_atlas.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"

#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using pd::atlas::HeatVariant;
constexpr double max_principle_roundoff = 1e-9;  // an overshoot of a convex combination: 300 K x 1e-16 / 2 K per step, x steps

const std::vector<HeatVariant> variants{{"agwai", "agwai"}, {"correspondence-heat", "correspondence", 0}, {"correspondence-heat-hg", "correspondence", 1}};

// The scene of one axis value: the base scene with that one field changed.
pd::atlas::HeatScene along(pd::atlas::HeatScene s, const std::string& axis, double value)
{
    if (axis == "k-contrast") s.k_contrast = value;
    else if (axis == "c-contrast") s.c_contrast = value;
    else pd::atlas::set_body_axis(s.geometry, axis, value);
    return s;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI), echoed and saved.
    pd::io::Case run("heat_stability_atlas_3d", "Largest stable thermal step per heat model and integrator on extreme scenes, against the step the project chooses.",
                     "reports/3d/heat_stability_atlas");
    pd::io::Options& opt = run.opt;
    pd::atlas::HeatScene base;
    opt.add_int("n", base.geometry.n, "points per edge of the cube (quick: 5)");
    opt.add("dx", base.geometry.dx, "lattice spacing", "m");
    opt.add("m", base.geometry.m, "horizon ratio delta/dx of the base scene");
    opt.add("k", base.k, "conductivity", "W/(m K)");
    opt.add("rho-c", base.rho_c, "volumetric heat capacity", "J/(m^3 K)");
    const int& steps = opt.add_int("steps", 600, "thermal steps of one explicit run and of the run at the default step (quick: 300)");
    const int& ladder_steps = opt.add_int("ladder-steps", 100, "thermal steps of one implicit or CVODE run (a growing mode shows within them)");
    const double& rel_tol = opt.add("rel-tol", 0.01, "bisection: bracket width relative to the limit");
    std::string all_models;
    std::vector<std::string> labels;
    for (const HeatVariant& v : variants) labels.push_back(v.label), all_models += (all_models.empty() ? "" : ",") + v.label;
    opt.add_string("models", all_models, "heat models (comma list; quick: agwai,correspondence-heat-hg)");
    opt.add_string("integrators", "explicit,implicit,cvode", "heat integrators (comma list; quick: explicit,implicit)");
    opt.add_string("axes", "m,jitter,damage,gap,partial,k-contrast,c-contrast,hourglass", "axes (comma list; quick: gap,k-contrast)");
    opt.add_string("m-values", "1.5,2,3.05,4,5", "horizon ratios of the m axis");
    opt.add_string("jitter-values", "0,0.2,0.4", "jitter of the jitter axis, fraction of dx");
    opt.add_string("damage-values", "0,0.3,0.6,0.9", "fractions of broken pairs of the damage axis");
    opt.add_string("gap-values", "0.3,0.1,0.01", "near-duplicate distances of the gap axis, fraction of dx (quick: 0.01)");
    opt.add_string("partial-values", "0,1", "partial volumes off (0) and on (1)");
    opt.add_string("k-contrast-values", "1,1e2,1e4,1e6", "conductivity ratios across the mid-plane (quick: 1e6)");
    opt.add_string("c-contrast-values", "1e-6,1e-3,1e3,1e6", "heat-capacity ratios across the mid-plane");
    opt.add_string("hourglass-values", "0,0.1,1,10,100", "suppression coefficients C_hg of the hourglass axis (correspondence heat only)");
    opt.add_string("ladder", "1,10,100,1000,10000", "step factors of the implicit schemes");
    for (const char* o : {"dx", "k", "rho-c", "rel-tol"}) opt.require_positive(o);
    opt.require_at_least("n", 3);
    opt.require_at_least("m", 1);
    opt.require_at_least("steps", 10);
    opt.require_at_least("ladder-steps", 10);
    run.parse(argc, argv);
    run.quick_default("n", 5);
    run.quick_default("steps", 300);
    run.quick_default("models", std::string("agwai,correspondence-heat-hg"));
    run.quick_default("integrators", std::string("explicit,implicit"));
    run.quick_default("axes", std::string("gap,k-contrast"));
    run.quick_default("gap-values", std::string("0.01"));
    run.quick_default("k-contrast-values", std::string("1e6"));
    base.geometry.n = opt.get_int("n"), base.geometry.dx = opt.get("dx"), base.geometry.m = opt.get("m");
    base.k = opt.get("k"), base.rho_c = opt.get("rho-c");
    const std::vector<std::string> models = pd::io::list_choices(opt, "models", labels);
    const std::vector<std::string> integrators = pd::io::list_choices(opt, "integrators", {"explicit", "implicit", "cvode"});
    const std::vector<std::string> all_axes{"m", "jitter", "damage", "gap", "partial", "k-contrast", "c-contrast", "hourglass"};
    const std::vector<std::string> axes = pd::io::list_choices(opt, "axes", all_axes);
    std::map<std::string, std::vector<double>> values;  // every list checked, chosen or not
    for (const std::string& a : all_axes) values[a] = pd::io::list_option(opt, a + "-values", pd::io::ListValues::non_negative);
    const std::vector<double> ladder = pd::io::list_option(opt, "ladder", pd::io::ListValues::positive);
    pd::atlas::check_body_axes(opt, values);
    for (const char* a : {"k-contrast", "c-contrast"})
        for (double r : values[a]) if (!(r > 0)) opt.fail(std::string("option --") + a + "-values: ratios must be positive");
    run.start();

    // 2.-5. Every model and integrator along every axis: one cell each (header).
    pd::io::CsvWriter csv(run.file("stability.csv"),
                          {"model", "integrator", "axis", "value", "nodes", "bonds", "broken", "dt_est_s", "factor_default", "factor_linear",
                           "factor_stable", "bracketed", "margin", "growing_modes", "complexity", "overshoot_default", "overshoot_stable", "runs",
                           "wall_s"});
    pd::io::CsvWriter runs(run.file("runs.csv"), {"model", "integrator", "axis", "value", "dt_factor", "stable", "range_growth", "unstable_step"});
    std::printf("%-23s %-8s %-10s %7s %8s %8s %3s %9s %9s %6s\n", "model", "scheme", "axis", "value", "stable", "linear", "grw", "over_def",
                "over_max", "wall_s");
    int cells = 0, growing = 0, off_linear = 0, unsafe_default = 0, implicit_unstable = 0;
    double worst_linear = 0, agwai_overshoot = 0, min_linear = NAN, max_linear = NAN;
    for (const HeatVariant& v : variants) {
        if (std::find(models.begin(), models.end(), v.label) == models.end()) continue;
        for (const std::string& scheme : integrators)
            for (const std::string& axis : axes)
                for (double value : values[axis]) {
                    HeatVariant w = v;
                    if (axis == "hourglass") {
                        if (v.model != "correspondence") continue;
                        w.C_hg = value;
                    }
                    const pd::HeatIntegrator integrator = pd::parse_heat_integrator(scheme);
                    const pd::atlas::HeatCell c = pd::atlas::heat_cell(w, along(base, axis, value), integrator, steps, ladder_steps,
                                                                              rel_tol, ladder);
                    const double stable = c.stable.threshold;
                    csv.row({v.label, scheme, axis, value, c.nodes, c.bonds, c.broken, c.dt_est, 0.5, c.linear, stable, int(c.bracketed),
                             stable / 0.5, c.growing, c.complexity, c.overshoot_default, c.overshoot, long(c.stable.points.size()), c.wall_s});
                    for (const auto& p : c.stable.points)
                        runs.row({v.label, scheme, axis, value, p.dt_factor, int(p.stable), p.energy_growth, p.unstable_step});
                    std::printf("%-23s %-8s %-10s %7.3g %8.4g %8.4f %3d %9.2e %9.2e %6.2f\n", v.label.c_str(), scheme.c_str(), axis.c_str(), value,
                                stable, c.linear, c.growing, c.overshoot_default, c.overshoot, c.wall_s);
                    std::fflush(stdout);
                    ++cells;
                    if (c.growing > 0) {  // unstable at every step: the operator, not the integrator
                        ++growing;
                        continue;
                    }
                    if (v.model == "agwai") agwai_overshoot = std::max(agwai_overshoot, c.overshoot_default);
                    if (integrator != pd::HeatIntegrator::explicit_euler) {
                        implicit_unstable += c.bracketed;
                        continue;
                    }
                    unsafe_default += !(stable > 0.5);
                    min_linear = std::fmin(min_linear, c.linear), max_linear = std::fmax(max_linear, c.linear);  // fmin: NaN until the first
                    const double e = std::abs(stable / c.linear - 1);
                    worst_linear = std::max(worst_linear, e);
                    off_linear += !(e <= rel_tol + 0.02);
                }
    }
    csv.close();
    runs.close();

    // 6. Checks, summary, verdict.
    run.check(off_linear == 0, "explicit Euler: measured limit = exact limit of the assembled operator within rel-tol + 2 %");
    run.property(agwai_overshoot <= max_principle_roundoff, "Agwai keeps the maximum principle at the default step (overshoot at round-off)");
    run.property(unsafe_default == 0, "explicit Euler: the default step (0.5 dt_G) is stable in every cell without a growing mode");
    run.property(implicit_unstable == 0, "implicit Euler and CVODE: stable up to the ladder's top in every cell without a growing mode");
    run.summary_observed({{"cells", double(cells), NAN, NAN, "-"},
                          {"cells_growing_mode", double(growing), NAN, NAN, "-"},
                          {"cells_default_unstable", double(unsafe_default), 0, NAN, "-"},
                          {"cells_implicit_unstable", double(implicit_unstable), 0, NAN, "-"},
                          {"worst_measured_vs_linear", worst_linear, 0, NAN, "-"},
                          {"min_factor_linear", min_linear, NAN, NAN, "-"},
                          {"max_factor_linear", max_linear, NAN, NAN, "-"},
                          {"agwai_overshoot_default", agwai_overshoot, 0, NAN, "-"}});
    return run.finish("%d cells (%d with a growing mode): explicit limit / dt_G %.3g..%.3g, measured vs exact within %.2g %%; default unstable in %d, "
                      "implicit schemes in %d", cells, growing, min_linear, max_linear, 100 * worst_linear, unsafe_default, implicit_unstable);
}

int main(int argc, char** argv) { return pd::io::guarded_main("heat_stability_atlas_3d", [&] { return run_case(argc, argv); }); }
