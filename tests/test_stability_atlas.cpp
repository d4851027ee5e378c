// The atlas' initial velocities (problems/common/stability_atlas.hpp): without_rigid_motion removes a
// rigid-body motion of a jittered body entirely and leaves a field without momentum unchanged. And
// pd_run's watch of the step as bonds break (problems/pd_run_integrate.hpp, DamageStepWatch) flags the
// step the atlas measured unstable on a correspondence cube with 90 % of its pairs broken.
#include "problems/common/stability_atlas.hpp"
#include "problems/pd_run_integrate.hpp"

#include <gtest/gtest.h>

namespace {

pd::Body<3> jittered_cube()
{
    pd::atlas::Scene s;
    s.n = 5, s.jitter = 0.3;
    return pd::atlas::body(s);
}

Eigen::Vector3d at(const pd::Field<3>& f, std::size_t i) { return {f.c[0][i], f.c[1][i], f.c[2][i]}; }

TEST(AtlasVelocities, RigidMotionIsRemovedEntirely)
{
    const pd::Body<3> b = jittered_cube();
    const Eigen::Vector3d a(1.0, -2.0, 0.5), omega(300.0, -100.0, 700.0);  // [m/s], [rad/s]
    pd::Field<3> v(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) {
        const Eigen::Vector3d x = at(b.x, i), u = a + omega.cross(x);  // about the origin, not the centre
        for (int d = 0; d < 3; ++d) v.c[d][i] = u(d);
    }
    pd::atlas::without_rigid_motion(b, v);
    for (std::size_t i = 0; i < b.size(); ++i) EXPECT_LE(at(v, i).norm(), 1e-12 * 3.0);  // of speeds ~3 m/s
}

TEST(AtlasVelocities, FieldWithoutMomentumIsKept)
{
    pd::atlas::Scene s;
    s.n = 5;
    const pd::Body<3> b = pd::atlas::body(s);  // a lattice symmetric about its centre
    const double c = 0.5 * s.n * s.dx;
    pd::Field<3> v(b.size()), w(b.size());
    for (std::size_t i = 0; i < b.size(); ++i)  // extension along x, contraction along y: no momentum, no spin
        v.c[0][i] = 1e3 * (b.x.c[0][i] - c), v.c[1][i] = -2e3 * (b.x.c[1][i] - c);
    w = v;
    pd::atlas::without_rigid_motion(b, w);
    for (std::size_t i = 0; i < b.size(); ++i) EXPECT_LE((at(w, i) - at(v, i)).norm(), 1e-12);
}

// reports/3d/stability_atlas/stability.csv, correspondence, damage 0.9 (6^3 cube): velocity Verlet is
// stable below 0.235 dt_SA (measured by bisection) and unstable at the old default 0.5 dt_SA.
TEST(DamageStepWatch, FlagsTheStepTheAtlasMeasuredUnstable)
{
    pd::atlas::Scene s;
    s.damage = 0.9;
    const pd::Body<3> b = pd::atlas::body(s);
    pd::Bonds bd = pd::atlas::bonds(s, b);
    const long broken = long(std::count(bd.intact.begin(), bd.intact.end(), 0));
    const pd::Elastic mat = pd::Elastic::from_E_nu(s.E, s.nu);
    const double c = pd::PMB::micromodulus({.material = mat, .dim = 3}, bd.influence, bd.delta);
    const double dt_sa = pd::critical_step_silling_askari(bd, s.rho, c).dt;
    pd::atlas::Variant v{"correspondence", {.name = "correspondence", .material = mat}};
    pd::atlas::with_variant(v, b, bd, [&](auto& model) {
        pd_run::DamageStepWatch unsafe, safe, early;
        unsafe.look(1, broken, 0.5 * dt_sa, model, bd, b, s.rho);
        EXPECT_EQ(unsafe.warnings, 1);
        safe.look(1, broken, 0.1 * dt_sa, model, bd, b, s.rho);  // below 0.5 x 0.235 dt_SA
        EXPECT_EQ(safe.warnings, 0);
        early.look(1, 10, 0.5 * dt_sa, model, bd, b, s.rho);  // 10 broken bonds: not yet 5 % of them, no look
        EXPECT_EQ(early.warnings, 0);
        return 0;
    });
}

}  // namespace
