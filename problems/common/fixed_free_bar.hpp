// problems/common/fixed_free_bar.hpp -- the fixed-free bar released from uniform strain (bar_modes_1d;
// seed 000b sec. 4.5): one PD run, and its integrators side by side.
// Specimen: bar [0, l], section A, cell-centred nodes x_i = (i + 1/2) dx, dx = l/N, delta = m dx,
//   families |xi| <= delta; the clamp is a layer of m cells outside the bar, x in [-delta, 0), held
//   at u = 0; the bar is released from rest at u = eps0 x.
// Run: LPS or PMB in 1D (only E enters), velocity Verlet (time/verlet.hpp) or Newmark (beta 1/4,
//   gamma 1/2, time/newmark.hpp) at dt_max = dt_scale x dt_SA, dt_SA the Silling-Askari step
//   (time/critical_step.hpp) with the 1D PMB micromodulus; k = floor(1/(f1 samples dt_max)) steps per
//   tip sample, n_out = ceil(t_end/(k dt_max)) samples and dt = t_end/(k n_out) (t_end a whole number
//   of samples; guarded runs keep dt = dt_max). At each sample the tip (last node, x = l - dx/2) and
//   the largest energy ratio (kinetic + strain)/initial; pd::Unstable (beyond 10 x the initial
//   energy) ends a guarded run (stability study) and is recorded, else it propagates.
// Integrators side by side: per (integrator, dt/dt_SA) the f1 error and E1 scores, and the amplitude
//   fraction in (6 f1, 12 f1] (analysis/band_fraction.hpp) of the record and of the exact series. The
//   bar's modes lie at (2k - 1) f1: the band is above the third (5 f1) and below the Nyquist frequency
//   of every record of >= 24 samples per T1. The released uniform strain excites every mode (amplitude
//   ~ 1/(2k - 1)^2), so the exact series has content there too: its value is printed beside ours.
#pragma once
#include "problems/common/analysis/band_fraction.hpp"
#include "pd/core/timer.hpp"
#include "pd/io/csv.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/newmark.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace pd {

struct FixedFreeBar {  // the case (SI), from the options
    double E, rho, l, A, eps0, f1;  // [Pa], [kg/m^3], [m], [m^2], [-], exact f1 [Hz]
    int samples;                    // tip samples per T1
    Influence w;                    // influence function omega
    PMB::Params::Calibration cal;   // PMB micromodulus
    bool newmark = false;           // integrator: Newmark, else velocity Verlet
};

struct FixedFreeBarRun {  // one PD bar: discretisation, step, tip record
    int N = 0, m = 0;
    long nodes = 0, bonds = 0, steps = 0, unstable_step = -1;
    double dx = 0, delta = 0, x_tip = 0, dt = 0, dt_crit = 0, growth = 0, wall_s = 0;  // [m], [s]
    std::vector<double> t_s{}, tip_m{};  // record: time [s], tip displacement [m]
};

// Clamp, release and integration of one run with the simulation type Sim (pd::Explicit or pd::Newmark).
template <class Sim, class Model>
void integrate_fixed_free_bar(FixedFreeBarRun& r, const Body<1>& body, Bonds& bonds, Model& model, const FixedFreeBar& b, long k,
                              long n_out, bool guard)
{
    Sim sim(body, bonds, model, b.rho);
    sim.boundary.fix(select<1>(body, [](const Vec<1>& p) { return p[0] < 0; }, "clamp layer"));
    for (std::size_t i = 0; i < body.size(); ++i) sim.u.c[0][i] = std::max(body.x.c[0][i], 0.0) * b.eps0;  // eps0 x; clamp 0
    sim.start();
    r.t_s = {0.0}, r.tip_m = {sim.u.c[0].back()};
    try {
        for (long j = 1; j <= n_out; ++j) {
            for (long s = 0; s < k; ++s) sim.step(r.dt);
            const Energies e = sim.check_energy();  // throws pd::Unstable beyond 10 x the initial energy
            r.growth = std::max(r.growth, (e.kinetic + e.strain) / sim.initial_energy());
            r.t_s.push_back(r.dt * k * j);
            r.tip_m.push_back(sim.u.c[0].back());
        }
    } catch (const Unstable& u) {
        if (!guard) throw;
        const Energies e = sim.energies();
        r.growth = (e.kinetic + e.strain) / sim.initial_energy();
        r.unstable_step = u.step;
    }
    r.steps = sim.step_count;
}

// One run of `model` ("lps" or "pmb") on N cells with horizon m dx at dt_max = dt_scale x dt_SA for t_end [s].
inline FixedFreeBarRun release_fixed_free_bar(const FixedFreeBar& b, const std::string& model, int N, int m, double dt_scale,
                                              double t_end, bool guard)
{
    const io::Timer timer;
    FixedFreeBarRun r{.N = N, .m = m, .dx = b.l / N, .delta = m * b.l / N};
    // Cells of the clamp layer [-delta, 0) and of the bar [0, l]; families |xi| <= delta.
    const Body<1> body = box<1>({-r.delta}, {b.l}, r.dx, b.A);
    Bonds bonds = build_bonds(body, r.delta, {.influence = b.w, .partial_volume = {}, .keep = {}});
    const PMB::Params pp{.material = Elastic::from_E_nu(b.E, 0.25),  // 1D: only kappa_1 = E enters
                         .dim = 1, .measure = b.A, .calibration = b.cal, .dx = r.dx};
    const double c = PMB::micromodulus(pp, b.w, r.delta);  // [N/m^4 in 1D]
    r.dt_crit = critical_step_silling_askari(bonds, b.rho, c).dt;
    const double dt_max = dt_scale * r.dt_crit;  // [s]
    const long k = std::max(1L, static_cast<long>(1.0 / (b.f1 * b.samples * dt_max)));  // steps per sample
    require_steps(std::ceil(t_end / dt_max), "--t-end / dt");
    const long n_out = static_cast<long>(std::ceil(t_end / (k * dt_max)));
    r.dt = guard ? dt_max : t_end / (k * n_out);  // stability runs keep dt = factor * dt_SA exactly
    r.nodes = static_cast<long>(body.size()), r.bonds = static_cast<long>(bonds.size()), r.x_tip = body.x.c[0].back();
    auto go = [&](auto&& pd_model) {
        using M = std::decay_t<decltype(pd_model)>;
        if (b.newmark) integrate_fixed_free_bar<Newmark<1, M>>(r, body, bonds, pd_model, b, k, n_out, guard);
        else integrate_fixed_free_bar<Explicit<1, M>>(r, body, bonds, pd_model, b, k, n_out, guard);
    };
    model == "lps" ? go(LPS({.material = pp.material, .dim = 1}, bonds)) : go(PMB(pp, bonds));
    r.wall_s = timer.seconds();
    return r;
}

struct BarIntegratorRow {
    std::string integrator;
    double dt_over_sa = 0, dt_s = 0;             // [-], [s]
    long steps = 0;
    double f1_rel_error = 0, E1_T1 = 0, E1 = 0;  // [-]
    double hf = 0, hf_exact = 0;                 // amplitude fraction in (6 f1, 12 f1] of the record and of the exact series [-]
    double wall_s = 0;                           // [s]
};

// One row per (newmark?, dt / dt_SA) case: run(newmark, factor) gives a FixedFreeBarRun; score(run)
// its scores f1, E1_T1, E1 and the exact record `exact` (reference/bar_1d_scores.hpp).
template <class RunFn, class ScoreFn>
std::vector<BarIntegratorRow> compare_bar_integrators(const std::vector<std::pair<bool, double>>& cases, double f1, RunFn&& run,
                                                      ScoreFn&& score)
{
    std::vector<BarIntegratorRow> rows;
    for (const auto& [newmark, factor] : cases) {
        const auto r = run(newmark, factor);
        const auto s = score(r);
        const double ts = r.t_s[1] - r.t_s[0];  // sample interval [s]
        rows.push_back({newmark ? "newmark" : "verlet", r.dt / r.dt_crit, r.dt, r.steps, s.f1 / f1 - 1, s.E1_T1, s.E1,
                        band_amplitude_fraction(r.tip_m, ts, 6 * f1, 12 * f1), band_amplitude_fraction(s.exact, ts, 6 * f1, 12 * f1),
                        r.wall_s});
    }
    return rows;
}

inline void write_bar_integrators(const std::filesystem::path& path, const std::vector<BarIntegratorRow>& rows)
{
    io::CsvWriter csv(path, {"integrator", "dt_over_dt_SA", "dt_s", "steps", "f1_rel_error", "E1_T1", "E1", "hf_fraction",
                             "hf_fraction_exact", "wall_s"});
    for (const auto& r : rows)
        csv.row({r.integrator, r.dt_over_sa, r.dt_s, r.steps, r.f1_rel_error, r.E1_T1, r.E1, r.hf, r.hf_exact, r.wall_s});
}

inline void print_bar_integrators(const std::vector<BarIntegratorRow>& rows, int N)
{
    std::printf("\nintegrators at N = %d (LPS, same record length): hf = amplitude fraction in (6 f1, 12 f1]\n", N);
    std::printf("%-10s %10s %11s %8s %12s %10s %10s %9s %9s %8s\n", "integrator", "dt/dt_SA", "dt_s", "steps", "f1_rel_err",
                "E1_T1", "E1", "hf", "hf_exact", "wall_s");
    for (const auto& r : rows)
        std::printf("%-10s %10.3f %11.4e %8ld %12.4e %10.4e %10.4e %9.4f %9.4f %8.3f\n", r.integrator.c_str(), r.dt_over_sa,
                    r.dt_s, r.steps, r.f1_rel_error, r.E1_T1, r.E1, r.hf, r.hf_exact, r.wall_s);
}

}  // namespace pd
