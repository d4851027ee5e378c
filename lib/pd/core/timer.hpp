// pd/core/timer.hpp -- wall-clock timer and a one-line progress display for long runs.
//
// Timer measures wall time with std::chrono::steady_clock (monotonic, unaffected by clock changes).
//
// Progress rewrites one stderr line with '\r': steps done/total, percentage, mean steps per
// second since the start, and the estimated time left (remaining steps / mean rate). It redraws at
// most every 0.25 s, so calling update() every step costs one clock read. It is silent when
// stderr is not a terminal (isatty(2) == 0: logs, pipes, CTest), when the environment variable CI
// is set, or when constructed with enabled = false (drivers pass !quick).
//
//     pd::io::Progress progress("integrate", n_steps, !quick);
//     for (long n = 0; n < n_steps; ++n) { step(); progress.update(n + 1); }
//     progress.finish();
#pragma once
#include "pd/core/state_archive.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>
#include <vector>

namespace pd::io {

class Timer {
public:
    Timer() : start_(clock::now()) {}
    // Wall time since construction or the last restart() [s].
    double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }
    // Returns seconds() and starts again from zero.
    double restart()
    {
        const auto now = clock::now();
        const double s = std::chrono::duration<double>(now - start_).count();
        start_ = now;
        return s;
    }

    // A checkpoint of the seconds so far (core/state_archive.hpp): a resumed run's timer goes on
    // from them, so that its wall time counts the time before the stop too.
    void state(StateArchive& ar, const std::string& name)
    {
        double s = seconds();
        ar(name, s);
        if (!ar.saving()) start_ = clock::now() - std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(s));
    }

private:
    using clock = std::chrono::steady_clock;
    clock::time_point start_;
};

// Quantile q in [0, 1] of v, linear between order statistics (q = 0.5: the median); for the
// interleaved timing ratios of problems/3d/model_cost.cpp and bench/damage_cost.cpp.
inline double quantile(std::vector<double> v, double q)
{
    std::sort(v.begin(), v.end());
    const double h = q * (v.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(h), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (h - lo) * (v[hi] - v[lo]);
}

class Progress {
public:
    Progress(std::string label, long total_steps, bool enabled)
        : label_(std::move(label)), total_(total_steps), active_(enabled && terminal_allows())
    {
    }
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    ~Progress() { finish(); }

    // True when stderr is a terminal and CI is not set: the conditions besides `enabled`.
    static bool terminal_allows() { return isatty(2) == 1 && std::getenv("CI") == nullptr; }

    bool active() const { return active_; }

    // step = number of steps done so far (0..total_steps).
    void update(long step)
    {
        if (!active_) return;
        last_step_ = step;
        const double t = timer_.seconds();
        if (t < next_draw_s_) return;
        next_draw_s_ = t + redraw_interval_s;
        draw(step, t, false);
    }

    // Ends the line (only if something was drawn) and turns the display off.
    void finish()
    {
        if (!active_) return;
        if (drawn_) {
            draw(last_step_, timer_.seconds(), true);
            std::fputc('\n', stderr);
            std::fflush(stderr);
        }
        active_ = false;
    }

private:
    static constexpr double redraw_interval_s = 0.25;  // at most 4 redraws per second [s]

    static std::string duration_text(double s)
    {
        char buf[32];
        const long v = static_cast<long>(s + 0.5);
        if (v < 60) std::snprintf(buf, sizeof buf, "%lds", v);
        else if (v < 3600) std::snprintf(buf, sizeof buf, "%ldm%02lds", v / 60, v % 60);
        else std::snprintf(buf, sizeof buf, "%ldh%02ldm", v / 3600, (v % 3600) / 60);
        return buf;
    }

    void draw(long step, double t, bool final)
    {
        const double done = static_cast<double>(step);
        const double total = static_cast<double>(total_);
        const double rate = t > 0.0 ? done / t : 0.0;  // mean steps per second since the start
        std::string eta = "?";
        if (rate > 0.0 && total_ > step) eta = duration_text((total - done) / rate);
        else if (total_ <= step) eta = "0s";
        char buf[256];
        const double pct = total_ > 0 ? 100.0 * done / total : 100.0;
        if (final)
            std::snprintf(buf, sizeof buf, "%s: %ld/%ld (%.0f%%)  %.3g steps/s  done in %s", label_.c_str(), step,
                          total_, pct, rate, duration_text(t).c_str());
        else
            std::snprintf(buf, sizeof buf, "%s: %ld/%ld (%.0f%%)  %.3g steps/s  ETA %s", label_.c_str(), step, total_,
                          pct, rate, eta.c_str());
        std::string line = buf;
        const std::size_t len = line.size();
        if (len < last_len_) line.append(last_len_ - len, ' ');  // blank out the rest of a longer line
        last_len_ = len;
        std::fprintf(stderr, "\r%s", line.c_str());
        std::fflush(stderr);
        drawn_ = true;
    }

    std::string label_;
    long total_;
    bool active_;
    bool drawn_ = false;
    long last_step_ = 0;
    std::size_t last_len_ = 0;
    double next_draw_s_ = redraw_interval_s;  // next redraw [s] since start; short runs draw nothing
    Timer timer_;
};

}  // namespace pd::io
