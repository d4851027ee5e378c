// The atlas' initial velocities (problems/common/stability_atlas.hpp): without_rigid_motion removes a
// rigid-body motion of a jittered body entirely and leaves a field without momentum unchanged.
#include "problems/common/stability_atlas.hpp"

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

}  // namespace
