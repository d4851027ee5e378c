// SUNDIALS CVODE (variable-order BDF, Newton iterations) for a stiff ODE system y' = F(t, y) with a
// sparse Jacobian dF/dy factorised by KLU: the third integrator of the PD heat equation,
// usable for any semi-discrete PD system whose Jacobian pattern is the bond graph.
// The Jacobian callback fills an Eigen row-major sparse matrix at (t, y); its pattern may change
// between calls (the SUNDIALS matrix is reallocated when it grows). An approximate Jacobian is
// allowed (modified Newton): it only slows convergence.
#pragma once
#include <Eigen/Sparse>

#include <functional>
#include <memory>
#include <vector>

namespace pd {

struct CvodeOptions {
    double rtol = 1e-8;        // relative tolerance [-]
    double atol = 1e-8;        // absolute tolerance [unit of y]
    long max_steps = 1000000;  // internal steps per advance() call
    double max_step = 0;       // largest internal step [s]; 0 = unlimited
};

struct CvodeStats {
    long steps = 0, rhs_evals = 0, jac_evals = 0, newton_iters = 0, error_test_fails = 0;
};

class CvodeBdf {
public:
    using Rhs = std::function<void(double t, const double* y, double* ydot)>;
    using SparseRowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
    using Jacobian = std::function<void(double t, const double* y, SparseRowMajor& J)>;

    CvodeBdf(std::vector<double> y0, double t0, Rhs rhs, Jacobian jac, const CvodeOptions& opt = {});
    ~CvodeBdf();
    CvodeBdf(const CvodeBdf&) = delete;
    CvodeBdf& operator=(const CvodeBdf&) = delete;

    // Integrates to t_out [s] and returns y(t_out). A failure throws one line quoting CVODE's message:
    // std::invalid_argument when no step can be taken from the initial time (the input's time
    // scale), else SolverFailure (core/errors.hpp); CVODE prints nothing itself.
    const std::vector<double>& advance(double t_out);
    // One internal step towards t_stop [s] (never past it); returns the new time. y() is the state there.
    double step(double t_stop);
    // CVODE's interpolant of order q within the last step, t in [time() - last step, time()].
    void dense_output(double t, std::vector<double>& y) const;
    const std::vector<double>& y() const { return y_; }
    double time() const { return t_; }
    CvodeStats stats() const;

    struct Impl;  // SUNDIALS objects and the callbacks' state

private:
    void integrate(double t_out, int task, const char* what);
    [[noreturn]] void fail(int flag, const char* what) const;
    std::unique_ptr<Impl> impl_;
    std::vector<double> y_;
    double t_ = 0;
};

}  // namespace pd
