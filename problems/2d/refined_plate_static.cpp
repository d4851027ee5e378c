// problems/2d/refined_plate_static.cpp -- a plate in uniform tension on a grid refined in one half
// (spec/002 sec. 5.1, V1): do variable horizons and their interface spoil the static solution?
// Case: plate 1 x 0.5 m, t = 0.01 m, E = 200 GPa (PMB plane stress: nu = 1/3), p = 200 MPa on one
// column of nodes at each end (b = p/h on that column), linearised bond-based PD solved statically
// (K u = F, the analytic PMB tangent at the reference). Grid: nodes at x = -0.5 + i dx0, y = -0.25 +
// j dx0 (101 x 51 at dx0 = 10 mm), delta0 = 3.015 dx0, exact cell areas in the horizon (IPA-Hybrid's
// areas, integration points at the nodes; bonds.hpp). Models A, B, C refine the left half (x < 0)
// 1, 2, 3 times, D, E, F the upper half (y > 0), by Method B with delta halving (core/refinement.hpp).
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
// |error| at 0 < x <= 0.1 m.
// Run: refined_plate_static_2d [--models A,B,C,D,E,F] [--dx0 0.01] [--quick] [--out DIR]
// Writes: runs.csv (one row per model, coupling, correction), lines.csv (the profiles), summary.csv,
// grid_<model>.vtu (the refined grid with its levels and the dual-horizon displacement, for ParaView).
#include "pd/core/refinement.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/refined_grid_vtu.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/solve/linear_solver.hpp"
#include "pd/solve/tangent.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace {
constexpr double on_axis = 1e-9;  // |coordinate| below which a node lies on a symmetry axis [m]

struct Plate {
    double Lx, Ly, t, dx0, delta0, E, p;  // [m], [m], [m], [m], [m], [Pa], [Pa]
};

// 2. The node-centred plate, then `levels` Method B refinements of the left (A-C) or upper (D-F) half.
pd::RefinedGrid<2> refined_plate(const Plate& P, int levels, bool upper)
{
    pd::Body<2> b;
    b.dx = P.dx0, b.measure = P.t;
    const long nx = std::lround(P.Lx / P.dx0), ny = std::lround(P.Ly / P.dx0);
    for (long j = 0; j <= ny; ++j)
        for (long i = 0; i <= nx; ++i) b.push({{-P.Lx / 2 + i * P.dx0, -P.Ly / 2 + j * P.dx0}}, P.dx0 * P.dx0 * P.t);
    pd::RefinedGrid<2> g(b, P.delta0);
    double setback = 0;  // distance from the axis beyond which level l starts [m] (header)
    for (int l = 1; l <= levels; ++l) {
        std::vector<int> split;
        for (int i : g.ids())
            if (g.level[i] == l - 1 && (upper ? g.x.c[1][i] : -g.x.c[0][i]) > setback + on_axis) split.push_back(i);
        setback += P.delta0 / std::pow(2.0, l - 1);
        g.split(split, pd::Refinement::delta);
    }
    return g;
}

struct Solution {
    pd::Body<2> body;
    pd::Field<2> u;
    std::vector<int> level;
    std::size_t bonds = 0;
    double ghost = 0, wall = 0;  // |sum of the internal forces| / load [-]; wall time [s]
};

// 3.-5. Families, PMB with the horizon factors (and the surface correction), supports, loads, K u = F.
Solution solve(const Plate& P, const pd::RefinedGrid<2>& g, pd::HorizonCoupling coupling, bool corrected)
{
    pd::io::Timer timer;
    Solution s{g.body(), {}, {}, 0, 0, 0};
    const std::size_t n = s.body.size();
    for (int i : g.ids()) s.level.push_back(g.level[i]);
    const std::vector<double> h = g.active_h();
    const pd::HorizonFamilies f = pd::build_variable_horizon_bonds(s.body, g.active_delta(), h, coupling, pd::PartialVolume::exact_area);
    const pd::PMB::Params mp{.material = pd::Elastic::from_E_nu(P.E, 1.0 / 3), .dim = 2, .plane = pd::Plane::stress, .measure = P.t};
    pd::PMB model(mp, f.bonds);
    model.scale_bonds(pd::horizon_factors(f, [&](double delta) { return pd::PMB::micromodulus(mp, pd::Influence{}, delta); }));
    if (corrected)
        pd::apply_surface_correction(model, s.body, f.bonds, pd::SurfaceCorrectionMethod::energy,
                                     {.reference = pd::SurfaceCorrectionOptions::Reference::classical,
                                      .kappa = pd::kappa_dim(mp.material, 2, mp.plane)});
    std::vector<std::uint8_t> held(2 * n, 0);
    Eigen::VectorXd F;
    std::vector<double> load(2 * n, 0.0);  // nodal force [N]
    for (std::size_t i = 0; i < n; ++i) {
        const double x = s.body.x.c[0][i], y = s.body.x.c[1][i], edge = (P.Lx + P.dx0) / 2;
        held[2 * i] = std::abs(x) < on_axis, held[2 * i + 1] = std::abs(y) < on_axis;
        if (std::abs(std::abs(x) + h[i] / 2 - edge) < on_axis) load[2 * i] = (x > 0 ? P.p : -P.p) / h[i] * s.body.volume[i];  // b = p/h
    }
    const pd::DofMap dofs(held);
    F = Eigen::VectorXd::Zero(dofs.free);
    for (std::size_t q = 0; q < 2 * n; ++q)
        if (dofs.index[q] >= 0) F[dofs.index[q]] = load[q];
    const Eigen::SparseMatrix<double> K = pd::tangent_pmb(model, s.body, f.bonds, s.body.x, dofs);
    pd::SparseSolver solver;
    std::string failure;
    const bool dual = coupling == pd::HorizonCoupling::dual;  // symmetric K: Cholesky; the plain variable horizon: LU
    Eigen::VectorXd U;
    if (!solver.factorise(K, dual ? pd::LinearSolver::cholesky : pd::LinearSolver::lu, 0, 0, failure) || !solver.solve(F, U, failure))
        throw std::runtime_error(failure);
    s.u = pd::Field<2>(n);
    for (std::size_t q = 0; q < 2 * n; ++q) s.u.c[q % 2][q / 2] = dofs.index[q] >= 0 ? U[dofs.index[q]] : 0.0;
    pd::Field<2> y = s.body.x, fi(n);  // the internal forces at the solution: their sum is the ghost force
    for (int d = 0; d < 2; ++d)
        for (std::size_t i = 0; i < n; ++i) y.c[d][i] += s.u.c[d][i];
    pd::internal_force(model, f.bonds, y, fi);
    for (int d = 0; d < 2; ++d) {
        double sum = 0;
        for (std::size_t i = 0; i < n; ++i) sum += fi.c[d][i] * s.body.volume[i];
        s.ghost = std::max(s.ghost, std::abs(sum) / (P.p * P.t * (P.Ly + P.dx0)));
    }
    s.bonds = f.bonds.size(), s.wall = timer.seconds();
    return s;
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
    for (const char* o : {"E", "p", "length", "width", "thickness", "dx0", "m"}) opt.require_positive(o);
    run.parse(argc, argv);
    run.quick_default("dx0", 0.025);
    run.quick_default("models", std::string("A,D"));
    for (char c : models)
        if (c != ',' && (c < 'A' || c > 'F')) opt.fail("option --models: layouts are A-F, comma-separated, got '" + models + "'");
    run.start();
    const Plate P{.Lx = Lx, .Ly = Ly, .t = t, .dx0 = dx0, .delta0 = m * dx0, .E = E, .p = p};
    const double strain = P.p / P.E, nu = 1.0 / 3;  // analytic u_x = strain x, u_y = -nu strain y
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
        const pd::RefinedGrid<2> g = refined_plate(P, levels, upper);
        std::vector<double> ux_dual;  // u_x on the line of the dual-horizon run without correction, to compare the couplings
        for (const pd::HorizonCoupling coupling : {pd::HorizonCoupling::dual, pd::HorizonCoupling::source})
            for (const bool corrected : {false, true}) {
                const Solution s = solve(P, g, coupling, corrected);
                const char* cname = coupling == pd::HorizonCoupling::dual ? "dual" : "variable";
                // 6. Errors along the line: y = 0 (A-C) or x = Lx/4 (D-F), the nodes nearest on the side of +y / +x.
                double peak = 0, plat_r = 0, plat_c = 0, max_uy = 0, dh_vs_vh = 0, scale = 0;
                int n_r = 0, n_c = 0;
                std::vector<double> ux_line;
                for (std::size_t i = 0; i < s.body.size(); ++i) {
                    const double x = s.body.x.c[0][i], y = s.body.x.c[1][i], hh = P.dx0 / std::pow(2.0, s.level[i]) / 2;
                    const double across = upper ? x - P.Lx / 4 : y;
                    if (across < -on_axis || across > hh + on_axis) continue;
                    const double ex = std::abs(x) > on_axis ? s.u.c[0][i] / (strain * x) - 1 : 0.0;
                    const double ey = std::abs(y) > on_axis ? s.u.c[1][i] / (-nu * strain * y) - 1 : 0.0;
                    lines.row({std::string(1, name), cname, corrected ? "energy" : "none", x, y, s.level[i], s.u.c[0][i], s.u.c[1][i], ex, ey});
                    ux_line.push_back(s.u.c[0][i]), scale = std::max(scale, std::abs(strain * x));
                    if (!upper && x > on_axis && x <= 0.1 * P.Lx + on_axis) peak = std::max(peak, std::abs(ex));
                    const double along = upper ? y : x;  // plateau windows on each half, away from interface and ends
                    const bool window = std::abs(along) >= 0.2 * (upper ? P.Ly : P.Lx) / 2 && std::abs(along) <= 0.8 * (upper ? P.Ly : P.Lx) / 2;
                    const bool refined_side = upper ? y > 0 : x < 0;
                    if (window) (refined_side ? plat_r : plat_c) += std::abs(upper ? ey : ex), ++(refined_side ? n_r : n_c);
                    if (upper && refined_side) max_uy = std::max(max_uy, std::abs(ey));
                }
                if (coupling == pd::HorizonCoupling::dual && !corrected) {
                    ux_dual = ux_line;
                    pd::io::write_refined_grid_vtu(run.file(std::string("grid_") + name + ".vtu"), g, {{"ux_m", s.u.c[0]}, {"uy_m", s.u.c[1]}});
                }
                if (coupling == pd::HorizonCoupling::source && !corrected)
                    for (std::size_t q = 0; q < ux_line.size(); ++q) dh_vs_vh = std::max(dh_vs_vh, std::abs(ux_line[q] - ux_dual[q]) / scale);
                plat_r /= std::max(n_r, 1), plat_c /= std::max(n_c, 1);
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
    return run.finish("plate in tension on half-refined grids (runs.csv, lines.csv)");
}

int main(int argc, char** argv) { return pd::io::guarded_main("refined_plate_static_2d", [&] { return run_case(argc, argv); }); }
