// Lattices (bodies of material points) in 1D, 2D and 3D: one node at the centre of each cubic
// cell of side dx whose centre lies inside a region; nodal volume = dx^D times the measure of
// the reduced dimensions (2D: thickness t; 1D: cross-section A). Regions: boxes, cylinders,
// spheres, 2D polygons with holes (seed 001 builds its plate from a polygon), and any predicate.
// Node sets are index lists selected by a region.
#pragma once
#include "pd/core/field.hpp"

#include <functional>
#include <string>
#include <vector>

namespace pd {

template <int D>
struct Body {
    Field<D> x;                  // reference positions [m]
    std::vector<double> volume;  // nodal volumes [m^3]
    double dx = 0;               // lattice spacing [m]; 0 for irregular point clouds
    double measure = 1;          // 2D thickness [m], 1D cross-section [m^2], 1 in 3D
    std::size_t size() const { return volume.size(); }
    void push(const Vec<D>& p, double v)
    {
        for (int d = 0; d < D; ++d) x.c[d].push_back(p[d]);
        volume.push_back(v);
    }
};

template <int D>
using Region = std::function<bool(const Vec<D>&)>;
using NodeSet = std::vector<int>;

// Cells of side dx tiling the box [lo, hi] (n_d = round((hi_d - lo_d)/dx) cells per axis), keeping
// the centres inside `inside` (all when empty). Throws std::invalid_argument on dx <= 0 or an
// empty box.
template <int D>
Body<D> fill(const Vec<D>& lo, const Vec<D>& hi, double dx, const Region<D>& inside = {}, double measure = 1);

template <int D>
Body<D> box(const Vec<D>& lo, const Vec<D>& hi, double dx, double measure = 1) { return fill<D>(lo, hi, dx, {}, measure); }

// Regions.
template <int D>
Region<D> in_box(const Vec<D>& lo, const Vec<D>& hi)
{
    return [=](const Vec<D>& p) { for (int d = 0; d < D; ++d) if (p[d] < lo[d] || p[d] > hi[d]) return false; return true; };
}
template <int D>
Region<D> in_ball(const Vec<D>& centre, double radius)  // sphere (3D), disc (2D), segment (1D)
{
    return [=](const Vec<D>& p) { return norm(p - centre) <= radius; };
}
// Cylinder with axis parallel to coordinate `axis`, through `centre`, radius R, axial extent [a0, a1].
Region<3> in_cylinder(const Vec<3>& centre, int axis, double radius, double a0, double a1);

// 2D polygon with holes (even-odd rule; vertices in order, closing edge implied).
struct Polygon {
    std::vector<Vec<2>> outer;
    std::vector<std::vector<Vec<2>>> holes;
    bool contains(const Vec<2>& p) const;
};
Region<2> in_polygon(Polygon poly);

// Node set of the points inside a region; throws std::invalid_argument naming `what` when empty.
template <int D>
NodeSet select(const Body<D>& body, const Region<D>& region, const std::string& what = "node set");

// Number of lattice layers of a grip at least `grip` thick: ceil(grip/dx), a whole number of cells
// (e.g. 2 delta with integer m) not gaining a layer from the round-off of grip/dx.
long grip_layers(double grip, double dx);

// Bar [0, L] x [0, W] x [0, T] (x axial) on a lattice dx, plus grip zones of ceil(grip/dx) layers
// added OUTSIDE each end: `left` holds the nodes with x < 0, `right` those with x > L.
struct GrippedBar {
    Body<3> body;
    NodeSet left, right;
    long grip_layers = 0;
};
GrippedBar gripped_bar(double L, double W, double T, double dx, double grip);

}  // namespace pd
