// reference/thermoelastic_bar.cpp -- see thermoelastic_bar.hpp.
#include "reference/thermoelastic_bar.hpp"

#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_mristep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pd::ref {

double thermoelastic_ramp(double t, double t_r)
{
    if (t <= 0) return 0;
    if (t_r <= 0 || t >= t_r) return 1;
    const double s = t / t_r;
    return s * s * s * (10 - 15 * s + 6 * s * s);
}

namespace {

// The semi-discrete system of the header, y = [u_1, v_1, theta_1, u_2, ...] (3 per inner node).
struct Semi {
    ThermoelasticBar bar;
    int n = 0;  // inner nodes M - 1
    double h = 0, kappa = 0;

    explicit Semi(const ThermoelasticBar& b) : bar(b), n(b.cells - 1), h(b.L / b.cells), kappa(b.k / (b.rho * b.c))
    {
        if (!(b.L > 0 && b.E > 0 && b.rho > 0 && b.k > 0 && b.c > 0) || !std::isfinite(b.alpha) || !std::isfinite(b.dT))
            throw std::invalid_argument("thermoelastic bar: L, E, rho, k, c must be positive, alpha and dT finite");
        if (!(b.ramp >= 0)) throw std::invalid_argument("thermoelastic bar: ramp must be >= 0");
        if (b.cells < 4 || b.cells % 2) throw std::invalid_argument("thermoelastic bar: cells must be even and >= 4");
    }
    double theta(const double* y, int i, double t) const
    {
        return i == 0 ? bar.dT * thermoelastic_ramp(t, bar.ramp) : i == bar.cells ? 0.0 : y[3 * (i - 1) + 2];
    }
    double u(const double* y, int i) const { return i == 0 || i == bar.cells ? 0.0 : y[3 * (i - 1)]; }
    // sigma_(i+1/2), i = 0 .. M-1 [Pa].
    double sigma(const double* y, int i, double t) const
    {
        return bar.E * ((u(y, i + 1) - u(y, i)) / h - bar.alpha * 0.5 * (theta(y, i, t) + theta(y, i + 1, t)));
    }
    void mechanics(const double* y, double* dy, double t) const  // du = v, dv = d sigma/dx / rho, dtheta = 0
    {
        double left = sigma(y, 0, t);
        for (int i = 1; i <= n; ++i) {
            const double right = sigma(y, i, t);
            dy[3 * (i - 1)] = y[3 * (i - 1) + 1];
            dy[3 * (i - 1) + 1] = (right - left) / (bar.rho * h);
            dy[3 * (i - 1) + 2] = 0;
            left = right;
        }
    }
    void add_heat(const double* y, double* dy, double t) const  // rho c dtheta = k theta_xx
    {
        for (int i = 1; i <= n; ++i)
            dy[3 * (i - 1) + 2] += kappa * (theta(y, i + 1, t) - 2 * theta(y, i, t) + theta(y, i - 1, t)) / (h * h);
    }
    void sample(const double* y, double t, ThermoelasticHistory& out) const
    {
        out.t_s.push_back(t);
        out.stress_left.push_back(sigma(y, 0, t));
        out.stress_right.push_back(sigma(y, bar.cells - 1, t));
        out.T_mid.push_back(theta(y, bar.cells / 2, t));
    }
};

int fast_rhs(double t, N_Vector y, N_Vector dy, void* s)
{
    static_cast<const Semi*>(s)->mechanics(N_VGetArrayPointer(y), N_VGetArrayPointer(dy), t);
    return 0;
}
int slow_rhs(double t, N_Vector y, N_Vector dy, void* s)
{
    N_VConst(0.0, dy);
    static_cast<const Semi*>(s)->add_heat(N_VGetArrayPointer(y), N_VGetArrayPointer(dy), t);
    return 0;
}
int full_rhs(double t, N_Vector y, N_Vector dy, void* s)
{
    const Semi& m = *static_cast<const Semi*>(s);
    m.mechanics(N_VGetArrayPointer(y), N_VGetArrayPointer(dy), t);
    m.add_heat(N_VGetArrayPointer(y), N_VGetArrayPointer(dy), t);
    return 0;
}

void ok(int flag, const char* what)
{
    if (flag < 0) throw std::runtime_error(std::string("thermoelastic bar reference: ") + what + " failed, flag " + std::to_string(flag));
}

// SUNDIALS context and state vector (zero), freed on every exit.
struct Session {
    SUNContext ctx = nullptr;
    N_Vector y = nullptr;
    explicit Session(int n)
    {
        ok(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
        y = N_VNew_Serial(3 * n, ctx);
        N_VConst(0.0, y);
    }
    ~Session() { N_VDestroy(y), SUNContext_Free(&ctx); }
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

// Samples y at each time of t_out, advancing with advance(to, t) (the integrator's call, t its time reached).
template <class Advance>
void sample_at(const Semi& semi, const std::vector<double>& t_out, N_Vector y, ThermoelasticHistory& out, Advance&& advance)
{
    double t = 0;
    for (double to : t_out) {
        if (to > t) advance(to, t);
        semi.sample(N_VGetArrayPointer(y), t, out);
    }
}

double seconds_since(std::chrono::steady_clock::time_point t0)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

ThermoelasticHistory thermoelastic_bar_mri(const ThermoelasticBar& bar, const std::vector<double>& t_out, double fast_cfl, double slow_fraction)
{
    Semi semi(bar);
    if (!(fast_cfl > 0) || !(slow_fraction > 0)) throw std::invalid_argument("thermoelastic bar: fast_cfl and slow_fraction must be positive");
    const auto t0 = std::chrono::steady_clock::now();
    Session s(semi.n);
    const double c = std::sqrt(bar.E / bar.rho);
    const double H_max = slow_fraction * semi.h * semi.h / semi.kappa;
    const double hf = std::min(fast_cfl * semi.h / c, H_max);  // a heat faster than the waves: one fast step per slow one
    const double H = std::floor(H_max / hf) * hf;
    void* inner = ARKStepCreate(fast_rhs, nullptr, 0.0, s.y, s.ctx);
    MRIStepInnerStepper stepper = nullptr;
    void* outer = nullptr;
    ThermoelasticHistory out;
    try {
        if (!inner) throw std::runtime_error("thermoelastic bar reference: ARKStepCreate failed");
        ok(ARKStepSetUserData(inner, &semi), "ARKStepSetUserData");
        ok(ARKStepSetOrder(inner, 4), "ARKStepSetOrder");
        ok(ARKStepSetFixedStep(inner, hf), "ARKStepSetFixedStep");
        ok(ARKStepSetMaxNumSteps(inner, -1), "ARKStepSetMaxNumSteps");
        ok(ARKStepCreateMRIStepInnerStepper(inner, &stepper), "ARKStepCreateMRIStepInnerStepper");
        outer = MRIStepCreate(slow_rhs, nullptr, 0.0, s.y, stepper, s.ctx);
        if (!outer) throw std::runtime_error("thermoelastic bar reference: MRIStepCreate failed");
        ok(MRIStepSetUserData(outer, &semi), "MRIStepSetUserData");
        ok(MRIStepSetFixedStep(outer, H), "MRIStepSetFixedStep");
        ok(MRIStepSetMaxNumSteps(outer, -1), "MRIStepSetMaxNumSteps");
        sample_at(semi, t_out, s.y, out, [&](double to, double& t) {
            ok(MRIStepSetStopTime(outer, to), "MRIStepSetStopTime");
            ok(MRIStepEvolve(outer, to, s.y, &t, ARK_NORMAL), "MRIStepEvolve");
        });
        ok(MRIStepGetNumSteps(outer, &out.slow_steps), "MRIStepGetNumSteps");
        ok(ARKStepGetNumSteps(inner, &out.fast_steps), "ARKStepGetNumSteps");
    } catch (...) {
        if (outer) MRIStepFree(&outer);
        if (stepper) MRIStepInnerStepper_Free(&stepper);
        if (inner) ARKStepFree(&inner);
        throw;
    }
    MRIStepFree(&outer), MRIStepInnerStepper_Free(&stepper), ARKStepFree(&inner);
    out.wall_s = seconds_since(t0);
    return out;
}

ThermoelasticHistory thermoelastic_bar_cvode(const ThermoelasticBar& bar, const std::vector<double>& t_out, double rtol)
{
    Semi semi(bar);
    if (!(rtol > 0)) throw std::invalid_argument("thermoelastic bar: rtol must be positive");
    const auto t0 = std::chrono::steady_clock::now();
    Session s(semi.n);
    const double c = std::sqrt(bar.E / bar.rho), scale_u = std::abs(bar.alpha * bar.dT) * bar.L;
    N_Vector atol = N_VClone(s.y);
    double* a = N_VGetArrayPointer(atol);
    for (int i = 0; i < semi.n; ++i)
        a[3 * i] = rtol * scale_u, a[3 * i + 1] = rtol * scale_u * c / bar.L, a[3 * i + 2] = rtol * std::abs(bar.dT);
    void* mem = CVodeCreate(CV_BDF, s.ctx);
    SUNMatrix A = SUNBandMatrix(3 * semi.n, 4, 4, s.ctx);  // bandwidths of the interleaved layout: 4 up, 4 down
    SUNLinearSolver LS = SUNLinSol_Band(s.y, A, s.ctx);
    ThermoelasticHistory out;
    auto release = [&] { CVodeFree(&mem), SUNLinSolFree(LS), SUNMatDestroy(A), N_VDestroy(atol); };
    try {
        if (!mem || !A || !LS) throw std::runtime_error("thermoelastic bar reference: CVODE set-up failed");
        ok(CVodeInit(mem, full_rhs, 0.0, s.y), "CVodeInit");
        ok(CVodeSetUserData(mem, &semi), "CVodeSetUserData");
        ok(CVodeSVtolerances(mem, rtol, atol), "CVodeSVtolerances");
        ok(CVodeSetLinearSolver(mem, LS, A), "CVodeSetLinearSolver");
        ok(CVodeSetMaxNumSteps(mem, -1), "CVodeSetMaxNumSteps");
        sample_at(semi, t_out, s.y, out, [&](double to, double& t) {
            ok(CVodeSetStopTime(mem, to), "CVodeSetStopTime");
            ok(CVode(mem, to, s.y, &t, CV_NORMAL), "CVode");
        });
        ok(CVodeGetNumSteps(mem, &out.fast_steps), "CVodeGetNumSteps");
    } catch (...) {
        release();
        throw;
    }
    release();
    out.wall_s = seconds_since(t0);
    return out;
}

}  // namespace pd::ref
