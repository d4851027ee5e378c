// reference/wave_speed.cpp -- plane longitudinal wave dispersion of linearised 3D PMB and LPS
// (continuum ball and lattice family sums) and pulse-averaged group velocity; formulas and
// sources in wave_speed.hpp. Never calls the peridynamics library (reference independence).
#include "reference/wave_speed.hpp"

#include <gsl/gsl_integration.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pd::ref {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double horizon_tolerance = 1e-10;  // lattice neighbours at exactly delta count (round-off)
constexpr int n_gauss_k = 256;               // Gauss-Legendre points of the spectral average

void require(bool ok, const char* what)
{
    if (!ok) throw std::invalid_argument(std::string("pd::ref wave_speed: ") + what);
}

void require_material(const WaveMaterial& mat)
{
    require(mat.K > 0 && mat.rho > 0 && mat.delta > 0, "K, rho and delta must be > 0");
    require(mat.model == WaveMaterial::Model::pmb || mat.G > 0, "LPS needs G > 0");
}

// n-point Gauss-Legendre rule on [a, b]: calls f(x, weight) at each point.
template <class F>
void gauss_legendre(int n, double a, double b, F&& f)
{
    gsl_integration_glfixed_table* t = gsl_integration_glfixed_table_alloc(n);
    for (int i = 0; i < n; ++i) {
        double x = 0, w = 0;
        gsl_integration_glfixed_point(a, b, i, &x, &w, t);
        f(x, w);
    }
    gsl_integration_glfixed_table_free(t);
}

// M1 = 4 pi int_0^delta omega(r) r^3 dr [m^4] (continuum, as the PMB micromodulus is calibrated).
double continuum_m1(const WaveMaterial& mat)
{
    double m1 = 0;
    gauss_legendre(96, 0.0, mat.delta, [&](double r, double w) { m1 += 4 * pi * mat.omega(r) * r * r * r * w; });
    return m1;
}

}  // namespace

double p_wave_speed(const WaveMaterial& mat)
{
    require_material(mat);
    const double G = mat.model == WaveMaterial::Model::pmb ? 0.6 * mat.K : mat.G;  // PMB: nu = 1/4, G = 3K/5
    return std::sqrt((mat.K + 4.0 * G / 3.0) / mat.rho);
}

LongitudinalDispersion LongitudinalDispersion::continuum(const WaveMaterial& mat, int n_gauss)
{
    require_material(mat);
    require(n_gauss >= 8, "n_gauss must be >= 8");
    LongitudinalDispersion d;
    d.mat_ = mat;
    d.k_max_ = std::numeric_limits<double>::infinity();
    // dV = 2 pi r^2 dr dmu with mu = xi_x / r (axisymmetric about x).
    gauss_legendre(n_gauss, 0.0, mat.delta, [&](double r, double wr) {
        gauss_legendre(n_gauss, -1.0, 1.0, [&](double mu, double wmu) {
            d.xi_x_.push_back(r * mu);
            d.r_.push_back(r);
            d.w_dV_.push_back(mat.omega(r) * 2 * pi * r * r * wr * wmu);
        });
    });
    d.c_ = 18.0 * mat.K / continuum_m1(mat);
    for (std::size_t p = 0; p < d.r_.size(); ++p) d.m_ += d.w_dV_[p] * d.r_[p] * d.r_[p];
    return d;
}

LongitudinalDispersion LongitudinalDispersion::lattice(const WaveMaterial& mat, double dx, bool pa_pdlammps)
{
    require_material(mat);
    require(dx > 0, "dx must be > 0");
    LongitudinalDispersion d;
    d.mat_ = mat;
    d.k_max_ = pi / dx;
    const double reach = mat.delta * (1 + horizon_tolerance);
    const long n = static_cast<long>(std::floor(reach / dx));
    for (long a = -n; a <= n; ++a)
        for (long b = -n; b <= n; ++b)
            for (long c = -n; c <= n; ++c) {
                const double r = dx * std::sqrt(double(a * a + b * b + c * c));
                if (r == 0 || r > reach) continue;
                double beta = 1;  // PA-PDLAMMPS partial volume (spec/002 sec. 3.2)
                if (pa_pdlammps && r > mat.delta - dx / 2) beta = std::min(1.0, (mat.delta + dx / 2 - r) / dx);
                d.xi_x_.push_back(a * dx);
                d.r_.push_back(r);
                d.w_dV_.push_back(mat.omega(r) * beta * dx * dx * dx);
            }
    d.c_ = 18.0 * mat.K / continuum_m1(mat);
    for (std::size_t p = 0; p < d.r_.size(); ++p) d.m_ += d.w_dV_[p] * d.r_[p] * d.r_[p];
    return d;
}

LongitudinalDispersion::Sums LongitudinalDispersion::sums(double k) const
{
    Sums s;
    if (mat_.model == WaveMaterial::Model::pmb) {
        // rho w^2 = c sum omega xi_x^2/r^3 (1 - cos k xi_x) dV; d/dk: c sum omega xi_x^3/r^3 sin(k xi_x) dV.
        for (std::size_t p = 0; p < r_.size(); ++p) {
            const double x = xi_x_[p], r3 = r_[p] * r_[p] * r_[p];
            s.a += w_dV_[p] * x * x / r3 * (1 - std::cos(k * x));
            s.da += w_dV_[p] * x * x * x / r3 * std::sin(k * x);
        }
        s.a *= c_;
        s.da *= c_;
        return s;
    }
    // LPS: rho w^2 = (9K - 15G) S1^2/m^2 + 30 G S2/m.
    double S1 = 0, dS1 = 0, S2 = 0, dS2 = 0;
    for (std::size_t p = 0; p < r_.size(); ++p) {
        const double x = xi_x_[p], r2 = r_[p] * r_[p];
        S1 += w_dV_[p] * x * std::sin(k * x);
        dS1 += w_dV_[p] * x * x * std::cos(k * x);
        S2 += w_dV_[p] * x * x / r2 * (1 - std::cos(k * x));
        dS2 += w_dV_[p] * x * x * x / r2 * std::sin(k * x);
    }
    const double A = 9 * mat_.K - 15 * mat_.G, B = 30 * mat_.G;
    s.a = A * S1 * S1 / (m_ * m_) + B * S2 / m_;
    s.da = 2 * A * S1 * dS1 / (m_ * m_) + B * dS2 / m_;
    return s;
}

double LongitudinalDispersion::omega2(double k) const { return sums(k).a / mat_.rho; }

double LongitudinalDispersion::omega(double k) const { return std::sqrt(omega2(k)); }

double LongitudinalDispersion::phase_velocity(double k) const { return omega(k) / k; }

double LongitudinalDispersion::group_velocity(double k, double dt) const
{
    const Sums s = sums(k);
    const double w = std::sqrt(s.a / mat_.rho);
    const double cg = s.da / (2 * mat_.rho * w);  // dw/dk = d(w^2)/dk / (2w)
    if (dt <= 0) return cg;
    const double h = 0.5 * w * dt;  // Verlet: sin(W dt/2) = w dt/2, dW/dk = dw/dk / sqrt(1 - h^2)
    return h < 1 ? cg / std::sqrt(1 - h * h) : std::numeric_limits<double>::quiet_NaN();
}

namespace {
// int_0^kmax exp(-k^2 wp^2/2) f(k) dk / int_0^kmax exp(-k^2 wp^2/2) dk.
template <class F>
double spectral_mean(const LongitudinalDispersion& disp, double wp, F&& f)
{
    require(wp > 0, "pulse width must be > 0");
    const double kmax = std::min(disp.k_max(), 12.0 / wp);  // weight e^-72 beyond 12/wp
    double num = 0, den = 0;
    gauss_legendre(n_gauss_k, 0.0, kmax, [&](double k, double w) {
        const double e = std::exp(-0.5 * k * k * wp * wp);
        num += w * e * f(k);
        den += w * e;
    });
    return num / den;
}
}  // namespace

double mean_group_velocity(const LongitudinalDispersion& disp, double pulse_width, double dt)
{
    return spectral_mean(disp, pulse_width, [&](double k) { return disp.group_velocity(k, dt); });
}

double mean_omega2(const LongitudinalDispersion& disp, double pulse_width)
{
    return spectral_mean(disp, pulse_width, [&](double k) { return disp.omega2(k); });
}

double least_squares_slope(const std::vector<double>& t, const std::vector<double>& y, double t0)
{
    require(t.size() == y.size(), "t and y must have the same length");
    double n = 0, st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k] >= t0) n += 1, st += t[k], sy += y[k], stt += t[k] * t[k], sty += t[k] * y[k];
    if (n < 2) return std::numeric_limits<double>::quiet_NaN();
    return (n * sty - st * sy) / (n * stt - st * st);
}

double max_relative_deviation(const std::vector<double>& s)
{
    double m = 0;
    for (double x : s) m = std::max(m, std::abs(x / s.front() - 1));
    return m;
}

}  // namespace pd::ref
