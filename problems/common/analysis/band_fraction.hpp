// problems/common/analysis/band_fraction.hpp -- the share of a sampled signal's amplitude that lies in
// a frequency band (the high-frequency content of a record, e.g. the spurious modes an integrator
// leaves in bar_modes_1d's tip record: problems/common/fixed_free_bar.hpp).
// The record u(t_j), j = 0..n-1 (uniform samples dt_s apart), is transformed by a plain DFT,
//   U_k = sum_j u_j exp(-2 pi i k j / n)   at f_k = k / (n dt_s), k = 1..n/2,
// and the measure is the amplitude fraction in the band (f_lo, f_hi],
//   fraction = sqrt(sum_band |U_k|^2 / sum_(k >= 1) |U_k|^2)   (the mean, k = 0, excluded),
// 0 for a constant record. Source: the discrete Fourier transform (by Parseval sum |U_k|^2 is the
// record's energy); O(n^2), meant for records of a few thousand samples.
#pragma once

#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

namespace pd {

// Amplitude fraction of the uniform record u (sample interval dt_s [s]) in the band (f_lo, f_hi] [Hz].
inline double band_amplitude_fraction(const std::vector<double>& u, double dt_s, double f_lo, double f_hi)
{
    const std::size_t n = u.size();
    double band = 0, total = 0;
    for (std::size_t k = 1; k <= n / 2; ++k) {
        double re = 0, im = 0;
        const double w = 2 * std::numbers::pi * static_cast<double>(k) / static_cast<double>(n);  // 2 pi k / n
        for (std::size_t j = 0; j < n; ++j) {  // U_k = sum_j u_j exp(-i w j)
            re += u[j] * std::cos(w * static_cast<double>(j));
            im -= u[j] * std::sin(w * static_cast<double>(j));
        }
        const double p = re * re + im * im, f = static_cast<double>(k) / (static_cast<double>(n) * dt_s);  // |U_k|^2, f_k [Hz]
        total += p;
        if (f > f_lo && f <= f_hi) band += p;
    }
    return total > 0 ? std::sqrt(band / total) : 0.0;
}

}  // namespace pd
