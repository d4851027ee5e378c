// problems/common/refined_wave.hpp -- a plane Gaussian wave in a free 2D plate whose grid is refined
// somewhere (spec/002 sec. 5.2-5.3; problems/2d/wave_refined_patch.cpp, wave_multilevel_2d.cpp):
// the families of a RefinedGrid (core/refinement.hpp) with PA-PDLAMMPS volumes and the plain
// variable or the dual horizon (core/variable_horizon.hpp), PMB plane stress (nu = 1/3), the pulse
// u_x = a exp(-(x/width)^2), v = 0, velocity Verlet, and what the drivers compare with the same wave on
// the uniform grid at the same step: the peak energy densities per node, the total energy and the
// displacement of a probe node.
#pragma once
#include "pd/core/refinement.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pd::wave {

struct Pulse {
    double E = 1, rho = 1;           // [Pa], [kg/m^3]
    double a = 0.2e-6, width = 0.01;  // amplitude and width of u_x(t = 0) [m]
    double t_end = 0, t_profile = 0;  // run length, time of the energy profile [s]
    Vec<2> probe{};                   // the node nearest this point records u_x [m]
};

// Families and PMB with the horizon factors.
struct WaveScene {
    Body<2> body;
    HorizonFamilies f;
    PMB model;
    WaveScene(const Pulse& p, const RefinedGrid<2>& g, HorizonCoupling coupling)
        : body(g.body()), f(build_variable_horizon_bonds(body, g.active_delta(), g.active_h(), coupling, PartialVolume::pa_pdlammps))
    {
        const PMB::Params mp{.material = Elastic::from_E_nu(p.E, 1.0 / 3), .dim = 2, .plane = Plane::stress};
        model = PMB(mp, f.bonds);
        model.scale_bonds(horizon_factors(f, [&](double delta) { return PMB::micromodulus(mp, Influence{}, delta); }));
    }
    double critical_step(double rho) const { return critical_step_silling_askari(f.bonds, rho, model.coef).dt; }  // eq. 3.14
};

struct WaveHistory {
    std::vector<double> W_max, K_max, T_max;  // per node, largest potential, kinetic, total energy density [J/m^3]
    std::vector<double> E_tot, u_probe;       // per step: total energy [J], probe u_x [m]
    std::vector<double> profile;              // W per node at t_profile [J/m^3]
    Body<2> body;
    double wall = 0;                          // [s]
};

// The pulse through the grid with step dt [s], the energies sampled every step.
inline WaveHistory run_wave(const Pulse& p, const RefinedGrid<2>& g, HorizonCoupling coupling, double dt)
{
    io::Timer timer;
    WaveScene sc(p, g, coupling);
    WaveHistory h;
    h.body = sc.body;
    const std::size_t n = h.body.size();
    Explicit<2, PMB> sim(h.body, sc.f.bonds, sc.model, p.rho);
    for (std::size_t i = 0; i < n; ++i) sim.u.c[0][i] = p.a * std::exp(-std::pow(h.body.x.c[0][i] / p.width, 2));
    sim.start();
    int probe = 0;
    for (std::size_t i = 0; i < n; ++i)
        if (norm(h.body.x[i] - p.probe) < norm(h.body.x[probe] - p.probe)) probe = static_cast<int>(i);
    h.W_max.assign(n, 0.0), h.K_max.assign(n, 0.0), h.T_max.assign(n, 0.0);
    const long steps = std::lround(std::ceil(p.t_end / dt)), at_profile = std::lround(p.t_profile / dt);
    for (long s = 0; s <= steps; ++s) {
        if (s > 0) sim.step(dt);
        const std::vector<double> W = sc.model.energy_density(sc.f.bonds, sim.positions());
        double E = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double K = 0.5 * p.rho * (sim.v.c[0][i] * sim.v.c[0][i] + sim.v.c[1][i] * sim.v.c[1][i]);
            h.W_max[i] = std::max(h.W_max[i], W[i]), h.K_max[i] = std::max(h.K_max[i], K), h.T_max[i] = std::max(h.T_max[i], W[i] + K);
            E += (W[i] + K) * h.body.volume[i];
        }
        h.E_tot.push_back(E), h.u_probe.push_back(sim.u.c[0][probe]);
        if (s == at_profile) h.profile = W;
    }
    h.wall = timer.seconds();
    return h;
}

// Over the refined nodes of g, the relative reduction 1 - peak_i / peak_ref(ancestor of i) of a peak
// energy density against the uniform run (whose node numbers are g's level-0 numbers): its largest
// and smallest value (a negative reduction is an increase).
struct PeakChange {
    double largest = -1e300, smallest = 1e300;
};
inline PeakChange peak_change(const RefinedGrid<2>& g, const std::vector<double>& peak, const std::vector<double>& peak_ref)
{
    PeakChange c;
    const std::vector<int> ids = g.ids();
    for (std::size_t q = 0; q < ids.size(); ++q) {
        if (g.level[ids[q]] == 0) continue;
        const double r = 1 - peak[q] / peak_ref[g.ancestor(ids[q])];
        c.largest = std::max(c.largest, r), c.smallest = std::min(c.smallest, r);
    }
    return c;
}

// The largest relative change of the total energy, and the largest |u - u_ref| at the probe (the
// reflected wave) over `scale` [m] (default: the largest |u_ref| there, the incident wave), against the
// uniform run with the same steps [-].
inline double energy_change(const WaveHistory& h, const WaveHistory& ref)
{
    double d = 0;
    for (std::size_t s = 0; s < ref.E_tot.size(); ++s) d = std::max(d, std::abs(1 - h.E_tot[s] / ref.E_tot[s]));
    return d;
}
inline double reflection(const WaveHistory& h, const WaveHistory& ref, double scale = 0)
{
    double d = 0, u_max = 0;
    for (double u : ref.u_probe) u_max = std::max(u_max, std::abs(u));
    for (std::size_t s = 0; s < ref.u_probe.size(); ++s) d = std::max(d, std::abs(h.u_probe[s] - ref.u_probe[s]));
    return d / (scale > 0 ? scale : u_max);
}

}  // namespace pd::wave
