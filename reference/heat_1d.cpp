// reference/heat_1d.cpp -- see heat_1d.hpp.
#include "reference/heat_1d.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::ref {

namespace {

void check_target(const HeatBar1D& bar, double T_target, const char* who)
{
    const double lo = std::min(bar.T0, bar.T_end), hi = std::max(bar.T0, bar.T_end);
    if (!(T_target > lo && T_target < hi))
        throw std::invalid_argument(std::string(who) + ": target temperature must lie strictly between T0 and T_end");
    if (!(bar.L > 0) || !(bar.alpha > 0)) throw std::invalid_argument(std::string(who) + ": L and alpha must be positive");
}

struct Crossing {
    const HeatBar1D* bar;
    double x, target;
};

double residual(double t, void* p)
{
    const auto* c = static_cast<const Crossing*>(p);
    return heat_bar_exact_temperature(*c->bar, c->x, t) - c->target;
}

}  // namespace

double heat_bar_exact_temperature(const HeatBar1D& bar, double x, double t)
{
    if (x <= 0 || x >= bar.L) return bar.T_end;
    if (t <= 0) return bar.T0;
    const double pi = std::numbers::pi;
    double sum = 0;
    for (int n = 1;; n += 2) {
        const double a = n * pi / bar.L;
        const double decay = std::exp(-bar.alpha * a * a * t);
        sum += 4 / (n * pi) * std::sin(a * x) * decay;
        if (4 / (n * pi) * decay < 1e-16) break;  // every later term is smaller still
    }
    return bar.T_end + (bar.T0 - bar.T_end) * sum;
}

double heat_bar_exact_time_to(const HeatBar1D& bar, double x, double T_target)
{
    check_target(bar, T_target, "heat_bar_exact_time_to");
    if (!(x > 0 && x < bar.L)) throw std::invalid_argument("heat_bar_exact_time_to: x must be inside the bar");
    Crossing c{&bar, x, T_target};
    const double t_scale = bar.L * bar.L / bar.alpha;  // diffusion time of the bar [s]
    double lo = 1e-12 * t_scale, hi = 1e-3 * t_scale;
    const double sign_lo = residual(lo, &c) < 0 ? -1 : 1;
    while ((residual(hi, &c) < 0 ? -1 : 1) == sign_lo) {
        lo = hi;
        hi *= 2;
        if (hi > 1e3 * t_scale) throw std::runtime_error("heat_bar_exact_time_to: target not reached");
    }
    gsl_function F{&residual, &c};
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &F, lo, hi);
    double t = 0.5 * (lo + hi);
    for (int it = 0; it < 200; ++it) {
        gsl_root_fsolver_iterate(s);
        t = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0, 1e-12) == GSL_SUCCESS)
            break;
    }
    gsl_root_fsolver_free(s);
    return t;
}

namespace {
// One implicit-Euler step of the 3-point scheme, (1 + 2r) T_i - r (T_{i-1} + T_{i+1}) = T_i^n for
// i = 1..N-1 with the end values held (Thomas algorithm); c and rhs are work arrays of size N+1.
void fd_implicit_step(std::vector<double>& T, double r, std::vector<double>& c, std::vector<double>& rhs)
{
    const int N = int(T.size()) - 1;
    for (int i = 1; i < N; ++i) rhs[i] = T[i] + (i == 1 ? r * T[0] : 0) + (i == N - 1 ? r * T[N] : 0);
    double b = 1 + 2 * r;
    c[1] = -r / b;
    rhs[1] /= b;
    for (int i = 2; i < N; ++i) {
        b = 1 + 2 * r + r * c[i - 1];
        c[i] = -r / b;
        rhs[i] = (rhs[i] + r * rhs[i - 1]) / b;
    }
    T[N - 1] = rhs[N - 1];
    for (int i = N - 2; i >= 1; --i) T[i] = rhs[i] - c[i] * T[i + 1];
}
}  // namespace

std::vector<double> heat_bar_fd_profile(const HeatBar1D& bar, int N, double dt, int steps)
{
    if (N < 2 || !(dt > 0) || steps < 0) throw std::invalid_argument("heat_bar_fd_profile: need N >= 2, dt > 0, steps >= 0");
    const double dx = bar.L / N, r = bar.alpha * dt / (dx * dx);
    std::vector<double> T(N + 1, bar.T0), c(N + 1), rhs(N + 1);
    T[0] = T[N] = bar.T_end;
    for (int n = 0; n < steps; ++n) fd_implicit_step(T, r, c, rhs);
    return T;
}

double heat_bar_fd_time_to(const HeatBar1D& bar, int N, double dt, double x, double T_target, double t_max)
{
    check_target(bar, T_target, "heat_bar_fd_time_to");
    if (N < 2 || !(dt > 0)) throw std::invalid_argument("heat_bar_fd_time_to: need N >= 2 and dt > 0");
    const double dx = bar.L / N, r = bar.alpha * dt / (dx * dx);
    const int probe = static_cast<int>(std::lround(x / dx));
    if (probe <= 0 || probe >= N) throw std::invalid_argument("heat_bar_fd_time_to: x must be an interior node");
    std::vector<double> T(N + 1, bar.T0), rhs(N + 1), c(N + 1);
    T[0] = T[N] = bar.T_end;
    const double up = bar.T_end > bar.T0 ? 1 : -1;  // direction of the change at the probe
    for (double t = 0; t < t_max; t += dt) {
        const double before = T[probe];
        fd_implicit_step(T, r, c, rhs);
        if (up * (T[probe] - T_target) >= 0) return t + dt * (T_target - before) / (T[probe] - before);
    }
    throw std::runtime_error("heat_bar_fd_time_to: target not reached within t_max");
}

}  // namespace pd::ref
