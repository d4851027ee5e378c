// lib/pd/time/cvode_bdf.cpp -- see cvode_bdf.hpp.
#include "pd/time/cvode_bdf.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "pd/core/errors.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace pd {

struct CvodeBdf::Impl {
    SUNContext ctx = nullptr;
    N_Vector y = nullptr;
    SUNMatrix J = nullptr;
    SUNLinearSolver LS = nullptr;
    void* mem = nullptr;
    Rhs rhs;
    Jacobian jac;
    SparseRowMajor Jeigen;
    double t0 = 0;
    std::string last_message;  // CVODE's last error or warning text, one line (its handler, below)

    // CVODE's messages (errors and warnings such as "t + h = t") go here instead of stderr: a failure
    // becomes one exception line that quotes the last of them.
    static void on_message(int, const char*, const char* function, char* msg, void* user)
    {
        std::string text = std::string(function) + ": " + msg;
        std::replace(text.begin(), text.end(), '\n', ' ');
        static_cast<Impl*>(user)->last_message = text;
    }

    static int f(realtype t, N_Vector y, N_Vector ydot, void* user)
    {
        auto* self = static_cast<Impl*>(user);
        self->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
        return 0;
    }
    static int jacobian(realtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector)
    {
        auto* self = static_cast<Impl*>(user);
        self->jac(t, N_VGetArrayPointer(y), self->Jeigen);
        self->Jeigen.makeCompressed();
        const auto nnz = static_cast<sunindextype>(self->Jeigen.nonZeros());
        if (SUNSparseMatrix_NNZ(J) < nnz && SUNSparseMatrix_Reallocate(J, nnz) != SUNMAT_SUCCESS) return -1;
        const int n = static_cast<int>(self->Jeigen.rows());
        sunindextype* rowptr = SUNSparseMatrix_IndexPointers(J);
        sunindextype* colind = SUNSparseMatrix_IndexValues(J);
        realtype* val = SUNSparseMatrix_Data(J);
        for (int r = 0; r <= n; ++r) rowptr[r] = self->Jeigen.outerIndexPtr()[r];
        std::copy(self->Jeigen.innerIndexPtr(), self->Jeigen.innerIndexPtr() + nnz, colind);
        std::copy(self->Jeigen.valuePtr(), self->Jeigen.valuePtr() + nnz, val);
        return 0;
    }
    ~Impl()
    {
        if (mem) CVodeFree(&mem);
        if (LS) SUNLinSolFree(LS);
        if (J) SUNMatDestroy(J);
        if (y) N_VDestroy(y);
        if (ctx) SUNContext_Free(&ctx);
    }
};

namespace {
void check(int flag, const char* what)
{
    if (flag < 0) throw std::runtime_error(std::string("CVODE: ") + what + " failed with flag " + std::to_string(flag));
}
}  // namespace

// A failed integration: at the initial time the solver cannot take a single step, so the input's
// time scale (material constants, sizes) is out of its reach: TimeScaleBeyondSolver (status 2);
// later it is a run that could not be continued: SolverFailure (status 3). One line each.
void CvodeBdf::fail(int flag, const char* what) const
{
    const std::string text = std::string("CVODE ") + what + " failed (flag " + std::to_string(flag) + ")" +
                             (impl_->last_message.empty() ? "" : ": " + impl_->last_message);
    if (t_ == impl_->t0)
        throw TimeScaleBeyondSolver(text + " -- at the initial time: the time scale of the input (material constants, sizes) is beyond the solver");
    throw SolverFailure(text);
}

CvodeBdf::CvodeBdf(std::vector<double> y0, double t0, Rhs rhs, Jacobian jac, const CvodeOptions& opt)
    : impl_(std::make_unique<Impl>()), y_(std::move(y0)), t_(t0)
{
    auto& m = *impl_;
    m.rhs = std::move(rhs);
    m.jac = std::move(jac);
    const auto n = static_cast<sunindextype>(y_.size());
    if (n == 0) throw std::invalid_argument("CvodeBdf: empty system");
    check(SUNContext_Create(nullptr, &m.ctx), "SUNContext_Create");
    m.y = N_VNew_Serial(n, m.ctx);
    std::copy(y_.begin(), y_.end(), N_VGetArrayPointer(m.y));
    m.jac(t0, y_.data(), m.Jeigen);  // first pattern, for the initial allocation
    m.Jeigen.makeCompressed();
    m.J = SUNSparseMatrix(n, n, std::max<sunindextype>(m.Jeigen.nonZeros(), 1), CSR_MAT, m.ctx);
    m.LS = SUNLinSol_KLU(m.y, m.J, m.ctx);
    if (!m.y || !m.J || !m.LS) throw std::runtime_error("CvodeBdf: SUNDIALS allocation failed");
    m.mem = CVodeCreate(CV_BDF, m.ctx);
    if (!m.mem) throw std::runtime_error("CvodeBdf: CVodeCreate failed");
    check(CVodeInit(m.mem, &Impl::f, t0, m.y), "CVodeInit");
    check(CVodeSetUserData(m.mem, &m), "CVodeSetUserData");
    check(CVodeSetErrHandlerFn(m.mem, &Impl::on_message, &m), "CVodeSetErrHandlerFn");
    m.t0 = t0;
    check(CVodeSStolerances(m.mem, opt.rtol, opt.atol), "CVodeSStolerances");
    check(CVodeSetLinearSolver(m.mem, m.LS, m.J), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(m.mem, &Impl::jacobian), "CVodeSetJacFn");
    check(CVodeSetMaxNumSteps(m.mem, opt.max_steps), "CVodeSetMaxNumSteps");
    if (opt.max_step > 0) check(CVodeSetMaxStep(m.mem, opt.max_step), "CVodeSetMaxStep");
}

CvodeBdf::~CvodeBdf() = default;

// One call of CVode towards t_out in the given task mode; keeps t_ and y_ in step with the solver.
void CvodeBdf::integrate(double t_out, int task, const char* what)
{
    realtype t = t_;
    const int flag = CVode(impl_->mem, t_out, impl_->y, &t, task);
    t_ = t;  // on a failure: where the solver stopped
    const double* p = N_VGetArrayPointer(impl_->y);
    std::copy(p, p + y_.size(), y_.begin());
    if (flag < 0) fail(flag, what);
}

const std::vector<double>& CvodeBdf::advance(double t_out)
{
    integrate(t_out, CV_NORMAL, "CVode");
    return y_;
}

double CvodeBdf::step(double t_stop)
{
    check(CVodeSetStopTime(impl_->mem, t_stop), "CVodeSetStopTime");
    integrate(t_stop, CV_ONE_STEP, "CVode (one step)");
    return t_;
}

void CvodeBdf::dense_output(double t, std::vector<double>& y) const
{
    N_Vector out = N_VNew_Serial(static_cast<sunindextype>(y_.size()), impl_->ctx);
    const int flag = CVodeGetDky(impl_->mem, t, 0, out);
    const double* p = N_VGetArrayPointer(out);
    y.assign(p, p + y_.size());
    N_VDestroy(out);
    check(flag, "CVodeGetDky");
}

CvodeStats CvodeBdf::stats() const
{
    CvodeStats s;
    long v = 0;
    CVodeGetNumSteps(impl_->mem, &v), s.steps = v;
    CVodeGetNumRhsEvals(impl_->mem, &v), s.rhs_evals = v;
    CVodeGetNumJacEvals(impl_->mem, &v), s.jac_evals = v;
    CVodeGetNumNonlinSolvIters(impl_->mem, &v), s.newton_iters = v;
    CVodeGetNumErrTestFails(impl_->mem, &v), s.error_test_fails = v;
    return s;
}

}  // namespace pd
