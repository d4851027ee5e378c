// Exact partial areas of 2D lattice cells within a horizon (spec/002 sec. 3.2: the partial areas of
// IPA-Hybrid, Seleson 2014, are computed analytically; the thesis does not print the formulas, so
// they are derived here). The area of the disc |p| <= R intersected with the rectangle
// [x0, x1] x [y0, y1] is
//   A = int_{x0}^{x1} max(0, min(y1, s(x)) - max(y0, -s(x))) dx,   s(x) = sqrt(R^2 - x^2) on |x| < R.
// The integrand changes form only where s(x) = |y0| or s(x) = |y1|, so between those abscissae it is
// one of y1 - y0, s - y0, y1 + s, 2 s or 0, each integrated in closed form with
//   int s dx = S(x) = (x s(x) + R^2 asin(x/R)) / 2.
// The fraction of a cell of side h centred at xi (in the lattice's axes) inside the horizon delta of
// the origin is that area over h^2 (bonds.hpp, PartialVolume::exact_area).
#pragma once
#include "pd/core/field.hpp"

#include <algorithm>
#include <cmath>

namespace pd {

inline double disc_rectangle_area(double R, double x0, double x1, double y0, double y1)
{
    const double a = std::max(x0, -R), b = std::min(x1, R);
    if (!(a < b) || !(y0 < y1)) return 0;
    auto s = [R](double x) { return std::sqrt(std::max(0.0, (R - x) * (R + x))); };  // not R^2 - x^2: exact 0 at x = R
    // asin(x/R) as atan2(x, s(x)): asin is ill-conditioned at x/R ~ +-1 (an edge an ulp from R gave a
    // negative area of 4e-8 h^2), atan2 is not.
    auto S = [R, &s](double x) { return 0.5 * (x * s(x) + R * R * std::atan2(x, s(x))); };
    double cut[6] = {a, b};
    int n = 2;
    for (double y : {y0, y1})
        if (std::abs(y) <= R)  // |y| = R: the tangent point x = 0 splits the range too
            for (double sign : {-1.0, 1.0}) {
                const double x = sign * std::sqrt((R - std::abs(y)) * (R + std::abs(y)));
                if (x > a && x < b) cut[n++] = x;
            }
    for (int p = 1; p < n; ++p)  // insertion sort of at most 6 values (std::sort trips GCC 12's -Warray-bounds here)
        for (int q = p; q > 0 && cut[q] < cut[q - 1]; --q) std::swap(cut[q], cut[q - 1]);
    double area = 0;
    for (int k = 0; k + 1 < n; ++k) {
        const double u = cut[k], v = cut[k + 1];
        if (!(u < v)) continue;
        const double m = s(0.5 * (u + v));  // which bounds are active, taken at the midpoint
        const bool top_disc = m < y1, bottom_disc = -m > y0;
        if ((top_disc ? m : y1) <= (bottom_disc ? -m : y0)) continue;  // no chord inside the rectangle
        double piece = 0;
        if (top_disc) piece += S(v) - S(u);
        else piece += y1 * (v - u);
        if (bottom_disc) piece += S(v) - S(u);
        else piece -= y0 * (v - u);
        area += piece;
    }
    return area;
}

// Fraction of the square cell of side h centred at xi (lattice axes) inside the disc of radius delta.
inline double cell_fraction_in_horizon(const Vec<2>& xi, double delta, double h)
{
    const double half = 0.5 * h;
    return disc_rectangle_area(delta, xi[0] - half, xi[0] + half, xi[1] - half, xi[1] + half) / (h * h);
}

}  // namespace pd
