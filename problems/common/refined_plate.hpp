// problems/common/refined_plate.hpp -- the plate of spec/002 sec. 5.1 (V1) on a grid refined in one
// half, solved statically (problems/2d/refined_plate_static.cpp): the node-centred grid and its
// Method B (or A) refinement, the families of the per-node horizons (exact cell areas), PMB with the horizon
// factors and optionally the energy surface correction, supports on the axes, the end loads, and
// K u = F with the analytic PMB tangent at the reference (supernodal Cholesky, CHOLMOD, for the
// symmetric dual-horizon stiffness; UMFPACK LU for the plain variable horizon's). The choices are written in the driver's header.
#pragma once
#include "pd/core/refinement.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/models/surface_correction.hpp"
#include "pd/solve/linear_solver.hpp"
#include "pd/solve/tangent.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd::plate {
constexpr double on_axis = 1e-9;  // |coordinate| below which a node lies on a symmetry axis [m]

struct Plate {
    double Lx, Ly, t, dx0, delta0, E, p;  // [m], [m], [m], [m], [m], [Pa], [Pa]
};

// The node-centred plate, then `levels` refinements of the left (A-C) or upper (D-F) half, by Method B
// (the source's) or Method A.
pd::RefinedGrid<2> refined_plate(const Plate& P, int levels, bool upper, pd::NodeGeneration generation = pd::NodeGeneration::cell_split)
{
    pd::Body<2> b;
    b.dx = P.dx0, b.measure = P.t;
    // Nodes at (i, j) dx0 within the plate (round-off slack 1e-9 dx0), so the axes x = 0 and y = 0
    // always carry nodes; a dx0 that does not divide the half sides leaves the plate a little shorter.
    const long nx = static_cast<long>(std::floor(P.Lx / 2 / P.dx0 + 1e-9)), ny = static_cast<long>(std::floor(P.Ly / 2 / P.dx0 + 1e-9));
    for (long j = -ny; j <= ny; ++j)
        for (long i = -nx; i <= nx; ++i) b.push({{i * P.dx0, j * P.dx0}}, P.dx0 * P.dx0 * P.t);
    pd::RefinedGrid<2> g(b, P.delta0);
    g.refine_nested([&](const pd::Vec<2>& x, double setback) { return (upper ? x[1] : -x[0]) > setback + on_axis; }, levels, pd::Refinement::delta, {},
                     generation);
    return g;
}

struct Solution {
    pd::Body<2> body;
    pd::Field<2> u;
    std::vector<int> level;
    std::size_t bonds = 0;
    double ghost = 0, wall = 0;  // |sum of the internal forces| / load [-]; wall time [s]
};

// Families, PMB with the horizon factors (and the surface correction), supports, loads, K u = F.
Solution solve(const Plate& P, const pd::RefinedGrid<2>& g, pd::HorizonCoupling coupling, bool corrected)
{
    pd::io::Timer timer;
    Solution s{g.body(), {}, {}, 0, 0, 0};
    const std::size_t n = s.body.size();
    for (int i : g.ids()) s.level.push_back(g.level[i]);
    const std::vector<double> h = g.active_h();
    const pd::HorizonFamilies f = pd::build_variable_horizon_bonds(s.body, g.active_delta(), h, coupling, pd::PartialVolume::exact_area);
    const pd::PMB::Params mp{.material = pd::Elastic::from_E_nu(P.E, 1.0 / 3), .dim = 2, .plane = pd::Plane::stress, .measure = P.t};
    pd::PMB model(mp, f.bonds);
    model.scale_bonds(pd::horizon_factors(f, [&](double delta) { return pd::PMB::micromodulus(mp, pd::Influence{}, delta); }));
    if (corrected)
        pd::apply_surface_correction(model, s.body, f.bonds, pd::SurfaceCorrectionMethod::energy,
                                     {.reference = pd::SurfaceCorrectionOptions::Reference::classical,
                                      .kappa = pd::kappa_dim(mp.material, 2, mp.plane)});
    std::vector<std::uint8_t> held(2 * n, 0);
    Eigen::VectorXd F;
    std::vector<double> load(2 * n, 0.0);  // nodal force [N]
    double edge = 0;  // the outer face of the end cells [m]
    for (std::size_t i = 0; i < n; ++i) edge = std::max(edge, std::abs(s.body.x.c[0][i]) + h[i] / 2);
    // Method A keeps the refined end nodes on the initial end line; they own the outer rim of their
    // initial cell, so their cells reach from |x| - h/2 to the end, and carry the traction on V / width.
    const bool kept = g.method == pd::NodeGeneration::midpoint;
    for (std::size_t i = 0; i < n; ++i) {
        const double x = s.body.x.c[0][i], y = s.body.x.c[1][i];
        held[2 * i] = std::abs(x) < on_axis, held[2 * i + 1] = std::abs(y) < on_axis;
        const double sign = x > 0 ? 1 : -1;
        if (std::abs(std::abs(x) + h[i] / 2 - edge) < on_axis) load[2 * i] = sign * P.p / h[i] * s.body.volume[i];  // b = p/h
        else if (kept && std::abs(std::abs(x) - (edge - P.dx0 / 2)) < on_axis)
            load[2 * i] = sign * P.p * s.body.volume[i] / (edge - std::abs(x) + h[i] / 2);
    }
    const pd::DofMap dofs(held);
    F = Eigen::VectorXd::Zero(dofs.free);
    for (std::size_t q = 0; q < 2 * n; ++q)
        if (dofs.index[q] >= 0) F[dofs.index[q]] = load[q];
    const Eigen::SparseMatrix<double> K = pd::tangent_pmb(model, s.body, f.bonds, s.body.x, dofs);
    pd::SparseSolver solver;
    std::string failure;
    const bool dual = coupling == pd::HorizonCoupling::dual;  // symmetric K: Cholesky; the plain variable horizon: LU (three levels: 300k dof)
    Eigen::VectorXd U;
    if (!solver.factorise(K, dual ? pd::LinearSolver::cholmod : pd::LinearSolver::umfpack, 0, 0, failure) || !solver.solve(F, U, failure))
        throw std::runtime_error(failure);
    s.u = pd::Field<2>(n);
    for (std::size_t q = 0; q < 2 * n; ++q) s.u.c[q % 2][q / 2] = dofs.index[q] >= 0 ? U[dofs.index[q]] : 0.0;
    pd::Field<2> y = s.body.x, fi(n);  // the internal forces at the solution: their sum is the ghost force
    for (int d = 0; d < 2; ++d)
        for (std::size_t i = 0; i < n; ++i) y.c[d][i] += s.u.c[d][i];
    pd::internal_force(model, f.bonds, y, fi);
    for (int d = 0; d < 2; ++d) {
        double sum = 0;
        for (std::size_t i = 0; i < n; ++i) sum += fi.c[d][i] * s.body.volume[i];
        s.ghost = std::max(s.ghost, std::abs(sum) / (P.p * P.t * (P.Ly + P.dx0)));
    }
    s.bonds = f.bonds.size(), s.wall = timer.seconds();
    return s;
}

}  // namespace pd::plate
