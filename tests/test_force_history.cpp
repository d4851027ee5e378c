// Window means and the two-peak reading of a force history (problems/common/analysis/force_history.hpp), on
// signals whose answers are known by hand.
#include "problems/common/analysis/force_history.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

TEST(ForceHistory, WindowMeanRemovesRingingOfWholePeriods)
{
    // F = 100 + 50 t/ms + 300 sin(2 pi t / 0.05 ms), steps of 1 us, windows of 0.25 ms = five
    // periods of the ringing: the 50 samples of each period of the sine sum to zero, so each mean
    // is the linear part alone (to round-off, 300 * 1e-15 per sample).
    pd::WindowMean w(0.25e-3);
    const double dt = 1e-6;
    for (int n = 1; n <= 1000; ++n) {
        const double t = n * dt;
        w.add(t, dt, 100 + 50 * t * 1e3 + 300 * std::sin(2 * std::numbers::pi * t / 0.05e-3));
    }
    ASSERT_EQ(w.mean.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
        const double t_mid = (k + 0.5) * 0.25e-3;
        EXPECT_NEAR(w.t_mid_s[k], t_mid, 1e-12);  // round-off of 250 summed 1 us steps, ~1e-17 s
        // Rectangle rule on the right ends of the steps: the linear part's mean is taken at
        // t_mid + dt/2, i.e. 50 N/ms * 0.5 us = 0.025 N above 100 + 50 t_mid.
        EXPECT_NEAR(w.mean[k], 100 + 50 * t_mid * 1e3 + 0.025, 1e-9) << k;
    }
    EXPECT_THROW(pd::WindowMean(0), std::invalid_argument);
}

TEST(ForceHistory, TwoPeaksFindsPeakDipAndSecondPeak)
{
    //            t:  0    1    2    3    4    5    6    7    8
    const std::vector<double> t{0, 1, 2, 3, 4, 5, 6, 7, 8};
    const std::vector<double> F{0, 250, 300, 240, 220, 260, 310, 450, 100};
    const pd::TwoPeaks p = pd::two_peaks(t, F);
    EXPECT_EQ(p.F1, 300);
    EXPECT_EQ(p.t1, 2);
    EXPECT_EQ(p.F_dip, 220);
    EXPECT_EQ(p.t_dip, 4);
    EXPECT_EQ(p.F2, 450);
    EXPECT_EQ(p.t2, 7);
}

TEST(ForceHistory, SmallWiggleIsNotAFirstPeakAndNoSecondPeakIsNaN)
{
    // 200 -> 195 is a 2.5 % drop: not a peak; 400 -> 100 never recovers: first peak without a second.
    const std::vector<double> t{0, 1, 2, 3, 4, 5, 6};
    const std::vector<double> F{0, 200, 195, 300, 400, 150, 100};
    const pd::TwoPeaks p = pd::two_peaks(t, F);
    EXPECT_EQ(p.F1, 400);
    EXPECT_EQ(p.t1, 4);
    EXPECT_EQ(p.F_dip, 100);
    EXPECT_EQ(p.t_dip, 6);
    EXPECT_TRUE(std::isnan(p.F2) && std::isnan(p.t2));
    const pd::TwoPeaks none = pd::two_peaks({0, 1, 2}, {0, 1, 2});
    EXPECT_TRUE(std::isnan(none.F1));
}
