// problems/common/cut_sphere.hpp -- a sphere on a cubic grid with cut surface cells, and a loading
// shell around it (spec/000c sec. 4.3: "nodes are cubes of constant side dx; surface cubes get volume
// and position corrected for the cut by the sphere"; the shell R_c of thickness Delta covers them).
// Cells of side dx centred on i dx (a node at the centre of the sphere). Each cell gives up to two
// nodes: its part inside the sphere r < R (a body node) and its part in the shell R <= r < R + Delta
// (a shell node), each at the centroid of that part with its volume. Parts smaller than min_fraction
// of a whole part (dx^3 for the body, Delta dx^2 for the shell) are dropped and their volume counted.
// Volumes and centroids of the cut cells: a q x q midpoint rule over the cell's (y, z) square with the
// x-extent of the chord exact, |x| <= sqrt(r^2 - y^2 - z^2), and its x-moment exact.
// Nodes: the body first (lattice order, x fastest), then the shell.
#pragma once
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd {

struct CutSphere {
    Body<3> body;
    std::size_t n_body = 0;            // nodes [0, n_body) are the sphere, [n_body, size) the shell
    std::vector<std::uint8_t> surface;  // per body node: 1 = its cell is cut by r = R (the outer layer)
    double R = 0, dx = 0, shell = 0;   // radius, cell side, shell thickness Delta [m]
    long cut_cells = 0;                // cells cut by r = R
    double dropped_volume = 0;         // [m^3]
    bool in_shell(std::size_t i) const { return i >= n_body; }
};

inline CutSphere cut_sphere(double R, double dx, double shell, int quadrature = 32, double min_fraction = 1e-3)
{
    if (!(R > 0 && dx > 0 && shell > 0)) throw std::invalid_argument("cut sphere: radius, cell side and shell thickness must be positive");
    if (!(dx < R)) throw std::invalid_argument("cut sphere: the cell side must be below the radius");
    CutSphere s;
    s.R = R, s.dx = dx, s.shell = shell;
    const double Ro = R + shell, h = 0.5 * dx;
    const long n = static_cast<long>(std::ceil(Ro / dx + 0.5));
    struct Part { double v = 0, mx = 0, my = 0, mz = 0; };
    Body<3> outer;
    // x-extent of the chord of radius r at (y, z) inside [x0, x1]: length and first moment.
    auto chord = [](double r2, double rho2, double x0, double x1, double& len, double& mom) {
        len = mom = 0;
        if (rho2 >= r2) return;
        const double a = std::sqrt(r2 - rho2), lo = std::max(x0, -a), hi = std::min(x1, a);
        if (hi > lo) len = hi - lo, mom = 0.5 * (hi * hi - lo * lo);
    };
    for (long k = -n; k <= n; ++k)
        for (long j = -n; j <= n; ++j)
            for (long i = -n; i <= n; ++i) {
                const Vec<3> c{{double(i) * dx, double(j) * dx, double(k) * dx}};
                double near2 = 0, far2 = 0;  // squared distances of the cell's nearest and farthest points
                for (int d = 0; d < 3; ++d) {
                    const double lo = c[d] - h, hi = c[d] + h, q = std::max({0.0, lo, -hi});
                    near2 += q * q, far2 += std::max(lo * lo, hi * hi);
                }
                if (near2 >= Ro * Ro) continue;
                if (far2 <= R * R) {  // whole cell inside the sphere
                    s.body.push(c, dx * dx * dx), s.surface.push_back(0);
                    continue;
                }
                Part in, sh;
                const double w = dx / quadrature;
                for (int qz = 0; qz < quadrature; ++qz)
                    for (int qy = 0; qy < quadrature; ++qy) {
                        const double y = c[1] - h + (qy + 0.5) * w, z = c[2] - h + (qz + 0.5) * w, rho2 = y * y + z * z;
                        double l1, m1, l2, m2;
                        chord(R * R, rho2, c[0] - h, c[0] + h, l1, m1);
                        chord(Ro * Ro, rho2, c[0] - h, c[0] + h, l2, m2);
                        in.v += l1 * w * w, in.mx += m1 * w * w, in.my += l1 * y * w * w, in.mz += l1 * z * w * w;
                        sh.v += (l2 - l1) * w * w, sh.mx += (m2 - m1) * w * w, sh.my += (l2 - l1) * y * w * w, sh.mz += (l2 - l1) * z * w * w;
                    }
                if (near2 < R * R) ++s.cut_cells;
                auto keep = [&](const Part& p, double whole, Body<3>& into) {
                    if (p.v <= 0) return false;
                    if (p.v < min_fraction * whole) { s.dropped_volume += p.v; return false; }
                    into.push({{p.mx / p.v, p.my / p.v, p.mz / p.v}}, p.v);
                    return true;
                };
                if (keep(in, dx * dx * dx, s.body)) s.surface.push_back(1);
                keep(sh, shell * dx * dx, outer);
            }
    s.n_body = s.body.size();
    for (std::size_t q = 0; q < outer.size(); ++q) s.body.push(outer.x[q], outer.volume[q]);
    return s;
}

}  // namespace pd
