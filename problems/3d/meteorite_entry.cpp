// problems/3d/meteorite_entry.cpp -- a 1 cm basalt meteorite heated by its entry into the atmosphere
// (Biondani 2018 sec. 9.2; spec/000c sec. 4, Table 9.5, V16 and V17). The scene (sphere, loading shell,
// surrogate heat flux, conduction, mechanics) is problems/common/meteorite_scene.hpp.
// --study thermal (V16): conduction only, 10 s from 30 C under the constant flux; the maximum
//   temperatures of the shell, of the body's outer cell layer ("surface") and of the body, the centre
//   temperature, and the heat trapped in the shell as a fraction of the heat supplied (Figs. 9.22-9.26;
//   --shell-factor 0.1 for the thinner shell; the fraction is 1 at the first step, all heat enters
//   through the shell, and falls with time: reported at 1 s and at the end). The heat books close:
//   supplied = body + shell content.
// --study spall (V17): weakly coupled, k and flux x 1000 over 2 ms (= 2 s of the real problem), the
//   multirate clocks of time/multirate.hpp (conduction every N_sync(MK) mechanical steps, chosen by the
//   fork's rule), Flanagan-Taylor correspondence with numerical viscosity eta = 3 and critical stretch.
//   Damage below the front: the mean node damage (over body-body bonds) of the body nodes within --cone
//   of the stagnation direction, in bins of depth dx (damage_profile.csv), at the instant equivalent to
//   1 s (1 ms at x 1000, the source's Figs. 9.27/9.28) and at the end. Two depths from it: the spall
//   depth, the centre of the bin of largest damage, and the damaged depth, the lower edge of the
//   deepest bin with at least a tenth of that damage (resolution dx = delta/3.05: near delta the
//   candidates are 0.82 and 1.15 delta, or 0.98 and 1.31 delta). The source: a crack parallel to the
//   front at a depth of about delta, the detached layer about delta thick.
// Run: meteorite_entry_3d [--study thermal|spall] [--delta D] [--shell-factor 1] [--quick] [--check]
//   [--out DIR] (--help: all). Writes history.csv, summary.csv, params.csv (spall: damage_profile.csv).
#include "pd/core/timer.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/time/multirate.hpp"
#include "problems/common/meteorite_scene.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

// The value of column `y` at time t, linear between the two samples around it.
double at_time(const std::vector<double>& t, const std::vector<double>& y, double when)
{
    for (std::size_t q = 1; q < t.size(); ++q)
        if (t[q] >= when) return y[q - 1] + (y[q] - y[q - 1]) * (when - t[q - 1]) / (t[q] - t[q - 1]);
    return NAN;
}

// Node counts; the source's model sizes (sec. 9.2.3-9.2.5) for its grids, delta = 0.5 and 1 mm at m = 3.05
// with the shell of thickness dx.
void mesh_rows(pd::io::Case& run, const pd::MeteoriteScene& sc)
{
    const bool source_grid = sc.p.m == 3.05 && sc.p.shell_factor == 1;
    const double published = !source_grid ? NAN : sc.p.delta == 0.5e-3 ? 145592 : sc.p.delta == 1e-3 ? 21488 : NAN;
    const double n = double(sc.s.body.size());
    run.summary({{"nodes", n, published, pd::io::relative_error(n, published), "-"},
                 {"shell_nodes", double(sc.s.body.size() - sc.s.n_body), NAN, NAN, "-"}});
}

int thermal_study(pd::io::Case& run, pd::MeteoriteScene& sc, double t_end)
{
    const double dt_max = sc.thermal_step();
    const long steps = std::max(1L, static_cast<long>(std::ceil(t_end / dt_max)));
    sc.field->dt = t_end / double(steps);
    std::printf("%ld thermal steps of %.4g s (critical %.4g s)\n", steps, sc.field->dt, dt_max / sc.p.dt_factor_heat);
    pd::io::CsvWriter hist(run.file("history.csv"), {"t_s", "T_max_shell_C", "T_max_surface_C", "T_max_body_C", "T_centre_C", "Q_supplied_J",
                                                     "Q_shell_J", "Q_body_J", "trapped_fraction"});
    std::vector<double> t{0}, shell{sc.p.T0}, surface{sc.p.T0}, body{sc.p.T0}, trapped{0};
    double balance = 0;  // largest |content - supplied| / supplied
    pd::io::Timer timer;
    for (long n = 1; n <= steps; ++n) {
        sc.field->advance();
        const pd::MeteoriteScene::Temperatures T = sc.temperatures();
        const double supplied = sc.power * sc.field->t(), qs = sc.heat_content(true), qb = sc.heat_content(false);
        balance = std::max(balance, std::abs(qs + qb - supplied) / supplied);
        t.push_back(sc.field->t()), shell.push_back(T.shell_max), surface.push_back(T.surface_max), body.push_back(T.body_max);
        trapped.push_back(qs / supplied);
        hist.row({sc.field->t(), T.shell_max, T.surface_max, T.body_max, T.centre, supplied, qs, qb, qs / supplied});
    }
    const double wall = timer.seconds();
    const pd::MeteoriteScene::Temperatures T = sc.temperatures();
    double excess = -HUGE_VAL;
    for (std::size_t q = 1; q < t.size(); ++q) excess = std::max(excess, shell[q] - surface[q]);
    pd::io::CsvWriter axis(run.file("axis_profile.csv"), {"x_m", "T_C", "shell"});  // the flight axis at the end (Fig. 9.22's mid-plane)
    for (std::size_t i = 0; i < sc.s.body.size(); ++i)
        if (std::abs(sc.s.body.x.c[1][i]) < 0.5 * sc.s.dx && std::abs(sc.s.body.x.c[2][i]) < 0.5 * sc.s.dx)
            axis.row({sc.s.body.x.c[0][i], sc.field->theta[i], double(sc.s.in_shell(i))});
    // The digest's critical steps for the source's grids (spec/000c sec. 4.4, derived): 0.038 s, 0.154 s.
    const bool source_grid = sc.p.m == 3.05 && sc.p.scale == 1 && sc.p.shell_factor == 1;
    const double dt_published = !source_grid ? NAN : sc.p.delta == 0.5e-3 ? 0.038 : sc.p.delta == 1e-3 ? 0.154 : NAN;
    const double P_law = sc.p.scale * sc.p.q_stag * std::numbers::pi * sc.p.R * sc.p.R;  // the surrogate's total power (header)
    const bool law = sc.p.flux_table.empty();
    const bool thin = sc.p.shell_factor == 0.1;  // the source's 10x thinner shell: its own published values
    const double t1 = 1.0 / sc.p.scale, t2 = 2.0 / sc.p.scale;  // 1 s and 2 s of the real problem
    run.summary_observed({{"T_surface_max_end", T.surface_max, thin ? 1200.0 : 1100.0, NAN, "C"},
                          {"T_shell_max_end", T.shell_max, thin ? 2700.0 : 1200.0, NAN, "C"},
                          {"T_centre_end", T.centre, NAN, NAN, "C"},
                          {"shell_excess_max", excess, thin ? NAN : 100, NAN, "K"},
                          {"rise_max_2s", at_time(t, body, t2) - sc.p.T0, 400, NAN, "K"},
                          {"trapped_fraction_1s", at_time(t, trapped, t1), thin ? 0.1 : NAN, NAN, "-"},  // it falls with time
                          {"trapped_fraction_end", trapped.back(), NAN, NAN, "-"}});
    mesh_rows(run, sc);
    run.summary({{"heat_input", sc.power, law ? P_law : NAN, law ? pd::io::relative_error(sc.power, P_law) : NAN, "W"},
                 {"heat_balance_error", balance, NAN, NAN, "-"},
                 {"dt_thermal_critical", dt_max / sc.p.dt_factor_heat, dt_published, pd::io::relative_error(dt_max / sc.p.dt_factor_heat, dt_published), "s"},
                 {"dt_thermal", sc.field->dt, NAN, NAN, "s"},
                 {"thermal_steps", double(steps), NAN, NAN, "-"},
                 {"wall", wall, NAN, NAN, "s"}});
    if (law)  // the node sum of a law with a kink at 90 deg: 2.5e-3, 6.8e-4, 1.8e-4 at delta = 2, 1, 0.5 mm
        run.check(std::abs(sc.power - P_law) <= 1e-2 * P_law, "the heat input is the surrogate's Q_s pi R^2 to 1 % (node quadrature of the shell)");
    run.property(balance < 1e-9, "heat supplied = heat content of body and shell to 1e-9 (Agwai conserves heat)");
    run.property(T.shell_max > T.surface_max && T.surface_max > T.centre, "shell hotter than the surface, surface hotter than the centre");
    return run.finish("%zu nodes, %ld thermal steps: surface %.0f C, shell %.0f C, centre %.0f C, trapped %.3f", sc.s.body.size(), steps,
                      T.surface_max, T.shell_max, T.centre, trapped.back());
}

int spall_study(pd::io::Case& run, pd::MeteoriteScene& sc, double t_end, double eta, double C_hg, double dt_factor, double cone, int sample)
{
    pd::MeteoriteMechanics mech(sc, eta, C_hg);
    pd::MultirateSteps clocks;
    try {
        clocks = pd::multirate_steps(t_end, mech.stable_step(dt_factor), sc.thermal_step());
    } catch (const std::invalid_argument& e) {
        run.opt.fail(std::string("options --t-end, --dt-factor: ") + e.what());
    }
    pd::require_steps(double(clocks.mech_steps), "--t-end / dt");
    const double dt = clocks.dt_mech;
    sc.field->dt = clocks.dt_thermal;
    std::printf("%ld mechanical steps of %.4g us, conduction every %ld (%.4g us), s0 %.4g, tau_b %.3g us\n", clocks.mech_steps, dt * 1e6,
                clocks.nsync_mk, clocks.dt_thermal * 1e6, mech.rule.s0, mech.visco.tau_b * 1e6);
    pd::io::CsvWriter hist(run.file("history.csv"), {"t_s", "T_max_body_C", "T_max_shell_C", "broken_bonds", "damage_max", "spall_depth_m",
                                                     "damaged_depth_m"});
    pd::io::CsvWriter prof(run.file("damage_profile.csv"), {"t_s", "depth_m", "damage_mean"});
    const double t_fig = 1.0 / sc.p.scale;  // the instant equivalent to 1 s of the real problem (1 ms at x 1000); none beyond t_end
    double depth_fig = NAN, depth_end = NAN, layer_fig = NAN, layer_end = NAN, phi_max = 0;
    bool unstable = false, fig_written = false;
    auto depth_of = [&](const std::vector<double>& prof_b) {  // header; nan while no bond of the cone has broken
        const auto peak = std::max_element(prof_b.begin(), prof_b.end());
        return *peak > 0 ? (double(peak - prof_b.begin()) + 0.5) * sc.s.dx : NAN;
    };
    auto layer_of = [&](const std::vector<double>& prof_b) {  // header; nan while no bond of the cone has broken
        const double top = *std::max_element(prof_b.begin(), prof_b.end());
        double depth = NAN;
        for (std::size_t b = 0; b < prof_b.size() && top > 0; ++b) if (prof_b[b] >= 0.1 * top) depth = double(b + 1) * sc.s.dx;
        return depth;
    };
    pd::io::Timer timer;
    double wall_steps = 0;
    long steps_here = 0;
    auto state = [&](pd::StateArchive& ar) {
        mech.ex.state(ar), hist.state(ar), prof.state(ar), timer.state(ar, "wall");
        ar("depth_fig", depth_fig), ar("layer_fig", layer_fig), ar("fig_written", fig_written);
        mech.refresh(sc.field->theta);  // a loaded field: the expansion's temperatures follow it
    };
    try {
        run.checkpoints().loop(clocks.mech_steps, state, [&] { mech.ex.start(); }, [&](long n) {
            pd::io::Timer step_timer;
            mech.ex.step(dt);
            wall_steps += step_timer.seconds(), ++steps_here;
            const bool fig = !fig_written && mech.ex.t >= t_fig - 0.5 * dt;
            if (n % sample != 0 && n != clocks.mech_steps && !fig) return true;
            const std::vector<double> profile = mech.front_damage_profile(cone);
            const pd::MeteoriteScene::Temperatures T = sc.temperatures();
            phi_max = 0;
            for (std::size_t i = 0; i < sc.s.n_body; ++i) phi_max = std::max(phi_max, mech.body_damage(i));
            depth_end = depth_of(profile), layer_end = layer_of(profile);
            hist.row({mech.ex.t, T.body_max, T.shell_max, double(mech.ex.broken_bonds), phi_max, depth_end, layer_end});
            if (fig || n == clocks.mech_steps) {
                for (std::size_t b = 0; b < profile.size(); ++b) prof.row({mech.ex.t, (double(b) + 0.5) * sc.s.dx, profile[b]});
                if (fig) depth_fig = depth_end, layer_fig = layer_end, fig_written = true;
            }
            return true;
        });
    } catch (const pd::Unstable& e) {
        std::printf("%s\n", e.what());
        unstable = true;
    }
    const double us_per_node_step = wall_steps * 1e6 * pd::max_threads() / (double(std::max(steps_here, 1L)) * double(sc.s.body.size()));
    const double d = sc.p.delta;
    run.summary_observed({{"spall_depth_1s", depth_fig, d, pd::io::relative_error(depth_fig, d), "m"},
                          {"spall_depth_end", depth_end, d, pd::io::relative_error(depth_end, d), "m"},
                          {"damaged_depth_1s", layer_fig, d, pd::io::relative_error(layer_fig, d), "m"},
                          {"damaged_depth_end", layer_end, d, pd::io::relative_error(layer_end, d), "m"}});
    mesh_rows(run, sc);
    run.summary({{"damage_max", phi_max, NAN, NAN, "-"},
                 {"broken_bonds", double(mech.ex.broken_bonds), NAN, NAN, "-"},
                 {"nsync_mk", double(clocks.nsync_mk), NAN, NAN, "-"},
                 {"steps", double(mech.ex.step_count), NAN, NAN, "-"},
                 {"us_per_node_step", us_per_node_step, NAN, NAN, "us"},
                 {"wall", timer.seconds(), NAN, NAN, "s"}});
    run.property(!unstable, "the run stays stable");
    return run.finish("%zu nodes, %ld steps: spall depth %.3g mm at 1 ms (delta %.3g mm), %.3g mm at the end", sc.s.body.size(), mech.ex.step_count,
                      depth_fig * 1e3, d * 1e3, depth_end * 1e3);
}

}  // namespace

static int run_case(int argc, char** argv)
{
    pd::io::Case run("meteorite_entry_3d", "Basalt meteorite entering the atmosphere: heat through a loading shell, thermal spallation (spec/000c V16, V17).",
                     "reports/3d/meteorite_entry");
    pd::io::Options& opt = run.opt;
    pd::add_meteorite_options(opt);
    std::string& study = opt.add_string("study", "thermal", "thermal: conduction only (V16); spall: weakly coupled (V17)", {"thermal", "spall"});
    opt.add("t-end", 0, "duration (by study: thermal 10 s, spall 2 ms)", "s");
    double& eta = opt.add("eta", 3, "numerical viscosity (spall, sec. 8.4.2)");
    double& C_hg = opt.add("C-hg", 0.02, "correspondence hourglass coefficient (spall; assumed)");
    double& dt_factor = opt.add("dt-factor", 0.5, "safety factor on the Silling-Askari step (spall)");
    double& cone = opt.add("cone", 30, "half-angle of the cone around the stagnation direction for the spall depth", "deg");
    int& sample = opt.add_int("sample", 500, "mechanical steps between samples (spall)");
    opt.require_at_least("C-hg", 0), opt.require_positive("dt-factor"), opt.require_range("cone", 0, 90, false, true);
    opt.require_range("eta", 1, 1e6, false, true), opt.require_at_least("sample", 1);
    run.allow_checkpoints();
    run.parse(argc, argv);
    const bool spall = study == "spall";  // the study's defaults of the options not given, then --quick's
    opt.set_default("t-end", spall ? 2e-3 : 10.0), opt.set_default("delta", spall ? 1e-3 : 0.5e-3), opt.set_default("scale", spall ? 1000.0 : 1.0);
    run.quick_default("delta", 2e-3);
    for (const char* o : {"t-end", "delta", "scale"}) if (!(opt.get(o) > 0)) opt.fail(std::string("option --") + o + " must be positive");
    const double delta = opt.get("delta"), scale = opt.get("scale");
    pd::MeteoriteParams par = pd::meteorite_params(opt, delta, scale);
    std::optional<pd::AngleTable> table;
    if (!par.flux_table.empty()) try {
            table.emplace(pd::read_angle_table(par.flux_table, "Q_W_m2"));
        } catch (const std::exception& e) {
            opt.fail(std::string("option --flux-table: ") + e.what());
        }
    if (table && table->min_value() < 0) opt.fail("option --flux-table: heat flux values must be >= 0 (inward)");
    run.start();
    pd::MeteoriteScene sc(par, table);
    sc.print();
    if (!(sc.power > 0)) opt.fail("option --flux-table: the table delivers no heat (power " + std::to_string(sc.power) + " W)");
    return spall ? spall_study(run, sc, opt.get("t-end"), eta, C_hg, dt_factor, cone * std::numbers::pi / 180, sample) : thermal_study(run, sc, opt.get("t-end"));
}

int main(int argc, char** argv) { return pd::io::guarded_main("meteorite_entry_3d", [&] { return run_case(argc, argv); }); }
