// reference/heat_prism.cpp -- see heat_prism.hpp.
#include "reference/heat_prism.hpp"
#include "reference/heat_cvode_session.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_spgmr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::ref {

namespace {

struct Grid {
    HeatPrism p;
    double cx, cy, cz;  // alpha / h^2 per axis [1/s]
    int id(int i, int j, int k) const { return (i * p.ny + j) * p.nz + k; }  // x slowest: band ny nz
};

// dT/dt of the 7-point scheme.
int rhs(realtype, N_Vector y, N_Vector ydot, void* user)
{
    const auto& g = *static_cast<const Grid*>(user);
    const double* T = N_VGetArrayPointer(y);
    double* d = N_VGetArrayPointer(ydot);
    for (int i = 0; i < g.p.nx; ++i)
        for (int j = 0; j < g.p.ny; ++j)
            for (int k = 0; k < g.p.nz; ++k) {
                const double Tc = T[g.id(i, j, k)];
                const double xm = i > 0 ? T[g.id(i - 1, j, k)] : 2 * g.p.T_end - Tc;           // Dirichlet ghost
                const double xp = i < g.p.nx - 1 ? T[g.id(i + 1, j, k)] : 2 * g.p.T_end - Tc;
                const double ym = j > 0 ? T[g.id(i, j - 1, k)] : Tc, yp = j < g.p.ny - 1 ? T[g.id(i, j + 1, k)] : Tc;  // mirror
                const double zm = k > 0 ? T[g.id(i, j, k - 1)] : Tc, zp = k < g.p.nz - 1 ? T[g.id(i, j, k + 1)] : Tc;
                d[g.id(i, j, k)] = g.cx * (xm - 2 * Tc + xp) + g.cy * (ym - 2 * Tc + yp) + g.cz * (zm - 2 * Tc + zp);
            }
    return 0;
}

// Krylov subspace of GMRES: the Newton matrix I - gamma J of the heat equation has a condition number
// ~ 4 alpha gamma / h^2 (a few hundred at most here), well within 30 iterations.
constexpr int krylov_dim = 30;

void ok(int flag, const char* what)
{
    if (flag < 0) throw std::runtime_error(std::string("heat_prism_time_to: ") + what + " failed, flag " + std::to_string(flag));
}

// The probe: mean of the 2 (even count) or 1 (odd) central cells per axis.
double centre(const Grid& g, const double* T)
{
    auto mid = [](int n) { return std::vector<int>(n % 2 ? std::vector<int>{n / 2} : std::vector<int>{n / 2 - 1, n / 2}); };
    double s = 0;
    int c = 0;
    for (int i : mid(g.p.nx))
        for (int j : mid(g.p.ny))
            for (int k : mid(g.p.nz)) s += T[g.id(i, j, k)], ++c;
    return s / c;
}

}  // namespace

PrismCrossing heat_prism_time_to(const HeatPrism& p, double T_target, double rtol, double t_max)
{
    if (p.nx < 2 || p.ny < 1 || p.nz < 1 || !(p.alpha > 0) || !(p.Lx > 0 && p.Ly > 0 && p.Lz > 0))
        throw std::invalid_argument("heat_prism_time_to: need nx >= 2, ny, nz >= 1, positive sizes and alpha");
    if (!(T_target > std::min(p.T0, p.T_end) && T_target < std::max(p.T0, p.T_end)))
        throw std::invalid_argument("heat_prism_time_to: target must lie strictly between T0 and T_end");
    Grid g{p, p.alpha * std::pow(p.nx / p.Lx, 2), p.alpha * std::pow(p.ny / p.Ly, 2), p.alpha * std::pow(p.nz / p.Lz, 2)};
    const sunindextype n = sunindextype(p.nx) * p.ny * p.nz;
    HeatCvodeSession cv(n, p.T0, SUN_PREC_NONE, krylov_dim, "heat_prism_time_to");
    void* mem = cv.mem;
    N_Vector y = cv.y;
    SUNMatrix J = nullptr;  // matrix-free
    PrismCrossing out;
    ok(CVodeInit(mem, rhs, 0.0, y), "CVodeInit");
    ok(CVodeSetUserData(mem, &g), "CVodeSetUserData");
    ok(CVodeSStolerances(mem, rtol, rtol * std::abs(p.T_end - p.T0)), "CVodeSStolerances");
    ok(CVodeSetLinearSolver(mem, cv.LS, J), "CVodeSetLinearSolver");  // GMRES, difference-quotient J v
    ok(CVodeSetMaxNumSteps(mem, 1000000), "CVodeSetMaxNumSteps");
    ok(CVodeSetStopTime(mem, t_max), "CVodeSetStopTime");
    const double sign = p.T_end > p.T0 ? 1 : -1;
    auto short_of_target = [&](const double* T) { return sign * (centre(g, T) - T_target) < 0; };
    realtype t = 0;
    bool found = false;
    while (!found && t < t_max) {
        const double t_prev = t;
        ok(CVode(mem, t_max, y, &t, CV_ONE_STEP), "CVode");
        ++out.steps;
        if (short_of_target(N_VGetArrayPointer(y))) continue;
        out.t = cv.crossing(t_prev, t, 1e-12 * (t - t_prev), short_of_target);
        found = true;
    }
    if (!found) throw std::runtime_error("heat_prism_time_to: target not reached by t_max");
    return out;
}

}  // namespace pd::ref
