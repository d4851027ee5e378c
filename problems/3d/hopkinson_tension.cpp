// problems/3d/hopkinson_tension.cpp -- dynamic tension of a 316L dog-bone in a split Hopkinson bar,
// strongly coupled thermo-mechanics (Biondani 2018 sec. 9.1; spec/000c sec. 3, Tables 9.1-9.4, V15, V18).
// The scene (specimen, constraints, physics, measurements) is problems/common/hopkinson_scene.hpp.
// Events: necking onset = the maximum of the end force averaged over +-5 us (Considere); fracture start
// = first node of the damage block with damage >= 0.5; fracture end = separation, the first sample at
// which no chain of intact bonds joins the two constraint layers. The run ends --after-separation
// (1 us) later, or at --t-end: at delta = 1 mm the fragments of the fracture zone (heated past melting,
// detached by the singular-node rule) reached km/s within 2 us of the separation and the run diverged,
// so nothing after it is kept (page: reports/3d/hopkinson_tension.md).
// Reference before necking (reference/j2_plasticity.hpp, no library code): a uniform adiabatic
// Johnson-Cook bar in uniaxial stress at the imposed rate, its force per reference area P at the
// measured gauge strain and its temperature at the measured local strain of the centreline's middle
// node, compared with the averaged engineering stress and the mid-section mean temperature at 44, 77
// and 110 us. Published: Table 9.1 (experiment) and sec. 9.1.3 (the thesis' PD run at 1 mm).
// Run: hopkinson_tension_3d [--delta 1e-3] [--t-end 250e-6] [--conduction off|on] [--nsync-mk 1]
//   [--nsync-mh 1] [--quick] [--check] [--out DIR] (--help: all).
// Writes: history.csv (samples), centreline.csv (profiles at --profile-times), curve.csv (stress and
// temperature against strain up to fracture start, PD and the uniform bar), summary.csv, params.csv.
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/core/timer.hpp"
#include "problems/common/hopkinson_scene.hpp"
#include "reference/j2_plasticity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace {

using Sample = pd::HopkinsonSample;

// Index of the sample nearest t (the samples are in time order).
std::size_t at(const std::vector<Sample>& s, double t)
{
    std::size_t best = 0;
    for (std::size_t k = 0; k < s.size(); ++k) if (std::abs(s[k].t - t) < std::abs(s[best].t - t)) best = k;
    return best;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI and degrees Celsius; defaults = Table 9.2 and sec. 9.1.2), echoed and saved.
    pd::io::Case run("hopkinson_tension_3d", "316L dog-bone in a tension Hopkinson bar: J-C plasticity, heating, micropotential (spec/000c V15).",
                     "reports/3d/hopkinson_tension");
    pd::io::Options& opt = run.opt;
    pd::add_hopkinson_options(opt);
    double& t_end = opt.add("t-end", 250e-6, "duration", "s");
    std::string& conduction = opt.add_string("conduction", "off", "Agwai conduction (the source drops it after the Table 9.3 study)", {"off", "on"});
    int &nsync_mk = opt.add_int("nsync-mk", 1, "mechanical steps per conduction step, N_sync(MK)"),
        &nsync_mh = opt.add_int("nsync-mh", 1, "mechanical steps per release of the plastic heat, N_sync(MH)");
    int& sample = opt.add_int("sample", 10, "steps between samples");
    double& after_sep = opt.add("after-separation", 1e-6, "run on for this long after the specimen separates (header)", "s");
    opt.add_string("profile-times", "44,77,110,144,177", "centreline profile instants [us] (Fig. 9.14)");
    opt.require_positive("t-end");
    opt.require_at_least("after-separation", 0);
    for (const char* o : {"nsync-mk", "nsync-mh", "sample"}) opt.require_at_least(o, 1);
    run.allow_checkpoints();
    run.parse(argc, argv);
    run.quick_default("delta", 2e-3);
    const std::vector<double> profile_us = pd::io::list_option(opt, "profile-times", pd::io::ListValues::positive);
    pd::HopkinsonParams par = pd::hopkinson_params(opt);
    par.conduction = conduction == "on", par.nsync_mk = nsync_mk, par.nsync_mh = nsync_mh;
    run.start();
    const std::filesystem::path& out = run.out();

    // 2.-3. The dog-bone, its node sets and the coupled scene (hopkinson_scene.hpp).
    pd::HopkinsonScene hs(par);
    const pd::Body<3>& body = hs.d.body;
    const std::size_t N = body.size();
    pd::require_steps(std::round(t_end / hs.dt), "--t-end / dt");
    const long steps = std::lround(t_end / hs.dt);
    const double dt = hs.dt, T_ref = par.jc.theta_ref;
    const pd::laws::JohnsonCook& jc = par.jc;
    hs.print();
    std::printf("%ld steps\n", steps);

    // 4. The run: samples, centreline profiles at the given instants.
    pd::io::CsvWriter hist(out / "history.csv", {"t_s", "bar_strain", "eps_gauge", "F_N", "sigma_eng_Pa", "T_mid_C", "T_centre_C", "T_max_line_C",
                                                 "eps_max_line", "damage_max", "broken_bonds"});
    pd::io::CsvWriter prof(out / "centreline.csv", {"t_us", "x_m", "T_C", "eps_xx", "ep", "damage"});
    std::vector<Sample> S;
    long next_profile = 0;
    double t_break = NAN;  // separation: the two constraint layers no longer joined by intact bonds [s]
    pd::io::Timer timer;
    double wall_steps = 0;
    long steps_here = 0;  // steps taken by this process (a resumed run: since the resume)
    bool unstable = false;
    auto state = [&](pd::StateArchive& ar) {
        hs.ex.state(ar), hist.state(ar), prof.state(ar), timer.state(ar, "wall"), ar.records("samples", S), ar("next_profile", next_profile);
        ar("t_separation", t_break);
    };
    try {
        run.checkpoints().loop(steps, state, [&] { hs.ex.start(); }, [&](long n) {
            pd::io::Timer step_timer;
            hs.ex.step(dt);
            wall_steps += step_timer.seconds(), ++steps_here;
            const std::size_t np = static_cast<std::size_t>(next_profile);
            const bool profile = np < profile_us.size() && hs.ex.t >= profile_us[np] * 1e-6 - 0.5 * dt;
            if (n % sample != 0 && n != steps && !profile) return true;
            const std::vector<double> phi = pd::point_damage(hs.bonds);
            const Sample s = hs.sample(phi);
            S.push_back(s);
            if (std::isnan(t_break) && s.phi_max >= 0.5 && !hs.ends_connected()) t_break = s.t;
            hist.row({s.t, 3000 * s.t, s.eps_g, s.F, s.F / hs.section, s.T_mid, s.T_centre, s.T_line, s.eps_line, s.phi_max,
                      double(hs.ex.broken_bonds)});
            if (profile) {
                for (std::size_t q = 0; q < hs.line.size(); ++q) {
                    const int i = hs.line[q];
                    prof.row({profile_us[np], body.x.c[0][i], hs.field->theta[i], hs.local_strain(q), hs.model.pts.ep_c[i], phi[i]});
                }
                ++next_profile;
            }
            return !(hs.ex.t >= t_break + after_sep);  // the run ends after_sep after the separation
        });
    } catch (const pd::Unstable& e) {
        std::printf("%s\n", e.what());
        unstable = true;
    }
    const double wall = timer.seconds();
    const double us_per_node_step = wall_steps * 1e6 * pd::max_threads() / (double(std::max(steps_here, 1L)) * double(N));

    // 5. Events (header), the uniform-bar reference before necking, summary and checks.
    std::vector<double> Fs(S.size());  // force averaged over +-5 us
    for (std::size_t q = 0; q < S.size(); ++q) {
        double sum = 0;
        int cnt = 0;
        for (const Sample& s : S) if (std::abs(s.t - S[q].t) <= 5e-6) sum += s.F, ++cnt;
        Fs[q] = sum / cnt;
    }
    double t_start = NAN, t_neck = NAN;
    std::size_t q_start = S.size();
    for (std::size_t q = 0; q < S.size() && q_start == S.size(); ++q) if (S[q].phi_max >= 0.5) q_start = q, t_start = S[q].t;
    const std::size_t q_peak = std::max_element(Fs.begin(), Fs.begin() + static_cast<long>(q_start)) - Fs.begin();
    if (q_peak < S.size()) t_neck = S[q_peak].t;
    const std::vector<pd::ref::UniaxialState> ref = pd::ref::adiabatic_uniaxial_jc(
        par.mat.E(), par.mat.nu(), {jc.A, jc.B, jc.n, jc.C, jc.epdot0}, {jc.m, jc.theta_ref, jc.theta_melt}, par.beta, par.rho * par.c, par.alpha,
        jc.theta_ref, par.rate, 1.0, 20000);
    auto ref_at = [&](double eps, auto member) {  // linear interpolation of the reference in strain
        const std::size_t j = std::min<std::size_t>(ref.size() - 1, std::max<std::size_t>(1, std::size_t(eps / ref[0].eps)));
        const double w = (eps - ref[j - 1].eps) / (ref[j].eps - ref[j - 1].eps);
        return (1 - w) * ref[j - 1].*member + w * ref[j].*member;
    };
    pd::io::CsvWriter curve(run.file("curve.csv"), {"source", "eps_gauge", "eps_centre", "sigma_eng_Pa", "T_C"});  // up to fracture start
    for (std::size_t q = 0; q < q_start; ++q) curve.row({"pd", S[q].eps_g, S[q].eps_c, Fs[q] / hs.section, S[q].T_mid});
    const double eps_last = q_start > 0 ? std::max(S[q_start - 1].eps_g, S[q_start - 1].eps_c) : 0;
    for (std::size_t j = 99; j < ref.size() && ref[j].eps <= eps_last; j += 100) curve.row({"uniform_bar", ref[j].eps, ref[j].eps, ref[j].P, ref[j].theta});
    std::printf("\nnecking onset %.1f us (experiment 145), fracture %.1f -> %.1f us (experiment 145 -> 197; thesis PD 129 -> 188)\n",
                t_neck * 1e6, t_start * 1e6, t_break * 1e6);
    std::printf("%8s %10s %12s %12s %9s %9s %9s %9s\n", "t_us", "eps_gauge", "sigma_Pa", "P_ref_Pa", "eps_c", "T_mid_C", "T_ref_C", "in");
    for (double tp : {44e-6, 77e-6, 110e-6}) {
        const std::string tag = std::to_string(std::lround(tp * 1e6)) + "us";
        if (S.empty() || tp > S.back().t) {  // the run ended before
            run.summary({pd::io::not_measured("sigma_eng_" + tag, NAN, "Pa"), pd::io::not_measured("T_rise_mid_" + tag, NAN, "K")});
            continue;
        }
        const std::size_t q = at(S, tp);
        const bool before = std::isnan(t_neck) || S[q].t < t_neck;
        const double sig = Fs[q] / hs.section, P = ref_at(S[q].eps_g, &pd::ref::UniaxialState::P);
        const double T_uni = ref_at(S[q].eps_c, &pd::ref::UniaxialState::theta);  // at the local centre strain
        std::printf("%8.1f %10.4f %12.5e %12.5e %9.4f %9.2f %9.2f %9s\n", S[q].t * 1e6, S[q].eps_g, sig, P, S[q].eps_c, S[q].T_mid, T_uni,
                    before ? "pre-neck" : "necked");
        if (before) {  // the uniform bar is the reference of the uniform gauge only
            run.summary({{"sigma_eng_" + tag, sig, P, pd::io::relative_error(sig, P), "Pa"},
                         {"T_rise_mid_" + tag, S[q].T_mid - T_ref, T_uni - T_ref, pd::io::relative_error(S[q].T_mid - T_ref, T_uni - T_ref), "K"}});
        } else {
            run.summary({pd::io::not_measured("sigma_eng_" + tag, P, "Pa"), pd::io::not_measured("T_rise_mid_" + tag, T_uni - T_ref, "K")});
        }
    }
    auto val = [&](double t, double Sample::*mem) { return std::isnan(t) ? NAN : S[at(S, t)].*mem; };
    run.summary_observed({{"t_necking", t_neck, 145e-6, pd::io::relative_error(t_neck, 145e-6), "s"},
                          {"t_fracture_start", t_start, 129e-6, pd::io::relative_error(t_start, 129e-6), "s"},
                          {"t_fracture_end", t_break, 188e-6, pd::io::relative_error(t_break, 188e-6), "s"},
                          {"x_fracture_start", val(t_start, &Sample::x_phi_max), NAN, NAN, "m"},
                          {"strain_fracture_start", val(t_start, &Sample::eps_line), 0.35, pd::io::relative_error(val(t_start, &Sample::eps_line), 0.35), "-"},
                          {"T_max_necking", val(t_neck, &Sample::T_line), 88, pd::io::relative_error(val(t_neck, &Sample::T_line), 88), "C"},
                          {"T_max_rupture", val(t_break, &Sample::T_line), 375, pd::io::relative_error(val(t_break, &Sample::T_line), 375), "C"}});
    run.summary({{"us_per_node_step", us_per_node_step, 84.1, NAN, "us"},
                 {"nodes", double(N), 71256, NAN, "-"},
                 {"threads", double(pd::max_threads()), NAN, NAN, "-"},
                 {"cells_across_gauge", std::round(par.shape.gauge_width / hs.d.hy), NAN, NAN, "-"},
                 {"cells_through_thickness", std::round(par.shape.thickness / hs.d.hz), NAN, NAN, "-"},
                 {"steps", double(hs.ex.step_count), 9432, NAN, "-"},
                 {"wall", wall, 7065, NAN, "s"}});
    run.property(!unstable, "the run stays stable");
    run.property(!S.empty() && S.back().T_mid > T_ref, "the gauge centre heats");
    return run.finish("%zu nodes, %ld steps, %.1f us per node-step per core", N, hs.ex.step_count, us_per_node_step);
}

int main(int argc, char** argv) { return pd::io::guarded_main("hopkinson_tension_3d", [&] { return run_case(argc, argv); }); }
