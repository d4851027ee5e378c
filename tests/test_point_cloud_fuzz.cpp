// Deterministic mutation fuzzing of the point-cloud reader (pd/io/point_cloud.hpp): valid clouds
// (1D, 2D, 3D; optional block, u, v, fixed, no_fail, T0, T_fixed columns; comments, blank lines,
// quoted fields) are mutated at the byte level (delete, insert, duplicate, swap, truncate, BOM, CR,
// CRLF, NUL, tabs, long lines) and at the token level (a number replaced by nan, inf, 1e308, -0,
// out-of-range integers, empty text, ...; header columns repeated, dropped, unknown; extra commas;
// rows repeated, swapped, dropped: point_cloud_mutations.hpp). Every input must either read into a
// PointCloud whose sizes agree and whose values are finite, with positive volumes, or throw
// PointCloudError with ONE line that starts with the file name. Any other exception, or a crash,
// fails; the input is printed escaped (after a crash it is left in the scratch file named on stderr).
#include <gtest/gtest.h>

#include "pd/io/point_cloud.hpp"

#include "point_cloud_mutations.hpp"
#include "scratch_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using namespace pd_test::point_cloud_mutations;

// What is wrong with a cloud the reader accepted ("" = nothing).
std::string check_cloud(const pd::io::PointCloud& pc, int dim)
{
    const std::size_t n = pc.size();
    if (n == 0) return "no points";
    for (int d = 0; d < 3; ++d)
        if (pc.x[d].size() != n || pc.u[d].size() != n || pc.v[d].size() != n) return "sizes differ (x, u, v)";
    if (pc.block.size() != n || pc.fixed.size() != n || pc.no_fail.size() != n || pc.T0.size() != n ||
        pc.T_fixed.size() != n || pc.line.size() != n)
        return "sizes differ (block, fixed, no_fail, T0, T_fixed, line)";
    std::set<std::array<double, 3>> at;
    for (std::size_t i = 0; i < n; ++i) {
        for (int d = 0; d < 3; ++d) {
            if (!std::isfinite(pc.x[d][i]) || !std::isfinite(pc.u[d][i]) || !std::isfinite(pc.v[d][i]))
                return "non-finite x, u or v at point " + std::to_string(i);
            if (d >= dim && (pc.x[d][i] != pc.x[d][0] || pc.u[d][i] != 0 || pc.v[d][i] != 0))
                return "coordinate, u or v beyond dim varies at point " + std::to_string(i);
            if (pc.fixed[i] && pc.v[d][i] != 0) return "fixed point with a velocity at point " + std::to_string(i);
        }
        if (!std::isfinite(pc.volume[i]) || !(pc.volume[i] > 0)) return "volume not finite and > 0 at point " + std::to_string(i);
        if (pc.has_column("T0") != std::isfinite(pc.T0[i])) return "T0 finite iff the column is given, point " + std::to_string(i);
        if (std::isinf(pc.T_fixed[i])) return "infinite T_fixed at point " + std::to_string(i);
        if (pc.fixed[i] > 1 || pc.no_fail[i] > 1) return "fixed / no_fail not 0 or 1 at point " + std::to_string(i);
        if (i > 0 && pc.line[i] <= pc.line[i - 1]) return "line numbers not increasing";
        if (!at.insert({pc.x[0][i], pc.x[1][i], pc.x[2][i]}).second) return "duplicate point " + std::to_string(i);
    }
    return "";
}

// The file of the running case, named on stderr if the reader crashes.
char crash_note[512];
extern "C" void on_crash(int sig)
{
    ssize_t ignored = write(2, crash_note, std::strlen(crash_note));
    (void)ignored;
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

}  // namespace

TEST(PointCloudFuzz, MutatedCloudsReadOrFailWithOneLine)
{
    const auto t0 = std::chrono::steady_clock::now();
    const fs::path file = pd_test::scratch_dir() / "cloud.csv";
    std::snprintf(crash_note, sizeof crash_note, "PointCloudFuzz: the reader crashed; the input is %s\n", file.c_str());
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS}) std::signal(sig, on_crash);

    const std::vector<Seed> base = seeds();
    for (const Seed& s : base) {  // the seeds themselves are valid
        std::ofstream(file, std::ios::binary) << s.text;
        EXPECT_NO_THROW({ EXPECT_EQ(check_cloud(pd::io::read_point_cloud(file, s.dim), s.dim), "") << s.text; }) << s.text;
    }

    Mutator mut{std::mt19937_64{20240611}};
    constexpr int cases = 4000;
    int accepted = 0, rejected = 0, failures = 0;
    std::size_t longest_message = 0;
    // Not failures, reported: messages that echo control bytes (NUL, CR, ...) or run very long.
    int control_messages = 0, long_messages = 0;
    std::string control_example, long_example;
    for (int k = 0; k < cases; ++k) {
        const Seed& seed = base[mut.pick(base.size())];
        std::string text = seed.text;
        for (std::size_t m = 0, n = 1 + mut.pick(3); m < n; ++m) mut.mutate(text);
        const int dim = mut.pick(4) == 0 ? 1 + static_cast<int>(mut.pick(3)) : seed.dim;
        std::ofstream(file, std::ios::binary | std::ios::trunc) << text;

        std::string problem;
        try {
            const pd::io::PointCloud pc = pd::io::read_point_cloud(file, dim);
            problem = check_cloud(pc, dim);
            ++accepted;
        } catch (const pd::io::PointCloudError& e) {
            const std::string msg = e.what();
            longest_message = std::max(longest_message, msg.size());
            if (std::any_of(msg.begin(), msg.end(), [](char c) { return static_cast<unsigned char>(c) < 32 && c != '\t'; }) &&
                control_messages++ == 0)
                control_example = escaped(msg, 300);
            if (msg.size() > 1000 && long_messages++ == 0) long_example = escaped(msg, 300);
            if (msg.find('\n') != std::string::npos) problem = "message of more than one line: " + escaped(msg, 600);
            else if (!msg.starts_with(file.string())) problem = "message does not start with the file name: " + escaped(msg, 600);
            ++rejected;
        } catch (const std::exception& e) {
            problem = std::string("exception other than PointCloudError: ") + typeid(e).name() + ": " + e.what();
        } catch (...) {
            problem = "non-standard exception";
        }
        if (!problem.empty() && ++failures <= 20)
            ADD_FAILURE() << "case " << k << " (dim " << dim << "): " << problem << "\ninput (escaped):\n" << escaped(text);
    }
    for (int sig : {SIGSEGV, SIGABRT, SIGFPE, SIGBUS}) std::signal(sig, SIG_DFL);
    EXPECT_EQ(failures, 0);
    EXPECT_GT(accepted, cases / 50);  // the mutations leave some clouds valid: the acceptance branch is exercised
    EXPECT_GT(rejected, cases / 2);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << cases << " mutated clouds: " << accepted << " read, " << rejected << " rejected (longest message "
              << longest_message << " characters); wall " << wall << " s\n";
    if (control_messages) std::cout << control_messages << " messages hold control bytes, e.g. " << control_example << "\n";
    if (long_messages) std::cout << long_messages << " messages are longer than 1000 characters, e.g. " << long_example << "\n";
    fs::remove_all(file.parent_path());
}
