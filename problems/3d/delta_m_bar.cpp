// problems/3d/delta_m_bar.cpp -- influence of the horizon delta and of m = delta/dx on the fracture
// time of a bar in uniform tension, critical stretch vs critical micropotential (Biondani 2018 sec. 8.5;
// spec/000c sec. 2.9, V11, erratum 10-11). Bar 1 x 1 x 5 mm (x the long axis), Si3N4 (E 310 GPa, nu 0.29,
// Gc = J_C 109.94 J/m^2, rho 3200 kg/m^3 assumed), correspondence linear law with hourglass 0.02 (the
// source does not state it), grips of ceil(delta/dx) layers added outside both ends (the thesis'
// fictitious constraint domain of thickness >= delta, 000a sec. 3.6), clamped and pulled apart to
// engineering strain 0.002 of the 5 mm bar in 100 us (20 1/s), no-fail in the grips and within 1 mm
// of each end of the bar, dt = 0.5 x Silling-Askari.
// Damage: stretch s0 = MO 3D (000c eq. 8.11; = PMB at the quasi-static estimate's accuracy),
// micropotential w_C = 4 J_C/(pi delta^4) (8.15). Fracture time = first broken bond; the run stops
// 5 us later.
// Reference: Tables 8.4 (micropotential) and 8.5 (stretch) as captioned, and the quasi-static
// estimate t = s0/(20 1/s) with the PMB s0 (000c eq. 8.9).
// Default: delta 0.38 and 0.61 mm at m = 3.05 and the delta = 0.61 mm row for every m (6 cells);
// --full: all 20 cells (problems/cases.txt); --quick: delta 0.61 mm, m 3.05 only.
// Run: delta_m_bar_3d [--deltas ...] [--ms ...] [--full] [--E --nu --rho --Gc --C-hg --rate --dt-factor]
//   [--no-hourglass-work] [--lateral-free] [--quick] [--check] [--out DIR]
// --rate: the pull still ends at strain 0.002 (at 0.002/rate); the published times hold for 20 1/s only.
// --lateral-free: the grips prescribe only the axial displacement (the lateral contraction is free).
// --grips inside: the end layers of width delta of the 5 mm bar itself are the grips (the free part
// then strains 1.1-1.3x the nominal strain).
// --no-hourglass-work: the micropotential leaves out the work of the hourglass forces, as Peridigm's
// (000c sec. 2.3 [CODE]); the default includes them (the work of the whole bond force).
// Writes: fracture_times.csv (delta, m, criterion, ours, published, quasi-static, wall, grip strain at the
// first break, distances of that bond from the nearer end and the nearest lateral face), summary.csv, params.csv.
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstdio>
#include <tuple>
#include <utility>

namespace {

using C3 = pd::Correspondence<3>;
const double table_delta[4] = {0.25e-3, 0.30e-3, 0.38e-3, 0.61e-3};  // [m]
const double table_m[5] = {2.05, 2.55, 3.05, 3.55, 4.05};
// Table 8.4 (micropotential) and 8.5 (stretch), fracture times [us], rows delta, columns m (captions).
const double table_micro[4][5] = {{44.8, 56.4, 42.3, 43.2, 40.0}, {41.3, 51.5, 40.4, 39.5, 37.0},
                                  {36.9, 46.3, 35.8, 35.5, 33.8}, {29.0, 36.9, 28.9, 29.1, 26.9}};
const double table_stretch[4][5] = {{49.5, 47.4, 43.9, 44.2, 39.1}, {42.7, 39.5, 38.5, 43.2, 37.2},
                                    {40.0, 38.4, 34.7, 34.4, 34.6}, {31.4, 34.7, 28.6, 30.4, 27.4}};

double published(double delta, double m, bool micro)
{
    for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 5; ++b)
            if (std::abs(delta - table_delta[a]) < 1e-9 && std::abs(m - table_m[b]) < 1e-9)
                return 1e-6 * (micro ? table_micro[a][b] : table_stretch[a][b]);
    return NAN;
}

constexpr double strain_end = 0.002;  // engineering strain at the end of the pull [-]

struct Material { pd::Elastic mat; double rho, Gc, C_hg, rate, dt_factor; bool hourglass_work, lateral_free, grips_inside; };
// The first broken bond: time [s] (NAN: none), wall time [s], distances of its midpoint from the nearer
// end and from the nearest lateral face [m].
struct Fracture { double t, wall, from_end, from_face; };

// Distances of the midpoint of the first broken bond (in CSR order) from the nearer end of the bar
// [x_lo, x_hi] and from the nearest lateral face of the lattice (box() rounds W/dx to whole cells) [m].
std::pair<double, double> first_break_position(const pd::Body<3>& body, const pd::Bonds& bonds, double x_lo, double x_hi)
{
    for (std::size_t i = 0; i < body.size(); ++i)
        for (std::int64_t k = bonds.begin(i); k < bonds.end(i); ++k) {
            if (bonds.intact[k]) continue;
            const pd::Vec<3> mid = 0.5 * (body.x[i] + body.x[bonds.partner[k]]);
            double from_face = HUGE_VAL;  // lateral faces y, z
            for (int a = 1; a < 3; ++a) {
                const auto [lo, hi] = std::minmax_element(body.x.c[a].begin(), body.x.c[a].end());
                from_face = std::min({from_face, mid[a] - (*lo - body.dx / 2), *hi + body.dx / 2 - mid[a]});
            }
            return {std::min(mid[0] - x_lo, x_hi - mid[0]), from_face};
        }
    return {NAN, NAN};
}

// One cell: the bar pulled to strain_end at the given rate, until 5 us after the first broken bond.
Fracture fracture_time(const Material& p, double delta, double m, bool micro, pd::io::Checkpoints& cp)
{
    pd::io::Timer timer;
    const double L = 5e-3, W = 1e-3, dx = delta / m, t_max = strain_end / p.rate;
    // Grips outside the bar [0, Lb] (Lb = L rounded to whole cells, so that both grips have
    // ceil(delta/dx) layers), or the end layers of the bar (--grips inside).
    pd::GrippedBar bar;
    double x_lo = 0, x_hi = std::lround(L / dx) * dx;  // ends of the bar [m]
    double gauge = x_hi, x_protect = x_hi;              // pulled length, reference of the far no-fail zone [m]
    if (p.grips_inside) {
        bar.body = pd::box<3>({{0, 0, 0}}, {{L, W, W}}, dx);
        const double x_max = *std::max_element(bar.body.x.c[0].begin(), bar.body.x.c[0].end());
        x_hi = x_max + dx / 2, gauge = L, x_protect = x_max;  // as this driver computed them before
        for (std::size_t i = 0; i < bar.body.size(); ++i) {
            if (bar.body.x.c[0][i] < delta) bar.left.push_back(static_cast<int>(i));
            if (bar.body.x.c[0][i] > x_max - delta) bar.right.push_back(static_cast<int>(i));
        }
    } else {
        bar = pd::gripped_bar(x_hi, W, W, dx, delta);
    }
    const pd::Body<3>& body = bar.body;
    const pd::NodeSet &left = bar.left, &right = bar.right;
    pd::Bonds bonds = pd::build_bonds(body, delta);
    bonds.enable_damage();
    C3 model({p.mat, C3::Law::linear, p.C_hg}, body, bonds);
    pd::Explicit<3, C3> ex(body, bonds, model, p.rho);
    pd::NodeSet protect;  // no-fail: within 1 mm of each end of the bar, grips included
    for (std::size_t i = 0; i < body.size(); ++i)
        if (body.x.c[0][i] < x_lo + 1e-3 || body.x.c[0][i] > x_protect - 1e-3) protect.push_back(static_cast<int>(i));
    const double u_end = 0.5 * strain_end * gauge;  // grip displacement at t_max [m]
    for (int d = 0; d < (p.lateral_free ? 1 : 3); ++d) {
        const double g = d == 0 ? u_end : 0;
        ex.boundary.prescribe({pd::Prescribed::Kind::displacement, left, d, pd::TimeFunction::ramp(-g, t_max)});
        ex.boundary.prescribe({pd::Prescribed::Kind::displacement, right, d, pd::TimeFunction::ramp(g, t_max)});
    }
    pd::CriticalStretch cs = pd::CriticalStretch::uniform(pd::s0_madenci_oterkus_3d(p.Gc, p.mat, delta));
    pd::CriticalMicropotential<3> mp;
    mp.w_c = pd::w_critical(p.Gc, delta);
    mp.hourglass_work = p.hourglass_work;
    cs.protect(protect, body.size());
    mp.protect(protect, body.size());
    if (micro) ex.scene.set_damage(mp);
    else ex.scene.set_damage(cs);
    const double c = pd::PMB::micromodulus({p.mat, 3}, pd::Influence{}, delta);
    const double dt = p.dt_factor * pd::critical_step_silling_askari(bonds, ex.rho, c).dt;
    double t_break = NAN, from_end = NAN, from_face = NAN;
    auto state = [&](pd::StateArchive& ar) {  // what a checkpoint holds (io/checkpoints.hpp)
        ex.state(ar), timer.state(ar, "wall"), ar("t_break", t_break), ar("from_end", from_end), ar("from_face", from_face);
    };
    cp.loop(std::numeric_limits<long>::max(), state, [&] { ex.start(); }, [&](long) {
        ex.step(dt);
        if (std::isnan(t_break) && ex.broken_bonds > 0) {
            t_break = ex.t;
            std::tie(from_end, from_face) = first_break_position(body, bonds, x_lo, x_hi);
        }
        return ex.t < t_max && (std::isnan(t_break) || ex.t < t_break + 5e-6);  // on until 5 us after the first break
    });
    return {t_break, timer.seconds(), from_end, from_face};
}

int run_case(int argc, char** argv)
{
    // 1. Options (defaults: the thesis' bar, rho and hourglass assumed), echoed and saved.
    pd::io::Case run("delta_m_bar_3d", "Fracture time of a bar vs delta and m (spec/000c V11).", "reports/3d/delta_m_bar");
    pd::io::Options& opt = run.opt;
    opt.add_string("deltas", "", "horizons (default: see header)");
    opt.add_string("ms", "", "ratios m (default: see header)");
    opt.add_flag("full", "all 20 cells of Tables 8.4-8.5");
    opt.add("E", 310e9, "Young's modulus", "Pa");
    opt.add("nu", 0.29, "Poisson's ratio", "-");
    opt.add("rho", 3200, "density (assumed)", "kg/m^3");
    opt.add("Gc", 109.94, "fracture energy G_c = J_C", "J/m^2");
    opt.add("C-hg", 0.02, "hourglass coefficient (assumed)", "-");
    opt.add_flag("no-hourglass-work", "micropotential without the work of the hourglass forces (Peridigm's)");
    opt.add_flag("lateral-free", "grips prescribe the axial displacement only (default: clamped, all three)");
    std::string& grips = opt.add_string("grips", "outside", "grip layers added outside the bar, or the bar's own end layers",
                                        {"outside", "inside"});
    opt.add("rate", 20, "engineering strain rate", "1/s");
    opt.add("dt-factor", 0.5, "safety factor on the Silling-Askari step", "-");
    for (const char* q : {"E", "rho", "Gc", "rate", "dt-factor"}) opt.require_positive(q);
    opt.require_range("nu", -1, 0.5, false, false);
    opt.require_at_least("C-hg", 0);
    run.allow_checkpoints();
    run.parse(argc, argv);
    const bool quick = run.quick(), full = opt.get_flag("full");
    std::vector<std::pair<double, double>> cells;  // (delta, m)
    if (opt.given("deltas") || opt.given("ms")) {
        if (!opt.given("deltas") || !opt.given("ms")) opt.fail("--deltas and --ms go together");
        for (double d : pd::io::list_option(opt, "deltas", pd::io::ListValues::positive))
            for (double m : pd::io::list_option(opt, "ms", pd::io::ListValues::positive)) {
                if (m < 1) opt.fail("--ms values must be >= 1");
                cells.push_back({d, m});
            }
    } else if (quick) {
        cells = {{0.61e-3, 3.05}};
    } else {
        for (double d : table_delta)
            for (double m : table_m)
                if (full || (m == 3.05 && d >= 0.38e-3) || d == 0.61e-3) cells.push_back({d, m});
    }
    run.start();
    const Material p{pd::Elastic::from_E_nu(opt.get("E"), opt.get("nu")), opt.get("rho"), opt.get("Gc"), opt.get("C-hg"),
                     opt.get("rate"), opt.get("dt-factor"), !opt.get_flag("no-hourglass-work"),
                     opt.get_flag("lateral-free"), grips == "inside"};

    // 2-5. Every cell, both criteria.
    pd::io::CsvWriter csv(run.file("fracture_times.csv"), {"delta_m", "m", "criterion", "t_fracture_s", "t_published_s", "rel_error",
                                                           "t_quasi_static_s", "wall_s", "strain_at_fracture", "break_from_end_m",
                                                           "break_from_face_m"});
    std::printf("%-8s %-5s %-8s %10s %10s %8s %10s %8s %9s %7s %7s\n", "delta_mm", "m", "rule", "ours_us", "pub_us", "error", "qs_us", "wall_s",
                "strain", "end_mm", "face_mm");
    std::vector<std::array<double, 3>> m305;  // (delta, t_micro, t_stretch) at m = 3.05
    for (auto [delta, m] : cells) {
        const double t_qs = pd::s0_pmb_3d(p.Gc, p.mat.K, delta) / p.rate;
        std::array<double, 3> row{delta, NAN, NAN};
        for (bool micro : {false, true}) {
            const auto [t, wall, from_end, from_face] = fracture_time(p, delta, m, micro, run.checkpoints());
            const double ref = published(delta, m, micro);
            const char* rule = micro ? "micro" : "stretch";
            std::printf("%-8.2f %-5.2f %-8s %10.2f %10.1f %+7.1f%% %10.1f %8.1f %9.3e %7.2f %7.2f\n", delta * 1e3, m, rule, t * 1e6, ref * 1e6,
                        100 * (t / ref - 1), t_qs * 1e6, wall, t * p.rate, from_end * 1e3, from_face * 1e3);  // signed: ours earlier < 0
            csv.row({delta, m, std::string(rule), t, ref, pd::io::relative_error(t, ref), t_qs, wall, t * p.rate, from_end, from_face});
            char key[64];
            std::snprintf(key, sizeof key, "t_%s_delta%.2fmm_m%.2f_s", rule, delta * 1e3, m);
            run.summary_observed({{key, t, ref, pd::io::relative_error(t, ref), "s"}});
            run.property(!std::isnan(t), std::string(key) + ": the bar breaks before the end of the pull");
            (micro ? row[1] : row[2]) = t;
        }
        if (m == 3.05) m305.push_back(row);
    }

    // 6. Trend of Tables 8.4-8.5: at equal m, the larger delta breaks earlier (both criteria).
    for (std::size_t a = 0; a + 1 < m305.size(); ++a)
        for (std::size_t b = a + 1; b < m305.size(); ++b) {
            if (m305[a][0] == m305[b][0]) continue;
            const auto& [small, large] = m305[a][0] < m305[b][0] ? std::pair{m305[a], m305[b]} : std::pair{m305[b], m305[a]};
            for (int r : {1, 2})
                run.property(large[r] < small[r], std::string(r == 1 ? "micro" : "stretch") + ": larger delta breaks earlier at m = 3.05");
        }
    return run.finish("trend: earlier fracture for larger delta; times against Tables 8.4-8.5 reported, not asserted");
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("delta_m_bar_3d", [&] { return run_case(argc, argv); }); }
