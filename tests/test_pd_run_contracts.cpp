// tests/test_pd_run_contracts.cpp -- the output and input contracts of build/bin/pd_run (reports/pd_run.md):
// file names, headers, 17 significant digits, energy rows and VTU snapshots; every invalid input exits 2
// with one stderr line naming the option or the file and line.
#include "pd/io/csv.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using pd::io::read_csv;

using namespace pd_test;  // the harness: pd_run, lattice_csv, write_file, steel, ...

// File names, headers, 17 significant digits, node ids; energy rows at 0, k, 2k, ... and the last
// step; VTU snapshots with their .pvd.
TEST(PdRun, OutputFilesFollowTheContract)
{
    const auto p = write_file("fmt.csv", "x,y,z,volume\n0.1,0.2,0.3,1e-9\n0.101,0.2,0.3,1e-9\n0.102,0.2,0.3,1e-9\n");
    const Result r = pd_run("fmt", "--input " + p.string() + steel +
                                       " --delta 1.5e-3 --steps 12 --output-steps 12,0,5 --energy-every 5 --vtu-every 10");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("dt = "), std::string::npos);  // the time step is printed
    for (const char* f : {"state_step0000.csv", "state_step0005.csv", "state_step0012.csv", "energy.csv", "params.csv",
                          "state_step0000.vtu", "state_step0010.vtu", "state_step0012.vtu", "state.pvd"})
        EXPECT_TRUE(fs::exists(r.dir / f)) << f;
    EXPECT_FALSE(fs::exists(r.dir / "state_step0010.csv"));
    const std::string state = slurp(r.dir / "state_step0000.csv");
    EXPECT_EQ(state.substr(0, state.find('\n')), "node_id,x,y,z,ux,uy,uz,vx,vy,vz");
    const std::size_t first = state.find('\n') + 1;
    EXPECT_EQ(state.substr(first, state.find('\n', first) - first),
              "0,0.10000000000000001,0.20000000000000001,0.29999999999999999,0,0,0,0,0,0");
    const auto st = read_csv(r.dir / "state_step0012.csv");
    for (std::size_t i = 0; i < st.rows.size(); ++i) EXPECT_EQ(st.rows[i].fields[0], std::to_string(i));
    const std::string energy = slurp(r.dir / "energy.csv");
    EXPECT_EQ(energy.substr(0, energy.find('\n')),
              "step,t_s,kinetic_J,strain_J,external_work_J,total_J,hourglass_work_J,dissipated_J,damage_released_J,balance_error_J");
    const auto e = read_csv(r.dir / "energy.csv");
    ASSERT_EQ(e.rows.size(), 4u);
    EXPECT_EQ(e.rows[1].fields[0], "5");
    EXPECT_EQ(e.rows[3].fields[0], "12");
}

// Every invalid input exits 2 with ONE stderr line naming the option or the file and line.
TEST(PdRun, BadInputsExitTwoWithOneLine)
{
    const std::string good = write_file("ok.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,1e-9\n").string();
    const std::string in = "--input " + good + " --delta 2e-3 --steps 10";
    const std::string bad_file = write_file("bad_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,-1\n").string();
    const std::string dup_file = write_file("dup_run.csv", "x,y,z,volume\n0,0,0,1e-9\n0,0,0,1e-9\n").string();
    const std::string txt_file = write_file("txt_run.csv", "x,y,z,volume\n0,zero,0,1e-9\n").string();
    const std::string z_file = write_file("z_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,1,1e-9\n").string();
    const std::string empty_file = write_file("empty_run.csv", "").string();
    const std::string comma_file = write_file("comma_run.csv", "x,y,z,volume,\n0,0,0,1e-9,\n").string();
    std::string flat = "x,y,z,volume\n";
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) flat += std::to_string(i * 1e-3) + "," + std::to_string(j * 1e-3) + ",0,1e-9\n";
    const std::string flat_file = write_file("flat_run.csv", flat).string();
    const std::string tiny_file = write_file("tiny_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,5e-324\n").string();
    const std::string far_file = write_file("far_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,1e-9\n1e20,0,0,1e-9\n").string();
    struct Case { std::string args, expect; };
    const std::vector<Case> cases = {
        {in + " --E -1 --nu 0.25 --rho 7800", "--E"},
        {in + " --E 200e9 --nu 0.5 --rho 7800", "--nu"},
        {in + steel + " --rho 0", "--rho"},
        {"--input " + good + steel + " --delta -1", "--delta"},
        {in + steel + " --dt 0", "--dt"},
        {in + steel + " --steps -1", "--steps"},
        {in + steel + " --output-steps 5,11", "--output-steps: step 11 is beyond --steps 10"},
        {in + steel + " --output-steps 1,x", "--output-steps"},
        {in + steel + " --K 1e9 --G 1e9", "--K"},
        {in + " --K 1e9 --nu 0.3 --rho 7800", "--K"},
        {in + " --rho 7800", "--E"},
        {in + " --E 1e9 --rho 7800", "--nu"},
        {in + steel + " --model foo", "--model"},
        {in + steel + " --model correspondence --hourglass -1", "--hourglass"},
        {in + steel + " --model scf --surface-correction energy --dx 1e-3", "--surface-correction energy applies to --model pmb or lps"},
        {in + steel + " --surface-correction energy", "--surface-correction energy needs --dx"},
        {in + steel + " --partial-volume pa-pdlammps", "--dx"},
        {in + steel + " --thickness 0.1", "--thickness"},
        {in + steel + " --dim 4", "--dim"},
        {in + steel + " --influence cubic", "--influence"},
        {in + steel + " --frobnicate 1", "--frobnicate"},
        {"--delta 2e-3" + steel, "--input"},
        {"--input " + bad_file + " --delta 2e-3" + steel, "bad_run.csv:3: column 'volume'"},
        {"--input " + dup_file + " --delta 2e-3" + steel, "dup_run.csv:3: duplicate point"},
        {"--input " + txt_file + " --delta 2e-3" + steel, "txt_run.csv:2: column 'y'"},
        {"--input " + z_file + " --dim 2 --delta 2e-3" + steel, "z_run.csv:3: column 'z'"},
        {"--input " + empty_file + " --delta 2e-3" + steel, "empty_run.csv: empty file"},
        {"--input " + (base() / "nowhere.csv").string() + " --delta 2e-3" + steel, "nowhere.csv: no such file"},
        {"--input " + base().string() + " --delta 2e-3" + steel, "not a regular file"},
        {"--input " + comma_file + " --delta 2e-3" + steel, "comma_run.csv:1: empty column name in the header (a trailing comma?)"},
        {"--input " + good + steel + " --delta 5e-4 --dt 1e-9", "--delta: no point has a bond within delta = 5e-04 m"},
        {"--input " + flat_file + steel + " --delta 1.5e-3 --model correspondence", "every shape tensor is singular"},
        {"--input " + tiny_file + steel + " --delta 2e-3", "tiny_run.csv:3: column 'volume': 5e-324 must be 0 or of magnitude 1e-30 to 1e30"},
        {"--input " + far_file + steel + " --delta 2e-3", "neighbour search: point 2 (0-based)"},
    };
    for (std::size_t k = 0; k < cases.size(); ++k) {
        const Result r = pd_run("bad" + std::to_string(k), cases[k].args);
        EXPECT_EQ(r.status, 2) << cases[k].args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_NE(r.err.find(cases[k].expect), std::string::npos) << cases[k].args << "\n" << r.err;
    }
}

// What spreadsheets write is read: a UTF-8 byte-order mark and CR-only line ends. Scenes that are
// partly empty run, with one warning line each: a point without bonds, a near-duplicate pair.
TEST(PdRun, BomCrLineEndsAndPartlyEmptyScenes)
{
    const std::string bom = write_file("bom_run.csv", "\xEF\xBB\xBFx,y,z,volume\r0,0,0,1e-9\r1e-3,0,0,1e-9\r").string();
    const Result r = pd_run("bom", "--input " + bom + steel + " --delta 2e-3 --steps 2");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("points 2, bonds 2"), std::string::npos) << r.out;
    const std::string lone = write_file("lone_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,1e-9\n1e-2,0,0,1e-9\n").string();
    const Result l = pd_run("lone", "--input " + lone + steel + " --delta 2e-3 --steps 2");
    EXPECT_EQ(l.status, 0) << l.err;
    EXPECT_NE(l.err.find("warning: 1 of 3 points have no bond within --delta"), std::string::npos) << l.err;
    const std::string near = write_file("near_run.csv", "x,y,z,volume\n0,0,0,1e-9\n1e-3,0,0,1e-9\n2e-3,0,0,1e-9\n2.000001e-3,0,0,1e-9\n").string();
    const Result d = pd_run("near", "--input " + near + steel + " --delta 1.5e-3 --steps 2");
    EXPECT_EQ(d.status, 0) << d.err;
    EXPECT_NE(d.err.find("warning: points 2 and 3 are 1e-09 m apart"), std::string::npos) << d.err;
}
