// problems/2d/kalthoff_winkler.cpp -- Kalthoff-Winkler edge impact on a double-notched steel plate,
// 2D plane-strain PMB with critical stretch (spec/002 sec. 7.3, case V9).
// Case: plate 100 mm along the impact (x) by 200 mm across it (y) (spec/002 infers "200 x 100 mm"
// from the 5,000 nodes at 2 mm; the orientation is Kalthoff's specimen: notch length = half the
// plate's depth), two notches from the left edge, 50 mm long, 50 mm apart, symmetric about the
// mid-line (bonds crossing them broken); the left-edge node row between the notches moves at
// v = 16.5 m/s (prescribed velocity: half the 33 m/s impact speed, equal impedances); all other
// edges free. Steel 18Ni1900: E 190 GPa, rho 8000 kg/m^3, Gc 22170 J/m^2, plane strain (PMB:
// nu = 1/4). m = 3, PA-PDLAMMPS volumes, 90 us.
// Reference: spec/002 Table/text of sec. 7.3 (adaptive level-1 PD, finest dx = 1 mm): crack
// initiation ~24 us, straight crack at 68 deg (experiment ~70 deg), v_max 1981 m/s = 71 % of the
// Rayleigh speed c_R = 2799.2 m/s (XFEM: 75 %).
// Compared: initiation time (tip one dx beyond the notch tip), crack angle (principal axis of the
// damaged nodes of each crack beyond 2 delta from its notch tip), maximum tip speed over 1.82 us
// windows (tip = connected damaged node farthest from the notch tip), for each dx of the list.
// Run: kalthoff_winkler_2d [--dx-list 1e-3,2e-3] [--v 16.5] [--quick] [--check] [--out DIR]
// Writes: summary.csv (first dx), convergence.csv, tip_history.csv, speed.csv, damage.csv,
// crack_path.csv (phi = 0.41), params.csv.
#include "problems/common/crack/crack_run.hpp"
#include "problems/common/crack/tip_recorder.hpp"
#include "problems/common/crack/work_precision.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/io/refined_grid_vtu.hpp"

#include <cstdio>

namespace {
constexpr double pi = 3.14159265358979323846;
constexpr double deg = 180 / pi;

struct Result {
    double dx, t_init, angle_up, angle_low, v_max, v_max_low, wall, dt;
    std::size_t nodes, bonds;
    long steps;
};

// tip_history<suffix>.csv and speed<suffix>.csv of both cracks, damage<suffix>.csv and on a lattice
// crack_path<suffix>.csv (phi = 0.41) of the last sample.
void write_tips(const std::filesystem::path& out, const std::string& suffix, const pd::crack::TipRecorder& up,
                const pd::crack::TipRecorder& low, double window, const pd::Body<2>* lattice)
{
    pd::io::CsvWriter th(out / ("tip_history" + suffix + ".csv"), {"crack", "t_s", "x_m", "y_m", "distance_m"}, false);
    pd::io::CsvWriter sp(out / ("speed" + suffix + ".csv"), {"crack", "t_s", "v_m_per_s"});
    for (const auto& [name, h] : {std::pair{"upper", &up.tips}, std::pair{"lower", &low.tips}}) {
        for (std::size_t l = 0; l < h->size(); ++l) th.row({name, h->t[l], h->x[l][0], h->x[l][1], h->advance[l]});
        for (const auto& s : h->speed(window)) sp.row({name, s.t, s.v});
    }
    pd::crack::write_damage_csv(out / ("damage" + suffix + ".csv"), up.x, up.phi);
    if (lattice) pd::crack::write_crack_path_csv(out / ("crack_path" + suffix + ".csv"), *lattice, up.phi);
}
}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI; defaults = spec/002 sec. 7.3), echoed and saved.
    pd::io::Case run("kalthoff_winkler_2d", "Kalthoff-Winkler impact on a double-notched plate (2D plane-strain PMB).",
                     "reports/2d/kalthoff_winkler");
    pd::io::Options& opt = run.opt;
    double& E = opt.add("E", 190e9, "Young's modulus", "Pa");
    double& rho = opt.add("rho", 8000, "density", "kg/m^3");
    double& Gc = opt.add("Gc", 22170, "fracture energy", "J/m^2");
    double& v_imp = opt.add("v", 16.5, "prescribed velocity of the impacted edge between the notches", "m/s");
    double& L = opt.add("length", 0.1, "plate depth along the impact (x)", "m");
    double& H = opt.add("height", 0.2, "plate height across the impact (y)", "m");
    double& a0 = opt.add("notch", 0.05, "notch length from the left edge", "m");
    double& gap = opt.add("notch-distance", 0.05, "distance between the notches (symmetric about the mid-line)", "m");
    opt.add_string("dx-list", "1e-3,2e-3", "lattice spacings (quick: 1e-3 to 50 us)");
    double& m = opt.add("m", 3, "horizon ratio delta/dx");
    std::string& pv = opt.add_string("partial-volume", "pa-pdlammps", "partial volumes", {"none", "pa-pdlammps"});
    double& dt_max = opt.add("dt", 70e-9, "largest time step (spec/002: 70 ns at dx = 1 mm)", "s");
    double& safety = opt.add("dt-factor", 0.8, "time step bound / Silling-Askari critical step");
    double& t_end = opt.add("t-end", 90e-6, "simulated time", "s");
    double& window = opt.add("window", 1.82e-6, "crack-speed window (spec/002: 1.82 us)", "s");
    double& threshold = opt.add("threshold", pd::crack::tip_threshold, "damage of a tip node");
    double& walk = opt.add("walk-threshold", 0.2, "damage of the nodes that connect a crack to its pre-crack");
    const pd::crack::AdaptiveCli adapt(opt, 15.3e-6, "both", "spec/002 V9: energy and damage triggers from 15.3 us");
    for (const char* o : {"E", "rho", "Gc", "v", "length", "height", "notch", "notch-distance", "dt", "dt-factor", "t-end", "window"})
        opt.require_positive(o);
    opt.require_at_least("m", 1);
    opt.require_range("threshold", 0, 1, false, true);
    opt.require_range("walk-threshold", 0, 1, false, true);
    run.allow_checkpoints();
    run.parse(argc, argv);
    if (!(a0 < L) || !(gap < H)) opt.fail("option --notch/--notch-distance: notches must lie inside the plate");
    adapt.validate(opt);
    const bool quick = run.quick();
    run.quick_default("t-end", 50e-6);  // initiation and the run of the cracks
    run.quick_default("dx-list", "1e-3");
    const std::vector<double> dxs = pd::io::list_option(opt, "dx-list", pd::io::ListValues::positive);
    // Quick scenes are too small to gain from threads (and a loaded machine makes each OpenMP barrier
    // wait for a descheduled thread): one thread unless --threads is given.
    run.quick_threads = 1;
    run.start();
    const std::filesystem::path& out = run.out();

    const pd::crack::Material2D mat{E, rho, Gc, pd::Plane::strain};
    const double y_up = 0.5 * (H + gap), y_low = 0.5 * (H - gap);  // notch lines [m]
    const pd::Vec<2> tip_up{{a0, y_up}}, tip_low{{a0, y_low}};
    auto impact = [&](const pd::Body<2>& body, double dx) {  // prescribed velocity on the left node row between the notches
        pd::Boundary<2> bc;
        bc.prescribe({pd::Prescribed::Kind::velocity, pd::select(body, pd::in_box<2>({{-1, y_low}}, {{dx, y_up}}), "impact zone"), 0,
                      pd::TimeFunction::constant(v_imp)});
        return bc;
    };
    // Tips every ~0.1 us: per notch, the damaged node farthest from the notch tip among those
    // connected to the notch band (steps <= 2.5 dx through nodes with phi >= 0.2, right of the notch
    // tip minus 2 delta, on the notch's side of the mid-line), not the notch band itself (x < tip - dx).
    auto recorder = [&](const pd::Vec<2>& tip, double dx) {
        const bool upper = tip[1] > H / 2;
        return pd::crack::TipRecorder{.origin = tip, .dir = {}, .threshold = threshold, .walk = walk, .step = 2.5 * dx,
            .region = [&, upper, dx](const pd::Vec<2>& p) { return p[0] > a0 - 2 * m * dx && (p[1] > H / 2) == upper; },
            .beyond = [&, dx](const pd::Vec<2>& p) { return p[0] >= a0 - dx; }, .tips = {}, .x = {}, .phi = {}, .phi0 = {}, .crack = {}};
    };
    // Metrics: initiation (either tip one dx beyond its notch), the angle of each crack (principal axis
    // of its damaged nodes beyond 2 delta from the notch tip), maximum speeds over the window.
    auto measure = [&](const pd::crack::TipRecorder& up, const pd::crack::TipRecorder& low, double dx, const pd::crack::RunInfo& info,
                       std::size_t nodes, std::size_t bonds) {
        auto angle = [&](const pd::crack::TipRecorder& rec) {
            std::vector<pd::Vec<2>> pts;
            for (std::size_t i = 0; i < rec.phi.size(); ++i)
                if (rec.crack[i] && rec.phi[i] >= threshold && norm(rec.x[i] - rec.origin) > 2 * m * dx) pts.push_back(rec.x[i]);
            return pts.size() >= 2 ? pd::crack::principal_angle(pts) * deg : pd::crack::nan;
        };
        std::printf("dx %.3g mm: %zu nodes, %zu bonds, dt %.3g ns (crit %.3g), %ld steps, %.1f s\n", dx * 1e3, nodes, bonds, info.dt * 1e9,
                    info.dt_crit * 1e9, info.steps, info.wall);
        return Result{dx, std::min(up.tips.initiation_time(0.99 * dx), low.tips.initiation_time(0.99 * dx)), angle(up), angle(low),
                      up.tips.max_speed(window), low.tips.max_speed(window), info.wall, info.dt, nodes, bonds, info.steps};
    };
    const long every = std::max(1L, std::lround(0.1e-6 / dt_max));

    std::vector<Result> results;
    for (std::size_t q = 0; q < dxs.size(); ++q) {
        // 2.-5. Discretisation, notches as broken bonds, the impact; integrate.
        const double dx = dxs[q];
        if (std::lround(y_low / dx) < 2 * m) opt.fail("option --dx-list: dx too coarse for the ligaments");
        const pd::Body<2> body = pd::box<2>({{0, 0}}, {{L, H}}, dx);
        pd::Bonds bonds = pd::build_bonds(body, m * dx, {.partial_volume = pd::parse_partial_volume(pv), .keep = {}});
        for (double y : {y_up, y_low}) {
            const auto keep = pd::cut_by_segment(body, {{-dx, y}}, {{a0, y}});
            pd::crack::break_bonds(bonds, [&](int i, int j) { return !keep(i, j); });
        }
        pd::crack::TipRecorder up = recorder(tip_up, dx), low = recorder(tip_low, dx);
        const pd::crack::RunInfo info = pd::crack::run_fracture_2d(body, bonds, mat, impact(body, dx), dt_max, safety, t_end, every,
            [&](double t, std::vector<double> p, auto&) { up(t, body.x, bonds, p), low(t, body.x, bonds, std::move(p)); },
            {.no_fail = {}, .show_progress = !quick, .checkpoints = &run.checkpoints(), .sampler_state = [&](pd::StateArchive& ar) {
                up.state(ar, "upper."), low.state(ar, "lower.");
            }});
        results.push_back(measure(up, low, dx, info, body.size(), bonds.size()));
        if (q == 0) write_tips(out, "", up, low, window, &body);
    }
    // The adaptive run (spec/002 sec. 7.3, V9): from the first dx, refined where the triggers fire.
    Result adaptive{};  // and its grid updates:
    pd::AdaptiveStats adaptive_stats;
    double refined_area = 0, coarse_broken = 0;  // [m^2] of level >= 1; level-0 bonds broken (V6d; the energy-only zone)
    if (adapt.on) {
        const double dx = dxs.front(), dx_fine = dx / (1 << adapt.levels);
        const auto up_cut = pd::segment_crossing({{-dx, y_up}}, {{a0, y_up}}), low_cut = pd::segment_crossing({{-dx, y_low}}, {{a0, y_low}});
        const pd::AdaptiveScene<2> scene{.pmb = {}, .rho = 0, .s0 = {},
                                         .cut = [&](const pd::Vec<2>& p, const pd::Vec<2>& q) { return up_cut(p, q) || low_cut(p, q); },
                                         .boundary = [&](const pd::Body<2>& b) { return impact(b, dx); }, .no_fail = {}};
        pd::crack::TipRecorder up = recorder(tip_up, dx), low = recorder(tip_low, dx);
        const pd::crack::AdaptiveInfo info = pd::crack::run_fracture_adaptive<2>(
            pd::RefinedGrid<2>(pd::box<2>({{0, 0}}, {{L, H}}, dx), m * dx), scene, adapt.options(pd::Refinement::delta, m, pd::parse_partial_volume(pv)),
            mat, dt_max, safety, t_end, std::max(1L, std::lround(0.1e-6 / std::min(dt_max, dt_max * dx_fine / dx))),
            [&](double t, const pd::AdaptiveFracture<2>& a) {
                up(t, a.body().x, a.bonds(), a.damage(), &a.initial_damage()), low(t, a.body().x, a.bonds(), a.damage(), &a.initial_damage());
                if (t < t_end * (1 - 1e-12)) return;
                pd::io::write_refined_grid_vtu(run.file("adaptive_grid.vtu"), a.grid(), {{"damage", a.damage()}});
                for (std::size_t i = 0; i < a.body().size(); ++i)
                    if (a.grid().level[a.ids()[i]] > 0) refined_area += a.body().volume[i] / a.body().measure;
            }, !quick);
        coarse_broken = static_cast<double>(info.coarse_broken);
        adaptive = measure(up, low, dx_fine, info.run, info.nodes_final, 0);
        adaptive_stats = info.stats;
        write_tips(out, "_adaptive", up, low, window, nullptr);
    }

    // 7. Tables and verdict. Rayleigh speed by Viktorov's approximation c_R = c_s (0.862 + 1.14 nu)/(1 + nu).
    const double nu = mat.nu(), cR = std::sqrt(E / (2 * (1 + nu) * rho)) * (0.862 + 1.14 * nu) / (1 + nu);
    const double cR_pub = 2799.2, t_pub = 24e-6, angle_pub = 68, angle_exp = 70, v_pub = 1981;  // spec/002 sec. 7.3
    pd::io::CsvWriter conv(out / "convergence.csv", {"dx_m", "delta_m", "m", "nodes", "bonds", "error", "rate", "wall_s", "t_init_s",
                                                     "angle_upper_deg", "angle_lower_deg", "v_max_upper_m_per_s",
                                                     "v_max_lower_m_per_s", "dt_s", "steps"});
    std::printf("\n%8s %8s %8s %10s %10s %10s %10s %8s\n", "dx_mm", "nodes", "t_i_us", "angle_up", "angle_low", "v_max_up", "v_max_low", "wall_s");
    for (const Result& r : results) {
        conv.row({r.dx, m * r.dx, m, r.nodes, r.bonds, pd::io::relative_error(r.angle_up, angle_pub), pd::crack::nan, r.wall, r.t_init,
                  r.angle_up, r.angle_low, r.v_max, r.v_max_low, r.dt, r.steps});
        std::printf("%8.3g %8zu %8.2f %10.1f %10.1f %10.0f %10.0f %8.1f\n", r.dx * 1e3, r.nodes, r.t_init * 1e6, r.angle_up, r.angle_low,
                    r.v_max, r.v_max_low, r.wall);
    }
    const Result& r = results.front();
    using pd::io::relative_error;
    const double nan = pd::crack::nan;
    run.summary_observed({
        {"t_init_s", r.t_init, t_pub, relative_error(r.t_init, t_pub), "s"},
        {"crack_angle_deg", r.angle_up, angle_pub, relative_error(r.angle_up, angle_pub), "deg"},
        {"crack_angle_vs_experiment_deg", r.angle_up, angle_exp, relative_error(r.angle_up, angle_exp), "deg"},
        {"crack_angle_lower_deg", r.angle_low, -angle_pub, relative_error(r.angle_low, -angle_pub), "deg"},
        {"v_max_m_per_s", r.v_max, v_pub, relative_error(r.v_max, v_pub), "m/s"},
        {"v_max_over_c_R", r.v_max / cR, v_pub / cR_pub, relative_error(r.v_max / cR, v_pub / cR_pub), "-"},
        {"c_R_m_per_s", cR, cR_pub, relative_error(cR, cR_pub), "m/s"},  // ours nu = 1/4, published nu = 0.3 (spec/002 sec. 9)
        {"nodes", static_cast<double>(r.nodes), nan, nan, "-"},
        {"wall_time", r.wall, nan, nan, "s"}});
    if (adapt.on) {  // error against run time (work_precision.hpp); published: +4,453 nodes (level 1), +6,902 (level 2)
        auto point = [&](const std::string& name, const Result& x) {
            return pd::crack::WorkPoint{name, x.dx, static_cast<double>(x.nodes), x.wall, {x.t_init, x.angle_up, x.angle_low, x.v_max}};
        };
        std::vector<pd::crack::WorkPoint> uniform;
        for (const Result& u : results) uniform.push_back(point("uniform", u));
        const std::vector<pd::crack::Quantity> qs{{"t_init", "s", "s", t_pub, t_pub}, {"crack_angle", "deg", "deg", angle_pub, angle_pub},
                                                  {"crack_angle_lower", "deg", "deg", -angle_pub, -angle_pub}, {"v_max", "m_per_s", "m/s", v_pub, v_pub}};
        const double nodes_pub = adapt.levels == 1 ? 5000 + 4453 : adapt.levels == 2 ? 5000 + 6902 : nan;
        pd::crack::report_work_precision(run, qs, uniform, point("adaptive", adaptive), dxs.front() / (1 << adapt.levels), adaptive_stats,
                                         std::abs(dxs.front() - 2e-3) < 1e-9 ? nodes_pub : nan, nan);
        // The zone: its area (published level 1: 4,453 new nodes from 2 mm cells split in four, 3 new
        // each, i.e. 4,453 / 3 x 4 mm^2, our inference) and the bonds broken outside it.
        const double area_pub = adapt.levels == 1 ? 4453.0 / 3 * 4e-6 : nan;
        run.summary_observed({{"refined_area_m2", refined_area, area_pub, relative_error(refined_area, area_pub), "m^2"},
                              {"coarse_bonds_broken_adaptive", coarse_broken, nan, nan, "-"}});
    }
    run.print_summary(30);

    // Tolerances: both crack angles within 10 deg of +-68 (the published value comes from an
    // adaptive grid; our uniform grid has weak bond directions at 63.4 and 71.6 deg near it:
    // spec/002 sec. 6.2), the tip faster than c_R / 2 (a running crack: 71 % PD, 75 % XFEM) and
    // slower than c_R, initiation within 25 % of 24 us (our tip rule and the published one may
    // differ by a few dx of growth, about 1 us each at the early tip speed). The up/down asymmetry
    // is reported, not checked.
    run.check(std::abs(r.angle_up - angle_pub) <= 10, "upper crack angle within 10 deg of 68 deg");
    run.check(std::abs(r.angle_low + angle_pub) <= 10, "lower crack angle within 10 deg of -68 deg");
    run.property(r.v_max < cR && r.v_max_low < cR, "maximum tip speeds below the Rayleigh speed");
    run.property(r.v_max > cR / 2 && r.v_max_low > cR / 2, "maximum tip speeds above half the Rayleigh speed");
    run.check(relative_error(r.t_init, t_pub) <= 0.25, "initiation within 25 % of 24 us");
    if (adapt.on) run.check(std::abs(adaptive.angle_up - angle_pub) <= 10, "adaptive run: upper crack angle within 10 deg of 68 deg");
    return run.finish("dx %.3g mm: initiation %.2f us (24), angle %.1f / %.1f deg (68), v_max %.0f m/s = %.0f %% c_R (71 %%)",
                      r.dx * 1e3, r.t_init * 1e6, r.angle_up, r.angle_low, r.v_max, 100 * r.v_max / cR);
}

int main(int argc, char** argv) { return pd::io::guarded_main("kalthoff_winkler_2d", [&] { return run_case(argc, argv); }); }
