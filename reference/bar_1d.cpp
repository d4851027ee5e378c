// reference/bar_1d.cpp -- classical references for the fixed-free bar released from uniform strain:
// exact frequencies, exact modal series and its closed form at the tip, the lumped linear FE bar
// (CVODE time integration, exact discrete modes, Eigen eigenfrequency), a frequency meter and the
// integral error metric. Source: spec/000b_models.md sec. 5.1 (T1), V1; thesis Eq. (4.36).
// Never calls the peridynamics library (reference independence, DESIGN.md).
#include "reference/bar_1d.hpp"

#include <Eigen/Eigenvalues>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunmatrix/sunmatrix_band.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pd::ref {

namespace {

constexpr double pi = std::numbers::pi;

void require(bool ok, const char* what)
{
    if (!ok) throw std::invalid_argument(std::string("pd::ref bar_1d: ") + what);
}

void require_bar(double E, double rho, double l)
{
    require(E > 0.0, "E must be > 0");
    require(rho > 0.0, "rho must be > 0");
    require(l > 0.0, "l must be > 0");
}

// Wave number of mode n of the fixed-free bar [1/m]: sin(k l) = +-1, cos(k l) = 0.
double wave_number(int n, double l) { return (2.0 * n - 1.0) * pi / (2.0 * l); }

// Nodal masses per unit cross-section of the lumped linear FE bar [kg/m^2], free nodes j = 1..N-1
// (index j-1): rho dx everywhere, rho dx / 2 at the free end (half of one element).
std::vector<double> lumped_masses(int N, double rho, double dx)
{
    std::vector<double> m(N - 1, rho * dx);
    m.back() = 0.5 * rho * dx;
    return m;
}

}  // namespace

// f_n = (2n-1)/4 sqrt(E/(rho l^2)) [Hz] (thesis Eq. 4.36), i.e. w_n = c k_n with k_n = (2n-1)pi/(2l).
double bar_frequency(int n, double E, double rho, double l)
{
    require(n >= 1, "mode number n must be >= 1");
    require_bar(E, rho, l);
    return (2.0 * n - 1.0) / 4.0 * std::sqrt(E / (rho * l * l));
}

// Modal series. Modes of rho u_tt = E u_xx with u(0) = 0, u_x(l) = 0: sin(k_n x), cos(k_n l) = 0.
// Coefficients from the orthogonality int_0^l sin(k_n x) sin(k_m x) dx = (l/2) delta_nm and v0 = 0:
//   b_n = (2/l) int_0^l eps0 x sin(k_n x) dx
//       = (2 eps0/l) [ -x cos(k_n x)/k_n + sin(k_n x)/k_n^2 ]_0^l
//       = (2 eps0/l) [ -l cos(k_n l)/k_n + sin(k_n l)/k_n^2 ]      (cos(k_n l) = 0,
//       = 2 eps0 (-1)^(n+1) / (l k_n^2)                              sin(k_n l) = (-1)^(n+1)).
// At x = l the factor (-1)^(n+1) squares away: u(l,t) = sum_n 8 eps0 l/((2n-1)^2 pi^2) cos(w_n t),
// the Fourier series of a triangle wave (terms ~ 1/n^2, see bar_tip_displacement_exact).
double bar_modal_displacement(double x, double t, double E, double rho, double l, double eps0,
                              int n_terms)
{
    require_bar(E, rho, l);
    require(n_terms >= 1, "n_terms must be >= 1");
    const double c = std::sqrt(E / rho);  // bar wave speed [m/s]
    double u = 0.0;                       // [m]
    // Sum the smallest terms first to limit round-off for large n_terms.
    for (int n = n_terms; n >= 1; --n) {
        const double k = wave_number(n, l);
        const double sign = (n % 2 == 1) ? 1.0 : -1.0;    // (-1)^(n+1)
        const double b = 2.0 * eps0 * sign / (l * k * k);  // b_n [m]
        u += b * std::sin(k * x) * std::cos(c * k * t);
    }
    return u;
}

// Closed form of the tip motion (d'Alembert). At t = 0 the bar carries stress E eps0 everywhere;
// the free end must be traction free, so an unloading wave leaves x = l at speed c. Behind it the
// stress is zero and the particle velocity is -c eps0 (momentum jump rho c dv = d sigma = -E eps0).
// The wave reflects at the clamp with the same stress jump, so behind the returning wave the bar is
// at rest in compression -E eps0; until it reaches the tip at t = 2l/c the tip keeps the velocity
// -c eps0: u_tip = eps0 l - c eps0 t reaches -eps0 l at t = 2l/c. Releasing the compression there
// gives +c eps0 for the next 2l/c, back to eps0 l at 4l/c. Result: a triangle wave of period
// P = 4l/c, u_tip = eps0 l (1 - 4 min(tau, P - tau)/P), tau = t mod P. This equals the series above
// by the classical identity 8/pi^2 sum_n cos((2n-1)theta)/(2n-1)^2 = 1 - 2|theta|/pi on [-pi, pi].
double bar_tip_displacement_exact(double t, double E, double rho, double l, double eps0)
{
    require_bar(E, rho, l);
    const double c = std::sqrt(E / rho);               // [m/s]
    const double P = 4.0 * l / c;                      // period [s]
    const double tau = std::fmod(std::abs(t), P);      // u is even in t (released from rest)
    const double s = std::min(tau, P - tau);           // distance to the nearest t = kP [s]
    return eps0 * l * (1.0 - 4.0 * s / P);             // triangle wave [m]
}

// ---------------------------------------------------------------------------------------------
// Lumped linear FE bar, per unit cross-section (A cancels in M u'' + K u = 0).
// Element stiffness E/dx [Pa/m]; free node j has acceleration
//   a_j = c^2/dx^2 (u_{j-1} - 2u_j + u_{j+1})   (interior, u_0 = 0 at the clamp),
//   a_{N-1} = 2 c^2/dx^2 (u_{N-2} - u_{N-1})     (free end, half mass).
// CVODE state interleaves y[2(j-1)] = u_j [m], y[2(j-1)+1] = v_j [m/s], so the Jacobian is banded
// with upper bandwidth 1 (du_j/dt = v_j, dv_j/du_{j+1}) and lower bandwidth 3 (dv_j/du_{j-1}).
namespace {

struct FeBarOde {
    int n_free;     // N - 1 free nodes
    double a_coef;  // c^2/dx^2 [1/s^2]
};

int fe_bar_rhs(sunrealtype, N_Vector y, N_Vector ydot, void* user_data)
{
    const auto* p = static_cast<const FeBarOde*>(user_data);
    const sunrealtype* Y = N_VGetArrayPointer(y);
    sunrealtype* D = N_VGetArrayPointer(ydot);
    const int m = p->n_free;
    for (int i = 0; i < m; ++i) {
        const double u_left = (i == 0) ? 0.0 : Y[2 * (i - 1)];  // clamp u_0 = 0
        const double u = Y[2 * i];
        D[2 * i] = Y[2 * i + 1];                                 // du/dt = v
        if (i < m - 1)
            D[2 * i + 1] = p->a_coef * (u_left - 2.0 * u + Y[2 * (i + 1)]);  // interior node
        else
            D[2 * i + 1] = 2.0 * p->a_coef * (u_left - u);                  // free end, mass/2
    }
    return 0;
}

// Constant Jacobian of fe_bar_rhs (the system is linear).
int fe_bar_jac(sunrealtype, N_Vector, N_Vector, SUNMatrix J, void* user_data, N_Vector, N_Vector,
               N_Vector)
{
    const auto* p = static_cast<const FeBarOde*>(user_data);
    SUNMatZero(J);
    const int m = p->n_free;
    for (int i = 0; i < m; ++i) {
        const double off = (i < m - 1) ? p->a_coef : 2.0 * p->a_coef;  // d a_i / d u_{i-1}
        SM_ELEMENT_B(J, 2 * i, 2 * i + 1) = 1.0;                        // d u_i' / d v_i
        SM_ELEMENT_B(J, 2 * i + 1, 2 * i) = -2.0 * p->a_coef;           // d a_i / d u_i (both rows)
        if (i > 0) SM_ELEMENT_B(J, 2 * i + 1, 2 * (i - 1)) = off;
        if (i < m - 1) SM_ELEMENT_B(J, 2 * i + 1, 2 * (i + 1)) = p->a_coef;
    }
    return 0;
}

// Owns the SUNDIALS objects of one integration; frees them on every exit path.
struct CvodeSession {
    SUNContext ctx = nullptr;
    N_Vector y = nullptr;
    N_Vector abstol = nullptr;
    SUNMatrix A = nullptr;
    SUNLinearSolver LS = nullptr;
    void* mem = nullptr;
    ~CvodeSession()
    {
        if (mem) CVodeFree(&mem);
        if (LS) SUNLinSolFree(LS);
        if (A) SUNMatDestroy(A);
        if (abstol) N_VDestroy(abstol);
        if (y) N_VDestroy(y);
        if (ctx) SUNContext_Free(&ctx);
    }
};

void check_cv(int flag, const char* call)
{
    if (flag < 0)
        throw std::runtime_error(std::string("pd::ref fe_bar_tip_history: ") + call +
                                 " failed with flag " + std::to_string(flag));
}

void check_grid(int N, double t_end, int n_out)
{
    require(N >= 2, "N must be >= 2");
    require(t_end > 0.0, "t_end must be > 0");
    require(n_out >= 1, "n_out must be >= 1");
}

}  // namespace

FeBarResult fe_bar_tip_history(int N, double E, double rho, double l, double eps0, double t_end,
                               int n_out)
{
    require_bar(E, rho, l);
    check_grid(N, t_end, n_out);
    constexpr double rtol = 1e-10;        // relative tolerance (brief: tight, 1e-10)
    constexpr double atol_factor = 1e-12; // absolute tolerance relative to the amplitude eps0 l
    constexpr long max_steps = 100000000; // per output interval; the stiff-free problem needs
                                          // every mode resolved, so steps are many but cheap
    const double c = std::sqrt(E / rho);  // [m/s]
    const double dx = l / (N - 1);        // [m]
    const int m = N - 1;
    FeBarOde ode{m, c * c / (dx * dx)};

    FeBarResult out;
    out.t_s.resize(n_out + 1);
    out.tip_m.resize(n_out + 1);
    for (int k = 0; k <= n_out; ++k) out.t_s[k] = t_end * k / n_out;
    out.tip_m[0] = eps0 * l;
    if (eps0 == 0.0) {  // released from rest, unstrained: stays at rest
        std::fill(out.tip_m.begin(), out.tip_m.end(), 0.0);
        return out;
    }

    CvodeSession s;
    check_cv(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
    s.y = N_VNew_Serial(2 * m, s.ctx);
    s.abstol = N_VNew_Serial(2 * m, s.ctx);
    if (!s.y || !s.abstol) throw std::runtime_error("pd::ref fe_bar_tip_history: N_VNew_Serial");
    sunrealtype* Y = N_VGetArrayPointer(s.y);
    sunrealtype* AT = N_VGetArrayPointer(s.abstol);
    const double u_scale = std::abs(eps0) * l;  // displacement scale [m]
    const double v_scale = std::abs(eps0) * c;  // velocity scale [m/s] (tip speed c eps0)
    for (int i = 0; i < m; ++i) {
        Y[2 * i] = eps0 * (i + 1) * dx;  // u(x,0) = eps0 x
        Y[2 * i + 1] = 0.0;              // released from rest
        AT[2 * i] = atol_factor * u_scale;
        AT[2 * i + 1] = atol_factor * v_scale;
    }

    // Adams-Moulton: no numerical damping of the undamped oscillations beyond the error control.
    s.mem = CVodeCreate(CV_ADAMS, s.ctx);
    if (!s.mem) throw std::runtime_error("pd::ref fe_bar_tip_history: CVodeCreate");
    check_cv(CVodeInit(s.mem, fe_bar_rhs, 0.0, s.y), "CVodeInit");
    check_cv(CVodeSetUserData(s.mem, &ode), "CVodeSetUserData");
    check_cv(CVodeSVtolerances(s.mem, rtol, s.abstol), "CVodeSVtolerances");
    s.A = SUNBandMatrix(2 * m, 1, 3, s.ctx);
    s.LS = SUNLinSol_Band(s.y, s.A, s.ctx);
    if (!s.A || !s.LS) throw std::runtime_error("pd::ref fe_bar_tip_history: band solver");
    check_cv(CVodeSetLinearSolver(s.mem, s.LS, s.A), "CVodeSetLinearSolver");
    check_cv(CVodeSetJacFn(s.mem, fe_bar_jac), "CVodeSetJacFn");
    check_cv(CVodeSetMaxNumSteps(s.mem, max_steps), "CVodeSetMaxNumSteps");

    for (int k = 1; k <= n_out; ++k) {
        sunrealtype t_reached = 0.0;
        check_cv(CVode(s.mem, out.t_s[k], s.y, &t_reached, CV_NORMAL), "CVode");
        out.tip_m[k] = Y[2 * (m - 1)];
    }
    return out;
}

// Discrete modes of the lumped FE bar. With phi_n(x_j) = sin(k_n x_j), k_n = (2n-1)pi/(2l),
// n = 1..N-1: interior rows give (c^2/dx^2)(2 - 2cos(k_n dx)) phi = (2c/dx)^2 sin^2(k_n dx/2) phi;
// the free-end row 2c^2/dx^2 (phi_{N-1} - phi_{N-2}) is the same expression because phi is even
// about x = l (cos(k_n l) = 0, so the ghost value phi_N equals phi_{N-2}). Hence
//   K phi_n = (w_n^h)^2 M phi_n,  w_n^h = (2c/dx) sin(k_n dx/2),
// and the modes are M-orthogonal, a_n = phi_n^T M u0 / phi_n^T M phi_n. (At the tip this sums to
// a_n phi_n(l) = eps0 dx^2 / (2 l sin^2(k_n dx/2)); the test checks that closed form independently.)
FeBarResult fe_bar_modal_tip_history(int N, double E, double rho, double l, double eps0,
                                     double t_end, int n_out)
{
    require_bar(E, rho, l);
    check_grid(N, t_end, n_out);
    const double c = std::sqrt(E / rho);  // [m/s]
    const double dx = l / (N - 1);        // [m]
    const int m = N - 1;
    const std::vector<double> mass = lumped_masses(N, rho, dx);
    std::vector<double> a(m), w(m), tip_shape(m);
    for (int n = 1; n <= m; ++n) {
        const double k = wave_number(n, l);
        double num = 0.0, den = 0.0;
        for (int j = 1; j <= m; ++j) {
            const double phi = std::sin(k * j * dx);
            num += mass[j - 1] * phi * eps0 * j * dx;  // phi^T M u0
            den += mass[j - 1] * phi * phi;            // phi^T M phi
        }
        a[n - 1] = num / den;                                   // modal amplitude [m]
        w[n - 1] = 2.0 * c / dx * std::sin(0.5 * k * dx);      // discrete circular frequency [rad/s]
        tip_shape[n - 1] = std::sin(k * m * dx);                // phi_n at the free end
    }
    FeBarResult out;
    out.t_s.resize(n_out + 1);
    out.tip_m.resize(n_out + 1);
    for (int s = 0; s <= n_out; ++s) {
        const double t = t_end * s / n_out;
        double u = 0.0;
        for (int n = m - 1; n >= 0; --n) u += a[n] * tip_shape[n] * std::cos(w[n] * t);
        out.t_s[s] = t;
        out.tip_m[s] = u;
    }
    return out;
}

// Lowest eigenvalue of the symmetric tridiagonal S = M^{-1/2} K M^{-1/2} (per unit cross-section):
// K_jj = 2E/dx (E/dx at the free end), K_j,j+1 = -E/dx; f1^h = sqrt(lambda_min)/(2 pi).
double fe_bar_frequency(int N, double E, double rho, double l)
{
    require_bar(E, rho, l);
    require(N >= 2, "N must be >= 2");
    const double dx = l / (N - 1);  // [m]
    const int m = N - 1;
    const double k_el = E / dx;     // element stiffness per unit area [Pa/m]
    const std::vector<double> mass = lumped_masses(N, rho, dx);
    Eigen::VectorXd diag(m), sub(std::max(m - 1, 0));
    for (int j = 0; j < m; ++j) diag[j] = ((j < m - 1) ? 2.0 * k_el : k_el) / mass[j];
    for (int j = 0; j + 1 < m; ++j) sub[j] = -k_el / std::sqrt(mass[j] * mass[j + 1]);
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
    solver.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
    if (solver.info() != Eigen::Success)
        throw std::runtime_error("pd::ref fe_bar_frequency: eigen solver failed");
    return std::sqrt(solver.eigenvalues()[0]) / (2.0 * pi);  // ascending order: lowest first [Hz]
}

// ---------------------------------------------------------------------------------------------
// Frequency meter, two stages.
// Stage 1, zero crossings (zero_crossing_frequency):
//  1. Remove the mean (trapezoidal mean over the record; refined in a second pass to the mean over
//     the whole periods between the first and last upward crossing).
//  2. Detect crossings with a Schmitt trigger: an upward crossing is recorded when the signal,
//     having been below -h, rises above +h (h = hysteresis_fraction of the peak |signal - mean|);
//     its time is the last zero crossing before that, linearly interpolated between samples.
//     Downward crossings symmetrically. High-frequency ripple smaller than h cannot create
//     spurious crossings; same-direction crossings closer than 0.5/f_guess are also rejected.
//  3. The period is the least-squares slope of crossing time against period index, for upward
//     and downward crossings separately; the two slopes are averaged, f = 1/period.
//  A constant offset shifts every crossing by the same time and leaves the slope unchanged. On a
//  strictly periodic signal this is exact up to interpolation error (exact for a triangle wave),
//  but when the harmonics are not exact multiples of f1 (dispersion in a discrete bar: mode n at
//  (2n-1) f1 (1 - O((n dx)^2))) they shift the crossings and bias f by up to ~1e-4 (FE bar, N=50).
// Stage 2, windowed sine fit (dominant_frequency): starting from the stage-1 value f0, maximise
//  over f the energy of the Hann-weighted least-squares fit s ~ a cos(2 pi f t) + b sin(2 pi f t)
//  + d. The fit carries its own offset and the negative-frequency image (no DC or image leakage);
//  the Hann window (sidelobes decaying as 1/bin^3) makes the harmonics at >= 3 f0, i.e. >= 2 n_per
//  bins away, negligible. The maximum is found by golden-section search on f0 +- 0.5/T_record,
//  inside the main lobe (half width 2/T_record), to a relative bracket of 1e-12.
namespace {

constexpr double hysteresis_fraction = 0.25;  // of the peak amplitude; above ripple, below peaks

struct Crossings {
    std::vector<double> up, down;  // times [s]
};

Crossings find_crossings(const std::vector<double>& t, const std::vector<double>& s, double mean,
                         double min_sep)
{
    double amp = 0.0;
    for (double v : s) amp = std::max(amp, std::abs(v - mean));
    const double h = hysteresis_fraction * amp;
    Crossings c;
    int state = 0;  // -1 low, +1 high, 0 unknown
    double t_up = std::numeric_limits<double>::quiet_NaN();
    double t_down = t_up;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double v = s[i] - mean;
        if (i > 0) {
            const double v0 = s[i - 1] - mean;
            // Linear interpolation of the zero between samples i-1 and i.
            if (v0 <= 0.0 && v > 0.0) t_up = t[i - 1] + (t[i] - t[i - 1]) * (-v0) / (v - v0);
            if (v0 >= 0.0 && v < 0.0) t_down = t[i - 1] + (t[i] - t[i - 1]) * v0 / (v0 - v);
        }
        if (v > h && state != 1) {
            if (state == -1 && !std::isnan(t_up) && (c.up.empty() || t_up - c.up.back() > min_sep))
                c.up.push_back(t_up);
            state = 1;
        } else if (v < -h && state != -1) {
            if (state == 1 && !std::isnan(t_down) &&
                (c.down.empty() || t_down - c.down.back() > min_sep))
                c.down.push_back(t_down);
            state = -1;
        }
    }
    return c;
}

// Trapezoidal integral of the piecewise-linear interpolant of s over [ta, tb] [unit s].
double integrate_between(const std::vector<double>& t, const std::vector<double>& s, double ta,
                         double tb)
{
    double sum = 0.0;
    for (std::size_t i = 1; i < t.size(); ++i) {
        const double lo = std::max(ta, t[i - 1]), hi = std::min(tb, t[i]);
        if (hi <= lo) continue;
        const double r = (s[i] - s[i - 1]) / (t[i] - t[i - 1]);
        const double s_lo = s[i - 1] + r * (lo - t[i - 1]), s_hi = s[i - 1] + r * (hi - t[i - 1]);
        sum += 0.5 * (s_lo + s_hi) * (hi - lo);
    }
    return sum;
}

// Least-squares slope of crossing time against period index (the period) [s]. The index of each
// crossing is its elapsed time over the median spacing, rounded, so a crossing missed in a noisy
// stretch does not corrupt the fit. NaN if fewer than 3 crossings (two full periods).
double ls_period(const std::vector<double>& times)
{
    const std::size_t n = times.size();
    if (n < 3) return std::numeric_limits<double>::quiet_NaN();
    std::vector<double> gaps(n - 1);
    for (std::size_t k = 1; k < n; ++k) gaps[k - 1] = times[k] - times[k - 1];
    std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
    const double p_median = gaps[gaps.size() / 2];  // [s]
    std::vector<double> idx(n);
    for (std::size_t k = 0; k < n; ++k) idx[k] = std::round((times[k] - times[0]) / p_median);
    double k_mean = 0.0, t_mean = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        k_mean += idx[k] / n;
        t_mean += times[k] / n;
    }
    double num = 0.0, den = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        num += (idx[k] - k_mean) * (times[k] - t_mean);
        den += (idx[k] - k_mean) * (idx[k] - k_mean);
    }
    return num / den;
}

}  // namespace

double zero_crossing_frequency(const std::vector<double>& t, const std::vector<double>& signal,
                               double f_guess)
{
    require(t.size() == signal.size(), "t and signal must have the same length");
    require(t.size() >= 3, "need at least 3 samples");
    require(f_guess > 0.0, "f_guess must be > 0");
    const double min_sep = 0.5 / f_guess;  // half the expected period [s]
    const double mean0 = integrate_between(t, signal, t.front(), t.back()) / (t.back() - t.front());
    Crossings c = find_crossings(t, signal, mean0, min_sep);
    if (c.up.size() >= 2) {  // mean over whole periods, then detect again
        const double ta = c.up.front(), tb = c.up.back();
        c = find_crossings(t, signal, integrate_between(t, signal, ta, tb) / (tb - ta), min_sep);
    }
    const double p_up = ls_period(c.up), p_down = ls_period(c.down);
    double period;
    if (!std::isnan(p_up) && !std::isnan(p_down))
        period = 0.5 * (p_up + p_down);
    else if (!std::isnan(p_up))
        period = p_up;
    else
        period = p_down;  // NaN if neither has two full periods
    return 1.0 / period;
}

namespace {

// Energy captured by the Hann-weighted least-squares fit of a cos + b sin + d at frequency f [Hz]:
// q = r^T G^{-1} r with G = sum w g g^T, r = sum w g s, g = (cos, sin, 1).
double windowed_fit_energy(const std::vector<double>& t, const std::vector<double>& s, double f)
{
    const double t0 = t.front(), T = t.back() - t.front();
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double w = 0.5 * (1.0 - std::cos(2.0 * pi * (t[i] - t0) / T));  // Hann window
        const double ph = 2.0 * pi * f * (t[i] - t0);
        const Eigen::Vector3d g(std::cos(ph), std::sin(ph), 1.0);
        G += w * g * g.transpose();
        r += w * s[i] * g;
    }
    return r.dot(G.ldlt().solve(r));
}

}  // namespace

double dominant_frequency(const std::vector<double>& t, const std::vector<double>& signal,
                          double f_guess)
{
    const double f0 = zero_crossing_frequency(t, signal, f_guess);
    if (std::isnan(f0)) return f0;
    constexpr double rel_bracket = 1e-12;                   // stop when the bracket is this small
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);     // 0.618...
    const double half_width = 0.5 / (t.back() - t.front()); // half a DFT bin [Hz]
    double lo = f0 - half_width, hi = f0 + half_width;
    double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
    double q1 = windowed_fit_energy(t, signal, x1), q2 = windowed_fit_energy(t, signal, x2);
    while (hi - lo > rel_bracket * f0) {  // golden-section search for the maximum
        if (q1 < q2) {
            lo = x1;
            x1 = x2;
            q1 = q2;
            x2 = lo + golden * (hi - lo);
            q2 = windowed_fit_energy(t, signal, x2);
        } else {
            hi = x2;
            x2 = x1;
            q2 = q1;
            x1 = hi - golden * (hi - lo);
            q1 = windowed_fit_energy(t, signal, x1);
        }
    }
    return 0.5 * (lo + hi);
}

double integral_relative_error(const std::vector<double>& a, const std::vector<double>& ref)
{
    require(a.size() == ref.size(), "series must have the same length");
    require(!a.empty(), "series must not be empty");
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        num += std::abs(a[i] - ref[i]);  // int |a - ref| dt / dt
        den += std::abs(ref[i]);         // int |ref| dt / dt
    }
    require(den > 0.0, "reference series is identically zero");
    return num / den;
}

}  // namespace pd::ref
