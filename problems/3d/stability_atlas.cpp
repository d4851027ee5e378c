// problems/3d/stability_atlas.cpp -- where velocity Verlet breaks, model by model, on stiff and extreme
// scenes, against the step the project chooses (issue 22).
// Case: a free n^3 cloud (default 6^3, dx = 1 mm, delta = 3.05 dx, steel E = 200 GPa, nu = 0.3,
// rho = 7800 kg/m^3), random velocities of 1e-3 sqrt(E/rho), changed along one axis at a time: m = delta/dx,
// point jitter, Poisson's ratio, the fraction of pairs broken, a near-duplicate point, partial volumes,
// the velocity amplitude (strains up to 10 %); for correspondence also the hourglass coefficient C_hg.
// Models: PMB, LPS, LPS-SCF, PALS, correspondence (C_hg 0 and 0.02, linear and Flanagan-Taylor law),
// standard linear solids (LPS, correspondence). Integrators: velocity Verlet, and Newmark (average
// acceleration) for the models with a positional force. Source: spec/000a sec. 3.3.2 (critical steps, eq. 3.14).
// Per cell (problems/common/stability_atlas.hpp), as factors of the Silling-Askari step dt_SA with the
// PMB spring: the measured largest stable step (bisection of short runs), von Neumann's 2/omega_max
// of the assembled stiffness (the reference of the measurement), the Gershgorin bound of the model's
// stiffness, 2/omega_max by power iteration, and the project's default step (pd::explicit_step:
// 0.5 x the smaller of dt_SA and the power-iteration step).
// Checked: measured = 2/omega_max within --rel-tol + 2 % (linear regime, symmetric stiffness); the Gershgorin step and the
// default step stable in every cell whose linearised body has no unstable (negative-stiffness) mode; Newmark's
// energy never past the guard on those bodies where the stiffness is symmetric and the motion small (its ladder
// stops where Newton fails: recorded, not a check).
// Run: stability_atlas_3d [--models pmb,lps,...] [--integrators verlet,newmark] [--axes m,jitter,nu,damage,gap,partial] [--n 6]
//      [--steps 600] [--quick] [--check] [--out DIR]
// Writes: stability.csv (one row per cell), runs.csv (every run of the bisection), summary.csv, params.csv.
#include "problems/common/stability_atlas.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"

#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace {

using pd::atlas::Variant;
using Kind = pd::Dissipation::Kind;
// The von Neumann check needs a symmetric stiffness: Littlewood's hourglass force is no gradient
// (asymmetry 4e-3 at C_hg = 0.02, 3e-2 at 0.2 on the base scene, column asymmetry of stability.csv).
constexpr double max_asymmetry = 1e-2;

// The models of the atlas, by label.
std::vector<Variant> variants(const pd::Elastic& mat)
{
    const pd::Dissipation sls{.kind = Kind::viscoelastic, .gamma_b = 1};
    return {{"pmb", {.name = "pmb", .material = mat}},
            {"lps", {.name = "lps", .material = mat}},
            {"lps-scf", {.name = "lps-scf", .material = mat}},
            {"pals", {.name = "pals", .material = mat}},
            {"correspondence", {.name = "correspondence", .material = mat}},
            {"correspondence-hg", {.name = "correspondence", .material = mat, .C_hg = 0.02}},
            {"correspondence-ft-hg", {.name = "correspondence", .material = mat, .C_hg = 0.02, .hypoelastic = true}},
            {"sls-lps", {.name = "lps", .material = mat}, sls},
            {"sls-correspondence-hg", {.name = "correspondence", .material = mat, .C_hg = 0.02, .hypoelastic = true}, sls}};
}

// The scene of one axis value: the base scene with that one field changed.
pd::atlas::Scene along(pd::atlas::Scene s, const std::string& axis, double value)
{
    if (axis == "strain") s.strain = value;
    else if (axis == "nu") s.nu = value;
    else pd::atlas::set_body_axis(s, axis, value);
    return s;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI), echoed and saved.
    pd::io::Case run("stability_atlas_3d", "Largest stable velocity-Verlet step per model on extreme scenes, against the step the project chooses.",
                     "reports/3d/stability_atlas");
    pd::io::Options& opt = run.opt;
    pd::atlas::Scene base;
    opt.add_int("n", base.n, "points per edge of the cube (quick: 5)");
    opt.add("dx", base.dx, "lattice spacing", "m");
    opt.add("m", base.m, "horizon ratio delta/dx of the base scene");
    opt.add("E", base.E, "Young's modulus", "Pa");
    opt.add("nu", base.nu, "Poisson's ratio of the base scene");
    opt.add("rho", base.rho, "density", "kg/m^3");
    const int& steps = opt.add_int("steps", 600, "steps of one run of the bisection (quick: 300)");
    opt.add("strain", base.strain, "amplitude of the random initial velocities over the bar wave speed sqrt(E/rho)");
    const double& rel_tol = opt.add("rel-tol", 0.01, "bisection: bracket width relative to the limit");
    std::vector<std::string> labels;
    for (const Variant& v : variants({})) labels.push_back(v.label);
    std::string all_models;
    for (const auto& l : labels) all_models += (all_models.empty() ? "" : ",") + l;
    opt.add_string("models", all_models, "models (comma list; quick: pmb,lps-scf,pals,correspondence-hg)");
    opt.add_string("axes", "m,jitter,nu,damage,gap,partial,strain,hourglass", "axes (comma list; quick: jitter,damage)");
    opt.add_string("integrators", "verlet", "integrators (comma list: verlet, newmark)");
    opt.add_string("newmark-ladder", "1,3,10,30,100,300,1000", "step factors (of dt_SA) tried with Newmark, in order");
    opt.add_string("m-values", "1.5,2,3.05,4,5", "horizon ratios of the m axis");
    opt.add_string("jitter-values", "0,0.1,0.2,0.3,0.4", "jitter of the jitter axis, fraction of dx (quick: 0.3)");
    opt.add_string("nu-values", "0.25,0.4,0.45,0.49,0.499", "Poisson's ratios of the nu axis");
    opt.add_string("damage-values", "0,0.3,0.6,0.9", "fractions of broken pairs of the damage axis (quick: 0.9)");
    opt.add_string("gap-values", "0.3,0.1,0.03,0.01", "near-duplicate distances of the gap axis, fraction of dx");
    opt.add_string("partial-values", "0,1", "partial volumes off (0) and on (1)");
    opt.add_string("strain-values", "0.001,0.01,0.03,0.1", "velocity amplitudes of the strain axis, over sqrt(E/rho)");
    opt.add_string("hourglass-values", "0,0.02,0.2,1,2", "Littlewood coefficients C_hg of the hourglass axis (correspondence models only)");
    for (const char* o : {"dx", "E", "rho", "strain", "rel-tol"}) opt.require_positive(o);
    opt.require_at_least("n", 3);
    opt.require_at_least("m", 1);
    opt.require_at_least("steps", 10);
    run.parse(argc, argv);
    run.quick_default("n", 5);
    run.quick_default("steps", 300);
    run.quick_default("models", std::string("pmb,lps-scf,pals,correspondence-hg"));
    run.quick_default("axes", std::string("jitter,damage"));
    run.quick_default("jitter-values", std::string("0.3"));
    run.quick_default("damage-values", std::string("0.9"));
    base.n = opt.get_int("n"), base.dx = opt.get("dx"), base.m = opt.get("m");
    base.E = opt.get("E"), base.nu = opt.get("nu"), base.rho = opt.get("rho"), base.strain = opt.get("strain");
    if (const std::string msg = pd::validate_elastic(base.E, base.nu, 3, pd::Plane::strain); !msg.empty()) opt.fail(msg);
    const std::vector<std::string> models = pd::io::list_choices(opt, "models", labels);
    const std::vector<std::string> all_axes{"m", "jitter", "nu", "damage", "gap", "partial", "strain", "hourglass"};
    const std::vector<std::string> axes = pd::io::list_choices(opt, "axes", all_axes);
    const std::vector<std::string> integrators = pd::io::list_choices(opt, "integrators", {"verlet", "newmark"});
    const std::vector<double> ladder = pd::io::list_option(opt, "newmark-ladder", pd::io::ListValues::positive);
    std::map<std::string, std::vector<double>> values;  // every list checked, chosen or not
    for (const std::string& a : all_axes) values[a] = pd::io::list_option(opt, a + "-values", pd::io::ListValues::non_negative);
    pd::atlas::check_body_axes(opt, values);
    for (double nu : values["nu"]) if (!(nu < 0.5)) opt.fail("option --nu-values: every ratio must be below 0.5");
    for (double e : values["strain"]) if (!(e > 0 && e <= 1)) opt.fail("option --strain-values: in (0, 1]");
    run.start();

    // 2.-5. Every model along every axis: one cell each (bodies, bonds, models and runs in the header).
    pd::io::CsvWriter csv(run.file("stability.csv"),
                          {"model", "integrator", "axis", "value", "nodes", "bonds", "broken", "dt_sa_s", "factor_default", "factor_bound",
                           "factor_mode", "factor_linear", "factor_stable", "margin", "negative_modes", "growth_rate_1_s", "asymmetry", "runs",
                           "wall_s"});
    pd::io::CsvWriter runs(run.file("runs.csv"), {"model", "integrator", "axis", "value", "dt_factor", "stable", "energy_growth", "unstable_step"});
    std::printf("%-22s %-7s %-9s %6s %8s %8s %8s %8s %8s %4s %6s\n", "model", "scheme", "axis", "value", "stable", "linear", "mode", "bound", "default",
                "neg", "wall_s");
    int unsafe_default = 0, unsafe_bound = 0, off_linear = 0, cells = 0, unstable_bodies = 0, newmark_energy = 0, newmark_newton = 0;
    double worst_linear = 0;
    for (const Variant& v : variants(pd::Elastic::from_E_nu(base.E, base.nu))) {
        if (std::find(models.begin(), models.end(), v.label) == models.end()) continue;
        for (const std::string& scheme : integrators) {
            for (const std::string& axis : axes)
                for (double value : values[axis]) {
                    Variant w = v;
                    if (axis == "hourglass") {
                        if (v.choice.name != "correspondence") continue;
                        w.choice.C_hg = value;
                    }
                    const pd::atlas::Integrator integrator = scheme == "newmark" ? pd::atlas::Integrator::newmark : pd::atlas::Integrator::verlet;
                    const pd::atlas::Scene s = along(base, axis, value);
                    const pd::atlas::Cell c = pd::atlas::cell(w, s, steps, rel_tol, true, integrator, ladder);
                    if (c.stable.points.empty()) continue;  // a model Newmark does not integrate (header)
                    const double stable = c.stable.threshold, chosen = c.chosen / c.dt_sa;
                    csv.row({v.label, scheme, axis, value, c.nodes, c.bonds, c.broken, c.dt_sa, chosen, c.bound, c.mode, c.linear, stable,
                             stable / chosen, c.negative, c.growth, c.asymmetry, long(c.stable.points.size()), c.wall_s});
                    for (const auto& p : c.stable.points)
                        runs.row({v.label, scheme, axis, value, p.dt_factor, int(p.stable), p.energy_growth, p.unstable_step});
                    std::printf("%-22s %-7s %-9s %6.3g %8.4f %8.4f %8.4f %8.4f %8.4f %4d %6.2f\n", v.label.c_str(), scheme.c_str(), axis.c_str(), value,
                                stable, c.linear, c.mode, c.bound, chosen, c.negative, c.wall_s);
                    std::fflush(stdout);
                    ++cells;
                    if (c.negative > 0) {  // unstable at every step: the model, not the integrator (header)
                        ++unstable_bodies;
                        continue;
                    }
                    if (integrator == pd::atlas::Integrator::newmark) {  // energy-stable on a linear body; Newton may fail (header)
                        const auto& last = c.stable.points.back();
                        newmark_newton += !last.stable && last.unstable_step == pd::atlas::newton_failed;
                        newmark_energy += !last.stable && last.unstable_step != pd::atlas::newton_failed && axis != "strain" &&
                                          c.asymmetry < max_asymmetry;
                        continue;
                    }
                    unsafe_default += !(chosen < stable);
                    unsafe_bound += !(c.bound <= stable * (1 + rel_tol));
                    if (!std::isnan(c.linear) && axis != "strain" && c.asymmetry < max_asymmetry) {  // von Neumann: linear, symmetric
                        const double e = std::abs(stable / c.linear - 1);
                        worst_linear = std::max(worst_linear, e);
                        off_linear += !(e <= rel_tol + 0.02);
                    }
                }
        }
    }
    csv.close();
    runs.close();

    // 6. Checks, summary, verdict.
    run.check(off_linear == 0, "measured limit = 2/omega_max of the assembled stiffness within rel-tol + 2 % (von Neumann)");
    run.property(unsafe_bound == 0, "the Gershgorin step is stable in every cell with a stable linearised body");
    run.property(unsafe_default == 0, "the default step is stable in every cell with a stable linearised body");
    run.property(newmark_energy == 0, "Newmark: no energy growth past the guard on a stable body in the small-motion regime");
    run.summary_observed({{"cells", double(cells), NAN, NAN, "-"},
                          {"cells_unstable_body", double(unstable_bodies), NAN, NAN, "-"},
                          {"cells_default_unstable", double(unsafe_default), 0, NAN, "-"},
                          {"cells_bound_unstable", double(unsafe_bound), 0, NAN, "-"},
                          {"worst_measured_vs_linear", worst_linear, 0, NAN, "-"},
                          {"cells_newmark_energy_growth", double(newmark_energy), 0, NAN, "-"},
                          {"cells_newmark_newton_failed", double(newmark_newton), NAN, NAN, "-"}});
    return run.finish("%d cells (%d with an unstable linearised body): default step unstable in %d, Gershgorin step in %d; "
                      "measured vs 2/omega_max within %.2g %%", cells, unstable_bodies, unsafe_default, unsafe_bound, 100 * worst_linear);
}

int main(int argc, char** argv) { return pd::io::guarded_main("stability_atlas_3d", [&] { return run_case(argc, argv); }); }
