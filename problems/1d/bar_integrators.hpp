// problems/1d/bar_integrators.hpp -- pieces of bar_modes_1d's comparison of velocity Verlet with
// Newmark (beta = 1/4, gamma = 1/2): the high-frequency measure of a tip record and the table.
// High-frequency content: the tip record u(t_j), j = 0..n-1 (uniform samples), is transformed by a
// plain DFT, U_k = sum_j u_j exp(-2 pi i k j / n), at f_k = k / (n dt_s); the measure is the
// amplitude fraction in the band (f_lo, f_hi],
//   hf = sqrt(sum_band |U_k|^2 / sum_(k >= 1) |U_k|^2)   (k up to n/2; the mean, k = 0, excluded).
// The fixed-free bar has modes at (2k - 1) f1; bar_modes_1d uses the band (6 f1, 12 f1], above the
// third mode (5 f1) and below the Nyquist frequency of every record it compares (>= 24 samples per
// T1). The exact modal series has content there too (the released uniform strain excites every
// mode with amplitude ~ 1/(2k - 1)^2), so the table prints the exact record's value beside ours.
#pragma once
#include "pd/io/csv.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace bar_modes {

inline double high_band_fraction(const std::vector<double>& u, double dt_s, double f_lo, double f_hi)
{
    const std::size_t n = u.size();
    double band = 0, total = 0;
    for (std::size_t k = 1; k <= n / 2; ++k) {
        double re = 0, im = 0;
        const double w = 2 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);
        for (std::size_t j = 0; j < n; ++j) {
            re += u[j] * std::cos(w * static_cast<double>(j));
            im -= u[j] * std::sin(w * static_cast<double>(j));
        }
        const double p = re * re + im * im, f = static_cast<double>(k) / (static_cast<double>(n) * dt_s);
        total += p;
        if (f > f_lo && f <= f_hi) band += p;
    }
    return total > 0 ? std::sqrt(band / total) : 0.0;
}

struct IntegratorRow {
    std::string integrator;
    double dt_over_sa = 0, dt_s = 0;             // [-], [s]
    long steps = 0;
    double f1_rel_error = 0, E1_T1 = 0, E1 = 0;  // [-]
    double hf = 0, hf_exact = 0;                 // high-band fraction of the record and of the exact series [-]
    double wall_s = 0;                           // [s]
};

// One row per (newmark?, dt / dt_SA) case: run(newmark, factor) gives a record with t_s, tip_m, dt,
// dt_crit, steps, wall_s; score(record) its scores f1, E1_T1, E1 and the exact record.
template <class RunFn, class ScoreFn>
std::vector<IntegratorRow> compare_integrators(const std::vector<std::pair<bool, double>>& cases, double f1, RunFn&& run,
                                               ScoreFn&& score)
{
    std::vector<IntegratorRow> rows;
    for (const auto& [newmark, factor] : cases) {
        const auto r = run(newmark, factor);
        const auto s = score(r);
        const double ts = r.t_s[1] - r.t_s[0];  // sample interval [s]
        rows.push_back({newmark ? "newmark" : "verlet", r.dt / r.dt_crit, r.dt, r.steps, s.f1 / f1 - 1, s.E1_T1, s.E1,
                        high_band_fraction(r.tip_m, ts, 6 * f1, 12 * f1), high_band_fraction(s.exact, ts, 6 * f1, 12 * f1),
                        r.wall_s});
    }
    return rows;
}

inline void write_integrators(const std::filesystem::path& path, const std::vector<IntegratorRow>& rows)
{
    pd::io::CsvWriter csv(path, {"integrator", "dt_over_dt_SA", "dt_s", "steps", "f1_rel_error", "E1_T1", "E1", "hf_fraction",
                                 "hf_fraction_exact", "wall_s"});
    for (const auto& r : rows)
        csv.row({r.integrator, r.dt_over_sa, r.dt_s, r.steps, r.f1_rel_error, r.E1_T1, r.E1, r.hf, r.hf_exact, r.wall_s});
}

inline void print_integrators(const std::vector<IntegratorRow>& rows, int N)
{
    std::printf("\nintegrators at N = %d (LPS, same record length): hf = amplitude fraction in (6 f1, 12 f1]\n", N);
    std::printf("%-10s %10s %11s %8s %12s %10s %10s %9s %9s %8s\n", "integrator", "dt/dt_SA", "dt_s", "steps", "f1_rel_err",
                "E1_T1", "E1", "hf", "hf_exact", "wall_s");
    for (const auto& r : rows)
        std::printf("%-10s %10.3f %11.4e %8ld %12.4e %10.4e %10.4e %9.4f %9.4f %8.3f\n", r.integrator.c_str(), r.dt_over_sa,
                    r.dt_s, r.steps, r.f1_rel_error, r.E1_T1, r.E1, r.hf, r.hf_exact, r.wall_s);
}

}  // namespace bar_modes
