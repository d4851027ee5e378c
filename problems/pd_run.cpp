// pd_run -- explicit dynamics of a user's point cloud (issue 2, "Users' own point clouds"), the CSV
// counterpart of Peridigm's text-file discretisation. Not a verification case: it has no reference
// and no --quick/--check; the physics it runs is verified by the tests of the library.
// Input: a CSV with columns x,y,z,volume [+ block, vx,vy,vz, ux,uy,uz, fixed, no_fail, T0, T_fixed] (pd/io/point_cloud.hpp).
// Model PMB, LPS, LPS+SCF, PALS (3D) or correspondence (2D/3D, linear small-strain law or in 3D the
// hypo-elastic one, Littlewood hourglass --hourglass C; --conventions peridigm: Peridigm's forms,
// problems/pd_run_conventions.hpp) (single material; block ids are passed through to the VTU files only), bond
// family |xi| <= delta, velocity Verlet (pd::Explicit), fixed points held at their initial
// displacement, dt default = 0.5 x the smaller of the Silling-Askari critical step with the PMB spring
// c omega / |xi| (spec/000a sec. 3.3.2, eq. 3.14) and 2/omega_max of the body (pd/time/explicit_step.hpp). --s0: critical-stretch bond breaking (spec/000c sec. 2.2)
// with the point damage phi in the state files (pd/damage/critical_stretch.hpp).
// Heat conduction (issue 4, problems/pd_run_heat.hpp): --heat agwai|correspondence adds a temperature
// field (columns T0, T_fixed) integrated by explicit/implicit Euler or CVODE; --mechanics off runs it alone.
// Dissipation (problems/pd_run_dissipation.hpp): --plasticity johnson-cook (3D) or --viscoelastic sls; with
// --heat the dissipated energy warms the points every --nsync-mh steps, and state files get ep.
// Run:    pd_run --input cloud.csv --E 200e9 --nu 0.25 --rho 7800 --delta 3e-3 --steps 1000
//         [--model pmb|lps|scf|pals|correspondence] [--hourglass C] [--dim 1|2|3] [--output-steps 0,500,1000]
//         [--vtu-every 100] [--s0 1e-3] [--heat agwai --k 50 --cv 500 [--mechanics off --thermal-steps 100]] [--help]
// Writes: DIR/params.csv, DIR/energy.csv (step,t_s,kinetic_J,strain_J,external_work_J,total_J[,dissipated_heat_J]),
//         DIR/state_stepNNNN.csv (node_id,x,y,z[,ux,uy,uz,vx,vy,vz][,damage][,ep][,T,Q_W_m3]), DIR/state_stepNNNN.vtu +
//         state.pvd, with --heat DIR/heat.csv (thermal_step,t_s,heat_J,T_min,T_max).
// Checkpoints (problems/pd_run_checkpoint.hpp): --checkpoint-every k, --restart FILE; SIGINT/SIGTERM
// stop after the current step with a checkpoint.
// Exit status: 0 done; 2 invalid input (one line naming the option or file:line); 3 unstable run
// (files written before the blow-up are kept); 128 + signal after SIGINT/SIGTERM. User page: reports/pd_run.md.
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/models/registry.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"
#include "pd_run_checks.hpp"
#include "pd_run_dissipation.hpp"
#include "pd_run_integrate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <type_traits>

namespace {

using namespace pd_run;

// 2.-3. Discretisation, bonds, time step and model for dimension D.
template <int D>
int run(Run cfg, const pd::io::PointCloud& pc)
{
    const pd::Body<D> body = pd::io::to_body<D>(pc, cfg.dx, cfg.measure);
    pd::BondOptions family;
    family.influence = cfg.influence;
    family.partial_volume = cfg.partial_volume;
    pd::Bonds bonds = pd::build_bonds(body, cfg.delta, family);
    if (cfg.s0 > 0) bonds.enable_damage();  // before the models: they and the heat see the intact flags
    long isolated = 0;
    for (std::size_t i = 0; i < body.size(); ++i) isolated += bonds.begin(i) == bonds.end(i);
    std::printf("points %zu, bonds %zu (ordered pairs), blocks %ld, fixed %ld, isolated %ld\n", body.size(),
                bonds.size(), pc.blocks(), pc.fixed_count(), isolated);
    if (pc.blocks() > 1) std::printf("note: %ld blocks share one material (per-block materials come later)\n", pc.blocks());
    warn_empty_scene(body, bonds, isolated);
    std::unique_ptr<HeatRun> heat;
    if (cfg.heat.model != "none") heat = make_heat<D>(cfg.heat, pc, body, bonds, cfg.out, fail);
    if (!cfg.mechanics) {
        std::fflush(stdout);
        return integrate_heat<D>(cfg, pc, *heat);
    }

    // The step (pd/time/explicit_step.hpp): 0.5 x the smaller of Silling-Askari (3.14) with the PMB
    // spring c omega / |xi| (times 1 + gamma_b for a standard linear solid: its instantaneous shear
    // modulus is G (1 + gamma_b)) and 2 / omega_max of the model's body, chosen once the model is built
    // (choose_step, pd_run_integrate.hpp).
    const pd::PMB::Params pmb{.material = cfg.material, .dim = D, .plane = cfg.plane, .measure = cfg.measure};
    const bool viscous = cfg.dissipation.kind == pd::Dissipation::Kind::viscoelastic;
    const double c = pd::PMB::micromodulus(pmb, bonds.influence, bonds.delta) * (viscous ? 1 + cfg.dissipation.gamma_b : 1.0);
    if (std::isnan(cfg.dt) && !std::isfinite(pd::critical_step_silling_askari(bonds, cfg.rho, c).dt))
        fail("option --dt is required: no point has a bond within --delta");
    // The model by name (models/registry.hpp); the surface correction of PMB (reference: its own
    // bulk energy) or LPS (reference: the classical energy); none: no change.
    const Conventions& cv = cfg.conventions;
    const pd::ModelChoice choice{.name = cfg.model, .material = cfg.material, .plane = cfg.plane, .measure = cfg.measure, .C_hg = cfg.hourglass,
                                 .hypoelastic = cv.hypoelastic, .hourglass_direction = cv.hourglass, .rotation = cv.rotation, .pals_base = cv.pals_base};
    auto simulate = [&](auto& model) {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (std::is_same_v<Model, pd::Correspondence<D>>) warn_singular_shape_tensors(model, D);
        if constexpr (requires { model.model.Kinv; }) warn_singular_shape_tensors(model.model, D);  // the inelastic correspondence
        if constexpr (std::is_same_v<Model, pd::PMB>) pd::apply_surface_correction(model, body, bonds, cfg.surface);
        if constexpr (std::is_same_v<Model, pd::LPS>)
            if (cfg.model == "lps")
                pd::apply_surface_correction(model, body, bonds, cfg.surface,
                                             {.reference = pd::SurfaceCorrectionOptions::Reference::classical});
        choose_step(cfg, model, bonds, body, c, heat.get());
        return integrate<D>(cfg, pc, body, bonds, model, heat.get());
    };
    if constexpr (D >= 2)  // the inelastic models (pd_run_dissipation.hpp)
        if (cfg.dissipation.kind != pd::Dissipation::Kind::none) return pd::with_dissipative_model(choice, cfg.dissipation, body, bonds, simulate);
    return pd::with_model(choice, body, bonds, simulate);
}


}  // namespace

int main(int argc, char** argv)
{
    // 1. Options (SI), cross-checks, echo and params.csv. A stop signal from here on ends the run
    //    after its first or current step, with a checkpoint (pd_run_checkpoint.hpp).
    catch_stop_signals();
    const double automatic = std::numeric_limits<double>::quiet_NaN();
    pd::io::Options opt(program, "Explicit dynamics (velocity Verlet) and heat conduction of a point cloud read from CSV; see reports/pd_run.md.");
    const std::string& input = opt.add_string("input", "", "point-cloud CSV: x,y,z,volume[,block,vx,vy,vz,ux,uy,uz,fixed,no_fail,T0,T_fixed]");
    const std::string& model = opt.add_string("model", "pmb", "material model (lps-scf or scf = LPS with the shear correction factor)",
                                              {"pmb", "lps", "lps-scf", "scf", "pals", "correspondence"});
    const std::string& surface = opt.add_string("surface-correction", "none",
                                                "surface correction of PMB or LPS (energy: Madenci-Oterkus; PMB needs --dx)", {"none", "energy"});
    const double& hourglass = opt.add("hourglass", 0.0, "Littlewood hourglass coefficient C_hg of correspondence (source: 0.02)");
    const int& dim = opt.add_int("dim", 3, "dimension (x, then y, then z are used)");
    opt.add("K", automatic, "bulk modulus, with --G (or give --E --nu)", "Pa");
    opt.add("G", automatic, "shear modulus, with --K", "Pa");
    opt.add("E", automatic, "Young's modulus, with --nu (or give --K --G)", "Pa");
    opt.add("nu", automatic, "Poisson's ratio, with --E (optional and unused in 1D)");
    const double& rho = opt.add("rho", automatic, "density (required)", "kg/m^3");
    const double& delta = opt.add("delta", automatic, "horizon: bonds with |xi| <= delta (required)", "m");
    const std::string& influence = opt.add_string("influence", "one", "influence function omega", {"one", "inv_xi", "triangular"});
    const std::string& pv = opt.add_string("partial-volume", "none", "partial volumes of boundary bonds", {"none", "pa-pdlammps"});
    const double& dx = opt.add("dx", automatic, "lattice spacing of the cloud (required by pa-pdlammps)", "m");
    const std::string& plane = opt.add_string("plane", "stress", "2D reduction (dim 2 only)", {"stress", "strain"});
    const double& thickness = opt.add("thickness", 1.0, "2D thickness implied by the volumes (dim 2 only)", "m");
    const double& area = opt.add("area", 1.0, "1D cross-section implied by the volumes (dim 1 only)", "m^2");
    const double& dt = opt.add("dt", automatic, "time step (default 0.5 x the smaller of the Silling-Askari step and 2/omega_max)", "s");
    const int& steps = opt.add_int("steps", 1000, "number of time steps");
    const std::string& out_steps = opt.add_string("output-steps", "", "steps written as state_stepNNNN.csv, e.g. 0,100,400 (default: last step; none: no state)");
    const int& energy_every = opt.add_int("energy-every", 10, "energy.csv row every k steps (and at the last step)");
    const int& vtu_every = opt.add_int("vtu-every", 0, "VTU snapshot every k steps and at the last step (0 = off)");
    const double& s0 = opt.add("s0", automatic, "critical stretch > 0: a bond stretched beyond it breaks for good; state "
                                                "CSV and VTU get the point damage (nan = no bond breaking)");
    const std::string& out = opt.add_string("out", "pd_run_out", "output folder");
    const int& checkpoint_every = opt.add_int("checkpoint-every", 0, "write OUT/checkpoint.pdstate every k steps (0 = only on SIGINT/SIGTERM)");
    const std::string& restart = opt.add_string("restart", "", "continue the run saved in this checkpoint (same options; --steps may grow)");
    const int& threads = opt.add_int("threads", 0, "OpenMP threads (0 = OpenMP default)");
    const int& max_steps = opt.add_int("max-steps", 100000000, "refuse a run of more time steps than this (0 = no limit)");
    const std::string& mech = opt.add_string("mechanics", "on", "off: heat conduction only (needs --heat)", {"on", "off"});
    const pd_run::HeatOptions heat = pd_run::add_heat_options(opt, automatic);
    const pd_run::ConventionOptions conventions = pd_run::add_convention_options(opt);
    const pd_run::DissipationOptions dissipation = pd_run::add_dissipation_options(opt, automatic);
    for (const char* name : {"K", "G", "rho", "delta", "dx", "thickness", "area", "dt", "k", "cv", "dt-thermal", "s0", "sls-tau"})
        opt.require_positive(name);
    opt.require_range("dim", 1, 3);
    opt.require_at_least("energy-every", 1);
    for (const char* name : {"thermal-steps", "steps", "vtu-every", "threads", "checkpoint-every", "max-steps"}) opt.require_at_least(name, 0);
    opt.parse(argc, argv);

    for (const char* name : {"input", "rho", "delta"})
        if (!opt.given(name)) fail(std::string("option --") + name + " is required (see --help)");
    check_model_options(opt, dim, model, surface, pv);
    const bool mechanics = mech == "on";
    if (!mechanics && heat.heat == "none") fail("option --mechanics off needs --heat agwai|correspondence");
    for (const char* name : {"E", "nu", "K", "G", "model", "hourglass", "surface-correction", "plane", "dt", "steps", "s0", "conventions",
                             "stress-law", "hourglass-direction", "rotation-increment", "rate-configuration", "start-stress", "pals-base"})
        if (!mechanics && opt.given(name)) fail(std::string("option --") + name + " applies to the mechanics (not --mechanics off)");
    pd_run::check_heat_options(opt, heat, mechanics, fail);

    Run cfg;
    cfg.plane = plane == "strain" ? pd::Plane::strain : pd::Plane::stress;
    if (mechanics) cfg.material = elastic_constants(opt, dim, cfg.plane);
    cfg.model = model == "scf" ? "lps-scf" : model;
    cfg.hourglass = hourglass;
    if (mechanics) cfg.conventions = pd_run::resolve_conventions(opt, conventions, cfg.model, dim, fail);
    cfg.dissipation = pd_run::dissipation_settings(opt, dissipation, cfg.model, dim, mechanics, heat.heat != "none", cfg.conventions.hypoelastic, fail);
    cfg.nsync_mh = dissipation.nsync_mh;
    cfg.surface = pd::parse_surface_correction(surface);
    if (hourglass < 0) fail("option --hourglass must be >= 0, got " + pd::io::format_shortest(hourglass));
    cfg.measure = dim == 2 ? thickness : dim == 1 ? area : 1.0;
    cfg.rho = rho;
    cfg.delta = delta;
    cfg.dx = opt.given("dx") ? dx : 0.0;
    cfg.influence = pd::Influence::parse(influence);
    cfg.partial_volume = pd::parse_partial_volume(pv);
    cfg.dt = dt;
    cfg.steps = mechanics ? steps : heat.steps;
    pd::step_limit() = max_steps;
    try {
        pd::require_steps(cfg.steps, mechanics ? "option --steps" : "option --thermal-steps");
    } catch (const std::invalid_argument& e) {
        fail(e.what());
    }
    cfg.mechanics = mechanics;
    cfg.heat = heat_settings(heat, rho, cfg.measure, energy_every);
    cfg.energy_every = energy_every;
    cfg.vtu_every = vtu_every;
    cfg.s0 = opt.given("s0") ? s0 : 0.0;
    try {
        cfg.output_steps = pd::io::parse_output_steps(out_steps, cfg.steps);
    } catch (const std::invalid_argument& e) {
        std::string msg = e.what();
        const std::size_t at = msg.find("beyond --steps");
        if (!mechanics && at != std::string::npos) msg.replace(at, 14, "beyond --thermal-steps");  // heat only: thermal steps
        fail(msg);
    }
    cfg.out = out;
    cfg.checkpoints.every = checkpoint_every;
    cfg.checkpoints.file = cfg.out / "checkpoint.pdstate";
    cfg.checkpoints.possible = heat.heat == "none" || heat.integrator != "cvode";
    if (!cfg.checkpoints.possible && (opt.given("checkpoint-every") || opt.given("restart")))
        fail(std::string("option --") + (opt.given("restart") ? "restart" : "checkpoint-every") +
             ": CVODE's internal history is not saved; use --thermal-integrator explicit or implicit");
    pd::set_threads(threads);

    pd::io::PointCloud pc;
    try {
        pc = pd::io::read_point_cloud(input, dim);
    } catch (const pd::io::PointCloudError& e) {
        fail(e.what());
    }
    check_cloud(pc, opt, mechanics, heat.heat != "none");
    cfg.checkpoints.fingerprint = physics_fingerprint(opt, pc);
    cfg.heat.resumed = !restart.empty();
    if (!restart.empty()) cfg.checkpoints.load(restart, cfg.steps, mechanics ? "--steps" : "--thermal-steps", cfg.out, fail);

    std::cout << program << ": options\n";
    opt.echo(std::cout);
    try {
        std::filesystem::create_directories(cfg.out);
        if (cfg.checkpoints.same_folder) pd::io::OutputManifest::resume(cfg.out);  // keeps the files of the run it continues
        else pd::io::OutputManifest::begin(cfg.out);               // the previous run's files in --out go first (csv.hpp)
        opt.save_csv(cfg.out / "params.csv");
    } catch (const std::exception& e) {
        fail("option --out: " + std::string(e.what()));
    }
    try {
        if (dim == 1) return run<1>(cfg, pc);
        if (dim == 2) return run<2>(cfg, pc);
        return run<3>(cfg, pc);
    } catch (const pd::TimeScaleBeyondSolver& e) {  // CVODE cannot start on the heat problem's time scale
        fail("options --k, --cv, --rho, --delta: " + std::string(e.what()));
    } catch (const std::invalid_argument& e) {  // a scene the library refuses (e.g. a point far beyond the others)
        fail(e.what());
    } catch (const std::exception& e) {  // e.g. a write error in the output folder
        std::cerr << program << ": " << e.what() << std::endl;
        return 1;
    }
}
