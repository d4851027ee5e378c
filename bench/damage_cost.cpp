// bench/damage_cost.cpp -- per-step cost of the critical-micropotential rule over the critical-stretch
// rule (damage/micropotential.hpp, damage/critical_stretch.hpp) on the scene of notched_plate_3d,
// before any bond breaks (tracker issue 6: micropotential <= 1.3x stretch; source ~1.6-2x).
// Scene: Si3N4 plate 10 x 10 x 1 mm (E 310 GPa, nu 0.29, rho 3200 kg/m^3, J_C = Gc 109.94 J/m^2),
// delta 1.5 mm (as the driver's default), m 3.05, notch of cut bonds at y = 5 mm from x = 0 to 5 mm,
// every bond with damage bookkeeping, no-fail bands 3 mm at both ends, grips (width delta) holding the
// plate at a uniform strain u_y = strain y, started from that strain (default 0.1 x s0 of MO 3D, so no
// bond breaks: checked); dt = 0.5 x Silling-Askari. Models: correspondence (linear law, hourglass 0.02,
// as the driver) and PMB.
// Timed: the whole velocity-Verlet step (Explicit::step: damage apply, force, micropotential
// increments, integration). For each model the stretch run and the micropotential run (same scene,
// model, dt) are alive at once and advance `block` steps in turn, order alternating, `blocks` times;
// the ratio of each block pair t_micro / t_stretch is kept; reported: median and [q25, q75] of the
// block ratios, the median per-step times, the load average at start and end (reports/3d/model_cost.md).
// Run: damage_cost [--models correspondence,pmb] [--delta 1.5e-3] [--m 3.05] [--block 20] [--blocks 100]
//      [--strain-factor 0.1] [--threads 1] [--no-header] [--check]
// Writes one CSV line per model to stdout:
//   model,nodes,bonds,threads,block,blocks,step_stretch_s,step_micro_s,ratio,q25,q75,broken_stretch,broken_micro,load_start,load_end
// --check: exit 1 if a bond broke or a step went unstable (the comparison would not be like for like).
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/options.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr double E_si3n4 = 310e9, nu_si3n4 = 0.29;  // [Pa], [-] (000c sec. 2.6)
constexpr double rho_si3n4 = 3200;                  // [kg/m^3] (ASSUMED, as notched_plate_3d)
constexpr double Jc_si3n4 = 109.94;                 // [J/m^2]
constexpr double side = 10e-3, thick = 1e-3;        // plate [m]
constexpr double no_fail = 3e-3;                    // no-fail band at each gripped end [m]
constexpr double C_hg = 0.02;                       // hourglass coefficient (the driver's)

double load1()
{
    std::ifstream f("/proc/loadavg");
    double l = NAN;
    f >> l;
    return l;
}

struct Scene {
    pd::Body<3> body;
    double delta = 0, dx = 0, y_notch = 0, strain = 0, dt = 0, s0 = 0;
    pd::NodeSet bottom, top, protect;
    pd::Elastic mat = pd::Elastic::from_E_nu(E_si3n4, nu_si3n4);
};

Scene make_scene(double delta, double m, double strain_factor)
{
    Scene s;
    s.delta = delta;
    s.dx = delta / m;
    s.body = pd::box<3>({{0, 0, 0}}, {{side, side, thick}}, s.dx);
    double y_lo = -HUGE_VAL, y_hi = HUGE_VAL;  // notch plane between the node layers nearest y = side/2
    for (double y : s.body.x.c[1]) {
        if (y <= 0.5 * side) y_lo = std::max(y_lo, y);
        else y_hi = std::min(y_hi, y);
    }
    s.y_notch = 0.5 * (y_lo + y_hi);
    for (std::size_t i = 0; i < s.body.size(); ++i) {
        const double y = s.body.x.c[1][i];
        if (y < delta) s.bottom.push_back(static_cast<int>(i));
        if (y > side - delta) s.top.push_back(static_cast<int>(i));
        if (y < no_fail || y > side - no_fail) s.protect.push_back(static_cast<int>(i));
    }
    s.s0 = pd::s0_madenci_oterkus_3d(Jc_si3n4, s.mat, delta);
    s.strain = strain_factor * s.s0;
    const pd::Bonds b = pd::build_bonds(s.body, delta);
    const double c = pd::PMB::micromodulus({s.mat, 3}, pd::Influence{}, delta);
    s.dt = 0.5 * pd::critical_step_silling_askari(b, rho_si3n4, c).dt;
    return s;
}

// One simulation with one damage rule; advance(k) returns the wall time of k steps [s].
template <class Model>
struct Run {
    pd::Bonds bonds;
    std::unique_ptr<Model> model;
    std::unique_ptr<pd::Explicit<3, Model>> ex;
    pd::CriticalStretch cs;
    pd::CriticalMicropotential<3> mp;
    bool unstable = false;

    template <class Make>
    Run(const Scene& s, bool micro, Make make)
    {
        pd::BondOptions notch;  // the notch of notched_plate_3d: bonds crossing it are cut
        notch.keep = pd::cut_by_rectangle(s.body, {{-s.dx, s.y_notch, -s.dx}}, {{0.5 * side + s.dx, 0, 0}}, {{0, 0, thick + 2 * s.dx}});
        bonds = pd::build_bonds(s.body, s.delta, notch);
        bonds.enable_damage();
        model = make(bonds);
        ex = std::make_unique<pd::Explicit<3, Model>>(s.body, bonds, *model, rho_si3n4);
        cs.s0 = s.s0;
        mp.w_c = pd::w_critical(Jc_si3n4, s.delta);
        cs.protect(s.protect, s.body.size());
        mp.protect(s.protect, s.body.size());
        if (micro) ex->scene.set_damage(mp);
        else ex->scene.set_damage(cs);
        for (std::size_t i = 0; i < s.body.size(); ++i) ex->u.c[1][i] = s.strain * (s.body.x.c[1][i] - 0.5 * side);
        for (int d = 0; d < 3; ++d)
            for (const pd::NodeSet* grip : {&s.bottom, &s.top}) {
                const double g = d == 1 ? s.strain * (grip == &s.top ? 0.5 * side : -0.5 * side) : 0;  // held [m]
                ex->boundary.prescribe({pd::Prescribed::Kind::displacement, *grip, d, pd::TimeFunction::constant(g)});
            }
        ex->start();
    }
    double advance(long k, double dt)
    {
        pd::io::Timer timer;
        try {
            for (long n = 0; n < k; ++n) ex->step(dt);
        } catch (const pd::Unstable&) {
            unstable = true;
        }
        return timer.seconds();
    }
};

struct Line {
    std::size_t bonds = 0;
    double step_stretch = 0, step_micro = 0, ratio = 0, q25 = 0, q75 = 0;
    long broken_stretch = 0, broken_micro = 0;
    bool unstable = false;
};

template <class Model, class Make>
Line measure(const Scene& s, Make make, int block, int blocks)
{
    Run<Model> st(s, false, make), mi(s, true, make);
    st.advance(block, s.dt);  // warm-up (first-call allocations)
    mi.advance(block, s.dt);
    std::vector<double> ratio, ts, tm;
    for (int b = 0; b < blocks; ++b) {
        double t_st, t_mi;
        if (b % 2 == 0) { t_st = st.advance(block, s.dt); t_mi = mi.advance(block, s.dt); }
        else { t_mi = mi.advance(block, s.dt); t_st = st.advance(block, s.dt); }
        ratio.push_back(t_mi / t_st);
        ts.push_back(t_st / block);
        tm.push_back(t_mi / block);
    }
    Line l;
    l.bonds = st.bonds.size();
    l.step_stretch = pd::io::quantile(ts, 0.5);
    l.step_micro = pd::io::quantile(tm, 0.5);
    l.ratio = pd::io::quantile(ratio, 0.5);
    l.q25 = pd::io::quantile(ratio, 0.25);
    l.q75 = pd::io::quantile(ratio, 0.75);
    l.broken_stretch = st.ex->broken_bonds;
    l.broken_micro = mi.ex->broken_bonds;
    l.unstable = st.unstable || mi.unstable;
    return l;
}

}  // namespace

int run_bench(int argc, char** argv)
{
    // 1. Options.
    pd::io::Options opt("damage_cost", "Per-step cost of micropotential over critical stretch (notched plate scene).");
    std::string& models = opt.add_string("models", "correspondence,pmb", "comma list of correspondence, pmb");
    double& delta = opt.add("delta", 1.5e-3, "horizon", "m");
    double& m = opt.add("m", 3.05, "horizon ratio delta/dx");
    int& block = opt.add_int("block", 20, "steps per turn");
    int& blocks = opt.add_int("blocks", 100, "turns per rule (block ratios)");
    double& strain_factor = opt.add("strain-factor", 0.1, "held strain / s0 (no bond may break)");
    int& threads = opt.add_int("threads", 1, "OpenMP threads");
    bool& no_header = opt.add_flag("no-header", "omit the CSV header line");
    bool& check = opt.add_flag("check", "exit 1 if a bond broke or a run went unstable");
    opt.require_positive("delta");
    opt.require_at_least("m", 1);
    opt.require_at_least("block", 1);
    opt.require_at_least("blocks", 1);
    opt.require_positive("strain-factor");
    opt.require_at_least("threads", 1);
    opt.parse(argc, argv);
    std::vector<std::string> names;
    {
        std::stringstream ss(models);
        for (std::string w; std::getline(ss, w, ',');) {
            if (w != "correspondence" && w != "pmb") opt.fail("--models: unknown model '" + w + "'");
            names.push_back(w);
        }
    }
    pd::set_threads(threads);

    // 2. Scene, then per model the interleaved measurement; one CSV line each.
    const Scene s = make_scene(delta, m, strain_factor);
    if (!no_header)
        std::printf("model,nodes,bonds,threads,block,blocks,step_stretch_s,step_micro_s,ratio,q25,q75,broken_stretch,broken_micro,load_start,load_end\n");
    bool ok = true;
    for (const std::string& name : names) {
        const double l0 = load1();
        Line l;
        if (name == "correspondence") {
            using C = pd::Correspondence<3>;
            l = measure<C>(s, [&](const pd::Bonds& b) { return std::make_unique<C>(C::Params{s.mat, C::Law::linear, C_hg}, s.body, b); },
                           block, blocks);
        } else {
            l = measure<pd::PMB>(s, [&](const pd::Bonds& b) { return std::make_unique<pd::PMB>(pd::PMB::Params{s.mat, 3}, b); },
                                 block, blocks);
        }
        std::printf("%s,%zu,%zu,%d,%d,%d,%.4e,%.4e,%.4f,%.4f,%.4f,%ld,%ld,%.2f,%.2f\n", name.c_str(), s.body.size(), l.bonds, threads, block,
                    blocks, l.step_stretch, l.step_micro, l.ratio, l.q25, l.q75, l.broken_stretch, l.broken_micro, l0, load1());
        std::fflush(stdout);
        ok = ok && l.broken_stretch == 0 && l.broken_micro == 0 && !l.unstable;
    }
    if (!ok) std::fprintf(stderr, "damage_cost: a bond broke or a run went unstable: the comparison is not like for like\n");
    return check && !ok ? 1 : 0;
}

int main(int argc, char** argv) { return pd::io::guarded_main("damage_cost", [&] { return run_bench(argc, argv); }); }
