// Case-study drivers stopped and resumed (io/checkpoints.hpp): a --quick run stopped every N steps
// (--stop-after: exit 130 and one line that names --resume; SIGTERM: 143) and continued by --resume
// until it ends writes the same files as the uninterrupted run, and removes its checkpoints. The
// files are compared byte for byte, but for the wall times (columns and summary rows named "wall"),
// the one thing a resumed run measures differently, and params.csv (it records --resume). The
// reference is the uninterrupted run of the same executable: the property under test is that a stop
// and a resume change no result, not the results' accuracy (the drivers' own tests check those).
#include "pd/io/csv.hpp"

#include "pd_run_harness.hpp"
#include "scratch_dir.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using pd_test::slurp;

using Outcome = pd_test::Result;
const auto run = pd_test::run_program;

std::vector<std::string> split(const std::string& line)
{
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    return f;
}

// A CSV file's text without its wall-time columns and rows (header names or first fields with "wall").
std::string without_wall_times(const fs::path& p)
{
    std::istringstream in(slurp(p));
    std::string line, text;
    std::vector<bool> keep;
    for (bool header = true; std::getline(in, line); header = false) {
        const std::vector<std::string> f = split(line);
        if (header)
            for (const std::string& c : f) keep.push_back(c.find("wall") == std::string::npos);
        if (!header && !f.empty() && f[0].find("wall") != std::string::npos) continue;
        for (std::size_t k = 0; k < f.size(); ++k)
            if (k >= keep.size() || keep[k]) text += f[k] + ",";
        text += "\n";
    }
    return text;
}

std::set<std::string> files_of(const fs::path& dir)
{
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
    names.erase("params.csv"), names.erase(".pd_files");
    return names;
}

void expect_same_files(const fs::path& whole, const fs::path& resumed)
{
    const std::set<std::string> names = files_of(whole);
    EXPECT_EQ(files_of(resumed), names);  // no checkpoint or .part file left
    for (const std::string& n : names) {
        if (n.size() > 4 && n.substr(n.size() - 4) == ".csv") EXPECT_EQ(without_wall_times(resumed / n), without_wall_times(whole / n)) << n;
        else EXPECT_EQ(slurp(resumed / n), slurp(whole / n)) << n;
    }
}

// The files a stopped run left under their own names (params.csv apart) are finished ones: equal to
// the uninterrupted run's; the files still being written keep their ".part" names.
void expect_finished_files_only(const fs::path& whole, const fs::path& stopped)
{
    for (const std::string& n : files_of(stopped)) {
        if (n.size() > 5 && n.substr(n.size() - 5) == ".part") continue;
        if (n.size() > 8 && n.substr(n.size() - 8) == ".pdstate") continue;
        ASSERT_TRUE(fs::exists(whole / n)) << n;
        EXPECT_EQ(without_wall_times(stopped / n), without_wall_times(whole / n)) << n << " is cut";
    }
}

// Runs exe with args whole, then stopped after every `stop` steps and resumed until it ends (at least
// `min_stops` stops, in at least `min_loops` different time loops), and compares the files.
void expect_resume_changes_nothing(const std::string& exe, const std::string& args, long stop, int min_stops, int min_loops)
{
    SCOPED_TRACE(exe);
    const fs::path dir = pd_test::scratch_dir() / exe;
    fs::remove_all(dir);
    fs::create_directories(dir);
    const Outcome whole = run(exe, args, dir / "whole");
    ASSERT_EQ(whole.status, 0) << whole.err;
    const std::string stop_after = " --stop-after " + std::to_string(stop);
    Outcome o = run(exe, args + stop_after + " --checkpoint-every 7", dir / "resumed");
    int stops = 0;
    std::set<std::string> loops;
    while (o.status == 128 + SIGINT && stops < 50) {
        ++stops;
        EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
        EXPECT_NE(o.err.find("stopped by SIGINT (--stop-after) after step"), std::string::npos) << o.err;
        EXPECT_NE(o.err.find("--resume"), std::string::npos) << o.err;
        const std::size_t at = o.err.find("of time loop ");
        if (at != std::string::npos) loops.insert(o.err.substr(at + 13, o.err.find(';', at) - at - 13));
        expect_finished_files_only(dir / "whole", dir / "resumed");
        o = run(exe, args + stop_after + " --resume", dir / "resumed");
    }
    ASSERT_EQ(o.status, 0) << o.err;
    EXPECT_GE(stops, min_stops);
    EXPECT_GE(static_cast<int>(loops.size()), min_loops);
    expect_same_files(dir / "whole", dir / "resumed");
}

}  // namespace

// run_fracture (problems/common/crack/crack_run.hpp): PMB with critical stretch, the tip histories of
// the sampler; two dx of the refinement list, so that the stops fall in both loops.
TEST(DriverResume, CrackBranchingGlassChangesNothing)
{
    expect_resume_changes_nothing("crack_branching_glass_2d", "--quick --dx-list 2e-3,1e-3 --t-end 30e-6", 400, 2, 2);
}

// An impactor (its motion is state), window means of the support force, a loop that ends early.
TEST(DriverResume, PmmaDiskImpactChangesNothing)
{
    expect_resume_changes_nothing("pmma_disk_impact_3d", "--quick", 300, 2, 1);
}

// Correspondence with critical stretch and the viscoelastic (Flanagan-Taylor) correspondence with
// critical micropotential, one history file each.
TEST(DriverResume, NotchedPlateChangesNothing)
{
    expect_resume_changes_nothing("notched_plate_3d",
                                  "--quick --runs stretch,visco --etas 1.1 --t-end 40e-6 --t-ramp 40e-6 --strain 4e-3", 1000, 2, 2);
}

// Loops that end on a condition (5 us after the first break), one per criterion; random critical
// stretch per seed.
TEST(DriverResume, DeltaMBarAndConcretePlateChangeNothing)
{
    expect_resume_changes_nothing("delta_m_bar_3d", "--quick --rate 200", 300, 2, 2);
    expect_resume_changes_nothing("concrete_plate_random_3d", "--quick", 300, 2, 2);
}

// Quasi-static load steps, each an ADR solve: the converged fields of the last two steps, the curve,
// and the committed Flanagan-Taylor state of pd::LoadStep.
TEST(DriverResume, LargeStretchChangesNothing)
{
    expect_resume_changes_nothing("large_stretch_3d", "--quick --model correspondence --steps 20", 6, 3, 1);
}

// A real signal: SIGTERM once the first checkpoint exists stops the run with status 143 and one line;
// --resume finishes it with the files of the uninterrupted run. A --resume without checkpoints, or
// with other options, is refused with one line and status 2.
TEST(DriverResume, SigtermStopsAndResumeRefusesForeignFolders)
{
    const std::string exe = "kalthoff_winkler_2d", args = "--quick";
    const fs::path dir = pd_test::scratch_dir();
    const Outcome whole = run(exe, args, dir / "whole");
    ASSERT_EQ(whole.status, 0) << whole.err;
    const fs::path out = dir / "stopped", se = dir / "stopped.stderr";
    const std::string cmd = "sh -c '" + std::string(PD_BIN_DIR) + "/" + exe + " " + args + " --checkpoint-every 5 --out " + out.string() +
                            " > /dev/null 2> " + se.string() + " & pid=$!; n=0; while [ ! -e " + (out / "checkpoint_0.pdstate").string() +
                            " ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; kill -TERM $pid; wait $pid'";
    const int raw = std::system(cmd.c_str());
    const std::string err = slurp(se);
    ASSERT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 128 + SIGTERM) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_NE(err.find("stopped by SIGTERM after step"), std::string::npos) << err;
    const Outcome refused = run(exe, args + " --v 20 --resume", out);
    EXPECT_EQ(refused.status, 2) << refused.err;
    EXPECT_NE(refused.err.find("option --resume: "), std::string::npos) << refused.err;
    EXPECT_NE(refused.err.find("in the checkpoint,"), std::string::npos) << refused.err;
    const Outcome resumed = run(exe, args + " --resume", out);
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    expect_same_files(dir / "whole", out);

    const Outcome empty = run(exe, args + " --resume", dir / "empty");
    EXPECT_EQ(empty.status, 2) << empty.err;
    EXPECT_EQ(std::count(empty.err.begin(), empty.err.end(), '\n'), 1) << empty.err;
    EXPECT_NE(empty.err.find("option --resume: no checkpoint in"), std::string::npos) << empty.err;
}

// A run killed outright (SIGKILL: no checkpoint of its own, its CSV files cut as ".part") resumes from
// its last --checkpoint-every checkpoint and redoes the steps after it, to the same files.
TEST(DriverResume, KilledRunResumesFromItsLastCadenceCheckpoint)
{
    const std::string exe = "crack_branching_glass_2d", args = "--quick --dx-list 2e-3,1e-3 --t-end 30e-6";
    const fs::path dir = pd_test::scratch_dir();
    const Outcome whole = run(exe, args, dir / "whole");
    ASSERT_EQ(whole.status, 0) << whole.err;
    const fs::path out = dir / "killed";
    const std::string cmd = "sh -c '" + std::string(PD_BIN_DIR) + "/" + exe + " " + args + " --checkpoint-every 50 --out " + out.string() +
                            " > /dev/null 2>&1 & pid=$!; n=0; while [ ! -e " + (out / "checkpoint_1.pdstate").string() +
                            " ] && [ $n -lt 600 ]; do sleep 0.01; n=$((n+1)); done; kill -KILL $pid; wait $pid'";
    const int raw = std::system(cmd.c_str());
    ASSERT_EQ(WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, 128 + SIGKILL);
    ASSERT_TRUE(fs::exists(out / "checkpoint_1.pdstate"));
    const Outcome resumed = run(exe, args + " --checkpoint-every 50 --resume", out);
    ASSERT_EQ(resumed.status, 0) << resumed.err;
    expect_same_files(dir / "whole", out);
}
