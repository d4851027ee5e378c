// problems/1d/thermoelastic_bar.cpp -- a bar clamped at both ends and heated at one: PD thermo-mechanics
// on two clocks against classical thermoelasticity (spec/000a sec. 2.11, 3.3.4-3.3.5; issue 20).
// Case: bar [0, L] at T0, clamped at both ends; the end x = 0 rises to T0 + dT as dT r(t),
//   r = s^3 (10 - 15 s + 6 s^2), s = t/t_r (smooth: a step would ring at every mode for ever, as nothing
//   damps it), the end x = L stays at T0. Cell-centred nodes x_i = (i + 1/2) dx, dx = L/N, delta = m dx,
//   half the volume for the neighbour at |xi| = delta (PartialVolume::pa_pdlammps: the 1D sums of PMB and
//   Agwai then equal their continuum integrals); each end is a layer of m cells outside the bar, held at
//   u = 0 and at its temperature. PMB or LPS (1D) with the thermal strain alpha (T - T0), Agwai conduction
//   (explicit Euler), velocity Verlet; one thermal step of N_sync(MK) dt_mech every N_sync(MK) mechanical
//   steps, before the forces (scene.hpp). An elastic bar dissipates nothing: N_sync(MH) plays no part.
// Reference: reference/thermoelastic_bar.hpp, the classical equations rho u_tt = E u_xx - E alpha theta_x,
//   rho c theta_t = k theta_xx semi-discretised on M cells and integrated by ARKODE MRIStep (mechanics
//   fast, heat slow); checked against the same system by monolithic CVODE and against M/2 cells.
// Quantities: the wall stress sigma_end (mean of the two walls' reactions per unit area: the PD layer
//   forces, the classical sigma_(1/2) and sigma_(M-1/2)) and T_mid (x = L/2), histories and values at
//   t_end. Error of a history: max over the samples of |PD - reference|, relative to max |reference|
//   for the stress and to dT for T_mid.
// Default parameters: steel (E 200 GPa, rho 7800, alpha 1.2e-5, cv 500) with k = 1e4 W/(m K), 200 times
//   steel's, so that the thermal critical step is ~400 mechanical steps at N = 100 and the heat reaches
//   the middle within t_end = 10 ms (about 2,500 wave transits); L = 20 mm, dT = 100 K, t_r = 1 ms.
// Run: thermoelastic_bar_1d [--model pmb|lps|both] [--N 100] [--m 3] [--nsync-mk 0] [--dt-factor 0.8]
//   [--E --rho --alpha --k --cv --L --dT --ramp --t-end] [--quick] [--check]; --nsync-mk 0: the study
//   N_sync(MK) = 1, 10, 100, 1000 and a monolithic run (N_sync 1 at dt/10), and the N study.
// Writes: history.csv, nsync.csv, convergence.csv, reference.csv, summary.csv, params.csv.
#include "pd/core/lattice.hpp"
#include "pd/core/timer.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/io/case.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/time/verlet.hpp"
#include "reference/thermoelastic_bar.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

struct Bar {
    double E, rho, alpha, k, cv, L, dT, ramp, t_end;  // SI
    int m, samples;                                   // delta/dx; samples of a history
};
constexpr double T0 = 293.15, area = 1e-4;  // [K], [m^2] (1D: cancels in every quantity reported)

struct Outcome {
    std::string model, status = "stable";
    int N = 0, nsync = 0;
    long steps = 0, thermal_steps = 0;  // mechanical and thermal steps taken
    double dt = 0, dt_heat_crit = 0, wall_s = 0;
    std::vector<double> t{}, stress{}, T_mid{};  // samples [s], [Pa], [K above T0]
};

// The hot end's r(t) of the header.
double rise(double t, double t_r)
{
    const double s = t_r > 0 ? std::clamp(t / t_r, 0.0, 1.0) : 1.0;
    return s * s * s * (10 - 15 * s + 6 * s * s);
}

// One PD run: N cells, N_sync(MK) = nsync, dt_mech = t_end / steps.
Outcome run_pd(const Bar& b, const std::string& name, int N, int nsync, long steps)
{
    const pd::io::Timer timer;
    Outcome o{.model = name, .N = N, .nsync = nsync, .steps = steps, .dt = b.t_end / double(steps)};
    const double dx = b.L / N, delta = b.m * dx;
    const pd::Body<1> body = pd::box<1>({-delta}, {b.L + delta}, dx, area);
    pd::Bonds bonds = pd::build_bonds(body, delta, {.partial_volume = pd::PartialVolume::pa_pdlammps, .keep = {}});
    const auto hot = pd::select<1>(body, [](const pd::Vec<1>& p) { return p[0] < 0; }, "hot layer");
    const auto cold = pd::select<1>(body, [&](const pd::Vec<1>& p) { return p[0] > b.L; }, "cold layer");
    pd::HeatLoads loads;
    for (int i : hot) loads.fixed.push_back(i), loads.fixed_value.push_back(T0 + b.dT);
    for (int i : cold) loads.fixed.push_back(i), loads.fixed_value.push_back(T0);
    loads.fixed_at = [&](std::size_t f, double t) { return f < hot.size() ? T0 + b.dT * rise(t, b.ramp) : T0; };
    auto field = pd::make_temperature_field(pd::Agwai({.k = b.k, .measure = area}, body, bonds), bonds,
                                            std::vector<double>(body.size(), b.rho * b.cv), loads,
                                            std::vector<double>(body.size(), T0), pd::HeatIntegrator::explicit_euler, nsync * o.dt);
    o.dt_heat_crit = field->critical_step();
    field->after_step = [&](const pd::TemperatureField& f) {  // explicit Euler keeps T in [T0, T0 + dT] while stable
        for (std::size_t i = 0; i < f.theta.size(); ++i)
            if (!(f.theta[i] >= T0 - 1e-6 * b.dT && f.theta[i] <= T0 + b.dT * (1 + 1e-6)))
                throw pd::Unstable("heat unstable at thermal step " + std::to_string(f.step) + ", node " + std::to_string(i) +
                                       ": T = " + std::to_string(f.theta[i]) + " K",
                                   f.step, static_cast<int>(i));
    };
    auto go = [&](auto model) {
        using M = decltype(model);
        model.set_thermal_expansion({b.alpha, T0, &field->theta});
        pd::Scene<1, M> scene(body, bonds, model);
        scene.set_heat(*field);
        pd::Explicit<1, M> sim(scene, b.rho);
        sim.boundary.fix(hot), sim.boundary.fix(cold), sim.start();
        auto sample = [&] {  // wall reactions per unit area, compression negative; T_mid between the middle nodes
            const auto& f = sim.internal_force_density();
            double left = 0, right = 0;
            for (int i : hot) left += f.c[0][i] * body.volume[i] / area;
            for (int i : cold) right -= f.c[0][i] * body.volume[i] / area;
            const int a = b.m + (N - 1) / 2, c = b.m + N / 2;
            o.t.push_back(sim.t), o.stress.push_back(0.5 * (left + right));
            o.T_mid.push_back(0.5 * (field->theta[a] + field->theta[c]) - T0);
        };
        sample();
        try {
            for (long s = 1; s <= steps; ++s) {
                sim.step(o.dt);
                if (s % (steps / b.samples) == 0) sample();  // steps: a multiple of 1000
            }
        } catch (const pd::Unstable& u) {
            o.status = std::string("unstable: ").append(u.what());
        }
        o.thermal_steps = field->step;
        if (o.status == "stable" && nsync * o.dt > o.dt_heat_crit) o.status = "above the thermal critical step (no blow-up within the run)";
    };
    const pd::Elastic mat = pd::Elastic::from_E_nu(b.E, 0.25);  // 1D: only E enters
    name == "lps" ? go(pd::LPS({.material = mat, .dim = 1}, bonds)) : go(pd::PMB({.material = mat, .dim = 1, .measure = area}, bonds));
    o.wall_s = timer.seconds();
    return o;
}

// max_j |a_j - b_j| / scale over the common samples (nan when a run stopped early).
double history_error(const std::vector<double>& a, const std::vector<double>& b, double scale)
{
    double e = a.size() == b.size() ? 0.0 : NAN;
    for (std::size_t j = 0; j < std::min(a.size(), b.size()); ++j) e = std::max(e, std::abs(a[j] - b[j]));
    return e / scale;
}
// sigma_end of a reference history: the mean of the two walls [Pa].
std::vector<double> wall_stress(const pd::ref::ThermoelasticHistory& h)
{
    std::vector<double> s(h.t_s.size());
    for (std::size_t j = 0; j < s.size(); ++j) s[j] = 0.5 * (h.stress_left[j] + h.stress_right[j]);
    return s;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    pd::io::Case run("thermoelastic_bar_1d", "Clamped bar heated at one end: PD thermo-mechanics on two clocks vs classical thermoelasticity.",
                     "reports/1d/thermoelastic_bar");
    pd::io::Options& opt = run.opt;
    const double &E = opt.add("E", 200e9, "Young's modulus", "Pa"), &rho = opt.add("rho", 7800, "density", "kg/m^3");
    const double& alpha = opt.add("alpha", 1.2e-5, "linear thermal expansion coefficient", "1/K");
    const double& k = opt.add("k", 1e4, "thermal conductivity (200 x steel's: see header)", "W/(m K)");
    const double &cv = opt.add("cv", 500, "specific heat", "J/(kg K)"), &L = opt.add("L", 0.02, "bar length", "m");
    const double& dT = opt.add("dT", 100, "temperature rise of the hot end", "K");
    const double &ramp = opt.add("ramp", 1e-3, "duration t_r of the hot end's rise", "s"), &t_end = opt.add("t-end", 0.01, "end time", "s");
    const std::string& model = opt.add_string("model", "both", "PD model", {"pmb", "lps", "both"});
    const int &N = opt.add_int("N", 100, "cells along the bar (even)"), &m = opt.add_int("m", 3, "horizon ratio delta/dx");
    const int& nsync = opt.add_int("nsync-mk", 0, "mechanical steps per thermal step; 0 = the study 1, 10, 100, 1000");
    const double& dt_factor = opt.add("dt-factor", 0.8, "mechanical step / Silling-Askari critical step");
    const int& ref_cells = opt.add_int("ref-cells", 200, "cells of the classical reference (even)");
    for (const char* p : {"E", "rho", "alpha", "k", "cv", "L", "dT", "t-end", "dt-factor"}) opt.require_positive(p);
    opt.require_at_least("N", 4), opt.require_at_least("m", 1), opt.require_at_least("nsync-mk", 0), opt.require_at_least("ref-cells", 8);
    run.time_scale_set_by("--t-end, --N, --k, --E, --rho");
    run.parse(argc, argv);
    run.quick_default("N", 50), run.quick_default("ref-cells", 100), run.quick_default("t-end", 0.004);
    run.start();
    if (N % 2 || ref_cells % 2 || !(ramp >= 0)) throw std::invalid_argument("options --N and --ref-cells must be even, --ramp >= 0");
    const Bar b{E, rho, alpha, k, cv, L, dT, ramp, t_end, m, 100};
    const std::vector<std::string> models = model == "both" ? std::vector<std::string>{"pmb", "lps"} : std::vector<std::string>{model};

    // 1. Mechanical step: dt_factor x Silling-Askari with the 1D PMB micromodulus, the step count a
    //    multiple of 1000 so that every N_sync of the study divides it (the same dt for all).
    auto steps_for = [&](int n) {
        const double dx = b.L / n, delta = m * dx;
        const double c = pd::PMB::micromodulus({.material = pd::Elastic::from_E_nu(b.E, 0.25), .dim = 1, .measure = area}, pd::Influence{}, delta);
        const pd::Body<1> body = pd::box<1>({-delta}, {b.L + delta}, dx, area);
        const pd::Bonds bonds = pd::build_bonds(body, delta, {.partial_volume = pd::PartialVolume::pa_pdlammps, .keep = {}});
        const double dt_sa = pd::critical_step_silling_askari(bonds, b.rho, c).dt;
        return 1000 * static_cast<long>(std::ceil(t_end / (dt_factor * dt_sa) / 1000));
    };

    // 2. The classical reference (MRIStep on ref_cells), its grid check (half the cells) and the monolithic CVODE run.
    std::vector<double> t_out;  // the samples: every steps/100 mechanical steps
    const long steps = steps_for(N);
    for (long s = 0; s <= steps; s += steps / b.samples) t_out.push_back(b.t_end * double(s) / double(steps));
    pd::ref::ThermoelasticBar cb{b.L, b.E, b.rho, b.alpha, b.k, b.cv, b.dT, b.ramp, ref_cells};
    const auto ref = pd::ref::thermoelastic_bar_mri(cb, t_out, 1.0);
    cb.cells = ref_cells / 2;
    const auto coarse = pd::ref::thermoelastic_bar_mri(cb, t_out, 1.0), mono = pd::ref::thermoelastic_bar_cvode(cb, t_out, 1e-8);
    const std::vector<double> ref_stress = wall_stress(ref), mono_stress = wall_stress(mono);
    const double s_scale = std::abs(*std::ranges::max_element(ref_stress, {}, [](double v) { return std::abs(v); }));  // max |sigma_ref|
    const double e_int = history_error(wall_stress(coarse), mono_stress, s_scale);
    pd::io::CsvWriter rc(run.file("reference.csv"), {"integrator", "cells", "fast_steps", "slow_steps", "wall_s", "stress_diff_vs_finest",
                                                     "T_mid_diff_vs_finest", "stress_diff_vs_cvode"});
    for (const auto* h : {&ref, &coarse, &mono})
        rc.row({h == &mono ? "cvode" : "mristep", h == &ref ? ref_cells : cb.cells, h->fast_steps, h->slow_steps, h->wall_s,
                history_error(wall_stress(*h), ref_stress, s_scale), history_error(h->T_mid, ref.T_mid, b.dT), history_error(wall_stress(*h), mono_stress, s_scale)});
    run.check(e_int < 1e-4, "reference: MRIStep and monolithic CVODE agree on the stress history within 1e-4 of its maximum");
    run.check(history_error(coarse.T_mid, mono.T_mid, b.dT) < 1e-6, "reference: MRIStep and CVODE agree on T_mid within 1e-6 dT");

    // 3. The N_sync study at N (or the one N_sync given), per model, beside the monolithic run (heat every
    //    step at dt/10); history.csv holds every run's samples.
    pd::io::CsvWriter hist(run.file("history.csv"), {"run", "t_s", "stress_Pa", "T_mid_K", "stress_ref_Pa", "T_mid_ref_K"});
    for (std::size_t j = 0; j < t_out.size(); ++j) hist.row({"reference", t_out[j], ref_stress[j], ref.T_mid[j], ref_stress[j], ref.T_mid[j]});
    pd::io::CsvWriter ns(run.file("nsync.csv"), {"model", "N", "nsync_mk", "dt_mech_s", "dt_heat_s", "dt_heat_crit_s", "steps", "thermal_steps",
                                                 "stress_error", "T_mid_error", "stress_error_vs_monolithic", "wall_s", "status"});
    auto errors = [&](const Outcome& o) { return std::make_pair(history_error(o.stress, ref_stress, s_scale), history_error(o.T_mid, ref.T_mid, b.dT)); };
    auto record = [&](const Outcome& o, const std::string& run_name, const Outcome* mono_pd) {
        const auto [es, eT] = errors(o);
        const double em = mono_pd ? history_error(o.stress, mono_pd->stress, s_scale) : 0.0;
        ns.row({o.model, o.N, o.nsync, o.dt, o.nsync * o.dt, o.dt_heat_crit, o.steps, o.thermal_steps, es, eT, em, o.wall_s, o.status});
        std::printf("  %-4s N %-4d N_sync %-4d dt %.3g s: stress error %.3e, T_mid error %.3e, vs monolithic %.3e, %.2f s  %s\n",
                    o.model.c_str(), o.N, o.nsync, o.dt, es, eT, em, o.wall_s, o.status.c_str());
        if (o.t.size() == t_out.size())
            for (std::size_t j = 0; j < t_out.size(); ++j) hist.row({run_name, o.t[j], o.stress[j], o.T_mid[j], ref_stress[j], ref.T_mid[j]});
    };
    const std::vector<int> study = nsync > 0 ? std::vector<int>{nsync} : std::vector<int>{1, 10, 100, 1000};
    for (const std::string& name : models) {
        const Outcome mono_pd = run_pd(b, name, N, 1, 10 * steps);
        record(mono_pd, name + "_monolithic", nullptr);
        int largest = 0;
        for (int q : study) {
            const Outcome o = run_pd(b, name, N, q, steps);
            record(o, name + "_nsync" + std::to_string(q), &mono_pd);
            if (o.status == "stable") largest = std::max(largest, q);
            if (q * o.dt <= o.dt_heat_crit)
                run.check(o.status == "stable", name + ": N_sync(MK) " + std::to_string(q) + " within the thermal critical step runs stable");
            if (q != study.front() || o.status != "stable") continue;
            const std::string tag = name == models.front() ? "" : name + "_";  // the first model's rows: stress_end, T_mid
            run.summary({tag + "stress_end", o.stress.back(), ref_stress.back(), pd::io::relative_error(o.stress.back(), ref_stress.back()), "Pa"});
            run.summary({tag + "T_mid", o.T_mid.back(), ref.T_mid.back(), pd::io::relative_error(o.T_mid.back(), ref.T_mid.back()), "K"});
        }
        // Largest stable N_sync of the study beside the Gershgorin bound dt_heat_crit/dt (explicit Euler).
        run.summary({name + "_nsync_max_stable", double(largest), std::floor(mono_pd.dt_heat_crit / (10 * mono_pd.dt)), NAN, "-"});
    }

    // 4. delta convergence (m fixed): N/2, N, 2N (even ones) at N_sync(MK) 10, against the reference.
    pd::io::CsvWriter conv(run.file("convergence.csv"), {"model", "N", "dx_m", "delta_m", "stress_error", "T_mid_error", "wall_s"});
    for (const std::string& name : models) {
        std::vector<double> es;
        for (int n : {N / 2, N, 2 * N}) {
            if (n < 4 || n % 2) continue;
            const Outcome o = run_pd(b, name, n, 10, steps_for(n));  // steps a multiple of 1000: the same sample times
            const auto [e_s, e_T] = errors(o);
            es.push_back(e_s);
            conv.row({name, n, b.L / n, m * b.L / n, e_s, e_T, o.wall_s});
            std::printf("  %-4s N %-4d (delta %.3g mm): stress error %.3e, T_mid error %.3e, %.2f s\n", name.c_str(), n, 1e3 * m * b.L / n, e_s, e_T, o.wall_s);
        }
        if (es.size() >= 2) run.property(es.back() < es.front(), name + ": the stress error falls with delta (m fixed)");
    }
    return run.finish("wall stress at t_end: classical %.4g Pa; PD per model and N_sync in nsync.csv", ref_stress.back());
}

int main(int argc, char** argv) { return pd::io::guarded_main("thermoelastic_bar_1d", [&] { return run_case(argc, argv); }); }
