// problems/3d/peridigm_cloud.cpp -- agreement with Peridigm, to round-off, on one point cloud, and
// what each of this library's conventions changes against Peridigm's.
// Case (scene A of reference/peridigm_cloud/README.md): a free steel bar, 24 x 6 x 6 nodes at 0.5 mm,
// horizon 3.0001 h, K = 160 GPa, G = 80 GPa, rho = 7800 kg/m^3, initial velocity vx = 10 sin(pi x/Lx),
// 100 velocity-Verlet steps of 5 ns; models PMB, LPS, PALS and correspondence (hourglass 0.02).
// Reference: Peridigm's displacements and velocities after 100 steps (an independent code).
// Compared, per model: max_i |u_i - u_i^P| / max_i |u_i^P| and the same for v, for Peridigm's
// conventions, ours, and Peridigm's with one of ours (the five of the hypo-elastic correspondence:
// stress law, hourglass direction, rotation increment, rate configuration, start stress; PALS: base
// influence functions). PMB and LPS have no such choice.
// --check: Peridigm's conventions agree within --tol for every model (round-off of 100 steps).
// Run: peridigm_cloud_3d [--reference DIR] [--tol 1e-10] [--check] [--out DIR]
// Writes: agreement.csv (model, ours_for, u_rel_diff, v_rel_diff, wall_s), summary.csv, params.csv.
#include "pd/core/timer.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/models/registry.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace {

// One set of conventions: Peridigm's forms except the one named (ours_for; "everything": all ours).
struct Variant {
    std::string ours_for;
    pd::ModelChoice choice;
    pd::RateFormPairing pairing;
};

std::vector<Variant> variants(const std::string& model, const pd::Elastic& mat, double C_hg, double dt)
{
    using pd::HourglassDirection, pd::laws::RotationIncrement;
    const pd::ModelChoice ours{.name = model, .material = mat, .C_hg = C_hg};
    pd::ModelChoice theirs = ours;
    pd::RateFormPairing peridigm_pairing;
    if (model == "correspondence") {
        theirs.hypoelastic = true, theirs.hourglass_direction = HourglassDirection::bond, theirs.rotation = RotationIncrement::peridigm;
        peridigm_pairing = {.end_of_step = true, .initial_velocity_step = dt};
    }
    if (model == "pals") theirs.pals_base = pd::PALS::Base::unit;
    std::vector<Variant> v{{"nothing", theirs, peridigm_pairing}, {"everything", ours, {}}};
    auto one = [&](const std::string& name, auto&& change) {
        Variant w{name, theirs, peridigm_pairing};
        change(w);
        v.push_back(w);
    };
    if (model == "correspondence") {
        one("stress_law", [](Variant& w) { w.choice.hypoelastic = false; });
        one("hourglass_direction", [](Variant& w) { w.choice.hourglass_direction = HourglassDirection::unit; });
        one("rotation_increment", [](Variant& w) { w.choice.rotation = RotationIncrement::rodrigues; });
        one("rate_configuration", [](Variant& w) { w.pairing.end_of_step = false; });
        one("start_stress", [](Variant& w) { w.pairing.initial_velocity_step = 0; });
    }
    return v;
}

// max_i |a_i - b_i| / max_i |b_i| over the three components of every node.
double relative_difference(const pd::Field<3>& a, const pd::io::CsvTable& ref, const char* const (&columns)[3])
{
    double diff = 0, scale = 0;
    for (int d = 0; d < 3; ++d) {
        const std::vector<double> b = ref.numbers(columns[d]);
        for (std::size_t i = 0; i < b.size(); ++i) diff = std::max(diff, std::abs(a.c[d][i] - b[i])), scale = std::max(scale, std::abs(b[i]));
    }
    return diff / scale;
}

int run_case(int argc, char** argv)
{
    // 1. Options (SI; the scene of the reference's README).
    pd::io::Case run("peridigm_cloud_3d", "Agreement with Peridigm on one point cloud; the effect of each convention.",
                     "reports/3d/peridigm_cloud");
    std::string& reference = run.opt.add_string("reference", "", "folder with Peridigm's A_cloud.csv and A_<model>_step0100.csv "
                                                                 "(empty: the source tree's reference/peridigm_cloud)");
    const double& K = run.opt.add("K", 160e9, "bulk modulus", "Pa");
    const double& G = run.opt.add("G", 80e9, "shear modulus", "Pa");
    const double& rho = run.opt.add("rho", 7800, "density", "kg/m^3");
    const double& delta = run.opt.add("delta", 1.50005e-3, "horizon (3.0001 h)", "m");
    const double& C_hg = run.opt.add("hourglass", 0.02, "correspondence hourglass coefficient");
    const double& dt = run.opt.add("dt", 5e-9, "time step", "s");
    const double& tol = run.opt.add("tol", 1e-10, "--check bound on the relative difference with Peridigm's conventions");
    for (const char* name : {"K", "G", "rho", "delta", "dt", "tol"}) run.opt.require_positive(name);
    run.opt.require_at_least("hourglass", 0);
    run.start(argc, argv);
    const std::filesystem::path dir = reference.empty() ? std::filesystem::path(PD_SOURCE_DIR) / "reference/peridigm_cloud" : std::filesystem::path(reference);

    // 2. Discretisation: Peridigm's point cloud, its initial velocity, the family |xi| <= delta.
    const pd::io::CsvTable cloud = pd::io::read_csv(dir / "A_cloud.csv");
    pd::Body<3> body;
    const std::vector<double> x = cloud.numbers("x"), y = cloud.numbers("y"), z = cloud.numbers("z"), V = cloud.numbers("volume");
    for (std::size_t i = 0; i < V.size(); ++i) body.push({{x[i], y[i], z[i]}}, V[i]);
    const char* const v0_columns[3] = {"vx0", "vy0", "vz0"};
    pd::Bonds bonds = pd::build_bonds(body, delta, pd::BondOptions{});
    std::printf("%zu nodes, %zu bonds (ordered pairs)\n", body.size(), bonds.size());

    constexpr int steps = 100;  // the reference's state is after 100 steps
    // 3.-5. Per model and set of conventions: 100 Verlet steps, then u and v against Peridigm's.
    pd::io::CsvWriter csv(run.file("agreement.csv"), {"model", "ours_for", "u_rel_diff", "v_rel_diff", "wall_s"});
    std::printf("\n%-15s %-20s %12s %12s %8s\n", "model", "ours_for", "u_rel_diff", "v_rel_diff", "wall_s");
    const char* const u_columns[3] = {"ux", "uy", "uz"};
    const char* const v_columns[3] = {"vx", "vy", "vz"};
    const pd::Elastic mat{.K = K, .G = G};
    double worst = 0;  // the largest relative difference with Peridigm's conventions [-]
    for (const std::string model : {"pmb", "lps", "pals", "correspondence"}) {
        const std::string file = "A_" + std::string(model == "correspondence" ? "corr" : model) + "_step0100.csv";
        const pd::io::CsvTable ref = pd::io::read_csv(dir / file);
        for (const Variant& w : variants(model, mat, C_hg, dt)) {
            pd::io::Timer timer;
            pd::Field<3> u, v;
            pd::with_model(w.choice, body, bonds, [&](auto& m) {
                pd::Explicit sim(body, bonds, m, rho);
                sim.scene.rate_pairing = w.pairing;
                for (int d = 0; d < 3; ++d) sim.v.c[d] = cloud.numbers(v0_columns[d]);
                sim.start();
                for (int n = 0; n < steps; ++n) sim.step(dt);
                u = sim.u, v = sim.v;
            });
            const double eu = relative_difference(u, ref, u_columns), ev = relative_difference(v, ref, v_columns);
            const double wall = timer.seconds();
            csv.row({model, w.ours_for, eu, ev, wall});
            std::printf("%-15s %-20s %12.3e %12.3e %8.3f\n", model.c_str(), w.ours_for.c_str(), eu, ev, wall);
            if (w.ours_for != "nothing") continue;
            worst = std::max({worst, eu, ev});
            run.summary({{model + "_u_rel_diff", eu, NAN, NAN, "-"}, {model + "_v_rel_diff", ev, NAN, NAN, "-"}});
            run.check(std::max(eu, ev) <= tol, model + " with Peridigm's conventions: u and v within --tol " + pd::io::format_shortest(tol) +
                                                   " of Peridigm's (round-off)");
        }
    }
    return run.finish("Peridigm's conventions: largest difference from Peridigm's four models %.1e (bound %.0e)", worst, tol);
}

}  // namespace

int main(int argc, char** argv) { return pd::io::guarded_main("peridigm_cloud_3d", [&] { return run_case(argc, argv); }); }
