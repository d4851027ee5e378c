// tests/test_reference_bar.cpp -- checks of reference/bar_1d (fixed-free bar released from uniform
// strain, spec/000b sec. 5.1 T1 and V1) against closed forms written independently here:
//   f_n = (2n-1)/4 sqrt(E/(rho l^2)) = 1265.92 Hz for n = 1 (thesis Eq. 4.36);
//   tip triangle wave (d'Alembert) and its tail bound 8/pi^2 sum_{n>N} 1/(2n-1)^2;
//   lumped FE bar, M = N-1 free nodes, theta_n = (2n-1) pi/(4M):
//     f_n^h = (c/(pi dx)) sin(theta_n)  and the tip solution
//     u_tip^h(t) = sum_n eps0 dx^2/(2 l sin^2 theta_n) cos(2 (c/dx) sin(theta_n) t)
//   (discrete sine modes; the amplitudes sum to eps0 l by sum_n csc^2 theta_n = 2 M^2).
#include "reference/bar_1d.hpp"

#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace {

using namespace pd::ref;
constexpr double pi = std::numbers::pi;
constexpr double E = 200e9;    // [Pa], spec 5.1
constexpr double rho = 7800.0; // [kg/m^3]
constexpr double l = 1.0;      // [m]
constexpr double eps0 = 1e-3;  // initial strain [-] (not given by the spec; any value, linear)
const double c = std::sqrt(E / rho);        // [m/s]
const double f1 = bar_frequency(1, E, rho, l);  // [Hz]
const double T1 = 1.0 / f1;                 // [s]

// Tip amplitude of mode n of the continuum series, 8 eps0 l/((2n-1)^2 pi^2) [m].
double tip_amplitude(int n) { return 8.0 * eps0 * l / (pi * pi * (2.0 * n - 1) * (2.0 * n - 1)); }

// Tail of the tip series beyond n_terms, the exact sup error of the truncated series (at t = 0):
// sum_{n>N} A_n = eps0 l - sum_{n<=N} A_n, since sum_n 1/(2n-1)^2 = pi^2/8 [m].
double tip_tail(int n_terms)
{
    double s = 0.0;
    for (int n = n_terms; n >= 1; --n) s += tip_amplitude(n);
    return eps0 * l - s;
}

// Exact tip history of the lumped FE bar from its closed-form modes (header formula) [m].
double fe_tip_closed_form(int N, double t)
{
    const int M = N - 1;
    const double dx = l / M;
    double u = 0.0;
    for (int n = M; n >= 1; --n) {
        const double th = (2.0 * n - 1.0) * pi / (4.0 * M);
        u += eps0 * dx * dx / (2.0 * l * std::sin(th) * std::sin(th)) *
             std::cos(2.0 * c / dx * std::sin(th) * t);
    }
    return u;
}

std::vector<double> triangle(const std::vector<double>& t, double shift)
{
    std::vector<double> u(t.size());
    for (std::size_t i = 0; i < t.size(); ++i)
        u[i] = bar_tip_displacement_exact(t[i] + shift, E, rho, l, eps0);
    return u;
}

std::vector<double> uniform_times(double t_end, int n_out)
{
    std::vector<double> t(n_out + 1);
    for (int i = 0; i <= n_out; ++i) t[i] = t_end * i / n_out;
    return t;
}

// CVODE tip history of the N = 200 FE bar over 2 T1, 400 intervals, computed once (~2 s).
const FeBarResult& cvode_n200()
{
    static const FeBarResult r = fe_bar_tip_history(200, E, rho, l, eps0, 2.0 * T1, 400);
    return r;
}

}  // namespace

TEST(ReferenceBar, FirstFrequencyMatchesSpec)
{
    EXPECT_NEAR(f1, 1265.92, 0.01);  // printed with 2 decimals in spec 5.1 / thesis 4.36
    EXPECT_NEAR(T1, 7.899e-4, 5e-8); // printed with 4 significant digits
    // Hand value: c = sqrt(2e11/7800) = 5063.697 m/s, f1 = c/(4l) = 1265.924 Hz.
    EXPECT_NEAR(f1, 5063.6968 / 4.0, 1e-3);
}

TEST(ReferenceBar, HigherFrequenciesAreOddMultiples)
{
    for (int n = 1; n <= 20; ++n)  // exact relation; tolerance is round-off
        EXPECT_NEAR(bar_frequency(n, E, rho, l), (2 * n - 1) * f1, 1e-12 * (2 * n - 1) * f1);
    EXPECT_THROW(bar_frequency(0, E, rho, l), std::invalid_argument);
    EXPECT_THROW(bar_frequency(1, -E, rho, l), std::invalid_argument);
}

TEST(ReferenceBar, TipTriangleWaveHandValues)
{
    const double u0 = eps0 * l;  // [m]
    const double P = 4.0 * l / c;  // period [s]
    EXPECT_NEAR(P, T1, 1e-15);
    EXPECT_NEAR(bar_tip_displacement_exact(0.0, E, rho, l, eps0), u0, 1e-18);
    EXPECT_NEAR(bar_tip_displacement_exact(l / c, E, rho, l, eps0), 0.0, 1e-18);
    EXPECT_NEAR(bar_tip_displacement_exact(2 * l / c, E, rho, l, eps0), -u0, 1e-18);
    EXPECT_NEAR(bar_tip_displacement_exact(3 * l / c, E, rho, l, eps0), 0.0, 1e-18);
    EXPECT_NEAR(bar_tip_displacement_exact(5 * P + 0.25 * l / c, E, rho, l, eps0), 0.75 * u0, 1e-15);
    // Tip velocity -c eps0 behind the unloading wave (d'Alembert), measured by a finite difference
    // on a linear stretch (exact up to round-off).
    const double h = 1e-6 * l / c;
    const double v = (bar_tip_displacement_exact(0.5 * l / c + h, E, rho, l, eps0) -
                      bar_tip_displacement_exact(0.5 * l / c - h, E, rho, l, eps0)) / (2 * h);
    EXPECT_NEAR(v, -c * eps0, 1e-6 * c * eps0);
}

TEST(ReferenceBar, ModalCoefficientsMatchGslQuadrature)
{
    // b_n = (2/l) int_0^l eps0 x sin(k_n x) dx by GSL adaptive quadrature, against the term n of
    // the series isolated as the difference of partial sums at (x, t = 0).
    // Requested relative accuracy 1e-10 (GSL refuses tighter on this smooth integrand); compared at 1e-9.
    gsl_integration_workspace* ws = gsl_integration_workspace_alloc(1000);
    const double x = 0.3 * l;  // sin(k_n x) != 0 for n = 1..8
    for (int n = 1; n <= 8; ++n) {
        double k = (2.0 * n - 1) * pi / (2 * l);
        gsl_function F{[](double s, void* p) { return eps0 * s * std::sin(*(double*)p * s); }, &k};
        double integral = 0.0, abserr = 0.0;
        gsl_integration_qag(&F, 0.0, l, 0.0, 1e-10, 1000, GSL_INTEG_GAUSS61, ws, &integral, &abserr);
        const double b_quad = 2.0 / l * integral;
        const double term = bar_modal_displacement(x, 0.0, E, rho, l, eps0, n) -
                            (n > 1 ? bar_modal_displacement(x, 0.0, E, rho, l, eps0, n - 1) : 0.0);
        EXPECT_NEAR(term / std::sin(k * x), b_quad, 1e-9 * std::abs(b_quad)) << "n = " << n;
    }
    gsl_integration_workspace_free(ws);
    // The series at t = 0 rebuilds u0 = eps0 x; error bounded by the tail sum (|sin| <= 1).
    for (double xi : {0.1, 0.5, 0.9})
        EXPECT_NEAR(bar_modal_displacement(xi * l, 0.0, E, rho, l, eps0, 2000), eps0 * xi * l,
                    tip_tail(2000));
}

TEST(ReferenceBar, ModalSeriesConvergesToTriangleWave)
{
    const std::vector<double> t = uniform_times(2.0 * T1, 4000);  // includes the corners 0, T1/2, T1
    double prev = 1e300;
    for (int n_terms : {10, 100, 1000, 2000}) {
        double sup = 0.0, sum_abs = 0.0;
        for (double ti : t) {
            const double e = std::abs(bar_modal_displacement(l, ti, E, rho, l, eps0, n_terms) -
                                      bar_tip_displacement_exact(ti, E, rho, l, eps0));
            sup = std::max(sup, e);
            sum_abs += e / t.size();
        }
        // The sup error is the tail sum, reached at the corners (all cosines = +-1); 1e-12: round-off.
        EXPECT_NEAR(sup, tip_tail(n_terms), 1e-12 * eps0 * l) << n_terms << " terms";
        EXPECT_LT(sup, prev);
        prev = sup;
        if (n_terms == 2000) {
            // 2000 terms: tail = 2/(pi^2 N) eps0 l = 1.0132e-4 eps0 l at the corners only (the
            // brief's "below 1e-4" needs N >= 2027 there); the mean error is far below 1e-4.
            EXPECT_LT(sup, 1.02e-4 * eps0 * l);
            EXPECT_LT(sum_abs, 1e-5 * eps0 * l);
        }
    }
    EXPECT_LT(tip_tail(2027), 1e-4 * eps0 * l);
}

TEST(ReferenceBar, FeFrequencyConvergesAtSecondOrder)
{
    std::vector<double> dx, err;
    for (int N : {50, 100, 200}) {
        const double h = l / (N - 1);
        const double f_fe = fe_bar_frequency(N, E, rho, l);
        // Eigen against the closed form (c/(pi dx)) sin(pi dx/(4l)); 1e-9: eigenvalue round-off
        // ~ eps * lambda_max/lambda_min ~ 1e-16 * 2.5e4.
        EXPECT_NEAR(f_fe, c / (pi * h) * std::sin(pi * h / (4 * l)), 1e-9 * f1) << "N = " << N;
        dx.push_back(h);
        err.push_back(std::abs(f_fe - f1));
    }
    for (int i = 0; i + 1 < 3; ++i) {
        const double order = std::log(err[i] / err[i + 1]) / std::log(dx[i] / dx[i + 1]);
        EXPECT_NEAR(order, 2.0, 0.1);  // error = f1 (pi dx/(4l))^2/6 + O(dx^4)
    }
}

TEST(ReferenceBar, CvodeMatchesExactFeModes)
{
    constexpr int N = 200, n_out = 400;
    const FeBarResult& cv = cvode_n200();
    const FeBarResult md = fe_bar_modal_tip_history(N, E, rho, l, eps0, 2.0 * T1, n_out);
    ASSERT_EQ(cv.t_s.size(), static_cast<std::size_t>(n_out + 1));
    ASSERT_EQ(cv.tip_m.size(), cv.t_s.size());
    EXPECT_DOUBLE_EQ(cv.t_s.back(), 2.0 * T1);
    double sup_cv = 0.0, sup_md = 0.0;
    for (int i = 0; i <= n_out; ++i) {
        const double u = fe_tip_closed_form(N, cv.t_s[i]);
        sup_cv = std::max(sup_cv, std::abs(cv.tip_m[i] - u));
        sup_md = std::max(sup_md, std::abs(md.tip_m[i] - u));
    }
    // Same semi-discrete system, so only time-integration error is left: CVODE local error
    // control rtol 1e-10 accumulated over ~1e5 steps (measured 3.4e-10 eps0 l); 1e-7 leaves
    // margin and stays 5 orders below the spatial discretisation error.
    EXPECT_LT(sup_cv, 1e-7 * eps0 * l);
    EXPECT_LT(sup_md, 1e-12 * eps0 * l);  // projection vs closed form: round-off only
}

TEST(ReferenceBar, FeTipWithinDiscretisationErrorOfTriangle)
{
    // Rigorous sup bound of |u^h_tip - u_tip| by the triangle inequality over modes:
    //   sum_{n<=M} |A_n^h - A_n| + A_n min(2, |w_n^h - w_n| t_end) + sum_{n>M} A_n.
    // It scales as dx^(2/3) (dispersion smears each kink over an Airy width (c t dx^2)^(1/3)).
    constexpr int N = 200;
    const int M = N - 1;
    const double dx = l / M, t_end = 2.0 * T1;
    double bound = tip_tail(M);
    for (int n = 1; n <= M; ++n) {
        const double th = (2.0 * n - 1) * pi / (4.0 * M);
        const double A_h = eps0 * dx * dx / (2 * l * std::sin(th) * std::sin(th));
        const double w = c * (2.0 * n - 1) * pi / (2 * l), w_h = 2 * c / dx * std::sin(th);
        bound += std::abs(A_h - tip_amplitude(n)) + tip_amplitude(n) * std::min(2.0, (w - w_h) * t_end);
    }
    const FeBarResult& cv = cvode_n200();
    const std::vector<double> tri = triangle(cv.t_s, 0.0);
    double sup = 0.0;
    for (std::size_t i = 0; i < tri.size(); ++i) sup = std::max(sup, std::abs(cv.tip_m[i] - tri[i]));
    EXPECT_LT(sup, bound + 1e-7 * eps0 * l);  // bound = 3.08e-2 eps0 l; measured 1.50e-2
    // Integral error E1 over 2 T1 (spec 5.1 metric), N = 200: 1.25e-3 (CVODE, 400 samples),
    // 1.16e-3 (exact FE modes, 800 samples); the 2e-3 cap is the 4/3-order trend below applied
    // to N = 100 (2.86e-3 / 2^(4/3) = 1.13e-3) with sampling margin. The order in dx is 4/3
    // (L1 of the Airy-smeared kinks: width^2 ~ dx^(4/3)); observed 1.26-1.30 (pre-asymptotic).
    const std::vector<int> nodes{50, 100, 200};
    std::vector<double> e1;
    for (int n_nodes : nodes) {
        const FeBarResult md = fe_bar_modal_tip_history(n_nodes, E, rho, l, eps0, t_end, 800);
        e1.push_back(integral_relative_error(md.tip_m, triangle(md.t_s, 0.0)));
    }
    EXPECT_LT(integral_relative_error(cv.tip_m, tri), 2e-3);
    for (int i = 0; i + 1 < 3; ++i) {
        const double dx_ratio = (nodes[i + 1] - 1.0) / (nodes[i] - 1.0);  // dx_i / dx_{i+1}
        const double order = std::log(e1[i] / e1[i + 1]) / std::log(dx_ratio);
        EXPECT_NEAR(order, 4.0 / 3.0, 0.15) << "E1 = " << e1[i] << " -> " << e1[i + 1];
    }
}

TEST(ReferenceBar, DominantFrequencyRecoversF1OnTriangleWave)
{
    // >= 8 periods, >= 50 samples per period, arbitrary phase and a non-integer number of periods.
    for (double periods : {8.0, 8.37, 16.0}) {
        const int n = static_cast<int>(std::round(periods * 50));
        const std::vector<double> t = uniform_times(periods * T1, n);
        const std::vector<double> u = triangle(t, 0.1234 * T1);
        EXPECT_NEAR(dominant_frequency(t, u, f1), f1, 1e-4 * f1) << periods << " periods";
        // Zero crossings of a piecewise-linear signal are interpolated exactly.
        EXPECT_NEAR(zero_crossing_frequency(t, u, f1), f1, 1e-12 * f1);
    }
    // Robustness: 5 % ripple at 37.3 f1 (like the explicit-PD high-frequency noise), guess 10 % off.
    const std::vector<double> t = uniform_times(16 * T1, 16 * 200);
    std::vector<double> u = triangle(t, 0.0);
    for (std::size_t i = 0; i < t.size(); ++i) u[i] += 0.05 * eps0 * l * std::sin(2 * pi * 37.3 * f1 * t[i]);
    EXPECT_NEAR(dominant_frequency(t, u, 1.1 * f1), f1, 1e-4 * f1);
    // Too short a record (one period): NaN, not a guess.
    const std::vector<double> t1 = uniform_times(T1, 50);
    EXPECT_TRUE(std::isnan(dominant_frequency(t1, triangle(t1, 0.0), f1)));
}

TEST(ReferenceBar, DominantFrequencyIsolatesDispersedFundamental)
{
    // Lumped FE bar N = 50: harmonics sit below (2n-1) f1^h, so the crossings wander; the windowed
    // fit returns the fundamental f1^h (measured 1.5e-7 relative), zero crossings only ~1e-4.
    constexpr int N = 50;
    const FeBarResult md = fe_bar_modal_tip_history(N, E, rho, l, eps0, 16 * T1, 1600);
    const double f_h = fe_bar_frequency(N, E, rho, l);
    EXPECT_NEAR(dominant_frequency(md.t_s, md.tip_m, f1), f_h, 2e-6 * f_h);
    EXPECT_NEAR(zero_crossing_frequency(md.t_s, md.tip_m, f1), f_h, 3e-4 * f_h);
}

TEST(ReferenceBar, IntegralRelativeErrorHandValues)
{
    // (|1-1| + |2-1| + |3-1|) / (1 + 1 + 1) = 3/3.
    EXPECT_DOUBLE_EQ(integral_relative_error({1.0, 2.0, 3.0}, {1.0, 1.0, 1.0}), 1.0);
    // (|0.5-1| + |-1.5+2|) / (1 + 2) = 1/3.
    EXPECT_DOUBLE_EQ(integral_relative_error({0.5, -1.5}, {1.0, -2.0}), 1.0 / 3.0);
    EXPECT_THROW(integral_relative_error({1.0}, {1.0, 2.0}), std::invalid_argument);
    EXPECT_THROW(integral_relative_error({1.0}, {0.0}), std::invalid_argument);
}
