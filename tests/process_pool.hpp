// Child processes of a test under a wall-clock limit (test_robustness.cpp): stdin from /dev/null,
// stdout to a file or /dev/null, stderr captured, killed after the limit; a batch runs on a few
// worker threads.
#pragma once

#include "pd_run_harness.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace pd_test::process_pool {

inline constexpr int workers = 4;  // processes at once (2 cores: most runs wait in parse or are killed)

// One process: argv, its stderr, how it ended.
struct Proc {
    std::vector<std::string> argv;
    int status = -1;      // exit status, or -1
    int signal = 0;       // terminating signal (not our kill)
    bool timed_out = false;
    std::chrono::milliseconds limit{0};  // this run's own limit (0: the caller's)
    std::string err;
};

inline std::string command_line(const std::vector<std::string>& argv)
{
    std::string s;
    for (const auto& a : argv) s += (s.empty() ? "" : " ") + (a.empty() ? std::string("''") : a);
    return s;
}

// Spawns argv with stdout to out_file (or /dev/null) and stderr to err_file; kills it after `limit`.
inline void execute(Proc& r, const std::filesystem::path& out_file, const std::filesystem::path& err_file, std::chrono::milliseconds limit)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out_file.empty() ? "/dev/null" : out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> args;
    for (auto& a : r.argv) args.push_back(a.data());
    args.push_back(nullptr);
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0) {
        r.err = "posix_spawn failed: " + std::string(std::strerror(rc));
        return;
    }
    const auto deadline = std::chrono::steady_clock::now() + (r.limit.count() > 0 ? r.limit : limit);
    int ws = 0;
    while (true) {
        const pid_t w = waitpid(pid, &ws, WNOHANG);
        if (w == pid) break;
        if (std::chrono::steady_clock::now() > deadline) {
            kill(pid, SIGKILL);
            waitpid(pid, &ws, 0);
            r.timed_out = true;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(4));
    }
    if (!r.timed_out) {
        if (WIFEXITED(ws)) r.status = WEXITSTATUS(ws);
        else if (WIFSIGNALED(ws)) r.signal = WTERMSIG(ws);
    }
    r.err = pd_test::slurp(err_file);
}

// Runs every Proc of `runs` on `workers` threads; run i writes below dir/i.
inline void execute_all(std::vector<Proc>& runs, const std::filesystem::path& dir, std::chrono::milliseconds limit)
{
    std::atomic<std::size_t> next{0};
    auto work = [&] {
        for (std::size_t i; (i = next++) < runs.size();) {
            const std::filesystem::path err = dir / ("case" + std::to_string(i) + ".err");
            execute(runs[i], {}, err, limit);
            std::filesystem::remove(err);
            std::error_code ec;
            std::filesystem::remove_all(dir / ("out" + std::to_string(i)), ec);  // --out of the case, if any
        }
    };
    std::vector<std::thread> pool;
    for (int w = 0; w < workers; ++w) pool.emplace_back(work);
    for (auto& t : pool) t.join();
}

}  // namespace pd_test::process_pool
