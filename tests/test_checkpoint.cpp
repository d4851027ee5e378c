// Checkpoint and restart of an explicit run (core/state_archive.hpp, Explicit::state/resume): a run
// saved after k steps to a file and resumed by a newly built integrator ends bit for bit where the
// uninterrupted run ends (displacements, velocities, intact bonds, energies), for bond breaking by
// critical stretch and by critical micropotential, for a model rebuilt from its bonds (LPS) and for
// models with history (plastic LPS, PALS and correspondence, viscoelastic LPS, Flanagan-Taylor and viscoelastic
// correspondence); a CSV file and a timer continue from their state. A damaged or foreign checkpoint is
// refused with one line.
#include "pd/core/lattice.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/models/viscoelastic_lps.hpp"
#include "pd/io/csv.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include "scratch_dir.hpp"

#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pd;

namespace {
constexpr double dx = 1e-3, dt = 5e-8, rho = 7800;
const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

Body<3> bar() { return box<3>({{0, 0, 0}}, {{6 * dx, 3 * dx, 3 * dx}}, dx); }

// The model a make() built: the value itself, or what a holder points to (a model that keeps a
// reference to another, e.g. the viscoelastic correspondence to its Flanagan-Taylor model).
template <class M>
M& model_of(M& m) { return m; }
template <class M>
M& model_of(std::unique_ptr<M>& m) { return *m; }
struct ViscoelasticHolder {
    std::unique_ptr<Correspondence<3>> inner;
    std::unique_ptr<ViscoelasticCorrespondence> model;
};
ViscoelasticCorrespondence& model_of(ViscoelasticHolder& h) { return *h.model; }

struct Outcome {
    Field<3> u, v;
    std::vector<std::uint8_t> intact;
    long step = 0, broken = 0;
    double kinetic = 0, strain = 0, external_work = 0;
};

// Runs `total` steps of a bar pulled apart by an initial velocity v_x = v0 x / L; with
// `checkpoint_at` > 0 it stops there, writes the checkpoint, and a new scene built the same way
// resumes from the file for the remaining steps. make(body, bonds) builds the model, rule() the
// damage rule (or a null pointer for none; it must outlive the run).
template <class Make, class Rule>
Outcome run(Make make, Rule* rule, long total, long checkpoint_at, const std::filesystem::path& file, double v0)
{
    const Body<3> body = bar();
    auto segment = [&](long from, long to, bool resume) {
        Bonds bonds = build_bonds(body, 3.015 * dx);
        auto holder = make(body, bonds);
        auto& model = model_of(holder);
        Explicit<3, std::remove_reference_t<decltype(model)>> ex(body, bonds, model, rho);
        Rule fresh = rule ? *rule : Rule{};
        if (rule) ex.scene.set_damage(fresh);
        for (std::size_t i = 0; i < body.size(); ++i) ex.v.c[0][i] = v0 * (body.x.c[0][i] / (6 * dx) - 0.5);
        if (resume) {
            StateArchive ar = StateArchive::read(file);
            ex.state(ar);
        } else {
            ex.start();
        }
        for (long n = from; n < to; ++n) ex.step(dt);
        if (to == checkpoint_at) {
            StateArchive ar;
            ex.state(ar);
            ar.write(file);
        }
        const Energies e = ex.energies();
        return Outcome{ex.u, ex.v, bonds.intact, ex.step_count, ex.broken_bonds, e.kinetic, e.strain, e.external_work};
    };
    if (checkpoint_at <= 0) return segment(0, total, false);
    segment(0, checkpoint_at, false);
    return segment(checkpoint_at, total, true);
}

void expect_identical(const Outcome& a, const Outcome& b)
{
    for (int d = 0; d < 3; ++d) {
        EXPECT_EQ(a.u.c[d], b.u.c[d]) << "u component " << d;
        EXPECT_EQ(a.v.c[d], b.v.c[d]) << "v component " << d;
    }
    EXPECT_EQ(a.intact, b.intact);
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.broken, b.broken);
    EXPECT_EQ(a.kinetic, b.kinetic);
    EXPECT_EQ(a.strain, b.strain);
    EXPECT_EQ(a.external_work, b.external_work);
}

template <class Make, class Rule>
void expect_restart_identical(Make make, Rule* rule, double v0, const char* what)
{
    SCOPED_TRACE(what);
    const std::filesystem::path file = pd_test::scratch_dir() / "run.pdstate";
    const long total = 80, at = 6;  // most pairs break within the first 40 steps
    const Outcome whole = run(make, rule, total, 0, file, v0);
    const Outcome resumed = run(make, rule, total, at, file, v0);
    if (rule) {  // bonds break before and after the checkpoint, so both halves are exercised
        const Outcome first = run(make, rule, at, 0, file, v0);
        EXPECT_GT(first.broken, 0);
        EXPECT_GT(whole.broken, first.broken);
    }
    expect_identical(whole, resumed);
}

auto make_pmb = [](const Body<3>&, const Bonds& b) { return PMB({.material = steel, .dim = 3}, b); };
auto make_lps = [](const Body<3>&, const Bonds& b) { return LPS({.material = steel, .dim = 3}, b); };
}  // namespace

// v0 = 20 m/s across 6 mm: the release waves from the free ends (c ~ 5 km/s) cap the strain near
// v0 / (2 c) ~ 2e-3, reached within the 80 steps (4 us).
TEST(Checkpoint, ExplicitRunWithCriticalStretchRestartsBitForBit)
{
    CriticalStretch stretch;
    stretch.s0 = 5e-4;
    expect_restart_identical(make_pmb, &stretch, 20.0, "PMB, critical stretch");
    expect_restart_identical(make_lps, &stretch, 20.0, "LPS (m_i rebuilt from the bonds), critical stretch");
}

TEST(Checkpoint, ExplicitRunWithCriticalMicropotentialRestartsBitForBit)
{
    CriticalMicropotential<3> micro;
    micro.w_c = w_critical(1.0, 3.015 * dx);  // J_C = 1 J/m^2: pairs break within the 80 steps
    expect_restart_identical(make_lps, &micro, 20.0, "LPS, critical micropotential");
}

TEST(Checkpoint, PlasticRunRestartsBitForBit)
{
    const laws::JohnsonCook soft{.A = 5e7, .B = 1e8, .n = 0.5};  // yields at strain ~ 2e-4
    auto make = [&](const Body<3>&, const Bonds& b) { return PlasticLPS({.material = steel, .dim = 3}, b, soft); };
    CriticalStretch* none = nullptr;
    expect_restart_identical(make, none, 20.0, "plastic LPS");
    auto make_pals = [&](const Body<3>& body, const Bonds& b) { return PlasticPALS({.material = steel}, body, b, soft); };
    expect_restart_identical(make_pals, none, 20.0, "plastic PALS");
    // Rate-dependent: a return redone from the committed history would flow again (plastic_correspondence.hpp).
    const laws::JohnsonCook rate_soft{.A = 5e7, .B = 1e8, .n = 0.5, .C = 0.1, .epdot0 = 1};
    auto make_corr = [&](const Body<3>& body, const Bonds& b) { return PlasticCorrespondence({.material = steel}, body, b, rate_soft); };
    expect_restart_identical(make_corr, none, 20.0, "plastic correspondence, rate dependent");
    CriticalMicropotential<3> micro;  // J_C = 1000 J/m^2: pairs break from step 5 on, before and after the checkpoint
    micro.w_c = w_critical(1000.0, 3.015 * dx);
    expect_restart_identical(make_corr, &micro, 20.0, "plastic correspondence, critical micropotential");
    // The history is what makes it a restart: plastic flow happened before the checkpoint.
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3.015 * dx);
    PlasticLPS model({.material = steel, .dim = 3}, b, soft);
    Explicit<3, PlasticLPS> ex(body, b, model, rho);
    for (std::size_t i = 0; i < body.size(); ++i) ex.v.c[0][i] = 20.0 * (body.x.c[0][i] / (6 * dx) - 0.5);
    ex.start();
    for (int n = 0; n < 6; ++n) ex.step(dt);  // the steps before the checkpoint
    EXPECT_GT(*std::max_element(model.pts.ep_c.begin(), model.pts.ep_c.end()), 0.0);
}

// The Maxwell branch relaxes over tau_b = 1 us, within the 4 us of the run.
TEST(Checkpoint, ViscoelasticRunRestartsBitForBit)
{
    auto make = [](const Body<3>&, const Bonds& b) {
        return ViscoelasticLPS({.lps = {.material = steel, .dim = 3}, .gamma_b = 1, .tau_b = 1e-6}, b);
    };
    CriticalStretch stretch;
    stretch.s0 = 5e-4;
    expect_restart_identical(make, &stretch, 20.0, "viscoelastic LPS, critical stretch");
}

// Rate-form stress (Flanagan-Taylor correspondence, with hourglass control): its unrotated stress,
// rotation and stretch are history; and the viscoelastic correspondence built on it, with bond
// breaking by critical stretch.
TEST(Checkpoint, RateFormCorrespondenceRestartsBitForBit)
{
    using C3 = Correspondence<3>;
    auto make_ft = [](const Body<3>& body, const Bonds& b) {
        return std::make_unique<C3>(C3::Params{steel, C3::Law::flanagan_taylor, 0.02}, body, b);
    };
    CriticalStretch* none = nullptr;
    expect_restart_identical(make_ft, none, 20.0, "Flanagan-Taylor correspondence");
    auto make_visco = [](const Body<3>& body, const Bonds& b) {
        ViscoelasticHolder h;
        h.inner = std::make_unique<C3>(C3::Params{steel, C3::Law::flanagan_taylor, 0.02}, body, b);
        h.model = std::make_unique<ViscoelasticCorrespondence>(*h.inner, ViscoelasticCorrespondence::Params{1, 1e-6}, body.x);
        return h;
    };
    CriticalStretch stretch;
    stretch.s0 = 5e-4;
    expect_restart_identical(make_visco, &stretch, 20.0, "viscoelastic correspondence, critical stretch");
}

// A CSV file filled by a run: the rows written before a checkpoint, restored into a new writer of the
// same file, are followed by the rows after it, as in one writer; a timer goes on from its seconds.
TEST(Checkpoint, CsvWriterAndTimerContinueFromTheirState)
{
    const std::filesystem::path dir = pd_test::scratch_dir();
    auto rows = [](io::CsvWriter& w, int from, int to) {
        for (int k = from; k < to; ++k) w.row({k, 0.1 * k});
    };
    {
        io::CsvWriter whole(dir / "whole.csv", {"k", "x"});
        rows(whole, 0, 10);
    }
    StateArchive saved;
    {
        io::CsvWriter first(dir / "cut.csv", {"k", "x"});
        rows(first, 0, 4);
        first.state(saved);
    }
    {
        std::ofstream(dir / "cut.csv") << "k,x\nrows of a later run that the restart must replace\n";
        io::CsvWriter again(dir / "cut.csv", {"k", "x"});
        const std::filesystem::path file = dir / "saved.pdstate";
        saved.write(file);
        StateArchive loaded = StateArchive::read(file);
        again.state(loaded);
        EXPECT_EQ(again.rows(), 4u);
        rows(again, 4, 10);
    }
    std::ifstream a(dir / "whole.csv"), b(dir / "cut.csv");
    const std::string ta((std::istreambuf_iterator<char>(a)), {}), tb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_EQ(ta, tb);

    StateArchive t;
    double stored = 100;  // a timer that had run 100 s before the stop
    t("wall", stored);
    t.write(dir / "timer.pdstate");
    StateArchive tl = StateArchive::read(dir / "timer.pdstate");
    io::Timer timer;
    timer.state(tl, "wall");
    EXPECT_GE(timer.seconds(), 100.0);
    EXPECT_LT(timer.seconds(), 160.0);  // plus this test's own time since
}

TEST(Checkpoint, ForeignOrDamagedFilesAreRefusedWithOneLine)
{
    const std::filesystem::path dir = pd_test::scratch_dir();
    StateArchive ar;
    std::vector<double> u{1, 2, 3};
    long step = 7;
    ar("u", u), ar("step", step);
    ar.write(dir / "a.pdstate");
    // Round trip.
    StateArchive in = StateArchive::read(dir / "a.pdstate");
    std::vector<double> u2;
    long step2 = 0;
    in("u", u2), in("step", step2);
    EXPECT_EQ(u2, u);
    EXPECT_EQ(step2, 7);
    EXPECT_FALSE(std::filesystem::exists(dir / "a.pdstate.part"));
    auto expect_refused = [](auto&& fn, const std::string& needle) {
        try {
            fn();
            ADD_FAILURE() << "accepted; expected: " << needle;
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(needle), std::string::npos) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    };
    // Another scene: the length differs from the run's array.
    std::vector<double> four(4, 0.0);
    expect_refused([&] { StateArchive::read(dir / "a.pdstate")("u", four); }, "has 3 values, the run has 4");
    expect_refused([&] { double x = 0; StateArchive::read(dir / "a.pdstate")("t", x); }, "no entry 't'");
    // A cut file, a foreign file, a missing file.
    const std::string whole = [&] {
        std::ifstream is(dir / "a.pdstate", std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(is), std::istreambuf_iterator<char>());
    }();
    std::ofstream(dir / "cut.pdstate", std::ios::binary) << whole.substr(0, whole.size() - 5);
    expect_refused([&] { StateArchive::read(dir / "cut.pdstate"); }, "cut.pdstate: the file is cut");
    std::ofstream(dir / "other.pdstate") << "x,y,z\n1,2,3\n";
    expect_refused([&] { StateArchive::read(dir / "other.pdstate"); }, "not a pd checkpoint");
    expect_refused([&] { StateArchive::read(dir / "missing.pdstate"); }, "cannot open");
}
