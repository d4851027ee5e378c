// Seed 001 pre-processing of a 2D body cut from a polygon (spec/001_004 sec. A.2 steps 2-5):
// lattice nodes inside the shape, boundary nodes (`isEdge`: one of the four grid neighbours
// missing) and the material volume coefficient `weight` of each node.
//   Interior node: weight = 1 (area dx^2).
//   Boundary node: zone = square of side 2 dx centred on the node, given by its 8 perimeter
//   points (4 corners, 4 side midpoints, i.e. the directions of the 8 grid neighbours); the point
//   of a direction holding an object node is pulled to half its distance from the centre; the
//   zone is intersected with the shape; weight = area(zone cap shape)/dx^2.
// The intersection area is exact (not the source's point sorting about a centroid, which it says
// fails at strongly concave corners): the zone is star-shaped about its node, so it is the union
// of 8 fan triangles T_k; each shape ring is the signed sum of triangles (o, a, b) over its edges
// (winding number, Green's theorem), so area(T_k cap ring) = sum over edges of
// orient(o, a, b) * area(T_k cap triangle(o, a, b)), each a convex-convex clip (Sutherland-Hodgman).
// The result depends only on the rings' point sets: holes and slit ("coincident segments")
// polygons of the source need no special case. Cost: 8 x (shape edges) clips per boundary node.
#pragma once
#include "pd/core/lattice.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace pd {

using Ring = std::vector<Vec<2>>;

double signed_area(const Ring& ring);   // shoelace, > 0 counter-clockwise [m^2]
double polygon_area(const Polygon& p);  // |outer| - sum |holes| [m^2]

// Area of convex polygon `convex` (either orientation) intersected with triangle a-b-c [m^2].
double convex_triangle_overlap(const Ring& convex, const Vec<2>& a, const Vec<2>& b, const Vec<2>& c);

// Area of (polygon star-shaped about `centre`, vertices in angular order) cap shape [m^2].
double star_shape_overlap(const Vec<2>& centre, const Ring& star, const Polygon& shape);

struct PolygonBody {
    Body<2> body;                    // nodes inside the shape; volume = weight dx^2 t [m^3]
    std::vector<std::uint8_t> edge;  // 1 = boundary node (isEdge)
    std::vector<double> weight;      // material volume coefficient [-]; 1 for interior nodes
};

// Weight rules: `none` every weight 1 (uncorrected volumes); `seed001` the source's zones (above);
// `shared_quarters` (ours, the source's stated intent "split overlapping zones in half" made exact):
// the plane is cut into quarter cells of side dx/2; a node owns its cell cap shape, and each
// quarter of a cell without node (centre outside the shape) goes in equal shares to the object
// nodes among the three cells that touch it at the quarter's inner corner. Zones never overlap, so
// no area is counted twice; only shape parts in quarters with no claimant are lost. Nodes whose 8
// neighbours are all object nodes keep weight 1 under every rule.
enum class WeightRule { none, seed001, shared_quarters };
WeightRule parse_weight_rule(const std::string& name);  // "none" | "seed001" | "shared-quarters"; throws otherwise

// Seed 001 steps 3-5: lattice of spacing dx over the shape's bounding box starting at its lower
// left corner + (dx/2, dx/2); nodes inside the shape (even-odd rule); isEdge; weights by `rule`.
// Throws std::invalid_argument when dx <= 0 or the shape holds no node.
PolygonBody polygon_body(const Polygon& shape, double dx, double thickness = 1, WeightRule rule = WeightRule::seed001);

}  // namespace pd
