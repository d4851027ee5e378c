// Uniaxial-stress curves of the continuum laws; formulas in uniaxial_stretch.hpp.
#include "reference/uniaxial_stretch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pd::ref {

namespace {

constexpr int intervals = 2000;  // Simpson intervals in the polar angle (even)

// int_0^pi f(theta) sin(theta) dtheta by Simpson's rule.
template <class F>
double sphere_integral(F&& f)
{
    const double h = std::numbers::pi / intervals;
    double s = 0;
    for (int k = 0; k <= intervals; ++k) {
        const double th = k * h;
        const double wk = (k == 0 || k == intervals) ? 1 : (k % 2 ? 4 : 2);
        s += wk * f(std::cos(th), std::sin(th)) * std::sin(th);
    }
    return s * h / 3;
}

// (P_xx, P_yy) of the PD continuum for F = diag(l, m, m). The azimuthal integrals are
// int n_x^2 dphi = 2 pi cos^2, int n_y^2 dphi = pi sin^2.
struct Pair { double xx, yy; };
Pair pd_stress(UniaxialLaw law, double K, double G, double l, double m)
{
    auto stretch = [&](double c, double s) { return std::sqrt(l * l * c * c + m * m * s * s); };  // |F n|
    const double pi = std::numbers::pi;
    if (law == UniaxialLaw::pmb_continuum) {
        const double c0 = 9 * K / (4 * pi);
        return {c0 * 2 * pi * l * sphere_integral([&](double c, double s) { return (1 - 1 / stretch(c, s)) * c * c; }),
                c0 * pi * m * sphere_integral([&](double c, double s) { return (1 - 1 / stretch(c, s)) * s * s; })};
    }
    const double theta = 3 / (4 * pi) * 2 * pi * sphere_integral([&](double c, double s) { return stretch(c, s) - 1; });
    auto t = [&](double c, double s) { const double Fn = stretch(c, s); return (3 * K * theta + 15 * G * (Fn - 1 - theta / 3)) / Fn; };
    return {2 * pi * l * sphere_integral([&](double c, double s) { return t(c, s) * c * c; }) / (4 * pi),
            pi * m * sphere_integral([&](double c, double s) { return t(c, s) * s * s; }) / (4 * pi)};
}

}  // namespace

UniaxialPoint uniaxial_stress(UniaxialLaw law, double K, double G, double lambda)
{
    if (!(lambda > 0) || !(K > 0) || !(G > 0)) throw std::invalid_argument("uniaxial_stress: lambda, K, G must be positive");
    const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));
    UniaxialPoint r;
    if (law == UniaxialLaw::hypoelastic) {
        r.sigma = E * std::log(lambda);
        r.mu = std::pow(lambda, -nu);
        r.P = r.sigma * r.mu * r.mu;
        return r;
    }
    if (law == UniaxialLaw::saint_venant_kirchhoff) {
        const double mu2 = 1 - nu * (lambda * lambda - 1);
        if (!(mu2 > 0)) throw std::domain_error("uniaxial_stress: SVK section collapsed (lambda^2 >= 1 + 1/nu)");
        r.mu = std::sqrt(mu2);
        r.P = E * lambda * (lambda * lambda - 1) / 2;
        r.sigma = r.P * lambda / (lambda * mu2);  // sigma = P F^T / J
        return r;
    }
    // PD continuum: P_yy(mu) is increasing in mu; bracket [1e-3, 2] and bisect to 1e-14.
    double lo = 1e-3, hi = 2;
    if (pd_stress(law, K, G, lambda, lo).yy > 0 || pd_stress(law, K, G, lambda, hi).yy < 0)
        throw std::domain_error("uniaxial_stress: no free lateral stretch in [1e-3, 2]");
    while (hi - lo > 1e-14) {
        const double mid = 0.5 * (lo + hi);
        (pd_stress(law, K, G, lambda, mid).yy > 0 ? hi : lo) = mid;
    }
    r.mu = 0.5 * (lo + hi);
    r.P = pd_stress(law, K, G, lambda, r.mu).xx;
    r.sigma = r.P / (r.mu * r.mu);
    return r;
}

double max_tangent_ratio(UniaxialLaw law, double K, double G, double lambda_max)
{
    constexpr int pieces = 100;
    const double h = (lambda_max - 1) / pieces;
    if (!(h > 0)) return 1;
    auto slope = [&](double l) { return (uniaxial_stress(law, K, G, l + h).P - uniaxial_stress(law, K, G, l).P) / h; };
    const double s0 = slope(1);
    double worst = 1;
    for (int k = 1; k < pieces; ++k) worst = std::max(worst, slope(1 + k * h) / s0);
    return worst;
}

}  // namespace pd::ref
