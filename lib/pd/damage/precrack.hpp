// Pre-cracks as cut bonds: a bond filter (BondOptions::keep) that drops every bond whose
// segment x_i - x_j crosses a crack: a segment in 2D, a planar rectangle in 3D. The test is
// evaluated for (min(i, j), max(i, j)), so i-j and j-i get the same answer bit for bit (a bond
// through the crack's end point could otherwise differ by round-off and leave a one-sided bond).
#pragma once
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace pd {

// 2D: crack segment a-b. Proper crossing test with orientations (touching counts as crossing).
// An orientation |d| <= touch_roundoff |b - a| |q - p| counts as 0 (touching): lattice coordinates
// such as (k + 1/2) dx are inexact in binary, so a bond through the crack tip would otherwise be
// cut or kept by round-off (spec/001_004 V3: 5 of the 10 tip-touching bonds of seed 001's plate).
inline constexpr double touch_roundoff = 1e-10;
// The crossing test on the end points p, q of a bond (true: the bond crosses the crack a-b).
inline std::function<bool(const Vec<2>&, const Vec<2>&)> segment_crossing(Vec<2> a, Vec<2> b)
{
    return [a, b](const Vec<2>& p, const Vec<2>& q) {
        auto orient = [](const Vec<2>& o, const Vec<2>& s, const Vec<2>& r) {
            return (s[0] - o[0]) * (r[1] - o[1]) - (s[1] - o[1]) * (r[0] - o[0]);
        };
        const double tol = touch_roundoff * norm(b - a) * norm(q - p);
        auto sign = [tol](double d) { return d > tol ? 1 : (d < -tol ? -1 : 0); };
        const int d1 = sign(orient(a, b, p)), d2 = sign(orient(a, b, q)), d3 = sign(orient(p, q, a)), d4 = sign(orient(p, q, b));
        return d1 * d2 <= 0 && d3 * d4 <= 0;
    };
}
inline std::function<bool(int, int)> cut_by_segment(const Body<2>& body, Vec<2> a, Vec<2> b)
{
    return [&body, crosses = segment_crossing(a, b)](int i, int j) {
        return !crosses(body.x[std::min(i, j)], body.x[std::max(i, j)]);  // same arithmetic for i-j and j-i
    };
}

// 3D: rectangle {corner + s e1 + t e2, s, t in [0, 1]}. A bond that touches it, edges included (within
// touch_roundoff, as in 2D), counts as cut; a bond lying in its plane is kept.
// The crossing test on the end points p, q of a bond (true: the bond crosses the rectangle).
inline std::function<bool(const Vec<3>&, const Vec<3>&)> rectangle_crossing(Vec<3> corner, Vec<3> e1, Vec<3> e2)
{
    const Vec<3> n{{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]}};
    return [corner, e1, e2, n](const Vec<3>& p, const Vec<3>& q) {
        const double tol = touch_roundoff * norm(n) * norm(q - p);  // |d| <= tol counts as on the plane
        double dp = dot(p - corner, n), dq = dot(q - corner, n);
        if (std::abs(dp) <= tol) dp = 0;
        if (std::abs(dq) <= tol) dq = 0;
        if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || dp == dq) return false;  // same side or in the plane
        const Vec<3> hit = p + (dp / (dp - dq)) * (q - p);
        const Vec<3> r = hit - corner;
        const double s = dot(r, e1) / dot(e1, e1), t = dot(r, e2) / dot(e2, e2);
        const double lo = -touch_roundoff, hi = 1 + touch_roundoff;  // edges touched within round-off count
        return s >= lo && s <= hi && t >= lo && t <= hi;
    };
}
inline std::function<bool(int, int)> cut_by_rectangle(const Body<3>& body, Vec<3> corner, Vec<3> e1, Vec<3> e2)
{
    return [&body, crosses = rectangle_crossing(corner, e1, e2)](int i, int j) {
        return !crosses(body.x[std::min(i, j)], body.x[std::max(i, j)]);  // same arithmetic for i-j and j-i
    };
}

}  // namespace pd
