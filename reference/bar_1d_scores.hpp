// reference/bar_1d_scores.hpp -- scores a sampled tip record of the fixed-free bar released from
// uniform strain against the classical references of bar_1d.hpp, and the von Neumann step limit of a
// 1D bond-based lattice. Header-only; never calls the peridynamics library (reference independence).
//
// BarScorer::score(t, u, x_tip, N): the record u(t) of the point x_tip (t uniform from 0) against
//   - the exact modal series u(x_tip, t) (n_modes terms, tail < 0.2 eps0 l / n_modes),
//   - the lumped linear FE bar with the same spacing dx = l/N (N + 1 nodes, tip at x = l): SUNDIALS
//     CVODE for N <= cvode_max_N, above it the exact discrete-mode solution of the same FE system
//     (CVODE's cost grows as N^2). FE records are cached per (N, number of samples).
// Scores: f1 of the record and of the FE record by dominant_frequency; the integral relative error
//   E1 = int|u - u_ref| dt / int|u_ref| dt (spec/000b sec. 5.1 reconstruction) over the first period
//   T1 = 1/f1_exact and over the whole record, and against the FE record.
//
// lattice_von_neumann_ratio: velocity Verlet / central differences on the interior of a uniform 1D
// lattice with pair springs of stiffness kappa_q to the neighbours at +-q (q = 1..m) is stable for
//   dt <= 2 / omega_max,  rho omega(Omega)^2 = 2 sum_q kappa_q (1 - cos q Omega)   (spec/000a 3.3.2),
// while Silling-Askari (3.14) gives dt_SA = sqrt(2 rho / (2 sum_q kappa_q)). The ratio
//   (2/omega_max) / dt_SA = sqrt(2 sum kappa_q / max_Omega sum kappa_q (1 - cos q Omega)) >= 1
// depends only on the shape of kappa_q (PMB: kappa_q ~ omega(q dx) / q).
#pragma once

#include "reference/bar_1d.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace pd::ref {

struct BarScores {
    double f1 = std::numeric_limits<double>::quiet_NaN();     // first frequency of the record [Hz]
    double f1_fe = std::numeric_limits<double>::quiet_NaN();  // first frequency of the FE record [Hz]
    double E1_T1 = std::numeric_limits<double>::quiet_NaN();  // E1 over the first T1 [-]
    double E1 = std::numeric_limits<double>::quiet_NaN();     // E1 over the whole record [-]
    double E1_fe = std::numeric_limits<double>::quiet_NaN();  // E1 against the FE record [-]
    std::vector<double> exact, fe;                            // reference records [m]
};

class BarScorer {
public:
    BarScorer(double E, double rho, double l, double eps0, int cvode_max_N, int n_modes)
        : E_(E), rho_(rho), l_(l), eps0_(eps0), cvode_max_N_(cvode_max_N), n_modes_(n_modes)
    {
    }

    BarScores score(const std::vector<double>& t, const std::vector<double>& u, double x_tip, int N, bool with_fe)
    {
        BarScores s;
        const double f1 = bar_frequency(1, E_, rho_, l_);  // [Hz]
        for (double ti : t) s.exact.push_back(bar_modal_displacement(x_tip, ti, E_, rho_, l_, eps0_, n_modes_));
        s.f1 = dominant_frequency(t, u, f1);
        const auto n1 = std::upper_bound(t.begin(), t.end(), (1 + 1e-9) / f1) - t.begin();  // samples with t <= T1
        auto head = [n1](const std::vector<double>& v) { return std::vector<double>(v.begin(), v.begin() + n1); };
        s.E1_T1 = integral_relative_error(head(u), head(s.exact));
        s.E1 = integral_relative_error(u, s.exact);
        if (!with_fe) return s;
        const int n_out = static_cast<int>(t.size()) - 1;
        std::vector<double>& fe = cache_[{N, n_out}];
        if (fe.empty())
            fe = (N <= cvode_max_N_ ? fe_bar_tip_history : fe_bar_modal_tip_history)(N + 1, E_, rho_, l_, eps0_,
                                                                                       t.back(), n_out).tip_m;
        s.fe = fe;
        s.f1_fe = dominant_frequency(t, s.fe, f1);
        s.E1_fe = integral_relative_error(u, s.fe);
        return s;
    }

private:
    double E_, rho_, l_, eps0_;  // [Pa], [kg/m^3], [m], [-]
    int cvode_max_N_, n_modes_;
    std::map<std::pair<int, int>, std::vector<double>> cache_;  // FE tip records by (N, n_out)
};

// kappa(q), q = 1..m: spring stiffness to the neighbours at distance q dx (any unit; only its shape
// matters). Omega is scanned on [0, pi] in steps of pi/20000 (the maximum to ~1e-8 relative).
inline double lattice_von_neumann_ratio(const std::function<double(int)>& kappa, int m)
{
    constexpr int n_scan = 20000;
    double sum = 0, peak = 0;
    for (int q = 1; q <= m; ++q) sum += kappa(q);
    for (int a = 0; a <= n_scan; ++a) {
        double s = 0;
        for (int q = 1; q <= m; ++q) s += kappa(q) * (1 - std::cos(q * std::numbers::pi * a / n_scan));
        peak = std::max(peak, s);
    }
    return std::sqrt(2 * sum / peak);
}

}  // namespace pd::ref
