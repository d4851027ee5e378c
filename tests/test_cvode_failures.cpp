// tests/test_cvode_failures.cpp -- a failed CVODE integration is one line, and CVODE prints nothing
// itself (issue 18, finding 8): no step possible from the initial time is an input error
// (std::invalid_argument, exit status 2), a failure later in the run a SolverFailure (status 3).
#include "pd/core/errors.hpp"
#include "pd/time/cvode_bdf.hpp"

#include <gtest/gtest.h>

#include "pd_run_harness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace {

using Sparse = pd::CvodeBdf::SparseRowMajor;

void one_by_one(double value, Sparse& J)
{
    J.resize(1, 1);
    J.setZero();
    J.insert(0, 0) = value;
}

// Advances to t_out, which must throw E with a one-line message while stderr stays silent; returns it.
template <class E>
std::string one_line_failure(pd::CvodeBdf& solver, double t_out)
{
    std::string what = "(no exception)";
    testing::internal::CaptureStderr();
    try {
        solver.advance(t_out);
    } catch (const E& e) {
        what = e.what();
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_NE(what, "(no exception)");
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    return what;
}

// y' = NaN: the error test fails at every step size, so CVODE cannot leave t = 0.
TEST(CvodeFailures, NoStepFromTheInitialTimeIsAnInputErrorOfOneLine)
{
    pd::CvodeBdf solver({1.0}, 0.0, [](double, const double*, double* ydot) { ydot[0] = std::nan(""); },
                        [](double, const double*, Sparse& J) { one_by_one(0.0, J); });
    const std::string what = one_line_failure<std::invalid_argument>(solver, 1.0);
    EXPECT_NE(what.find("initial time"), std::string::npos) << what;
}

// y' = y^2, y(0) = 1: y = 1/(1 - t) blows up at t = 1; CVODE integrates up to close to it, then fails.
TEST(CvodeFailures, AFailureLaterInTheRunIsASolverFailureOfOneLine)
{
    pd::CvodeOptions opt;
    opt.max_steps = 2000;
    pd::CvodeBdf solver({1.0}, 0.0, [](double, const double* y, double* ydot) { ydot[0] = y[0] * y[0]; },
                        [](double, const double* y, Sparse& J) { one_by_one(2 * y[0], J); }, opt);
    one_line_failure<pd::SolverFailure>(solver, 2.0);
    EXPECT_GT(solver.time(), 0.5);  // the run got well past its start
}

}  // namespace

// In a driver the message names the options that set the time scale (Case::time_scale_set_by):
// a conductivity of 1e25 W/(m K) leaves CVODE no step at t = 0 on the 1D bar.
TEST(CvodeFailures, ADriverNamesTheOptionsOfTheTimeScale)
{
    const pd_test::Result r = pd_test::run_program("agwai_bar_1d", "--quick --integrator cvode --k 1e25", testing::TempDir() + "cvode_driver");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find("error: options --k, --rho, --c, --length, --N, --m: CVODE"), std::string::npos) << r.err;
}
