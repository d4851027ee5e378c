// problems/3d/wave_block.cpp -- plane longitudinal (P) wave in a 3D PMB or LPS block: wave speed,
// momentum and energy conservation of velocity Verlet.
// Case: block L x W x W on a cubic lattice dx, horizon delta = m dx, at rest, given the velocity
// v_x = v0 exp(-((x - L/2)/w)^2); it splits into two half pulses running to +-x. Every node has
// u_y = u_z = 0 (uniaxial strain) and the lateral faces are periodic: image layers of ghost nodes
// copy the x-motion (and LPS state) of their interior image, so the block is a slab of an infinite
// body and the pulse is an exact plane P wave. (Free lateral faces, --lateral free, soften a skin
// delta thick - the PD surface effect - and the speed is no longer that of a plane wave.) Free
// ends x = 0, L are never reached.
// Source: issue 2; spec/000a sec. 2.9 (linear theory), 3.3 (Verlet, critical step); spec/002 sec.
// 2.3, 3.4, 5.2 (Gaussian wave tests). Reference: reference/wave_speed.hpp: local c_P =
// sqrt((K + 4G/3)/rho) (PMB: G = 3K/5), the nonlocal dispersion omega(k) of the continuum ball and
// of the lattice family (+ Verlet); the energy centroid of each half pulse moves at the energy-
// weighted mean group velocity <c_g> of the pulse spectrum (exact for linear forces; measured on
// the Verlet shadow energy density, which the scheme conserves).
// Compared: centroid speed vs lattice <c_g> (check), continuum <c_g> and c_P; momentum (round-off);
// energy drift at dt and dt/2 vs the Verlet identity E_n - E_0 = dt^2/8 sum rho a_n^2 V (order 2).
// Run: wave_block_3d [--model pmb|lps] [--dx 5e-4] [--m 3] [--quick] [--check] [--out DIR]
// Writes: summary.csv, energy.csv, energy_half_dt.csv, centroid.csv, dispersion.csv, params.csv.
#include "pd/io/guarded_main.hpp"
#include "pd/bc/lateral_images.hpp"
#include "pd/io/case.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/registry.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"
#include "reference/wave_speed.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>

namespace {

struct Pulse { double rho, v0, x0, w; };   // [kg/m^3], [m/s], centre [m], half-width [m]
struct History { std::vector<double> t, energy, shadow, momentum, distance; };  // [s], [J], [J], [kg m/s], [m]

// Velocity Verlet from the pulse to t = steps dt; ghosts copy u, v, a of their image before each
// step, so they move exactly as the image. Diagnostics over the interior nodes, ~100 samples.
template <class Model>
History integrate(Model& model, const pd::ImageBlock& blk, pd::Bonds& bonds, const Pulse& p, double dt, long steps,
                  const std::filesystem::path& energy_csv, pd::io::CsvWriter* centroid_csv, bool show_progress)
{
    pd::Explicit<3, Model> sim(blk.body, bonds, model, p.rho);
    pd::NodeSet all(blk.body.size());
    std::iota(all.begin(), all.end(), 0);
    for (int d : {1, 2}) sim.boundary.prescribe({pd::Prescribed::Kind::displacement, all, d, pd::TimeFunction::constant(0)});
    for (std::size_t i = 0; i < all.size(); ++i) sim.v.c[0][i] = p.v0 * std::exp(-std::pow((blk.body.x.c[0][i] - p.x0) / p.w, 2));
    sim.start();
    pd::io::CsvWriter csv(energy_csv, {"t_s", "kinetic_J", "strain_J", "total_J", "shadow_J", "momentum_kg_m_s"});
    History h;
    auto sample = [&] {
        const std::vector<double> W = sim.scene.model.energy_density(bonds, sim.positions());
        double ke = 0, se = 0, a2 = 0, P = 0, mr[2] = {0, 0}, er[2] = {0, 0};
        for (int i : blk.interior) {
            const double V = blk.body.volume[i], v = sim.v.c[0][i], ai = sim.a.c[0][i];
            ke += 0.5 * p.rho * v * v * V, se += W[i] * V, a2 += p.rho * ai * ai * V, P += p.rho * v * V;
            // Centroids of the shadow energy density (conserved by Verlet, so its centroid moves at
            // exactly the Verlet group velocity): right (s > 0) and left half pulse.
            const double e = 0.5 * p.rho * v * v + W[i] - dt * dt / 8 * p.rho * ai * ai, s = blk.body.x.c[0][i] - p.x0;
            mr[s < 0] += std::abs(s) * e * V, er[s < 0] += e * V;
        }
        const double shadow = ke + se - dt * dt / 8 * a2;  // conserved exactly by linear Verlet
        h.t.push_back(sim.t), h.energy.push_back(ke + se), h.shadow.push_back(shadow), h.momentum.push_back(P);
        h.distance.push_back(0.5 * (mr[0] / er[0] + mr[1] / er[1]));
        csv.row({sim.t, ke, se, ke + se, shadow, P});
        if (centroid_csv) centroid_csv->row({sim.t, mr[0] / er[0], mr[1] / er[1], h.distance.back()});
        sim.check_energy();  // the library's guard: pd::Unstable names the step and node
    };
    const long every = std::max(1L, steps / 100);  // about 100 samples per run
    pd::io::Progress progress("integrate", steps, show_progress);
    sample();
    for (long n = 1; n <= steps; ++n) {
        for (pd::Field<3>* f : {&sim.u, &sim.v, &sim.a}) pd::copy_images(blk, *f);
        sim.step(dt);
        if (n % every == 0 || n == steps) sample();
        progress.update(n);
    }
    return h;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI), echoed and saved.
    pd::io::Case run("wave_block_3d", "Plane P-wave pulse in a laterally periodic 3D PMB/LPS block: speed vs dispersion, momentum, energy.",
                     "reports/3d/wave_block");
    pd::io::Options& opt = run.opt;
    std::string& model_name = opt.add_string("model", "pmb", "material model", {"pmb", "lps"});
    double& E = opt.add("E", 200e9, "Young's modulus", "Pa");
    double& nu = opt.add("nu", 0.25, "Poisson's ratio (PMB uses only K: nu = 1/4 implied)");
    double& rho = opt.add("rho", 7800, "density", "kg/m^3");
    double& dx = opt.add("dx", 5e-4, "lattice spacing (quick: 2e-3)", "m");
    double& m = opt.add("m", 3, "horizon ratio delta/dx");
    std::string& influence_name = opt.add_string("influence", "one", "influence function", {"one", "inv_xi", "triangular"});
    std::string& pv_name = opt.add_string("partial-volume", "none", "partial volumes", {"none", "pa-pdlammps"});
    double& L = opt.add("length", 0.4, "block length along x (quick: 0.3)", "m");
    double& W = opt.add("width", 3e-3, "block width and height (periodic: one period; quick: 4e-3)", "m");
    std::string& lateral = opt.add_string("lateral", "periodic", "lateral faces", {"periodic", "free"});
    double& w = opt.add("pulse-width", 0.01, "Gaussian half-width w of the velocity pulse", "m");
    double& v0 = opt.add("v0", 0.1, "peak initial velocity (small: linear regime)", "m/s");
    double& dt_factor = opt.add("dt-factor", 0.5, "time step / Silling-Askari critical step");
    double& t_end = opt.add("t-end", std::nan(""), "end time (nan: the pulse's 3w tail stops delta short of the ends)", "s");
    for (const char* o : {"E", "rho", "dx", "length", "width", "pulse-width", "v0", "dt-factor", "t-end"}) opt.require_positive(o);
    opt.require_at_least("m", 1);
    run.parse(argc, argv);
    if (const std::string msg = pd::validate_elastic(E, nu, 3, pd::Plane::strain); !msg.empty()) opt.fail(msg);
    const bool quick = run.quick();
    run.quick_default("dx", 2e-3);
    run.quick_default("length", 0.3);
    run.quick_default("width", 4e-3);
    run.start();
    const std::filesystem::path& out = run.out();
    pd::io::Timer timer;

    // 2. Discretisation: interior Nx x n x n cells, ghost layers as deep as the family reaches.
    const double delta = m * dx;
    const long Nx = std::lround(L / dx), n = std::lround(W / dx);
    const long g = lateral == "periodic" ? static_cast<long>(std::floor(m * (1 + pd::horizon_roundoff))) : 0;
    if (n < 1) opt.fail("option --width must be at least one cell dx");
    const pd::ImageBlock blk = pd::make_image_block(Nx, n, g, dx);
    const pd::Influence influence = pd::Influence::parse(influence_name);
    std::vector<std::uint8_t> ghost(blk.body.size(), 0);
    for (int i : blk.ghosts) ghost[i] = 1;
    pd::BondOptions bo{.influence = influence, .partial_volume = pd::parse_partial_volume(pv_name),
                       .keep = [&](int i, int j) { return !(ghost[i] && ghost[j]); }};  // ghost-ghost bonds unused
    pd::Bonds bonds = pd::build_bonds(blk.body, delta, bo);

    // 3. Model and reference dispersion (continuum ball; lattice family; Verlet), time step.
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const pd::PMB::Params pmb_params{.material = mat, .dim = 3};
    const double c_pmb = pd::PMB::micromodulus(pmb_params, influence, delta);  // also the LPS stand-in (critical_step.hpp)
    const double dt_crit = pd::critical_step_silling_askari(bonds, rho, c_pmb).dt;
    pd::ref::WaveMaterial wm{model_name == "pmb" ? pd::ref::WaveMaterial::Model::pmb : pd::ref::WaveMaterial::Model::lps,
                             mat.K, mat.G, rho, delta, [&](double r) { return influence(r, delta); }};
    const double cP = pd::ref::p_wave_speed(wm);
    const auto cont = pd::ref::LongitudinalDispersion::continuum(wm);
    const auto latt = pd::ref::LongitudinalDispersion::lattice(wm, dx, pv_name == "pa-pdlammps");
    const double travel_max = 0.5 * L - 3 * w - delta;   // centre travel until the 3w tail is delta from an end [m]
    const double speed_margin = 1.1;                     // lattice pulses may outrun c_P by a few %
    if (std::isnan(t_end)) t_end = travel_max / (speed_margin * cP);
    else if (t_end * speed_margin * cP > travel_max) std::printf("warning: --t-end lets the pulses reach the free ends\n");
    const double t_fit = 3 * w / cP;  // halves separated (overlap energy < e^-18): fit from here
    if (!(t_end > 1.5 * t_fit)) opt.fail("option --t-end/--length too short: the half pulses need to travel > 4.5 w");
    pd::require_steps(3 * std::ceil(t_end / (dt_factor * dt_crit)), "--t-end / dt (at dt and dt/2)");
    const long steps = static_cast<long>(std::ceil(t_end / (dt_factor * dt_crit)));
    const double dt = t_end / steps;
    std::printf("nodes %zu (interior %zu, ghosts %zu), bonds %zu, delta %.4g m, dt %.4g s (%.3g x critical), %ld steps\n",
                blk.body.size(), blk.interior.size(), blk.ghosts.size(), bonds.size(), delta, dt, dt / dt_crit, steps);

    // 4.-5. Initial pulse, uniaxial strain, periodic images; integrate at dt and dt/2.
    const Pulse pulse{rho, v0, 0.5 * Nx * dx, w};
    History h1, h2;
    {
        pd::io::CsvWriter centroid(out / "centroid.csv", {"t_s", "right_m", "left_m", "distance_m"});
        pd::with_model<pd::PMB, pd::LPS>(pd::ModelChoice{.name = model_name, .material = mat}, blk.body, bonds, [&](auto& model) {
            pd::LateralImages wrapped(model, blk);
            h1 = integrate(wrapped, blk, bonds, pulse, dt, steps, out / "energy.csv", &centroid, !quick);
            h2 = integrate(wrapped, blk, bonds, pulse, dt / 2, 2 * steps, out / "energy_half_dt.csv", nullptr, !quick);
        });
    }
    const double wall = timer.seconds();

    // 6. Compare with reference/, write CSVs, print table and verdict.
    const double c1 = pd::ref::least_squares_slope(h1.t, h1.distance, t_fit);  // centroid speeds [m/s]
    const double c2 = pd::ref::least_squares_slope(h2.t, h2.distance, t_fit);
    const double cg1 = pd::ref::mean_group_velocity(latt, w, dt), cg2 = pd::ref::mean_group_velocity(latt, w, dt / 2);
    const double cg_cont = pd::ref::mean_group_velocity(cont, w);
    const double p_drift = pd::ref::max_relative_deviation(h1.momentum), e_max = pd::ref::max_relative_deviation(h1.energy);
    const double shadow = pd::ref::max_relative_deviation(h1.shadow);
    const double e1 = h1.energy.back() / h1.energy.front() - 1, e2 = h2.energy.back() / h2.energy.front() - 1;
    const double e_pred = dt * dt / 8 * pd::ref::mean_omega2(latt, w);  // (dt^2/8)<omega^2>: strain = kinetic
    const double order = std::log2(e1 / e2), nan = std::nan("");
    using pd::io::relative_error;
    const double cg_w = latt.group_velocity(1 / w), cph_w = latt.phase_velocity(1 / w);
    run.summary({
        {"wave_speed", c1, cg1, relative_error(c1, cg1), "m/s"},                  // vs lattice <c_g> (+ Verlet)
        {"wave_speed_half_dt", c2, cg2, relative_error(c2, cg2), "m/s"},
        {"wave_speed_vs_continuum", c1, cg_cont, relative_error(c1, cg_cont), "m/s"},  // nonlocal, no lattice
        {"wave_speed_vs_c_P", c1, cP, relative_error(c1, cP), "m/s"},                  // local
        {"group_velocity_k_1_over_w", cg_w, cP, relative_error(cg_w, cP), "m/s"},     // lattice, k = 1/w
        {"phase_velocity_k_1_over_w", cph_w, cP, relative_error(cph_w, cP), "m/s"},
        {"momentum_drift", p_drift, 0, nan, "-"},
        {"energy_drift_max", e_max, 2 * e_pred, nan, "-"},                              // a priori bound
        {"energy_drift", e1, e_pred, relative_error(e1, e_pred), "-"},                   // at t_end
        {"energy_drift_half_dt", e2, e_pred / 4, relative_error(e2, e_pred / 4), "-"},
        {"energy_drift_order", order, 2, relative_error(order, 2), "-"},
        {"shadow_energy_drift", shadow, 0, nan, "-"},
        {"wall_time", wall, nan, nan, "s"}});
    pd::io::CsvWriter disp(out / "dispersion.csv", {"k_1_m", "omega_lattice_rad_s", "c_phase_lattice_m_s", "c_group_lattice_m_s",
                                                     "c_phase_continuum_m_s", "c_group_continuum_m_s", "spectrum_weight"});
    const int n_k = 100;  // dispersion.csv rows over (0, pi/dx]
    for (int q = 1; q <= n_k; ++q) {
        const double k = latt.k_max() * q / n_k;
        disp.row({k, latt.omega(k), latt.phase_velocity(k), latt.group_velocity(k), cont.phase_velocity(k), cont.group_velocity(k),
                  std::exp(-0.5 * k * k * w * w)});
    }
    run.print_summary(36, 7);

    // Tolerances (reasons in reports/3d/wave_block.md): speed 1e-4 (seen 1e-11 to 1e-6: second-order
    // nonlinearity, slow tails crossing the centre; the gaps to continuum and c_P are 1e-2); momentum
    // 1e-10 (round-off: antisymmetric pair forces summed by two owners); energy offset at t_end within
    // 5% of (dt^2/8)<omega^2> (Verlet: E_n - E_0 = dt^2/8 sum rho a_n^2 V for linear forces; strain =
    // kinetic once separated), max below 2x that (strain <= total), order 2 +- 0.1; shadow energy 1e-6
    // (nonlinear terms ~ v0/c_P ~ 2e-5 times the 1e-3 offset).
    run.check(relative_error(c1, cg1) < 1e-4 && relative_error(c2, cg2) < 1e-4, "wave speed at dt and dt/2 within 1e-4 of the lattice <c_g>");
    run.property(p_drift < 1e-10, "momentum drift below 1e-10");
    // The 5 % has no bound of the 'strain = kinetic' approximation behind it, only the 0.04-1.5 % seen.
    run.regression_bound(relative_error(e1, e_pred) < 0.05, "energy offset at t_end within 5 % of (dt^2/8)<omega^2> (margin over measured)");
    run.check(e_max < 2 * e_pred, "largest energy offset below 2 (dt^2/8)<omega^2>");
    run.check(std::abs(order - 2) < 0.1, "energy offset of order 2 +- 0.1 in dt");
    run.property(shadow < 1e-6, "shadow energy drift below 1e-6");
    return run.finish("%s wave speed %.2f m/s vs lattice dispersion %.2f m/s (%.2e), c_P %.2f m/s; momentum drift %.1e; "
                      "energy offset %.2e (order %.2f); %.1f s", model_name.c_str(), c1, cg1, relative_error(c1, cg1), cP, p_drift,
                      e1, order, wall);
}

int main(int argc, char** argv) { return pd::io::guarded_main("wave_block_3d", [&] { return run_case(argc, argv); }); }
