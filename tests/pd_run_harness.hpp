// Runs build/bin/pd_run (or any executable of the build) from a test: scratch files, the command line,
// captured stdout/stderr and the exit status (shared by the pd_run and driver tests).
#pragma once
#include "pd/io/csv.hpp"

#include "scratch_dir.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace pd_test {

inline std::filesystem::path base() { return scratch_dir(); }

inline std::string slurp(const std::filesystem::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

inline std::filesystem::path write_file(const std::string& name, const std::string& text)
{
    std::filesystem::create_directories(base());
    const std::filesystem::path p = base() / name;
    std::ofstream(p) << text;
    return p;
}

struct Result {
    int status = -1;
    std::string out, err;
    std::filesystem::path dir;  // --out folder
};

// Runs build/bin/<exe> with `args`; stdout and stderr are captured (in capture + ".stdout", ".stderr"),
// with the exit status (-1 when it did not exit normally).
inline Result run_captured(const std::string& exe, const std::string& args, const std::filesystem::path& capture)
{
    Result r;
    const std::filesystem::path so = capture.string() + ".stdout", se = capture.string() + ".stderr";
    const std::string cmd = std::string(PD_BIN_DIR) + "/" + exe + " " + args + " > " + so.string() + " 2> " + se.string();
    const int raw = std::system(cmd.c_str());
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = slurp(so);
    r.err = slurp(se);
    return r;
}

// The same with --out `out` (the captured output beside the folder).
inline Result run_program(const std::string& exe, const std::string& args, const std::filesystem::path& out)
{
    Result r = run_captured(exe, args + " --out " + out.string(), out);
    r.dir = out;
    return r;
}

// Runs pd_run with `args` and --out base()/tag (removed first).
inline Result pd_run(const std::string& tag, const std::string& args)
{
    std::filesystem::remove_all(base() / tag);
    std::filesystem::create_directories(base());
    return run_program("pd_run", args, base() / tag);
}

inline std::string num(double v) { return pd::io::format_double(v); }

// n^3 simple cubic lattice of spacing dx; `extra(i, j, k)` appends the optional columns.
inline std::string lattice_csv(int n, double dx, const std::string& extra_header,
                               const std::function<std::string(int, int, int)>& extra)
{
    std::string s = "x,y,z,volume" + extra_header + "\n";
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i)
                s += num((i + 0.5) * dx) + "," + num((j + 0.5) * dx) + "," + num((k + 0.5) * dx) + "," +
                     num(dx * dx * dx) + extra(i, j, k) + "\n";
    return s;
}

inline const std::string steel = " --E 200e9 --nu 0.25 --rho 7800";  // material options [SI]

}  // namespace pd_test
