// problems/3d/pals_units_runs.hpp -- steps 2, 4 and 5 of pals_units_3d in one unit system: the gripped
// bar scene (every input converted to the system's units before the lattice is built; gauge layers
// nearest L/2 -+ delta with their nodes next to the axis), the measurement of eq. (4.37) (sigma = F/(W T)
// from the pulled grip's reaction, eps from the section-mean u_x and from the axis nodes), the explicit
// ramp run (velocity Verlet, dt = t_ramp/ceil(t_ramp/(SF dt_crit)), E_end at t_ramp, E_mean over the last
// quarter of the ramp, energy guard every 1000 steps) and the quasi-static reference E by ADR.
#pragma once
#include "problems/common/grips.hpp"
#include "pd/core/timer.hpp"
#include "problems/common/measure/bar_sections.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/dynamic_relaxation.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pals_units {

struct Units {
    std::string name;
    double L, M, T;                                      // one length, mass, time unit in m, kg, s
    double stress() const { return M / (L * T * T); }   // one stress unit [Pa]
};

// One lattice in one unit system (all members in that system's units): the gauged bar (grips 2 delta).
struct Scene : pd::GaugedBar {
    double U, t_ramp, rho;
    pd::Bonds bonds;
    std::vector<int> sec_a, sec_b, mid_a, mid_b;  // gauge layers (axis nodes last); their nodes within dx of the axis
};

Scene make_scene(const Units& u, double L, double W, double T, double strain, double dx, double m, double t_ramp, double rho)
{
    const double l = u.L, delta = m * dx / l;
    Scene s{pd::gauged_bar(L / l, W / l, T / l, dx / l, delta, 2 * delta), strain * L / l, t_ramp / u.T, rho / (u.M / (l * l * l)), {}, {}, {}, {}, {}};
    s.bonds = pd::build_bonds(s.bar.body, s.delta);
    auto axis = [&](int i) { return pd::near_bar_axis(s.bar.body, i, s.W, s.T, s.dx); };
    for (int i : s.gauge.sec_a) (axis(i) ? s.mid_a : s.sec_a).push_back(i);  // each section: the axis nodes last
    for (int i : s.gauge.sec_b) (axis(i) ? s.mid_b : s.sec_b).push_back(i);
    s.sec_a.insert(s.sec_a.end(), s.mid_a.begin(), s.mid_a.end());
    s.sec_b.insert(s.sec_b.end(), s.mid_b.begin(), s.mid_b.end());
    return s;
}

// sigma and eps of (4.37) from the internal force density f and displacement u (scene units):
// eps from the section means and, as the source's "two points near the section centre", eps_axis.
struct Measure { double sigma, eps, eps_axis; };
Measure measure(const Scene& s, const pd::Field<3>& f, const pd::Field<3>& u)
{
    auto mean = [&](const pd::NodeSet& set) { return pd::mean_axial_displacement(u, set); };
    const double dist = s.gauge.dist;
    return {pd::grip_stress(f, s), (mean(s.sec_b) - mean(s.sec_a)) / dist, (mean(s.mid_b) - mean(s.mid_a)) / dist};
}

struct Outcome {
    double E_end = NAN, E_mean = NAN, E_axis = NAN, dt = 0, dt_crit = 0, wall_s = 0;  // scene units
    long steps = 0, bad_step = -1, bad_node = -1;
    std::string message;
};

template <class Model>
Outcome run_explicit(Scene& s, Model& model, double sf, double c_pmb)
{
    Outcome o;
    pd::Explicit<3, Model> sim(s.bar.body, s.bonds, model, s.rho);
    pd::grip_bar_ends(sim.boundary, s.bar.left, s.bar.right, pd::TimeFunction::ramp(s.U, s.t_ramp), pd::Grips::clamped);
    sim.start();
    o.dt_crit = pd::critical_step_silling_askari(s.bonds, sim.rho, c_pmb).dt;
    pd::require_steps(std::ceil(s.t_ramp / (sf * o.dt_crit)), "--t-ramp / dt");
    o.steps = static_cast<long>(std::ceil(s.t_ramp / (sf * o.dt_crit)));
    o.dt = s.t_ramp / o.steps;
    const long window = std::max(o.steps / 4, 1L), guard_every = 1000;  // guard: one energy pass per 1000 steps
    double sum_sigma = 0, sum_eps = 0, sum_axis = 0;
    const pd::io::Timer timer;
    try {
        for (long n = 1; n <= o.steps; ++n) {
            sim.step(o.dt);
            if (n % guard_every == 0 || n == o.steps) sim.check_energy();
            if (n <= o.steps - window) continue;
            const Measure q = measure(s, sim.internal_force_density(), sim.u);
            sum_sigma += q.sigma, sum_eps += q.eps, sum_axis += q.eps_axis;
            if (n == o.steps) o.E_end = q.sigma / q.eps;
        }
        o.E_mean = sum_sigma / sum_eps;
        o.E_axis = sum_sigma / sum_axis;
    } catch (const pd::Unstable& e) { o.bad_step = e.step; o.bad_node = e.node; o.message = e.what(); }
    o.wall_s = timer.seconds();
    return o;
}

// Quasi-static E of the same scene by ADR, warm-started from the uniform uniaxial field.
template <class Model>
double quasi_static(Scene& s, Model& model, const pd::Field<3>& bound, double nu)
{
    pd::DynamicRelaxation<3, Model> adr(s.bar.body, s.bonds, model, bound);
    pd::Boundary<3> bc;
    pd::grip_bar_ends(bc, s.bar.left, s.bar.right, pd::TimeFunction::constant(s.U), pd::Grips::clamped);
    pd::Field<3> u(s.bar.body.size());
    pd::uniaxial_bar_field(s.bar.body, s.L, s.W, s.T, s.U, s.U / s.L, nu, pd::Grips::clamped, u);
    const pd::RelaxationResult r = adr.solve(u, bc, 0, 1e-6, 200000);  // tol as bar_stiffness; not converged: NaN (fails --check)
    const Measure q = measure(s, adr.internal_force_density(), u);
    return r.converged ? q.sigma / q.eps : NAN;
}

}  // namespace pals_units
