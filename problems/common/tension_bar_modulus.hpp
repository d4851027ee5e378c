// problems/common/tension_bar_modulus.hpp -- the measured modulus of the T4 explicit tension bar
// (pals_units_3d; seed 000b sec. 4.7, Table 4.2; spec/000b sec. 5.4, V4) in a chosen unit system.
// Units: a system is its units of length, mass and time in m, kg, s (SI 1, 1, 1; MMGS 1e-3, 1e-3, 1;
//   CGS 1e-2, 1e-3, 1); its stress unit is M/(L T^2) [Pa]. Every input is converted before the lattice
//   is built: lengths / L, times / T, rho / (M/L^3).
// Specimen: the gauged bar (pd::gauged_bar, grips 2 delta long outside both ends, delta = m dx) with its
//   gauge layers split at the axis (pd::axis_gauge, measure/bar_sections.hpp).
// Explicit run: clamped grips (grips.hpp), the right one pulled by a linear ramp to U = strain L at
//   t_ramp; velocity Verlet with N = ceil(t_ramp/(SF dt_crit)) equal steps dt = t_ramp/N, dt_crit the
//   Silling-Askari step with the PMB micromodulus (time/critical_step.hpp); energy guard every 1000
//   steps and at the last (pd::Unstable ends the run and is recorded). The measurement (4.37) of every
//   step in the last quarter (at least one step): E_end = sigma/eps at t_ramp, E_mean = sum sigma /
//   sum eps over the window, E_axis the same with eps_axis.
// Quasi-static: the same bar and grips at U by ADR from the uniform uniaxial field (tolerance 1e-6 as
//   bar_stiffness_3d), E_qs = sigma/eps; NaN when ADR does not converge.
#pragma once
#include "problems/common/grips.hpp"
#include "problems/common/measure/bar_sections.hpp"
#include "pd/core/timer.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/dynamic_relaxation.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace pd {

struct UnitSystem {
    std::string name;
    double L, M, T;                                     // one length, mass, time unit in m, kg, s
    double stress() const { return M / (L * T * T); }  // one stress unit [Pa]
};

// One lattice in one unit system (every member in that system's units).
struct TensionBar : GaugedBar {
    double U, t_ramp, rho;  // end displacement, ramp time, density
    Bonds bonds;
    AxisGauge axes;         // gauge layers split at the axis
};

// The bar L x W x T (x axial) on lattice dx with delta = m dx, pulled to `strain` in t_ramp, of
// density rho (SI inputs: [m], [-], [m], [-], [s], [kg/m^3]) in the units u.
inline TensionBar tension_bar_in_units(const UnitSystem& u, double L, double W, double T, double strain, double dx, double m,
                                       double t_ramp, double rho)
{
    const double l = u.L, delta = m * dx / l;
    TensionBar s{gauged_bar(L / l, W / l, T / l, dx / l, delta, 2 * delta), strain * L / l, t_ramp / u.T, rho / (u.M / (l * l * l)), {}, {}};
    s.bonds = build_bonds(s.bar.body, s.delta);
    s.axes = axis_gauge(s);
    return s;
}

struct RampModulus {  // the explicit run (units of the bar)
    double E_end = NAN, E_mean = NAN, E_axis = NAN, dt = 0, dt_crit = 0, wall_s = 0;  // wall_s [s]
    long steps = 0, bad_step = -1, bad_node = -1;  // bad_*: where pd::Unstable stopped the run (-1: stable)
    std::string message;
};

// The explicit ramp run of `model` at dt = t_ramp/ceil(t_ramp/(sf dt_crit)); c_pmb: the PMB micromodulus of dt_crit.
template <class Model>
RampModulus pull_by_ramp(TensionBar& s, Model& model, double sf, double c_pmb)
{
    RampModulus o;
    Explicit<3, Model> sim(s.bar.body, s.bonds, model, s.rho);
    grip_bar_ends(sim.boundary, s.bar.left, s.bar.right, TimeFunction::ramp(s.U, s.t_ramp), Grips::clamped);
    sim.start();
    o.dt_crit = critical_step_silling_askari(s.bonds, sim.rho, c_pmb).dt;
    require_steps(std::ceil(s.t_ramp / (sf * o.dt_crit)), "--t-ramp / dt");
    o.steps = static_cast<long>(std::ceil(s.t_ramp / (sf * o.dt_crit)));
    o.dt = s.t_ramp / o.steps;
    const long window = std::max(o.steps / 4, 1L), guard_every = 1000;  // guard: one energy pass per 1000 steps
    double sum_sigma = 0, sum_eps = 0, sum_axis = 0;
    const io::Timer timer;
    try {
        for (long n = 1; n <= o.steps; ++n) {
            sim.step(o.dt);
            if (n % guard_every == 0 || n == o.steps) sim.check_energy();
            if (n <= o.steps - window) continue;
            const GaugeSample q = sample_gauge(sim.internal_force_density(), sim.u, s, s.axes);
            sum_sigma += q.sigma, sum_eps += q.eps, sum_axis += q.eps_axis;
            if (n == o.steps) o.E_end = q.sigma / q.eps;
        }
        o.E_mean = sum_sigma / sum_eps;
        o.E_axis = sum_sigma / sum_axis;
    } catch (const Unstable& e) { o.bad_step = e.step; o.bad_node = e.node; o.message = e.what(); }
    o.wall_s = timer.seconds();
    return o;
}

// Quasi-static E of the same bar by ADR (bound: its density bound), warm-started from the uniform
// uniaxial field of Poisson's ratio nu.
template <class Model>
double quasi_static_modulus(TensionBar& s, Model& model, const Field<3>& bound, double nu)
{
    DynamicRelaxation<3, Model> adr(s.bar.body, s.bonds, model, bound);
    Boundary<3> bc;
    grip_bar_ends(bc, s.bar.left, s.bar.right, TimeFunction::constant(s.U), Grips::clamped);
    Field<3> u(s.bar.body.size());
    uniaxial_bar_field(s.bar.body, s.L, s.W, s.T, s.U, s.U / s.L, nu, Grips::clamped, u);
    const RelaxationResult r = adr.solve(u, bc, 0, 1e-6, 200000);  // tol as bar_stiffness; not converged: NaN (fails --check)
    const GaugeSample q = sample_gauge(adr.internal_force_density(), u, s, s.axes);
    return r.converged ? q.sigma / q.eps : NAN;
}

}  // namespace pd
