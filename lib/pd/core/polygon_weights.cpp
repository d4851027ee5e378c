// Seed 001 polygon body, boundary nodes and volume weights (see polygon_weights.hpp).
#include "pd/core/polygon_weights.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace pd {

namespace {

double cross(const Vec<2>& o, const Vec<2>& a, const Vec<2>& b)  // 2 x signed area of o-a-b
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Sutherland-Hodgman: keeps the part of `poly` left of the directed line e0 -> e1.
Ring clip_left(const Ring& poly, const Vec<2>& e0, const Vec<2>& e1)
{
    Ring out;
    const std::size_t n = poly.size();
    for (std::size_t k = 0; k < n; ++k) {
        const Vec<2>& p = poly[k];
        const Vec<2>& q = poly[(k + 1) % n];
        const double dp = cross(e0, e1, p), dq = cross(e0, e1, q);
        if (dp >= 0) out.push_back(p);
        if ((dp >= 0) != (dq >= 0)) out.push_back(p + (dp / (dp - dq)) * (q - p));  // edge meets the line
    }
    return out;
}

}  // namespace

double signed_area(const Ring& ring)
{
    double a = 0;
    for (std::size_t k = 0, n = ring.size(); k < n; ++k) {
        const Vec<2>& p = ring[k];
        const Vec<2>& q = ring[(k + 1) % n];
        a += p[0] * q[1] - q[0] * p[1];  // shoelace
    }
    return a / 2;
}

double polygon_area(const Polygon& p)
{
    double a = std::abs(signed_area(p.outer));
    for (const Ring& h : p.holes) a -= std::abs(signed_area(h));
    return a;
}

double convex_triangle_overlap(const Ring& convex, const Vec<2>& a, const Vec<2>& b, const Vec<2>& c)
{
    Ring poly = cross(a, b, c) >= 0 ? Ring{a, b, c} : Ring{a, c, b};
    const bool ccw = signed_area(convex) >= 0;
    const std::size_t n = convex.size();
    for (std::size_t k = 0; k < n && poly.size() >= 3; ++k) {
        const Vec<2>& e0 = convex[k];
        const Vec<2>& e1 = convex[(k + 1) % n];
        poly = ccw ? clip_left(poly, e0, e1) : clip_left(poly, e1, e0);
    }
    return poly.size() >= 3 ? std::abs(signed_area(poly)) : 0.0;
}

double star_shape_overlap(const Vec<2>& centre, const Ring& star, const Polygon& shape)
{
    // Each ring counts with the sign that makes the outer ring positive and the holes negative.
    std::vector<std::pair<const Ring*, double>> rings{{&shape.outer, signed_area(shape.outer) >= 0 ? 1.0 : -1.0}};
    for (const Ring& h : shape.holes) rings.push_back({&h, signed_area(h) >= 0 ? -1.0 : 1.0});
    double area = 0;
    for (std::size_t k = 0, n = star.size(); k < n; ++k) {
        const Ring fan{centre, star[k], star[(k + 1) % n]};  // fan triangle T_k of the zone
        for (const auto& [ring, sign] : rings)
            for (std::size_t e = 0, m = ring->size(); e < m; ++e) {
                const Vec<2>& a = (*ring)[e];
                const Vec<2>& b = (*ring)[(e + 1) % m];
                const double o = cross(centre, a, b);
                if (o == 0) continue;  // degenerate triangle: no area
                // Green's theorem / winding number: area(T_k cap ring) = sum sign(o) area(T_k cap (centre, a, b)).
                area += sign * (o > 0 ? 1.0 : -1.0) * convex_triangle_overlap(fan, centre, a, b);
            }
    }
    return std::max(area, 0.0);  // the exact sum is >= 0; round-off only
}

WeightRule parse_weight_rule(const std::string& name)
{
    if (name == "none") return WeightRule::none;
    if (name == "seed001") return WeightRule::seed001;
    if (name == "shared-quarters") return WeightRule::shared_quarters;
    throw std::invalid_argument("unknown weight rule '" + name + "' (none, seed001, shared-quarters)");
}

namespace {
double square_overlap(const Vec<2>& centre, double half, const Polygon& shape)  // area(square cap shape) [m^2]
{
    const Ring sq{centre + Vec<2>{{half, -half}}, centre + Vec<2>{{half, half}}, centre + Vec<2>{{-half, half}}, centre + Vec<2>{{-half, -half}}};
    return star_shape_overlap(centre, sq, shape);
}
}  // namespace

PolygonBody polygon_body(const Polygon& shape, double dx, double thickness, WeightRule rule)
{
    if (!(dx > 0)) throw std::invalid_argument("polygon_body: dx must be positive");
    if (shape.outer.size() < 3) throw std::invalid_argument("polygon_body: the outer ring needs 3 vertices");
    Vec<2> lo = shape.outer[0], hi = shape.outer[0];
    for (const Vec<2>& p : shape.outer)
        for (int d = 0; d < 2; ++d) { lo[d] = std::min(lo[d], p[d]); hi[d] = std::max(hi[d], p[d]); }
    PolygonBody out;
    out.body = fill<2>(lo, hi, dx, in_polygon(shape), thickness);
    const std::size_t N = out.body.size();
    if (N == 0) throw std::invalid_argument("polygon_body: no lattice node inside the shape");

    // Grid index of each node (cell centres lo + (i + 1/2) dx) and a dense lookup with a margin of
    // one cell, so that neighbours off the grid read as "no object node".
    const long nx = std::lround((hi[0] - lo[0]) / dx) + 2, ny = std::lround((hi[1] - lo[1]) / dx) + 2;
    std::vector<int> grid(static_cast<std::size_t>(nx * ny), -1);
    std::vector<std::array<long, 2>> ij(N);
    for (std::size_t i = 0; i < N; ++i) {
        const Vec<2> p = out.body.x[i];
        ij[i] = {std::lround((p[0] - lo[0]) / dx - 0.5) + 1, std::lround((p[1] - lo[1]) / dx - 0.5) + 1};
        grid[ij[i][0] + nx * ij[i][1]] = static_cast<int>(i);
    }
    auto occupied = [&](long a, long b) { return a >= 0 && a < nx && b >= 0 && b < ny && grid[a + nx * b] >= 0; };

    // Step 4: boundary node when one of the four edge neighbours is not an object node.
    out.edge.assign(N, 0);
    for (std::size_t i = 0; i < N; ++i) {
        const auto [a, b] = ij[i];
        out.edge[i] = !(occupied(a + 1, b) && occupied(a - 1, b) && occupied(a, b + 1) && occupied(a, b - 1));
    }

    // Step 5: weights. The 8 perimeter directions in counter-clockwise order from +x.
    constexpr std::array<std::array<int, 2>, 8> dirs{{{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};
    out.weight.assign(N, 1.0);
    if (rule == WeightRule::seed001)
        for (std::size_t i = 0; i < N; ++i) {
            if (!out.edge[i]) continue;
            const Vec<2> c = out.body.x[i];
            Ring zone;
            for (const auto& d : dirs) {
                const double f = occupied(ij[i][0] + d[0], ij[i][1] + d[1]) ? 0.5 : 1.0;  // halved toward object nodes
                zone.push_back(c + (f * dx) * Vec<2>{{double(d[0]), double(d[1])}});
            }
            out.weight[i] = star_shape_overlap(c, zone, shape) / (dx * dx);
        }
    if (rule == WeightRule::shared_quarters)
        for (std::size_t i = 0; i < N; ++i) {
            const auto [a, b] = ij[i];
            bool all8 = true;
            for (const auto& d : dirs) all8 = all8 && occupied(a + d[0], b + d[1]);
            if (all8) continue;
            const Vec<2> c = out.body.x[i];
            double area = square_overlap(c, dx / 2, shape);  // own cell cap shape
            for (const auto& d : dirs) {
                if (occupied(a + d[0], b + d[1])) continue;
                const long pa = a + d[0], pb = b + d[1];  // empty cell p
                for (int sx : {-1, 1})
                    for (int sy : {-1, 1}) {
                        // Quarter of p toward (sx, sy); claimants: object nodes among p + (sx, 0), (0, sy), (sx, sy).
                        const long cand[3][2] = {{pa + sx, pb}, {pa, pb + sy}, {pa + sx, pb + sy}};
                        int claimants = 0;
                        bool mine = false;
                        for (const auto& q : cand)
                            if (occupied(q[0], q[1])) {
                                ++claimants;
                                mine = mine || (q[0] == a && q[1] == b);
                            }
                        if (!mine) continue;
                        const Vec<2> qc = c + Vec<2>{{(d[0] + 0.25 * sx) * dx, (d[1] + 0.25 * sy) * dx}};
                        area += square_overlap(qc, dx / 4, shape) / claimants;
                    }
            }
            out.weight[i] = area / (dx * dx);
        }
    for (std::size_t i = 0; i < N; ++i) out.body.volume[i] *= out.weight[i];
    return out;
}

}  // namespace pd
