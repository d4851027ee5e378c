// reference/heat_kirchhoff.cpp -- see heat_kirchhoff.hpp.
#include "reference/heat_kirchhoff.hpp"
#include "reference/heat_cvode_session.hpp"

#include <cvode/cvode.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pd::ref {

double kirchhoff_linear_phi(double k0, double beta, double T0, double T)
{
    const double u = T - T0;
    return k0 * (u + 0.5 * beta * u * u);  // int_T0^T k0 (1 + beta (s - T0)) ds
}

double kirchhoff_linear_inverse(double k0, double beta, double T0, double P)
{
    const double disc = 1 + 2 * beta * P / k0;  // beta u^2/2 + u - P/k0 = 0
    if (!(disc >= 0)) throw std::domain_error("kirchhoff_linear_inverse: k becomes negative on the way");
    return T0 + 2 * P / (k0 * (1 + std::sqrt(disc)));  // rationalised root, no cancellation as beta -> 0
}

double kirchhoff_linear_steady(double k0, double beta, double T0, double L, double T_a, double T_b, double x)
{
    const double Pa = kirchhoff_linear_phi(k0, beta, T0, T_a), Pb = kirchhoff_linear_phi(k0, beta, T0, T_b);
    return kirchhoff_linear_inverse(k0, beta, T0, Pa + (Pb - Pa) * x / L);  // Phi linear in x
}

double en1993_steel_k(double T)
{
    T = std::clamp(T, 20.0, 1200.0);
    return T < 800 ? 54 - 3.33e-2 * T : 27.3;
}

double en1993_steel_phi(double T)
{
    auto lin = [](double t) { return 54 * (t - 20) - 1.665e-2 * (t * t - 400); };  // int_20^t (54 - 3.33e-2 s) ds
    if (T < 20) return (54 - 3.33e-2 * 20) * (T - 20);  // clamped: k(20) below 20 C
    if (T < 800) return lin(T);
    return lin(800) + 27.3 * (T - 800);               // 27.3 from 800 C (and clamped above 1200 C)
}

namespace {

double call_k(double T, void* p) { return (*static_cast<const Conductivity*>(p))(T); }

struct PhiTarget {
    const KirchhoffBar* bar;
    double P;
};
double phi_residual(double T, void* p)
{
    const auto* t = static_cast<const PhiTarget*>(p);
    return t->bar->phi(T) - t->P;
}

}  // namespace

KirchhoffBar::KirchhoffBar(Conductivity k, double L, double T_a, double T_b) : k_(std::move(k)), L_(L), T_a_(T_a), T_b_(T_b)
{
    if (!k_ || !(L > 0)) throw std::invalid_argument("KirchhoffBar: need k(T) and L > 0");
    phi_b_ = phi(T_b);
}

double KirchhoffBar::phi(double T) const
{
    if (T == T_a_) return 0;
    gsl_error_handler_t* old = gsl_set_error_handler_off();
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
    gsl_function F{&call_k, const_cast<Conductivity*>(&k_)};
    double result = 0, err = 0;
    const int status = gsl_integration_qags(&F, std::min(T_a_, T), std::max(T_a_, T), 0, 1e-13, 1000, w, &result, &err);
    gsl_integration_workspace_free(w);
    gsl_set_error_handler(old);
    // GSL_EROUND: the requested 1e-13 is below what round-off allows; the result is still at round-off.
    if (status != GSL_SUCCESS && status != GSL_EROUND)
        throw std::runtime_error(std::string("KirchhoffBar::phi: quadrature failed: ") + gsl_strerror(status));
    return T >= T_a_ ? result : -result;
}

double KirchhoffBar::flux() const { return -phi_b_ / L_; }

double KirchhoffBar::temperature(double x) const
{
    PhiTarget target{this, phi_b_ * x / L_};
    // Bracket: start with [T_a, T_b] and widen (Phi is increasing since k > 0).
    double lo = std::min(T_a_, T_b_), hi = std::max(T_a_, T_b_);
    for (double w = hi - lo + 1; phi(lo) > target.P; w *= 2) lo -= w;
    for (double w = hi - lo + 1; phi(hi) < target.P; w *= 2) hi += w;
    if (phi(lo) == target.P) return lo;
    if (phi(hi) == target.P) return hi;
    gsl_function F{&phi_residual, &target};
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &F, lo, hi);
    double T = 0.5 * (lo + hi);
    for (int it = 0; it < 300; ++it) {
        gsl_root_fsolver_iterate(s);
        T = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0, 1e-13) == GSL_SUCCESS) break;
    }
    gsl_root_fsolver_free(s);
    return T;
}

// ---- transient method of lines ----
namespace {

struct Mol {
    const KBar1D* bar;
    int n;
    double h;                         // cell size [m]
    std::vector<double> phi, k, sub, diag, sup, work;
};

void ok(int flag, const char* what)
{
    if (flag < 0) throw std::runtime_error(std::string("kbar_transient: ") + what + " failed, flag " + std::to_string(flag));
}

// rho c dT_i/dt = [(Phi_{i+1} - Phi_i)/h_r - (Phi_i - Phi_{i-1})/h_l] / h, h_l, h_r = h or h/2 to a held end.
int mol_rhs(realtype, N_Vector y, N_Vector ydot, void* user)
{
    auto& m = *static_cast<Mol*>(user);
    const double* T = N_VGetArrayPointer(y);
    double* d = N_VGetArrayPointer(ydot);
    const double phi_end = m.bar->phi(m.bar->T_end);
    for (int i = 0; i < m.n; ++i) m.phi[i] = m.bar->phi(T[i]);
    for (int i = 0; i < m.n; ++i) {
        const double left = i > 0 ? (m.phi[i] - m.phi[i - 1]) / m.h : (m.phi[i] - phi_end) / (0.5 * m.h);
        const double right = i < m.n - 1 ? (m.phi[i + 1] - m.phi[i]) / m.h : (phi_end - m.phi[i]) / (0.5 * m.h);
        d[i] = (right - left) / (m.h * m.bar->rho_c);
    }
    return 0;
}

// Exact Jacobian: dPhi_j/dT_j = k(T_j); stores k at y.
int mol_psetup(realtype, N_Vector y, N_Vector, booleantype, booleantype* jcur, realtype, void* user)
{
    auto& m = *static_cast<Mol*>(user);
    const double* T = N_VGetArrayPointer(y);
    for (int i = 0; i < m.n; ++i) m.k[i] = m.bar->k(T[i]);
    *jcur = SUNTRUE;
    return 0;
}

// Solves (I - gamma J) z = r with the tridiagonal J by the Thomas algorithm.
int mol_psolve(realtype, N_Vector, N_Vector, N_Vector r, N_Vector z, realtype gamma, realtype, int, void* user)
{
    auto& m = *static_cast<Mol*>(user);
    const double* R = N_VGetArrayPointer(r);
    double* Z = N_VGetArrayPointer(z);
    const double c = gamma / (m.h * m.bar->rho_c);
    for (int i = 0; i < m.n; ++i) {
        const double hl = i > 0 ? m.h : 0.5 * m.h, hr = i < m.n - 1 ? m.h : 0.5 * m.h;
        m.sub[i] = i > 0 ? -c * m.k[i - 1] / hl : 0;
        m.sup[i] = i < m.n - 1 ? -c * m.k[i + 1] / hr : 0;
        m.diag[i] = 1 + c * m.k[i] * (1 / hl + 1 / hr);
    }
    m.work[0] = m.sup[0] / m.diag[0];
    Z[0] = R[0] / m.diag[0];
    for (int i = 1; i < m.n; ++i) {
        const double b = m.diag[i] - m.sub[i] * m.work[i - 1];
        m.work[i] = m.sup[i] / b;
        Z[i] = (R[i] - m.sub[i] * Z[i - 1]) / b;
    }
    for (int i = m.n - 2; i >= 0; --i) Z[i] -= m.work[i] * Z[i + 1];
    return 0;
}

double centre(const Mol& m, const double* T) { return m.n % 2 ? T[m.n / 2] : 0.5 * (T[m.n / 2 - 1] + T[m.n / 2]); }

}  // namespace

KBarResult kbar_transient(const KBar1D& bar, int n, double t_end, double rtol, double T_target)
{
    if (n < 2 || !(bar.L > 0) || !(bar.rho_c > 0) || !(t_end > 0) || !bar.k || !bar.phi)
        throw std::invalid_argument("kbar_transient: need n >= 2, L, rho c, t_end > 0, k and phi");
    const bool cross = T_target > std::min(bar.T0, bar.T_end) && T_target < std::max(bar.T0, bar.T_end);
    Mol m{&bar, n, bar.L / n, std::vector<double>(n), std::vector<double>(n), std::vector<double>(n),
          std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
    HeatCvodeSession cv(n, bar.T0, SUN_PREC_LEFT, 10, "kbar_transient");  // exact preconditioner: 1-2 iterations
    void* mem = cv.mem;
    N_Vector y = cv.y;
    KBarResult out;
    ok(CVodeInit(mem, mol_rhs, 0.0, y), "CVodeInit");
    ok(CVodeSetUserData(mem, &m), "CVodeSetUserData");
    ok(CVodeSStolerances(mem, rtol, rtol * std::abs(bar.T_end - bar.T0)), "CVodeSStolerances");
    ok(CVodeSetLinearSolver(mem, cv.LS, nullptr), "CVodeSetLinearSolver");
    ok(CVodeSetPreconditioner(mem, mol_psetup, mol_psolve), "CVodeSetPreconditioner");
    ok(CVodeSetMaxNumSteps(mem, 10000000), "CVodeSetMaxNumSteps");
    ok(CVodeSetStopTime(mem, t_end), "CVodeSetStopTime");
    const double sign = bar.T_end > bar.T0 ? 1 : -1;
    auto short_of_target = [&](const double* T) { return sign * (centre(m, T) - T_target) < 0; };
    realtype t = 0;
    while (t < t_end) {
        const double t_prev = t;
        ok(CVode(mem, t_end, y, &t, CV_ONE_STEP), "CVode");
        ++out.steps;
        if (!cross || out.t_cross >= 0 || short_of_target(N_VGetArrayPointer(y))) continue;
        out.t_cross = cv.crossing(t_prev, t, 1e-13 * t, short_of_target);  // bisection on the interpolant of the last step
    }
    const double* T = N_VGetArrayPointer(y);
    for (int i = 0; i < n; ++i) out.x.push_back((i + 0.5) * m.h), out.T.push_back(T[i]);
    return out;
}

}  // namespace pd::ref
