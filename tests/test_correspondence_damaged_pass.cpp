// The damaged correspondence passes (models/correspondence.hpp): the point pass and the Flanagan-Taylor
// update form K^-1 and m again only for the families whose intact flags changed, and then equal, bit for
// bit, a model built on the damaged bonds.
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"

#include <gtest/gtest.h>

#include "correspondence_fixtures.hpp"

#include <cstdint>
#include <random>

using namespace pd;
using namespace pd_test::correspondence_fixtures;

// The damaged point pass forms K and m again only for the families whose intact flags changed since
// it last formed them, and keeps them elsewhere: after pairs of the centre node break between two
// passes, every node's K^-1, m, F and P equal (bit for bit) those of a model built on the damaged bonds.
TEST(Correspondence, DamagedPassReformsTheShapeTensorsOfChangedFamiliesOnly)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    std::mt19937 gen(7);
    const Field<3> y = affine<3>(body, random_matrix(gen, 1e-3), Eigen::Vector3d::Zero());
    Correspondence<3> model({.material = steel}, body, b);
    model.point_pass(b, y);
    const int c = 3 + 6 * (3 + 6 * 3);
    int q = 0;
    for_family(b, c, [&](std::int64_t k, int) { if (q++ % 3 == 0) b.break_pair(k); });
    model.point_pass(b, y);
    Correspondence<3> fresh({.material = steel}, body, b);
    fresh.point_pass(b, y);
    const Correspondence<3> intact_model({.material = steel}, body, build_bonds(body, m_ratio * dx));
    EXPECT_FALSE(intact_model.Kinv[c] == model.Kinv[c]);  // the breaks did change the centre's K
    for (std::size_t i = 0; i < body.size(); ++i) {
        ASSERT_TRUE(model.Kinv[i] == fresh.Kinv[i]) << i;
        ASSERT_TRUE(model.F[i] == fresh.F[i]) << i;
        ASSERT_TRUE(model.P[i] == fresh.P[i]) << i;
        for (int d = 0; d < 3; ++d) ASSERT_EQ(model.m_xi.c[d][i], fresh.m_xi.c[d][i]) << i;
    }
}

// The same reuse in the Flanagan-Taylor update of a damaged body: after pairs of the centre node break
// between two updates, every node's K^-1 and m equal those of a model built on the damaged bonds and
// updated once.
TEST(Correspondence, FlanaganTaylorDamagedUpdateReformsTheShapeTensorsOfChangedFamiliesOnly)
{
    using C3 = Correspondence<3>;
    const Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    std::mt19937 gen(11);
    const Field<3> y = affine<3>(body, random_matrix(gen, 1e-3), Eigen::Vector3d::Zero());
    const Field<3> v(body.size());
    C3 model({.material = steel, .law = C3::Law::flanagan_taylor}, body, b);
    model.update_stress(b, y, v, 1e-8);
    const int c = 3 + 6 * (3 + 6 * 3);
    int q = 0;
    for_family(b, c, [&](std::int64_t k, int) { if (q++ % 3 == 0) b.break_pair(k); });
    model.update_stress(b, y, v, 1e-8);
    C3 fresh({.material = steel, .law = C3::Law::flanagan_taylor}, body, b);
    fresh.update_stress(b, y, v, 1e-8);  // K formed by the same pass (another pass may round differently)
    const C3 intact_model({.material = steel, .law = C3::Law::flanagan_taylor}, body, build_bonds(body, m_ratio * dx));
    EXPECT_FALSE(intact_model.Kinv[c] == model.Kinv[c]);
    for (std::size_t i = 0; i < body.size(); ++i) {
        ASSERT_TRUE(model.Kinv[i] == fresh.Kinv[i]) << i;
        for (int d = 0; d < 3; ++d) ASSERT_EQ(model.m_xi.c[d][i], fresh.m_xi.c[d][i]) << i;
    }
}
