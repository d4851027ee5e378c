// problems/2d/refined_plate_static.cpp -- a plate in uniform tension on a grid refined in one half
// (spec/002 sec. 5.1, V1): do variable horizons and their interface spoil the static solution?
// Case: plate 1 x 0.5 m, t = 0.01 m, E = 200 GPa (PMB plane stress: nu = 1/3), p = 200 MPa on one
// column of nodes at each end (b = p/h on that column), linearised bond-based PD solved statically
// (K u = F, the analytic PMB tangent at the reference). Grid: nodes at x = -0.5 + i dx0, y = -0.25 +
// j dx0 (101 x 51 at dx0 = 10 mm), delta0 = 3.015 dx0, exact cell areas in the horizon (IPA-Hybrid's
// areas, integration points at the nodes; bonds.hpp). Models A, B, C refine the left half (x < 0)
// 1, 2, 3 times, D, E, F the upper half (y > 0), by Method B with delta halving (core/refinement.hpp;
// --nodes A: Method A, midpoints around kept parents, the cell volumes of eq. 3.4 read as geometry).
// Our reading of the zone (the source shows it only in figures): level l splits the level l-1 nodes
// beyond the horizons of the levels below (setback delta0 + ... + delta_(l-2) from the axis), so no
// node sees one two levels finer. Supports: u_x = 0 on the nodes of x = 0, u_y = 0 on those of y = 0
// (the refined half has none there, as in the source). Couplings: dual horizon (no ghost force) and
// the plain variable horizon (core/variable_horizon.hpp); surface correction none or energy (classical
// reference, surface_correction.hpp).
// Reference: u_x = (p/E) x, u_y = -nu (p/E) y (spec/002 eq. 4.1). Published (order of magnitude, the
// source's supports and load rows are not given): A-C peak error of u_x in the coarse interface zone
// 31.5 %, plateau errors 7 % refined / 5 % coarse, 1.5 % / 2 % with the surface correction; D-F
// largest error of u_y 15 %; dual and plain variable horizon nearly identical for B and C.
// Measures along y = 0 (A-C; refined side: the nodes nearest above it) and x = 0.25 m (D-F): pointwise
// relative errors; plateau = mean |error| over 0.1 <= |x| <= 0.4 m on each side; peak = largest
// |error| at 0 < x <= 0.1 m. m-study (--m-list): L2 = sqrt(sum (u - u_ref)^2 / sum u_ref^2) on each
// side (eq. 4.2 without its printed 1/q, which puts the slopes two orders below the published ones)
// and |d L2 / d m| against the published 2.2e-2 / 0.3e-2 (A-C) and 3.6e-2 / 5.8e-3 (D-F).
// Run: refined_plate_static_2d [--models A,B,C,D,E,F] [--nodes B|A] [--dx0 0.01] [--m-list ...] [--quick] [--out DIR]
// Writes: runs.csv (one row per model, coupling, correction), lines.csv (the profiles), m_study.csv, summary.csv,
// grid_<model>.vtu (the refined grid with its levels and the dual-horizon displacement, for ParaView).
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/io/refined_grid_vtu.hpp"
#include "problems/common/refined_plate.hpp"

#include <cmath>
#include <cstdio>
#include <string>

using pd::plate::on_axis, pd::plate::Plate, pd::plate::Solution;

namespace {
struct LineNode {
    double x, y;
    int level;
    double ux, uy, ex, ey;  // [m], [m], relative errors [-]
};
struct LineErrors {
    double peak = 0, plat_r = 0, plat_c = 0, max_uy = 0;  // header
    double L2_r = 0, L2_c = 0;                            // relative L2 error (eq. 4.2), refined / coarse side
    std::vector<LineNode> nodes;
};

// 6. Errors along the line y = 0 (A-C) or x = Lx/4 (D-F): the nodes nearest it on the side of +y / +x.
LineErrors line_errors(const Plate& P, const Solution& s, bool upper)
{
    const double strain = P.p / P.E, nu = 1.0 / 3;  // analytic u_x = strain x, u_y = -nu strain y
    LineErrors r;
    int n_r = 0, n_c = 0;
    double se[2] = {0, 0}, sa[2] = {0, 0};  // sums of squared errors and of squared analytic values, refined / coarse
    for (std::size_t i = 0; i < s.body.size(); ++i) {
        const double x = s.body.x.c[0][i], y = s.body.x.c[1][i], hh = P.dx0 / std::pow(2.0, s.level[i]) / 2;
        const double across = upper ? x - std::round(P.Lx / 4 / P.dx0) * P.dx0 : y;  // the node column nearest x = Lx/4
        if (across < -on_axis || across > hh + on_axis) continue;
        const double ex = std::abs(x) > on_axis ? s.u.c[0][i] / (strain * x) - 1 : 0.0;
        const double ey = std::abs(y) > on_axis ? s.u.c[1][i] / (-nu * strain * y) - 1 : 0.0;
        r.nodes.push_back({x, y, s.level[i], s.u.c[0][i], s.u.c[1][i], ex, ey});
        if (!upper && x > on_axis && x <= 0.1 * P.Lx + on_axis) r.peak = std::max(r.peak, std::abs(ex));
        const double along = upper ? y : x, half = (upper ? P.Ly : P.Lx) / 2;  // plateau windows away from interface and ends
        const bool window = std::abs(along) >= 0.2 * half - on_axis && std::abs(along) <= 0.8 * half + on_axis, refined_side = upper ? y > 0 : x < 0;
        if (window) (refined_side ? r.plat_r : r.plat_c) += std::abs(upper ? ey : ex), ++(refined_side ? n_r : n_c);
        if (upper && refined_side) r.max_uy = std::max(r.max_uy, std::abs(ey));
        const double u = upper ? s.u.c[1][i] : s.u.c[0][i], u_an = upper ? -nu * strain * y : strain * x;
        se[refined_side ? 0 : 1] += (u - u_an) * (u - u_an), sa[refined_side ? 0 : 1] += u_an * u_an;
    }
    r.plat_r /= std::max(n_r, 1), r.plat_c /= std::max(n_c, 1);
    r.L2_r = std::sqrt(se[0] / sa[0]), r.L2_c = std::sqrt(se[1] / sa[1]);  // eq. 4.2 without its printed 1/q (header)
    return r;
}
}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI; defaults: spec/002 sec. 4.1).
    pd::io::Case run("refined_plate_static_2d", "Plate in tension on a half-refined grid: variable and dual horizons (spec/002 V1).",
                     "reports/2d/refined_plate_static");
    pd::io::Options& opt = run.opt;
    const double& E = opt.add("E", 200e9, "Young's modulus (PMB plane stress: nu = 1/3)", "Pa");
    const double& p = opt.add("p", 200e6, "end traction", "Pa");
    const double& Lx = opt.add("length", 1.0, "plate length (x)", "m");
    const double& Ly = opt.add("width", 0.5, "plate width (y)", "m");
    const double& t = opt.add("thickness", 0.01, "plate thickness", "m");
    double& dx0 = opt.add("dx0", 0.01, "initial grid spacing (quick: 0.025)", "m");
    double& m = opt.add("m", 3.015, "delta0 / dx0");
    std::string& models = opt.add_string("models", "A,B,C,D,E,F", "refinement layouts (A-C: left half 1-3 levels; D-F: upper half; quick: A,D)");
    opt.add_string("m-list", "1.515,2.015,3.015,4.015,5.015",
                   "m-study: dx0 = (delta0 - 0.015 dx0)/(m - 0.015), the source's 20 ... 6 mm (quick: 2.015,3.015; none: no study)");
    std::string& m_models = opt.add_string("m-models", "A,D", "layouts of the m-study (dual horizon, no correction; quick: A)");
    const std::string& nodes = opt.add_string("nodes", "B", "node generation: B (cell splitting, the source's) or A (midpoint insertion, parent kept)",
                                              {"B", "A"});
    for (const char* o : {"E", "p", "length", "width", "thickness", "dx0", "m"}) opt.require_positive(o);
    run.parse(argc, argv);
    run.quick_default("dx0", 0.025);
    run.quick_default("models", std::string("A,D"));
    run.quick_default("m-list", std::string("2.015,3.015"));
    run.quick_default("m-models", std::string("A"));
    const std::vector<double> m_list = opt.get_string("m-list") == "none" ? std::vector<double>{} : pd::io::list_option(opt, "m-list", pd::io::ListValues::positive);
    for (char c : models)
        if (c != ',' && (c < 'A' || c > 'F')) opt.fail("option --models: layouts are A-F, comma-separated, got '" + models + "'");
    run.start();
    const pd::NodeGeneration generation = nodes == "A" ? pd::NodeGeneration::midpoint : pd::NodeGeneration::cell_split;
    const Plate P{.Lx = Lx, .Ly = Ly, .t = t, .dx0 = dx0, .delta0 = m * dx0, .E = E, .p = p};
    const double nan = std::nan("");

    pd::io::CsvWriter runs(run.file("runs.csv"), {"model", "levels", "coupling", "surface_correction", "nodes", "bonds", "peak_err_ux_coarse",
                                                  "plateau_err_ux_refined", "plateau_err_ux_coarse", "max_err_uy_refined", "ghost_force", "wall_s"});
    pd::io::CsvWriter lines(run.file("lines.csv"), {"model", "coupling", "surface_correction", "x_m", "y_m", "level", "ux_m", "uy_m",
                                                    "rel_err_ux", "rel_err_uy"}, false);
    std::printf("%5s %6s %4s %8s %10s %10s %10s %10s %10s %8s\n", "model", "coupl", "sc", "nodes", "peak_ux", "plat_ref", "plat_crs",
                "max_uy", "ghost", "wall_s");
    for (char name : models) {
        if (name == ',') continue;
        const int levels = (name - 'A') % 3 + 1;
        const bool upper = name >= 'D';
        const pd::RefinedGrid<2> g = pd::plate::refined_plate(P, levels, upper, generation);
        std::vector<double> ux_dual;  // u_x on the line of the dual-horizon run without correction, to compare the couplings
        for (const pd::HorizonCoupling coupling : {pd::HorizonCoupling::dual, pd::HorizonCoupling::source})
            for (const bool corrected : {false, true}) {
                const Solution s = pd::plate::solve(P, g, coupling, corrected);
                const char* cname = coupling == pd::HorizonCoupling::dual ? "dual" : "variable";
                const LineErrors e = line_errors(P, s, upper);
                const double peak = e.peak, plat_r = e.plat_r, plat_c = e.plat_c, max_uy = e.max_uy;
                std::vector<double> ux_line;
                double dh_vs_vh = 0, scale = 0;
                for (const LineNode& n : e.nodes) {
                    lines.row({std::string(1, name), cname, corrected ? "energy" : "none", n.x, n.y, n.level, n.ux, n.uy, n.ex, n.ey});
                    ux_line.push_back(n.ux), scale = std::max(scale, std::abs(P.p / P.E * n.x));
                }
                if (coupling == pd::HorizonCoupling::dual && !corrected) {
                    ux_dual = ux_line;
                    pd::io::write_refined_grid_vtu(run.file(std::string("grid_") + name + ".vtu"), g, {{"ux_m", s.u.c[0]}, {"uy_m", s.u.c[1]}});
                }
                if (coupling == pd::HorizonCoupling::source && !corrected)
                    for (std::size_t q = 0; q < ux_line.size(); ++q) dh_vs_vh = std::max(dh_vs_vh, std::abs(ux_line[q] - ux_dual[q]) / scale);
                runs.row({std::string(1, name), levels, cname, corrected ? "energy" : "none", s.body.size(), s.bonds, upper ? nan : peak, plat_r,
                          plat_c, upper ? max_uy : nan, s.ghost, s.wall});
                std::printf("%5c %6s %4s %8zu %10.4f %10.4f %10.4f %10.4f %10.2e %8.2f\n", name, cname, corrected ? "yes" : "no", s.body.size(),
                            upper ? nan : peak, plat_r, plat_c, upper ? max_uy : nan, s.ghost, s.wall);
                std::fflush(stdout);

                // 7. Summary against the published values, and the checks.
                const std::string key = std::string(1, name) + "_" + cname + (corrected ? "_corrected" : "");
                const bool headline = coupling == pd::HorizonCoupling::dual;
                if (headline && !upper && !corrected) run.summary({"peak_err_ux_coarse_" + key, peak, 0.315, std::abs(peak - 0.315) / 0.315, "-"});
                if (headline && upper && !corrected) run.summary({"max_err_uy_refined_" + key, max_uy, 0.15, std::abs(max_uy - 0.15) / 0.15, "-"});
                const double ref_r = upper ? nan : corrected ? 0.015 : 0.07, ref_c = upper ? nan : corrected ? 0.02 : 0.05;
                if (headline) {
                    run.summary({"plateau_err_refined_" + key, plat_r, ref_r, std::abs(plat_r - ref_r) / ref_r, "-"});
                    run.summary({"plateau_err_coarse_" + key, plat_c, ref_c, std::abs(plat_c - ref_c) / ref_c, "-"});
                    // Round-off of the pair forces (eps x their sum, up to ~1e-11 of the load here); the plain variable
                    // horizon's ghost forces are percents of it.
                    run.property(s.ghost < 1e-8, std::string("model ") + name + ": dual-horizon internal forces sum to zero (round-off)");
                } else if (!corrected) {
                    run.summary({std::string("dual_vs_variable_ux_") + name, dh_vs_vh, nan, nan, "-"});
                    run.summary({std::string("ghost_force_variable_") + name, s.ghost, nan, nan, "-"});
                }
                run.property(plat_c < 0.2 && plat_r < 0.2, "model " + key + ": plateau errors below 20 % (the skin effect is a few %)");
            }
    }
    lines.flush();

    // 8. The m-study (sec. 5.1): the grid refined at (nearly) fixed horizons, dx0 = (delta0 - 0.015 dx0) /
    //    (m - 0.015) (at the defaults 20, 15, 10, 7.5, 6 mm for m = 1.515 ... 5.015, delta0 = m dx0 = 30.3 ...
    //    30.09 mm); the L2 error (eq. 4.2) on each side against m, and its least-squares slope.
    pd::io::CsvWriter mstudy(run.file("m_study.csv"), {"model", "m", "dx0_m", "nodes", "L2_refined", "L2_coarse", "max_err_uy_refined", "wall_s"});
    for (char name : m_models) {
        if (name == ',' || m_list.empty()) continue;
        const bool upper = name >= 'D';
        double sm = 0, smm = 0, sr = 0, smr = 0, sc = 0, smc = 0;  // sums of the least-squares fits
        for (const double mm : m_list) {
            Plate Pm = P;
            Pm.dx0 = (P.delta0 - 0.015 * P.dx0) / (mm - 0.015), Pm.delta0 = mm * Pm.dx0;
            const Solution s = pd::plate::solve(Pm, pd::plate::refined_plate(Pm, (name - 'A') % 3 + 1, upper, generation), pd::HorizonCoupling::dual, false);
            const LineErrors e = line_errors(Pm, s, upper);
            mstudy.row({std::string(1, name), mm, Pm.dx0, s.body.size(), e.L2_r, e.L2_c, upper ? e.max_uy : nan, s.wall});
            std::printf("m-study %c: m = %.3f, %zu nodes, L2 refined %.3e, coarse %.3e%s\n", name, mm, s.body.size(), e.L2_r, e.L2_c,
                        upper ? (", max u_y error " + std::to_string(e.max_uy)).c_str() : "");
            sm += mm, smm += mm * mm, sr += e.L2_r, smr += mm * e.L2_r, sc += e.L2_c, smc += mm * e.L2_c;
            if (upper && (mm == m_list.front() || mm == m_list.back())) {  // source, model E: 23 % at m = 1.515, 31 % at m = 5.015
                const double pub = name != 'E' ? nan : mm == 1.515 ? 0.23 : mm == 5.015 ? 0.31 : nan;
                run.summary({"max_err_uy_refined_" + std::string(1, name) + "_m" + std::to_string(mm).substr(0, 5), e.max_uy, pub,
                             std::abs(e.max_uy - pub) / pub, "-"});
            }
        }
        const double k = double(m_list.size()), det = k * smm - sm * sm;
        if (m_list.size() < 2 || det <= 0) continue;
        const double slope_r = std::abs((k * smr - sm * sr) / det), slope_c = std::abs((k * smc - sm * sc) / det);
        const double pub_r = upper ? 3.6e-2 : 2.2e-2, pub_c = upper ? 5.8e-3 : 3e-3;  // Figs. 4.11, 4.20 (read as |d L2 / d m|)
        run.summary({std::string("L2_slope_refined_") + name, slope_r, pub_r, std::abs(slope_r - pub_r) / pub_r, "1/m"});
        run.summary({std::string("L2_slope_coarse_") + name, slope_c, pub_c, std::abs(slope_c - pub_c) / pub_c, "1/m"});
    }
    mstudy.flush();
    return run.finish("plate in tension on half-refined grids (runs.csv, lines.csv)");
}

int main(int argc, char** argv) { return pd::io::guarded_main("refined_plate_static_2d", [&] { return run_case(argc, argv); }); }
