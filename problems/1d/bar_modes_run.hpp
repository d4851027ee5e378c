// problems/1d/bar_modes_run.hpp -- one PD run of bar_modes_1d: the fixed-free bar of length l with a
// clamp layer of m cells outside x = 0, released from u = eps0 x (x in the bar), integrated by velocity
// Verlet or Newmark (beta 1/4, gamma 1/2) at dt = dt_scale x dt_SA (Silling-Askari with the 1D PMB
// micromodulus), the tip (last node) sampled `samples` times per T1. Steps 2-5 of the driver.
#pragma once
#include "pd/core/timer.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/newmark.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

namespace bar_modes {

struct Bar {  // the case (SI), from the options
    double E, rho, l, A, eps0, f1;  // [Pa], [kg/m^3], [m], [m^2], [-], exact f1 [Hz]
    int samples;                    // tip samples per T1
    pd::Influence w;                // influence function omega
    pd::PMB::Params::Calibration cal;  // PMB micromodulus
    bool newmark = false;           // integrator: Newmark, else velocity Verlet
};

struct Run {  // one PD bar: discretisation, step, tip record
    int N = 0, m = 0;
    long nodes = 0, bonds = 0, steps = 0, unstable_step = -1;
    double dx = 0, delta = 0, x_tip = 0, dt = 0, dt_crit = 0, growth = 0, wall_s = 0;  // [m], [s]
    std::vector<double> t_s{}, tip_m{};  // record: time [s], tip displacement [m]
};

// Velocity Verlet (pd::Explicit) or Newmark (pd::Newmark), k steps per sample; guard = catch
// pd::Unstable (stability study).
template <class Sim, class Model>
void integrate(Run& r, const pd::Body<1>& body, pd::Bonds& bonds, Model& model, const Bar& b, long k, long n_out, bool guard)
{
    // 4. Clamp layer held at u = 0; u0 = eps0 x in the bar, released from rest.
    Sim sim(body, bonds, model, b.rho);
    sim.boundary.fix(pd::select<1>(body, [](const pd::Vec<1>& p) { return p[0] < 0; }, "clamp layer"));
    for (std::size_t i = 0; i < body.size(); ++i) sim.u.c[0][i] = std::max(body.x.c[0][i], 0.0) * b.eps0;  // eps0 x; clamp 0
    sim.start();
    r.t_s = {0.0}, r.tip_m = {sim.u.c[0].back()};
    try {  // 5. Integrate, sampling the tip (last node) every k steps.
        for (long j = 1; j <= n_out; ++j) {
            for (long s = 0; s < k; ++s) sim.step(r.dt);
            const pd::Energies e = sim.check_energy();  // throws pd::Unstable beyond 10 x the initial energy
            r.growth = std::max(r.growth, (e.kinetic + e.strain) / sim.initial_energy());
            r.t_s.push_back(r.dt * k * j);
            r.tip_m.push_back(sim.u.c[0].back());
        }
    } catch (const pd::Unstable& u) {
        if (!guard) throw;
        const pd::Energies e = sim.energies();
        r.growth = (e.kinetic + e.strain) / sim.initial_energy();
        r.unstable_step = u.step;
    }
    r.steps = sim.step_count;
}

Run run_pd(const Bar& b, const std::string& model, int N, int m, double dt_scale, double t_end, bool guard)
{
    const pd::io::Timer timer;
    Run r{.N = N, .m = m, .dx = b.l / N, .delta = m * b.l / N};
    // 2. Discretisation: cells of the clamp layer [-delta, 0) and of the bar [0, l]; families |xi| <= delta.
    const pd::Body<1> body = pd::box<1>({-r.delta}, {b.l}, r.dx, b.A);
    pd::Bonds bonds = pd::build_bonds(body, r.delta, {.influence = b.w, .partial_volume = {}, .keep = {}});
    // 3. Model; time step from Silling-Askari with the 1D PMB micromodulus.
    const pd::PMB::Params pp{.material = pd::Elastic::from_E_nu(b.E, 0.25),  // 1D: only kappa_1 = E enters
                             .dim = 1, .measure = b.A, .calibration = b.cal, .dx = r.dx};
    const double c = pd::PMB::micromodulus(pp, b.w, r.delta);  // [N/m^4 in 1D]
    r.dt_crit = pd::critical_step_silling_askari(bonds, std::vector<double>(body.size(), b.rho), c).dt;
    const double dt_max = dt_scale * r.dt_crit;  // [s]
    const long k = std::max(1L, static_cast<long>(1.0 / (b.f1 * b.samples * dt_max)));  // steps per sample
    pd::require_steps(std::ceil(t_end / dt_max), "--t-end / dt");
    const long n_out = static_cast<long>(std::ceil(t_end / (k * dt_max)));
    r.dt = guard ? dt_max : t_end / (k * n_out);  // stability runs keep dt = factor * dt_SA exactly
    r.nodes = static_cast<long>(body.size()), r.bonds = static_cast<long>(bonds.size()), r.x_tip = body.x.c[0].back();
    auto go = [&](auto&& pd_model) {
        using M = std::decay_t<decltype(pd_model)>;
        if (b.newmark) integrate<pd::Newmark<1, M>>(r, body, bonds, pd_model, b, k, n_out, guard);
        else integrate<pd::Explicit<1, M>>(r, body, bonds, pd_model, b, k, n_out, guard);
    };
    model == "lps" ? go(pd::LPS({.material = pp.material, .dim = 1}, bonds)) : go(pd::PMB(pp, bonds));
    r.wall_s = timer.seconds();
    return r;
}

}  // namespace bar_modes
