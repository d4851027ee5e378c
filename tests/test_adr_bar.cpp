// ADR with the PALS and correspondence stiffness bounds (time/dynamic_relaxation.hpp) on the thin
// bars of bar_stiffness_3d (spec/000b V2: 10 x 2 x 1 mm, E = 100 GPa, nu = 0.33, dx = l3/n,
// delta = 3.05 dx, grips of 2 delta outside the bar, right grip u_x = 1 % of l2): PALS at n = 1, 2
// and correspondence (linear law, C_hg = 0.02) at n = 2 diverged with the PMB stand-in density
// (reports/3d/bar_stiffness.md); with the bounds they converge (relative residual 1e-6).
// Regression-free: the assertion is convergence, plus a finite positive reaction.
#include "pd/models/correspondence.hpp"
#include "pd/models/pals.hpp"
#include "pd/time/dynamic_relaxation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <type_traits>

using namespace pd;

namespace {
constexpr double L = 10e-3, W = 2e-3, T = 1e-3, U = 0.01 * L;  // [m]

template <class Model>
RelaxationResult relax_bar(int n, double& reaction)
{
    const double dx = T / n, delta = 3.05 * dx;
    const GrippedBar bar = gripped_bar(L, W, T, dx, 2 * delta);
    Bonds bonds = build_bonds(bar.body, delta);
    const Elastic mat = Elastic::from_E_nu(100e9, 0.33);
    Model model = [&] {
        if constexpr (std::is_same_v<Model, PALS>) return PALS({.material = mat}, bar.body, bonds);
        else return Model({.material = mat, .law = Model::Law::linear, .C_hg = 0.02}, bar.body, bonds);
    }();
    DynamicRelaxation<3, Model> adr(bar.body, bonds, model);  // density from stiffness_bound(model, ...)
    Boundary<3> bc;
    bc.prescribe({Prescribed::Kind::displacement, bar.left, 0, TimeFunction::constant(0)});
    bc.prescribe({Prescribed::Kind::displacement, bar.right, 0, TimeFunction::constant(U)});
    Field<3> u(bar.body.size());
    for (std::size_t i = 0; i < bar.body.size(); ++i) {  // the driver's warm start: uniform uniaxial field
        u.c[0][i] = U * std::clamp(bar.body.x.c[0][i] / L, 0.0, 1.0);
        u.c[1][i] = -0.33 * U / L * (bar.body.x.c[1][i] - W / 2);
        u.c[2][i] = -0.33 * U / L * (bar.body.x.c[2][i] - T / 2);
    }
    const RelaxationResult r = adr.solve(u, bc, 0, 1e-6, 100000);
    reaction = 0;  // axial reaction of the loaded (right) grip [N]
    for (int i : bar.right) reaction -= adr.internal_force_density().c[0][i] * bar.body.volume[i];
    return r;
}
}  // namespace

TEST(ADRBar, PALSConvergesAtN1AndN2)
{
    for (int n : {1, 2}) {
        double F = 0;
        const RelaxationResult r = relax_bar<PALS>(n, F);
        std::printf("[ ADR ] PALS n = %d: %s, %ld iterations, reaction %.4e N\n", n, r.message.c_str(), r.iterations, F);
        EXPECT_TRUE(r.converged) << "n = " << n << ": " << r.message;
        EXPECT_GT(F, 0);
    }
}

TEST(ADRBar, CorrespondenceConvergesAtN2)
{
    double F = 0;
    const RelaxationResult r = relax_bar<Correspondence<3>>(2, F);
    std::printf("[ ADR ] correspondence n = 2: %s, %ld iterations, reaction %.4e N\n", r.message.c_str(), r.iterations, F);
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_GT(F, 0);
}
