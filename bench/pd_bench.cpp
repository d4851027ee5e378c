// bench/pd_bench.cpp -- bond throughput of THE bond loop (bond_loop.hpp) on a 3D simple-cubic box.
// Scene: N x N x N nodes, spacing dx, horizon delta = m dx, influence 1, no partial volumes, no
// bond breaking; steel-like E = 200 GPa, nu = 1/4, rho = 7850 kg/m^3; PMB (continuum micromodulus), LPS,
// PALS (default base functions), or correspondence (linear law, Littlewood hourglass control
// C_hg = 0.02 as in model_cost_3d).
// Initial state: isotropic stretch 1e-4 plus a smooth wave, so every bond carries a force.
// Timed (steady_clock, after one untimed warm-up):
//   --what step (default): S velocity-Verlet steps of pd::Explicit::step at 0.5 x the
//     Silling-Askari critical step (force + integration + stability guard), like LAMMPS' loop;
//   --what force: S calls of pd::internal_force (LPS, correspondence: point pass + bond pass).
// bond_updates_per_s = bonds * steps / wall_s with bonds = ordered pairs i->j (|xi| <= delta):
// one update is one bond force evaluation in one step. --repeat R reports the fastest of R runs.
// --verify reruns everything on 1 thread and exits 1 unless u, v and f agree bit for bit;
// --checksum prints a hash of the bits of u, v and f to stderr (to compare separate runs).
// --damage switches the bond-damage bookkeeping on (every bond intact), i.e. times the loop
// variant of damaged scenes.
// Run: pd_bench --model pmb|lps|pals|correspondence --n N --m 3 --steps S --threads T [--what step|force] [--repeat R]
//      [--verify] [--checksum] [--damage]
// Writes: CSV header (unless --no-header) and one line
//   model,nodes,bonds,steps,threads,wall_s,bond_updates_per_s
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/options.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/core/parallel.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <numbers>
#include <string>

namespace {

constexpr double E_steel = 200e9;    // Young's modulus [Pa]
constexpr double nu_pmb = 0.25;      // Poisson's ratio fixed by PMB in 3D [-]
constexpr double rho_steel = 7850;   // density [kg/m^3]
constexpr double stretch0 = 1e-4;    // initial isotropic stretch [-]
constexpr double wave0 = 1e-5;       // initial wave amplitude / box side [-]
constexpr double dt_safety = 0.5;    // fraction of the critical step (spec/000a sec. 3.3.2)
constexpr double C_hg = 0.02;        // correspondence hourglass coefficient (the source's, as model_cost_3d)

struct Scene {
    pd::Body<3> body;
    pd::Bonds bonds;
    pd::Field<3> u0;  // initial displacement [m]
};

Scene make_scene(int n, int m, double dx, bool damage)
{
    Scene s;
    const double side = n * dx;
    s.body = pd::box<3>({0, 0, 0}, {side, side, side}, dx);
    s.bonds = pd::build_bonds(s.body, m * dx);
    if (damage) s.bonds.enable_damage();
    s.u0.resize(s.body.size());
    for (std::size_t i = 0; i < s.body.size(); ++i) {
        const pd::Vec<3> x = s.body.x[i];
        const double wave = wave0 * side * std::sin(2 * std::numbers::pi * x[0] / side) *
                            std::cos(2 * std::numbers::pi * x[1] / side);
        s.u0.set(i, stretch0 * x + pd::Vec<3>{{wave, -wave, 0.5 * wave}});
    }
    return s;
}

struct Outcome {
    double wall_s = 0;                 // fastest of the repeats [s]
    pd::Field<3> u, v, f;              // final state, for --verify
};

template <class Model>
Outcome run(Scene& s, Model& model, const std::string& what, int steps, int repeat, int threads)
{
    pd::set_threads(threads);
    Outcome out;
    out.wall_s = 1e300;
    if (what == "force") {
        pd::Field<3> y;
        pd::add_fields(s.body.x, s.u0, y);
        pd::internal_force(model, s.bonds, y, out.f);  // warm-up
        for (int r = 0; r < repeat; ++r) {
            pd::io::Timer timer;
            for (int k = 0; k < steps; ++k) pd::internal_force(model, s.bonds, y, out.f);
            out.wall_s = std::min(out.wall_s, timer.seconds());
        }
        out.u = s.u0;
        return out;
    }
    pd::Bonds& bonds = s.bonds;  // no damage law is attached, so no bond breaks
    pd::Explicit<3, Model> sim(s.body, bonds, model, rho_steel);
    sim.u = s.u0;
    sim.start();
    const pd::PMB::Params pmb{.material = pd::Elastic::from_E_nu(E_steel, nu_pmb)};
    const double c = pd::PMB::micromodulus(pmb, pd::Influence{}, bonds.delta);
    const double dt = dt_safety * pd::critical_step_silling_askari(bonds, sim.rho, c).dt;
    sim.step(dt);  // warm-up
    for (int r = 0; r < repeat; ++r) {
        pd::io::Timer timer;
        for (int k = 0; k < steps; ++k) sim.step(dt);
        out.wall_s = std::min(out.wall_s, timer.seconds());
    }
    out.u = sim.u;
    out.v = sim.v;
    out.f = sim.internal_force_density();
    return out;
}

// FNV-1a hash of the bits of the fields.
std::uint64_t hash_bits(std::initializer_list<const pd::Field<3>*> fields)
{
    std::uint64_t h = 14695981039346656037ull;
    for (const auto* field : fields)
        for (const auto& comp : field->c)
            for (double v : comp) {
                std::uint64_t b;
                std::memcpy(&b, &v, sizeof b);
                h = (h ^ b) * 1099511628211ull;
            }
    return h;
}

bool same_bits(const pd::Field<3>& a, const pd::Field<3>& b)
{
    for (int d = 0; d < 3; ++d) {
        if (a.c[d].size() != b.c[d].size()) return false;
        if (!a.c[d].empty() && std::memcmp(a.c[d].data(), b.c[d].data(), a.c[d].size() * sizeof(double)) != 0)
            return false;
    }
    return true;
}

}  // namespace

int run_bench(int argc, char** argv)
{
    // 1. Options.
    pd::io::Options opt("pd_bench", "Bond throughput of the bond loop on an N^3 simple-cubic box.");
    std::string& model_name = opt.add_string("model", "pmb", "material model", {"pmb", "lps", "pals", "correspondence"});
    int& n = opt.add_int("n", 20, "nodes per side of the cube");
    int& m = opt.add_int("m", 3, "horizon ratio delta/dx");
    int& steps = opt.add_int("steps", 100, "timed steps (force evaluations for --what force)");
    int& threads = opt.add_int("threads", 1, "OpenMP threads");
    std::string& what = opt.add_string("what", "step", "timed work: Verlet step or force only", {"step", "force"});
    int& repeat = opt.add_int("repeat", 1, "timed runs; the fastest is reported");
    double& dx = opt.add("dx", 1e-3, "lattice spacing", "m");
    bool& verify = opt.add_flag("verify", "rerun on 1 thread and require bit-identical u, v, f");
    bool& checksum = opt.add_flag("checksum", "print a hash of the bits of u, v, f to stderr");
    bool& damage = opt.add_flag("damage", "bond-damage bookkeeping on (all bonds intact)");
    bool& no_header = opt.add_flag("no-header", "omit the CSV header line");
    opt.require_at_least("n", 2);
    opt.require_at_least("m", 1);
    opt.require_at_least("steps", 1);
    opt.require_at_least("threads", 1);
    opt.require_at_least("repeat", 1);
    opt.require_positive("dx");
    opt.parse(argc, argv);

    // 2. Discretisation and model.
    Scene s = make_scene(n, m, dx, damage);
    const pd::Elastic material = pd::Elastic::from_E_nu(E_steel, nu_pmb);
    auto bench = [&](auto& model, int t) { return run(s, model, what, steps, repeat, t); };
    auto measure = [&](int t) {
        if (model_name == "pmb") {
            pd::PMB model(pd::PMB::Params{.material = material}, s.bonds);
            return bench(model, t);
        }
        if (model_name == "correspondence") {
            using C = pd::Correspondence<3>;
            C model(C::Params{.material = material, .law = C::Law::linear, .C_hg = C_hg}, s.body, s.bonds);
            return bench(model, t);
        }
        if (model_name == "pals") {
            pd::PALS model(pd::PALS::Params{.material = material}, s.body, s.bonds);
            return bench(model, t);
        }
        pd::LPS model(pd::LPS::Params{.material = material}, s.bonds);
        return bench(model, t);
    };

    // 3. Timed run, CSV line.
    const Outcome out = measure(threads);
    const double bonds = static_cast<double>(s.bonds.size());
    if (!no_header) std::printf("model,nodes,bonds,steps,threads,wall_s,bond_updates_per_s\n");
    std::printf("%s,%zu,%zu,%d,%d,%.6f,%.4e\n", model_name.c_str(), s.body.size(), s.bonds.size(), steps, threads,
                out.wall_s, bonds * steps / out.wall_s);
    std::fflush(stdout);

    // 4. Optional checks: hash of the final state; same bits on 1 thread.
    if (checksum)
        std::fprintf(stderr, "pd_bench: checksum %016llx (%s, n %d, %d steps, %d threads)\n",
                     static_cast<unsigned long long>(hash_bits({&out.u, &out.v, &out.f})), what.c_str(), n, steps, threads);
    if (verify) {
        const Outcome ref = measure(1);
        const bool ok = same_bits(out.u, ref.u) && same_bits(out.v, ref.v) && same_bits(out.f, ref.f);
        std::fprintf(stderr, "pd_bench: verify %s: u, v, f on %d threads %s those on 1 thread\n", ok ? "PASS" : "FAIL",
                     threads, ok ? "bit-identical to" : "DIFFER from");
        return ok ? 0 : 1;
    }
    return 0;
}

int main(int argc, char** argv) { return pd::io::guarded_main("pd_bench", [&] { return run_bench(argc, argv); }); }
