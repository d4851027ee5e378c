// problems/common/analysis/force_history.hpp -- reading a load history the way a drop-weight test is read:
// window means of a force sampled at every time step (the mean over a window is the impulse over
// the window divided by its length, so it removes the ringing of the specimen without shifting
// the signal), and the "first peak, dip, second peak" shape of the force (spec/001_004 V7: the
// reaction of a clamped disc under a falling weight peaks, drops while damage spreads under the
// tip, and rises again to final failure).
#pragma once
#include "pd/core/state_archive.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <vector>

namespace pd {

// Means of a signal over consecutive windows of a fixed length; add() once per time step.
class WindowMean {
public:
    explicit WindowMean(double window) : window_(window)
    {
        if (!(window > 0)) throw std::invalid_argument("WindowMean: window must be > 0");
    }
    // Adds value held over the step (t - dt, t]; closes a window when it is full.
    void add(double t, double dt, double value)
    {
        sum_ += value * dt, span_ += dt;
        if (span_ >= window_ * (1 - 1e-12)) {  // round-off of the summed steps
            t_mid_s.push_back(t - 0.5 * span_), mean.push_back(sum_ / span_);
            sum_ = 0, span_ = 0;
        }
    }
    std::vector<double> t_mid_s;  // window centres [s]
    std::vector<double> mean;     // window means [unit of the signal]

    void state(StateArchive& ar, const std::string& name)
    {
        ar(name + ".t_mid", t_mid_s), ar(name + ".mean", mean), ar(name + ".sum", sum_), ar(name + ".span", span_);
    }

private:
    double window_, sum_ = 0, span_ = 0;
};

struct TwoPeaks {
    double F1 = NAN, t1 = NAN;         // first peak [N], [s]
    double F_dip = NAN, t_dip = NAN;   // lowest value after it, before the force regains F1
    double F2 = NAN, t2 = NAN;         // largest value after the dip (NaN: no second peak)
};

// First peak: the first local maximum followed by a fall below (1 - drop) of itself before the
// signal exceeds it again. Dip: the smallest value between it and the sample where the force first
// exceeds F1 again (or the end). Second peak: the largest value after the dip that exceeds F1.
inline TwoPeaks two_peaks(const std::vector<double>& t, const std::vector<double>& F, double drop = 0.1)
{
    if (t.size() != F.size()) throw std::invalid_argument("two_peaks: t and F differ in length");
    TwoPeaks p;
    const std::size_t n = F.size();
    for (std::size_t q = 1; q + 1 < n; ++q) {
        if (F[q] < F[q - 1] || F[q] <= F[q + 1]) continue;
        std::size_t r = q + 1, dip = q + 1;
        for (; r < n && F[r] <= F[q]; ++r)
            if (F[r] < F[dip]) dip = r;
        if (F[dip] >= (1 - drop) * F[q]) continue;
        p.F1 = F[q], p.t1 = t[q], p.F_dip = F[dip], p.t_dip = t[dip];
        for (std::size_t s = r; s < n; ++s)
            if (std::isnan(p.F2) || F[s] > p.F2) p.F2 = F[s], p.t2 = t[s];
        return p;
    }
    return p;
}

}  // namespace pd
