// Tangent stiffness K = -dF_int/du [N/m] of the nodal internal forces F_int,i = f_i V_i (f from
// bond_loop.hpp's internal_force), as an Eigen::SparseMatrix over the free dofs of a DofMap
// (dof (i, d) numbered node-major, constrained dofs left out). K is symmetric for the
// variational models (PMB, LPS, PALS: F = -dU/du), not in general for correspondence.
//
// PMB, analytic: bond k = i->j carries f_i += coef_k g(Y), g(Y) = (1 - L/|Y|) Y (pmb.hpp), so
//   dg/dY = (1 - L/|Y|) I + (L/|Y|) n n^T,  n = Y/|Y|  (linearised spring plus geometric term),
//   K_(i)(j) = -V_i coef_k dg/dY,  K_(i)(i) = +V_i sum_k coef_k dg/dY   (Y = y_j - y_i).
// Any other model (LPS, SCF, PALS, correspondence: whatever internal_force accepts), by central
// differences, one column group per colour and component:
//   K_(i,e)(a,d) = -V_i (f_ie(y + h_+ e_ad) - f_ie(y - h_- e_ad)) / (h_+ + h_-),
// h_+- the steps as actually represented in floating point ((y + h) - y), so the rounding of y
// does not enter the quotient.
// Reach and colours. Row i of F depends on u_a only for a within r hops of i in the bond graph:
// r = 1 for bond-based models (f_i sums pair forces of i's own bonds); r = 2 for models with a
// point pass or a non-ordinary bond force (LPS theta_j, PALS p_j, correspondence F_j of partner j
// depend on j's family). Columns a, b can be perturbed together iff no row sees both, i.e. their
// reach sets N_r[a], N_r[b] are disjoint: hop distance > 2r (3 for PMB, 5 for state-based). The
// families are symmetric (build_bonds), so the rows influenced by a are N_r[a]. Greedy colouring
// in node order, each row keeping the bitset of colours already seen. Measured on the cubic lattice
// 20^3 with delta = 3.05 dx (tests/test_tangent.cpp): 222 colours for r = 1 (lower bound: the
// 123-node family is a clique), 1395 for r = 2 (lower bound: the 829-node 2-hop ball). Every
// colour costs D x 2 force evaluations, so an FD tangent costs ~ 8400 of them in a large 3D body
// (bar_stiffness_3d's 10 x 2 x 1 mm bar: 104 colours at n = 2, 584 at n = 5).
// Step: error of a central difference ~ (h/L)^2 (curvature of |Y| over the shortest bond L) plus
// eps X / h (rounding of f at the coordinate scale X = max|y|); balanced at h = (eps X L^2)^(1/3).
// Damage: broken bonds stay in the graph (a superset of the true pattern: safe).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/pmb.hpp"

#include <Eigen/Sparse>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace pd {

// Free-dof numbering: index[i * D + d] = position among the free dofs, -1 when constrained.
struct DofMap {
    std::vector<int> index;
    int free = 0;
    DofMap() = default;
    explicit DofMap(const std::vector<std::uint8_t>& constrained) : index(constrained.size(), -1)
    {
        for (std::size_t q = 0; q < constrained.size(); ++q)
            if (!constrained[q]) index[q] = free++;
    }
    static DofMap all(std::size_t dofs) { return DofMap(std::vector<std::uint8_t>(dofs, 0)); }
};

// Hops of the bond graph within which a node's force depends on the displacements (header).
template <class Model>
constexpr int tangent_reach()
{
    return (Model::has_point_pass || !detail::is_ordinary<Model>()) ? 2 : 1;
}

struct Colouring {
    int reach = 1;
    int count = 0;                        // number of colours
    std::vector<int> colour;              // per node
    std::vector<std::vector<int>> nodes;  // nodes of each colour
    std::vector<std::int64_t> offset;     // CSR of the reach sets N_r[a] (sorted, a included)
    std::vector<int> rows;
};

// Reach sets and greedy colouring of the bond graph (header).
inline Colouring colour_bond_graph(const Bonds& b, int reach)
{
    if (reach < 1) throw std::invalid_argument("colour_bond_graph: reach must be >= 1");
    const std::size_t n = b.nodes();
    Colouring c;
    c.reach = reach;
    c.offset.assign(n + 1, 0);
    std::vector<int> mark(n, -1), front, next, set;
    for (std::size_t a = 0; a < n; ++a) {  // breadth-first search to depth `reach`
        set.assign(1, static_cast<int>(a));
        mark[a] = static_cast<int>(a);
        front = set;
        for (int hop = 0; hop < reach; ++hop) {
            next.clear();
            for (int i : front)
                for_family(b, i, [&](std::int64_t, int j) {
                    if (mark[j] != static_cast<int>(a)) {
                        mark[j] = static_cast<int>(a);
                        next.push_back(j);
                    }
                });
            set.insert(set.end(), next.begin(), next.end());
            front.swap(next);
        }
        std::sort(set.begin(), set.end());
        c.rows.insert(c.rows.end(), set.begin(), set.end());
        c.offset[a + 1] = static_cast<std::int64_t>(c.rows.size());
    }
    std::vector<std::vector<std::uint64_t>> seen(n);  // colours already influencing each row
    std::vector<std::uint64_t> forbidden;
    c.colour.assign(n, -1);
    for (std::size_t a = 0; a < n; ++a) {
        forbidden.assign(forbidden.size(), 0);
        for (std::int64_t q = c.offset[a]; q < c.offset[a + 1]; ++q) {
            const auto& s = seen[c.rows[q]];
            if (s.size() > forbidden.size()) forbidden.resize(s.size(), 0);
            for (std::size_t w = 0; w < s.size(); ++w) forbidden[w] |= s[w];
        }
        int col = 0;
        while (col / 64 < static_cast<int>(forbidden.size()) && (forbidden[col / 64] >> (col % 64) & 1)) ++col;
        c.colour[a] = col;
        c.count = std::max(c.count, col + 1);
        for (std::int64_t q = c.offset[a]; q < c.offset[a + 1]; ++q) {
            auto& s = seen[c.rows[q]];
            if (s.size() <= static_cast<std::size_t>(col / 64)) s.resize(col / 64 + 1, 0);
            s[col / 64] |= std::uint64_t{1} << (col % 64);
        }
    }
    c.nodes.assign(c.count, {});
    for (std::size_t a = 0; a < n; ++a) c.nodes[c.colour[a]].push_back(static_cast<int>(a));
    return c;
}

// Finite-difference step h = (eps X L^2)^(1/3) [m] (header), X = max |y|, L = shortest bond.
template <int D>
double tangent_step(const Bonds& b, const Field<D>& y)
{
    double L = INFINITY, X = 0;
    for (double l : b.length) L = std::min(L, l);
    for (int d = 0; d < D; ++d)
        for (double v : y.c[d]) X = std::max(X, std::abs(v));
    if (!std::isfinite(L)) L = 1;  // no bonds: any positive step
    return std::cbrt(DBL_EPSILON * std::max(X, L) * L * L);
}

// Coloured central-difference tangent at positions y (the model's point-pass state is left at the
// last perturbed evaluation: re-evaluate the force at y before reading it). h <= 0: tangent_step.
template <int D, class Model>
Eigen::SparseMatrix<double> tangent_fd(Model& model, const Body<D>& body, const Bonds& bonds, const Field<D>& y,
                                       const DofMap& dofs, const Colouring& col, double h = 0)
{
    const std::size_t n = body.size();
    if (y.size() != n || bonds.nodes() != n || dofs.index.size() != n * D || col.colour.size() != n)
        throw std::invalid_argument("tangent_fd: body, bonds, positions, dofs and colouring sizes differ");
    if (!(h > 0)) h = tangent_step(bonds, y);
    Eigen::SparseMatrix<double> K(dofs.free, dofs.free);
    Eigen::VectorXi per_col = Eigen::VectorXi::Zero(dofs.free);
    for (std::size_t a = 0; a < n; ++a)
        for (int d = 0; d < D; ++d)
            if (const int c = dofs.index[a * D + d]; c >= 0)
                for (std::int64_t q = col.offset[a]; q < col.offset[a + 1]; ++q)
                    for (int e = 0; e < D; ++e) per_col[c] += dofs.index[col.rows[q] * D + e] >= 0;
    K.reserve(per_col);
    Field<D> yp = y, fp(n), fm(n);
    std::vector<double> step(n);
    for (int c = 0; c < col.count; ++c)
        for (int d = 0; d < D; ++d) {
            bool any = false;
            for (int a : col.nodes[c]) any = any || dofs.index[a * D + d] >= 0;
            if (!any) continue;
            for (int a : col.nodes[c]) yp.c[d][a] = y.c[d][a] + h;
            internal_force(model, bonds, yp, fp);
            for (int a : col.nodes[c]) {
                step[a] = yp.c[d][a] - y.c[d][a];  // h_+ as represented
                yp.c[d][a] = y.c[d][a] - h;
                step[a] += y.c[d][a] - yp.c[d][a];  // + h_-
            }
            internal_force(model, bonds, yp, fm);
            for (int a : col.nodes[c]) {
                yp.c[d][a] = y.c[d][a];
                const int cc = dofs.index[a * D + d];
                if (cc < 0) continue;
                for (std::int64_t q = col.offset[a]; q < col.offset[a + 1]; ++q) {  // rows in increasing order
                    const int i = col.rows[q];
                    for (int e = 0; e < D; ++e)
                        if (const int r = dofs.index[i * D + e]; r >= 0)
                            K.insert(r, cc) = -body.volume[i] * (fp.c[e][i] - fm.c[e][i]) / step[a];
                }
            }
        }
    K.makeCompressed();
    return K;
}

// Analytic PMB tangent at positions y (header).
template <int D>
Eigen::SparseMatrix<double> tangent_pmb(const PMB& model, const Body<D>& body, const Bonds& bonds, const Field<D>& y,
                                        const DofMap& dofs)
{
    const std::size_t n = body.size();
    if (y.size() != n || bonds.nodes() != n || dofs.index.size() != n * D)
        throw std::invalid_argument("tangent_pmb: body, bonds, positions and dofs sizes differ");
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(bonds.size() * D * D * 2);
    for (std::size_t i = 0; i < n; ++i)
        for_intact_bonds(bonds, i, [&](std::int64_t k, int j) {
            Vec<D> Y = y[j] - y[i];
            const double ylen = norm(Y), L = model.length[k] * (1 + model.bond_thermal_strain(i, j));  // rest length
            const double w = body.volume[i] * model.coef[k];
            for (int e = 0; e < D; ++e) {
                const int ri = dofs.index[i * D + e];
                if (ri < 0) continue;
                for (int d = 0; d < D; ++d) {
                    const double g = w * ((e == d ? 1 - L / ylen : 0.0) + L / ylen * Y[e] * Y[d] / (ylen * ylen));
                    if (const int cj = dofs.index[j * D + d]; cj >= 0) trip.emplace_back(ri, cj, -g);
                    if (const int ci = dofs.index[i * D + d]; ci >= 0) trip.emplace_back(ri, ci, g);
                }
            }
        });
    Eigen::SparseMatrix<double> K(dofs.free, dofs.free);
    K.setFromTriplets(trip.begin(), trip.end());
    return K;
}

// The model's tangent: analytic for PMB, coloured finite differences otherwise (col must have
// reach tangent_reach<Model>()).
template <int D, class Model>
Eigen::SparseMatrix<double> tangent(Model& model, const Body<D>& body, const Bonds& bonds, const Field<D>& y,
                                    const DofMap& dofs, const Colouring& col, double h = 0)
{
    if constexpr (std::is_same_v<Model, PMB>) return tangent_pmb(model, body, bonds, y, dofs);
    else return tangent_fd(model, body, bonds, y, dofs, col, h);
}

}  // namespace pd
