// problems/2d/grid_orientation.cpp -- dependence of a crack path on the orientation of the lattice
// (spec/002 ch. 5, sec. 6, cases V4-V5), 2D plane-stress PMB with critical stretch.
// Case: square plate 0.25 x 0.25 m, edge pre-crack 0.05 m from the left edge along the mid-line
// (its position is ambiguous in the source; bonds crossing it broken), sudden uniform traction
// 0.8 MPa on the top and bottom layers (total force sigma L per unit thickness), free edges;
// E 73.4 GPa, rho 2440 kg/m^3, s0 = 2.1070e-4 at m = 3 and dx = 1 mm, i.e. Gc = 7.0013 J/m^2
// (eq. 2.15b), so s0_m = s0_3 sqrt(3/m) at fixed dx. The lattice is rotated by theta about the
// plate centre; nodes outside the plate are dropped. PA-PDLAMMPS volumes by default (the source
// used IPA-Hybrid); `--partial-volume exact-area` takes IPA-Hybrid's exact cell areas (bonds.hpp)
// with the integration points at the nodes.
// Reference: spec/002 sec. 6: 0 deg horizontal; rotated grids deviate along weak (bond)
// directions at m = 3; m = 6 (10 deg) and m = 7 (5 deg) give horizontal paths (Table 5.2). The
// source has no metric; ours: the crack centreline (mean normal offset of the damaged nodes per
// dx bin, crack_metrics.hpp) against the line y = L/2: RMS, max and slope angle; a path is
// "horizontal" when its centreline stays within 3 dx of the line (the m = 3 horizon, for every m).
// Run: grid_orientation_2d [--angles 0,10] [--m-list 3,6] [--dx 2e-3] [--partial-volume pa-pdlammps]
//   [--quick] [--out DIR]
// The full study (angles 0,5,10,20,30,40; m 3..7; dx 1 mm) is in problems/cases.txt.
// Writes: summary.csv, paths.csv (centrelines), runs.csv, params.csv.
#include "problems/common/crack/crack_run.hpp"
#include "problems/common/crack/rotated_plate.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"

#include <cstdio>

namespace {
constexpr double pi = 3.14159265358979323846;

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI; defaults: a subset of spec/002 ch. 5 on a coarser lattice).
    pd::io::Case run("grid_orientation_2d", "Crack path vs lattice orientation and m (2D PMB, spec/002 ch. 5).", "reports/2d/grid_orientation");
    pd::io::Options& opt = run.opt;
    const pd::crack::GridPlateOptions plate = pd::crack::add_grid_plate_options(opt);
    double &E = plate.E, &rho = plate.rho, &Gc = plate.Gc, &sigma = plate.sigma, &L = plate.L, &a0 = plate.a0;
    double& dx = opt.add("dx", 2e-3, "lattice spacing (source: 1e-3; quick: 4e-3)", "m");
    opt.add_string("angles", "0,10", "lattice rotations (deg), comma-separated; with --m-list: all pairs");
    opt.add_string("m-list", "3,6", "horizon ratios delta/dx, comma-separated; with --angles: all pairs");
    std::string& pv = opt.add_string("partial-volume", "pa-pdlammps", "partial volumes", {"none", "pa-pdlammps", "exact-area"});
    double& dt_max = opt.add("dt", 100e-9, "largest time step (source: 100 ns at 1 mm)", "s");
    double& safety = opt.add("dt-factor", 0.8, "time step bound / Silling-Askari critical step");
    double& t_end = opt.add("t-end", 560e-6, "simulated time (quick: 200 us)", "s");
    double& walk = opt.add("walk-threshold", 0.2, "damage of the nodes that connect a crack to its pre-crack");
    for (const char* o : {"E", "rho", "Gc", "sigma", "size", "crack", "dx", "dt", "dt-factor", "t-end"}) opt.require_positive(o);
    opt.require_range("walk-threshold", 0, 1, false, true);
    run.allow_checkpoints();
    run.parse(argc, argv);
    if (!(a0 < L)) opt.fail("option --crack must be shorter than --size");
    const bool quick = run.quick();
    run.quick_default("dx", 4e-3);
    run.quick_default("t-end", 200e-6);
    // Runs (rotation [deg], m): by default 0/3, 10/3, 10/6 (the horizontal, deviated and corrected
    // cases of spec/002 Table 5.2; quick: 0/3, 10/3); all pairs of --angles and --m-list if either is given.
    std::vector<std::pair<double, double>> runs_list;
    if (opt.given("angles") || opt.given("m-list")) {
        const std::vector<double> as = pd::io::list_option(opt, "angles", pd::io::ListValues::non_negative);
        const std::vector<double> ms = pd::io::list_option(opt, "m-list", pd::io::ListValues::positive);
        for (double a : as)
            for (double m : ms) runs_list.push_back({a, m});
    } else {
        runs_list = {{0, 3}, {10, 3}};
        if (!quick) runs_list.push_back({10, 6});
    }
    for (const auto& [a, m] : runs_list) {
        if (a >= 90) opt.fail("option --angles: rotations must be below 90 deg");
        if (m < 1) opt.fail("option --m-list: m must be at least 1");
    }
    // Quick scenes are too small to gain from threads (and a loaded machine makes each OpenMP barrier
    // wait for a descheduled thread): one thread unless --threads is given.
    run.quick_threads = 1;
    run.start();
    const std::filesystem::path& out = run.out();
    const pd::crack::Material2D mat{E, rho, Gc, pd::Plane::stress};
    const double thr = pd::crack::tip_threshold, nan = pd::crack::nan;

    pd::io::CsvWriter runs(out / "runs.csv", {"angle_deg", "m", "dx_m", "nodes", "bonds", "s0", "crack_advance_m", "rms_m", "max_m",
                                              "path_angle_deg", "horizontal", "wall_s"});
    pd::io::CsvWriter paths(out / "paths.csv", {"angle_deg", "m", "x_m", "offset_m"}, false);
    std::printf("%8s %4s %8s %10s %10s %10s %10s %11s %8s\n", "grid_deg", "m", "nodes", "advance_mm", "rms_mm", "max_mm", "angle_deg",
                "path", "wall_s");
    for (const auto& [a_deg, m] : runs_list) {
            // 2. Discretisation and pre-crack.
            const double delta = m * dx, theta = a_deg * pi / 180;
            const pd::Body<2> body = pd::crack::rotated_plate(L, dx, theta);
            pd::Bonds bonds = pd::build_bonds(body, delta, {.partial_volume = pd::parse_partial_volume(pv), .lattice_angle = theta, .keep = {}});
            const auto keep = pd::cut_by_segment(body, {{-dx, L / 2}}, {{a0, L / 2}});
            pd::crack::break_bonds(bonds, [&](int i, int j) { return !keep(i, j); });

            // 3.-4. Traction layers 1.4 dx deep (at least one node row at any rotation, exactly one at
            //       0 deg); b such that the total force is sigma L per unit thickness.
            const pd::Boundary<2> bc = pd::crack::layer_loads(body, L, 1.4 * dx, sigma);

            // 5. Integrate (damage sampled only at the end).
            std::vector<double> phi, seeds;
            const pd::crack::RunInfo info = pd::crack::run_fracture_2d(body, bonds, mat, bc, dt_max, safety, t_end,
                std::numeric_limits<long>::max(), [&](double, std::vector<double> p, auto&) {
                    if (seeds.empty()) seeds = p;
                    phi = std::move(p);
                }, {.no_fail = {}, .show_progress = !quick, .checkpoints = &run.checkpoints(),
                    .sampler_state = [&](pd::StateArchive& ar) { ar("phi", phi), ar("seeds", seeds); }});

            // 6. Path of the crack connected to the pre-crack, against the line y = L/2.
            pd::crack::Mask s(body.size());
            for (std::size_t i = 0; i < body.size(); ++i) s[i] = seeds[i] >= thr;
            const pd::crack::Mask crack = pd::crack::connected_damage(bonds, phi, s, 2.5 * dx, walk);
            const pd::Vec<2> origin{{0, L / 2}}, dir{{1, 0}};
            const pd::crack::Tip tip = pd::crack::tip_along(body.x, phi, origin, dir, thr, crack);
            const double advance = tip.node >= 0 ? tip.advance - a0 : nan;
            const pd::crack::PathDeviation dev =
                pd::crack::path_deviation(body.x, phi, origin, dir, dx, a0 + delta, tip.node >= 0 ? tip.advance : a0, thr, crack);
            const double ang = dev.angle * 180 / pi;
            const bool horizontal = dev.max <= 3 * dx;  // centreline within 3 dx of the line, for every m
            runs.row({a_deg, m, dx, body.size(), bonds.size(), s0_pmb(Gc, E, delta, 2, pd::Plane::stress), advance, dev.rms, dev.max, ang,
                      horizontal ? 1 : 0, info.wall});
            for (std::size_t k = 0; k < dev.s.size(); ++k) paths.row({a_deg, m, dev.s[k], dev.n[k]});
            std::printf("%8.1f %4.1f %8zu %10.1f %10.2f %10.2f %10.1f %11s %8.1f\n", a_deg, m, body.size(), advance * 1e3, dev.rms * 1e3,
                        dev.max * 1e3, ang, std::isnan(ang) ? "no growth" : (horizontal ? "horizontal" : "deviated"), info.wall);
            char name[64];
            // Expected (spec/002 sec. 6, Table 5.2): 0 deg horizontal; rotated m = 3 deviated; m >= 6 horizontal.
            const double expect = a_deg == 0 || m >= 6 ? 1 : (m <= 3 ? 0 : nan);
            std::snprintf(name, sizeof name, "horizontal_grid%g_m%g", a_deg, m);
            run.summary({name, horizontal ? 1.0 : 0.0, expect, nan, "-"});
            std::snprintf(name, sizeof name, "path_max_offset_grid%g_m%g_m", a_deg, m);
            run.summary({name, dev.max, nan, nan, "m"});
            std::snprintf(name, sizeof name, "path_rms_grid%g_m%g_m", a_deg, m);
            run.summary({name, dev.rms, nan, nan, "m"});
            std::snprintf(name, sizeof name, "path_angle_grid%g_m%g_deg", a_deg, m);
            run.summary_observed({{name, ang, nan, nan, "deg"}});
            run.property(!std::isnan(ang), std::string("crack grows on the ") + std::to_string(static_cast<int>(a_deg)) + " deg grid, m = " +
                                            std::to_string(m).substr(0, 4));
            if (a_deg == 0) run.property(horizontal, "0 deg grid: horizontal path (spec/002 Fig. 5.1b)");
        }
    paths.flush();
    return run.finish("crack paths on %zu grids (runs.csv)", runs_list.size());
}

int main(int argc, char** argv) { return pd::io::guarded_main("grid_orientation_2d", [&] { return run_case(argc, argv); }); }
