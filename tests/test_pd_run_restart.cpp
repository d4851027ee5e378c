// pd_run checkpoints (problems/pd_run_checkpoint.hpp): a run stopped at a checkpoint and continued by
// --restart writes the same files, byte for byte, as the uninterrupted run (an explicit run with
// bond breaking, heat runs by explicit and implicit Euler, plastic and viscous runs heating the
// points); SIGTERM stops a run after its step with
// a checkpoint and complete CSV files; a checkpoint of another run, a cut one, or one with CVODE is
// refused with exit 2 and one line.
#include "pd_run_harness.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>

using namespace pd_test;

namespace {
// 8 x 4 x 4 nodes, the halves moving apart at 20 m/s: the bonds across the mid-plane break from
// the first steps on (tests/test_pd_run_damage.cpp), a temperature step along x for the heat runs.
std::filesystem::path pulled_block(bool moving = true, bool warm = false)
{
    std::string s = std::string("x,y,z,volume") + (moving ? ",vx" : "") + (warm ? ",T0" : "") + "\n";
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 8; ++i)
                s += num((i + 0.5) * 1e-3) + "," + num((j + 0.5) * 1e-3) + "," + num((k + 0.5) * 1e-3) + ",1e-9" +
                     (moving ? std::string(",") + num(i < 4 ? -20 : 20) : "") + (warm ? std::string(i < 2 ? ",100" : ",20") : "") + "\n";
    return write_file(std::string(moving ? "pulled" : "still") + (warm ? "_warm" : "") + ".csv", s);
}

// Runs `args` for `total` steps, once whole and once as a run of `at` steps with a checkpoint every
// `every` steps, continued from its last checkpoint by --restart into the same folder; the named
// files must be identical. A checkpoint at the short run's last step off the output cadence makes
// the restart drop that run's last-step rows; one before it makes the restart redo the steps after.
void expect_restart_identical(const std::string& tag, const std::string& args, const char* steps_option, int total, int at, int every,
                              const std::vector<std::string>& files)
{
    SCOPED_TRACE(tag);
    const Result whole = pd_run(tag + "_whole", args + " " + steps_option + " " + std::to_string(total));
    ASSERT_EQ(whole.status, 0) << whole.err;
    const Result first = pd_run(tag + "_cut", args + " " + steps_option + " " + std::to_string(at) + " --checkpoint-every " +
                                                  std::to_string(every));
    ASSERT_EQ(first.status, 0) << first.err;
    const std::filesystem::path ckpt = first.dir / "checkpoint.pdstate";
    ASSERT_TRUE(std::filesystem::exists(ckpt));
    // Continue into the same folder (pd_run() would clear it: the command is spelled out here).
    const std::string cmd = std::string(PD_BIN_DIR) + "/pd_run " + args + " " + steps_option + " " + std::to_string(total) +
                            " --restart " + ckpt.string() + " --out " + first.dir.string() + " > /dev/null 2> " +
                            (base() / (tag + "_restart.stderr")).string();
    ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(base() / (tag + "_restart.stderr"));
    for (const std::string& f : files) {
        ASSERT_TRUE(std::filesystem::exists(whole.dir / f)) << f;
        EXPECT_EQ(slurp(first.dir / f), slurp(whole.dir / f)) << f;
    }
}
}  // namespace

TEST(PdRunRestart, ExplicitRunWithBondBreakingContinuesBitForBit)
{
    const auto p = pulled_block();
    for (const std::string model : {"pmb", "lps", "correspondence --hourglass 0.02"})
        expect_restart_identical("explicit_" + model.substr(0, 4),
                                 "--input " + p.string() + steel + " --model " + model +
                                     " --delta 3e-3 --s0 1e-3 --energy-every 5 --vtu-every 10",
                                 "--steps", 40, 23, 23,
                                 {"energy.csv", "state_step0040.csv", "state_step0010.vtu", "state_step0040.vtu", "state.pvd"});
}

TEST(PdRunRestart, HeatRunsContinueBitForBit)
{
    const auto p = pulled_block(true, true), still = pulled_block(false, true);
    const std::string heat = " --heat agwai --k 50 --cv 500 --delta 2.5e-3";
    for (const char* integrator : {"explicit", "implicit"})
        expect_restart_identical(std::string("heat_") + integrator,
                                 "--input " + still.string() + heat + " --mechanics off --rho 7800 --thermal-integrator " + integrator,
                                 "--thermal-steps", 30, 13, 6, {"heat.csv", "state_step0030.csv"});
    // Mechanics with bond breaking and the heat on the mechanical clock.
    expect_restart_identical("both", "--input " + p.string() + heat + steel + " --s0 1e-3 --dt 2e-8 --dt-thermal 1e-7 --energy-every 5", "--steps",
                             40, 23, 23, {"energy.csv", "heat.csv", "state_step0040.csv"});
}

TEST(PdRunRestart, DissipativeRunsContinueBitForBit)
{
    // The plastic and viscous histories, the heat not yet released (N_sync(MH) = 4: the checkpoint at
    // step 23 falls between releases), the heat guard's ceiling and the dissipated_heat_J column.
    const auto p = pulled_block(true, true);
    const std::string scene = " --heat agwai --k 50 --cv 500 --delta 3e-3" + steel + " --dt 2e-8 --nsync-mk 1 --energy-every 5";
    const std::pair<std::string, std::string> runs[] = {
        {"plastic_lps", "lps --plasticity johnson-cook --jc-A 1e8"},
        {"plastic_corr", "correspondence --plasticity johnson-cook --jc-A 1e8 --jc-m 1 --jc-T-ref 20 --jc-T-melt 1400"},
        {"viscous_corr", "correspondence --stress-law flanagan-taylor --viscoelastic sls --sls-tau 1e-7"}};
    for (const auto& [tag, model] : runs)
        expect_restart_identical("dissipative_" + tag, "--input " + p.string() + scene + " --nsync-mh 4 --model " + model, "--steps", 40, 23, 23,
                                 {"energy.csv", "heat.csv", "state_step0040.csv"});
}

TEST(PdRunRestart, SigtermStopsWithACheckpointAndCompleteFiles)
{
    const auto p = pulled_block();
    const std::string args = "--input " + p.string() + steel + " --model pmb --delta 3e-3 --s0 1e-3 --energy-every 1";
    // A run of 10^7 steps, stopped by SIGTERM once it has opened energy.csv (its step loop is next;
    // the handler is installed first thing in main), at most 30 s later.
    const std::filesystem::path dir = base() / "sigterm";
    const std::string cmd = "sh -c '" + std::string(PD_BIN_DIR) + "/pd_run " + args + " --steps 10000000 --out " + dir.string() +
                            " > /dev/null 2> " + (base() / "sigterm.stderr").string() + " & pid=$!; n=0; while [ ! -e " +
                            (dir / "energy.csv.part").string() + " ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; " +
                            "sleep 0.2; kill -TERM $pid; wait $pid'";
    const int raw = std::system(cmd.c_str());
    const std::string err = slurp(base() / "sigterm.stderr");
    ASSERT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 128 + SIGTERM) << err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(err, m, std::regex("stopped by SIGTERM after step ([0-9]+); checkpoint "))) << err;
    const long stopped = std::stol(m[1]);
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    // energy.csv is complete (renamed from its .part) and ends with the step the run stopped after.
    ASSERT_TRUE(std::filesystem::exists(dir / "energy.csv"));
    EXPECT_FALSE(std::filesystem::exists(dir / "energy.csv.part"));
    const auto energy = pd::io::read_csv(dir / "energy.csv");
    ASSERT_EQ(energy.rows.size(), static_cast<std::size_t>(stopped + 1));
    EXPECT_EQ(energy.rows.back().fields[0], std::to_string(stopped));
    // The checkpoint continues the run.
    const std::string more = std::string(PD_BIN_DIR) + "/pd_run " + args + " --steps " + std::to_string(stopped + 10) + " --restart " +
                             (dir / "checkpoint.pdstate").string() + " --out " + dir.string() + " > /dev/null 2>&1";
    ASSERT_EQ(std::system(more.c_str()), 0);
    EXPECT_EQ(pd::io::read_csv(dir / "energy.csv").rows.size(), static_cast<std::size_t>(stopped + 11));
}

TEST(PdRunRestart, ForeignCutOrCvodeCheckpointsExitTwoWithOneLine)
{
    const auto p = pulled_block();
    const std::string args = "--input " + p.string() + " --nu 0.25 --rho 7800 --delta 3e-3 --s0 1e-3";
    const Result first = pd_run("ckpt", args + " --E 200e9 --steps 10 --checkpoint-every 10");
    ASSERT_EQ(first.status, 0) << first.err;
    const std::string ckpt = (first.dir / "checkpoint.pdstate").string();
    std::ofstream(base() / "cut.pdstate") << slurp(ckpt).substr(0, 100);
    const std::pair<std::string, std::string> cases[] = {
        {" --E 100e9 --steps 20 --restart " + ckpt, "'E = 2e+11 [Pa]' in the checkpoint, 'E = 1e+11 [Pa]' in this run"},
        {" --E 200e9 --steps 5 --restart " + ckpt, "option --steps: the checkpoint is at step 10, beyond 5: nothing to continue"},
        {" --E 200e9 --steps 10 --restart " + ckpt, "the end of the run at 10: nothing to continue"},
        {" --E 200e9 --steps 20 --restart " + (base() / "cut.pdstate").string(), "option --restart: checkpoint"},
        {" --E 200e9 --steps 20 --restart " + p.string(), "not a pd checkpoint"},
        {" --E 200e9 --heat agwai --k 50 --cv 500 --thermal-integrator cvode --checkpoint-every 5", "option --checkpoint-every"},
    };
    for (const auto& [extra, needle] : cases) {
        const Result r = pd_run("refused", args + extra);
        EXPECT_EQ(r.status, 2) << extra << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << extra << ": " << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << extra << ": " << r.err;
    }
}
