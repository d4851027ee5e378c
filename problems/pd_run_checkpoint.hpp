// problems/pd_run_checkpoint.hpp -- checkpoints of pd_run (problems/pd_run.cpp): --checkpoint-every N
// writes <out>/checkpoint.pdstate every N steps (core/state_archive.hpp: atomically, the previous one
// stays until the new one is complete); SIGINT or SIGTERM stops the run after the step in progress,
// writes a final checkpoint and closes the CSV files; --restart FILE continues the run of FILE so
// that it ends bit for bit as the uninterrupted run (energy.csv and heat.csv include the rows written
// before the checkpoint; state and VTU files of earlier steps stay in the checkpoint's folder).
// A checkpoint holds the integrator's fields, the intact bonds, the damage rule's state, the heat
// field, the rows of energy.csv and heat.csv, the VTU series, the step, and a fingerprint of the
// physics (every option but those a restart may change, below, and a checksum of the point cloud).
// CVODE's internal history (order, step sizes, Nordsieck array) is not saved: with
// --thermal-integrator cvode there are no checkpoints.
#pragma once
#include "pd/core/state_archive.hpp"
#include "pd/io/checkpoints.hpp"
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pd_run {

using pd::io::catch_stop_signals;
using pd::io::first_difference;
using pd::io::stop_signal;

// The physics of a run as text (io/checkpoints.hpp): every option but those a restart may change
// (where and how often output goes, and how long the run is), and the point cloud's size and
// checksum (FNV-1a of its columns' bytes).
inline std::string physics_fingerprint(const pd::io::Options& opt, const pd::io::PointCloud& pc)
{
    const std::string options =
        pd::io::options_fingerprint(opt, {"restart", "checkpoint-every", "out", "threads", "steps", "thermal-steps", "output-steps", "max-steps"});
    std::uint64_t h = 1469598103934665603ull;
    auto mix = [&](const void* p, std::size_t n) {
        for (std::size_t q = 0; q < n; ++q) h = (h ^ static_cast<const unsigned char*>(p)[q]) * 1099511628211ull;
    };
    auto mix_all = [&](const auto& v) { mix(v.data(), v.size() * sizeof v[0]); };
    for (int d = 0; d < 3; ++d) mix_all(pc.x[d]), mix_all(pc.u[d]), mix_all(pc.v[d]);
    mix_all(pc.volume), mix_all(pc.fixed), mix_all(pc.no_fail), mix_all(pc.T0), mix_all(pc.T_fixed);
    char cloud[96];
    std::snprintf(cloud, sizeof cloud, "  point cloud = %zu points, checksum %016llx\n", pc.size(), static_cast<unsigned long long>(h));
    return options + cloud;
}

// Whether a log row or snapshot of step n belongs to a run whose last step is `last`: on the cadence
// `every`, or the last step. A restart to more steps drops the rows its checkpoint's run wrote only
// because that run ended there, so that its files are those of the uninterrupted run.
inline bool on_cadence(long n, long every, long last) { return n % every == 0 || n == last; }

// A step number stored as a double in a checkpoint (log rows, snapshots), checked before the cast.
inline long step_number(double v)
{
    if (!(v >= 0 && v < 9e18 && v == std::floor(v))) throw std::invalid_argument("checkpoint: a stored step is not a step number");
    return static_cast<long>(v);
}

struct Checkpoints {
    long every = 0;                             // steps between checkpoints (0: only on a stop signal)
    bool possible = true;                       // false with CVODE (its history is not saved)
    std::filesystem::path file;                 // where this run writes them: <out>/checkpoint.pdstate
    std::string fingerprint;                    // physics_fingerprint of this run
    std::shared_ptr<pd::StateArchive> restart;  // the checkpoint this run continues; null: a new run
    long first = 0;                             // the step the run starts from (the checkpoint's)
    bool same_folder = false;                   // restarted into the checkpoint's folder (its files are kept)

    // Reads the checkpoint `path` that a run of `steps` steps (option steps_option) into `out`
    // continues: its physics must be this run's, its step before `steps`; fail(message) otherwise.
    template <class Fail>
    void load(const std::filesystem::path& path, long steps, const std::string& steps_option, const std::filesystem::path& out, Fail fail)
    {
        try {
            restart = std::make_shared<pd::StateArchive>(pd::StateArchive::read(path));
            std::string saved;
            (*restart)("pd_run.physics", saved);
            if (const std::string diff = first_difference(saved, fingerprint); !diff.empty())
                fail("option --restart: the checkpoint is of another run: " + diff);
            (*restart)("pd_run.step", first);
        } catch (const std::invalid_argument& e) {
            fail("option --restart: " + std::string(e.what()));
        }
        if (first < 0) fail("option --restart: the checkpoint's step is negative");
        if (first >= steps)
            fail("option " + steps_option + ": the checkpoint is at step " + std::to_string(first) +
                 (first > steps ? ", beyond " : ", the end of the run at ") + std::to_string(steps) + ": nothing to continue");
        std::error_code ec;
        same_folder = std::filesystem::equivalent(path.parent_path().empty() ? "." : path.parent_path(), out, ec);
    }

    // Writes the checkpoint of step n; state(ar) adds the run's parts.
    template <class State>
    void write(long n, State&& state) const
    {
        pd::StateArchive ar;
        std::string text = fingerprint;
        ar("pd_run.physics", text);
        long step = n;
        ar("pd_run.step", step);
        state(ar);
        ar.write(file);
    }
};

}  // namespace pd_run
