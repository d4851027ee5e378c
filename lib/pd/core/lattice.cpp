// Lattice generation and node sets (see lattice.hpp).
#include "pd/core/lattice.hpp"
#include "pd/core/errors.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace pd {

template <int D>
Body<D> fill(const Vec<D>& lo, const Vec<D>& hi, double dx, const Region<D>& inside, double measure)
{
    if (!(dx > 0)) throw std::invalid_argument("lattice spacing dx must be positive");
    std::array<long, D> n{};
    long total = 1;
    std::array<double, D> nd{};
    double cells = 1;  // in floating point: the long product may overflow
    for (int d = 0; d < D; ++d) {
        nd[d] = std::round((hi[d] - lo[d]) / dx);
        if (!(nd[d] >= 1)) throw std::invalid_argument("lattice box is thinner than one cell");
        cells *= nd[d];
    }
    // Per node the body holds D + 1 doubles; the bonds, fields and models built on it take ~1 KiB.
    char what[64];
    std::snprintf(what, sizeof what, "a lattice of %.3g cells (box / dx)", cells);
    require_memory(cells * 1024.0, what);
    for (int d = 0; d < D; ++d) {
        n[d] = static_cast<long>(nd[d]);
        total *= n[d];
    }
    Body<D> body;
    body.dx = dx;
    body.measure = measure;
    const double cell_volume = std::pow(dx, D) * measure;
    std::array<long, D> idx{};
    for (long c = 0; c < total; ++c) {
        long rest = c;
        for (int d = 0; d < D; ++d) { idx[d] = rest % n[d]; rest /= n[d]; }  // x fastest
        Vec<D> p;
        for (int d = 0; d < D; ++d) p[d] = lo[d] + (idx[d] + 0.5) * dx;
        if (!inside || inside(p)) body.push(p, cell_volume);
    }
    return body;
}

Region<3> in_cylinder(const Vec<3>& centre, int axis, double radius, double a0, double a1)
{
    return [=](const Vec<3>& p) {
        double r2 = 0;
        for (int d = 0; d < 3; ++d)
            if (d != axis) r2 += (p[d] - centre[d]) * (p[d] - centre[d]);
        return r2 <= radius * radius && p[axis] >= a0 && p[axis] <= a1;
    };
}

namespace {
// Even-odd crossing test of a ray towards +x.
bool ring_contains(const std::vector<Vec<2>>& ring, const Vec<2>& p)
{
    bool in = false;
    const std::size_t n = ring.size();
    for (std::size_t a = 0, b = n - 1; a < n; b = a++) {
        const Vec<2>& u = ring[a];
        const Vec<2>& v = ring[b];
        if ((u[1] > p[1]) != (v[1] > p[1])) {
            const double x_cross = u[0] + (p[1] - u[1]) * (v[0] - u[0]) / (v[1] - u[1]);
            if (p[0] < x_cross) in = !in;
        }
    }
    return in;
}
}  // namespace

bool Polygon::contains(const Vec<2>& p) const
{
    if (!ring_contains(outer, p)) return false;
    for (const auto& h : holes)
        if (ring_contains(h, p)) return false;
    return true;
}

Region<2> in_polygon(Polygon poly)
{
    return [poly = std::move(poly)](const Vec<2>& p) { return poly.contains(p); };
}

template <int D>
NodeSet select(const Body<D>& body, const Region<D>& region, const std::string& what)
{
    NodeSet s;
    for (std::size_t i = 0; i < body.size(); ++i)
        if (region(body.x[i])) s.push_back(static_cast<int>(i));
    if (s.empty()) throw std::invalid_argument(what + " is empty (no node inside its region)");
    return s;
}

long grip_layers(double grip, double dx)
{
    // A grip of a whole number of cells must not gain a layer from the round-off of grip/dx:
    // shrink by the relative tolerance of the horizon rule first.
    constexpr double roundoff = 1e-10;
    return static_cast<long>(std::ceil(grip / dx * (1 - roundoff)));
}

GrippedBar gripped_bar(double L, double W, double T, double dx, double grip)
{
    GrippedBar bar;
    bar.grip_layers = grip_layers(grip, dx);
    const double g = bar.grip_layers * dx;
    bar.body = box<3>({{-g, 0, 0}}, {{L + g, W, T}}, dx);
    bar.left = select<3>(bar.body, [](const Vec<3>& p) { return p[0] < 0; }, "left grip");
    bar.right = select<3>(bar.body, [L](const Vec<3>& p) { return p[0] > L; }, "right grip");
    return bar;
}

template Body<1> fill<1>(const Vec<1>&, const Vec<1>&, double, const Region<1>&, double);
template Body<2> fill<2>(const Vec<2>&, const Vec<2>&, double, const Region<2>&, double);
template Body<3> fill<3>(const Vec<3>&, const Vec<3>&, double, const Region<3>&, double);
template NodeSet select<1>(const Body<1>&, const Region<1>&, const std::string&);
template NodeSet select<2>(const Body<2>&, const Region<2>&, const std::string&);
template NodeSet select<3>(const Body<3>&, const Region<3>&, const std::string&);

}  // namespace pd
