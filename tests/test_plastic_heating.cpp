// Plastic heating through a scene's temperature field (scene.hpp, DissipativeModel; plastic_points.hpp;
// spec/000a sec. 3.3.5, spec/000b eq. 5.22). Reference, closed form: a perfectly plastic J2 material
// (Johnson-Cook with B = 0, C = 0, yield stress A) under the uniaxial strain path eps_xx = 0 .. eps_end
// in S equal steps has, once yielded, the equivalent plastic strain increment 2/3 d eps per step (the
// deviatoric strain increment's equivalent value), and the radial return telescopes exactly:
//   lambda_total = (2 G eps_end - A) / (3 G) = 2/3 (eps_end - A/(2 G)),
// so an adiabatic body (conduction off) heats by beta_TQ A lambda_total / (rho c) at every node. The
// affine motion y = F x gives every correspondence node, surface nodes included, the exact F.
// With temperature_field set the law reads the field: a second step at a hotter field returns to the
// softened yield stress A (1 - theta*^m).
#include "pd/core/lattice.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/scene.hpp"
#include "pd/time/heat_cvode.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

using namespace pd;

namespace {
constexpr double dx = 1e-3, rho_c = 3.9e6, theta0 = 293.15, beta = 0.9, dt = 1e-7;  // [m], [J/(m^3 K)], [K], [-], [s]
const Elastic steel = Elastic::from_E_nu(200e9, 0.3);

Field<3> stretched(const Body<3>& body, double eps)
{
    Field<3> u(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) u.c[0][i] = eps * body.x.c[0][i];
    return u;
}
}  // namespace

TEST(PlasticHeating, AdiabaticUniaxialStrainHeatsByBetaTimesThePlasticWork)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{5 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.5 * dx);
    const Bonds isolated = build_bonds(body, 0.5 * dx);  // no bonds: conduction off
    const laws::JohnsonCook law{.A = 3e8, .B = 0, .n = 1};
    const double eps_end = 0.01, eps_y = law.A / (2 * steel.G);
    ASSERT_LT(4 * eps_y, eps_end);
    for (long nsync : {1L, 5L}) {
        PlasticCorrespondence model({.material = steel}, body, bonds, law, beta);
        auto field = make_temperature_field(Agwai({.k = 50}, body, isolated), isolated, std::vector<double>(body.size(), rho_c), HeatLoads{},
                                            std::vector<double>(body.size(), theta0), HeatIntegrator::explicit_euler, dt);
        Scene<3, PlasticCorrespondence> scene(body, bonds, model);
        scene.set_heat(*field, nsync);
        const int S = 40;
        Field<3> f(body.size()), u_old = stretched(body, 0.0);
        for (int n = 1; n <= S + static_cast<int>(nsync); ++n) {  // the last nsync steps hold eps_end: the release of the rest
            const Field<3> u = stretched(body, eps_end * std::min(n, S) / S);
            scene.advance_heat(n, dt);
            scene.internal_forces(u_old, u, dt, f);
            scene.commit();
            u_old = u;
        }
        const double lambda = 2.0 / 3.0 * (eps_end - eps_y);
        const double rise = beta * law.A * lambda / rho_c;
        for (std::size_t i = 0; i < body.size(); ++i) {
            ASSERT_NEAR(model.pts.ep_c[i], lambda, 1e-12) << i;
            ASSERT_NEAR(field->theta[i] - theta0, rise, 1e-9 * rise) << "N_sync(MH) " << nsync << ", node " << i;
        }
    }
}

TEST(PlasticHeating, TheLawReadsTheFieldTemperature)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 2.5 * dx);
    const laws::JohnsonCook law{.A = 3e8, .B = 0, .n = 1, .m = 1, .theta_ref = theta0, .theta_melt = theta0 + 1000};
    PlasticCorrespondence model({.material = steel}, body, bonds, law, beta);
    std::vector<double> theta(body.size(), theta0 + 250);  // theta* = 1/4: yield 3/4 A
    model.pts.set_temperature_field(&theta);
    Field<3> f;
    Field<3> y = stretched(body, 0.01);
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < body.size(); ++i) y.c[d][i] += body.x.c[d][i];
    internal_force(model, bonds, y, dt, f, nullptr);
    for (std::size_t i = 0; i < body.size(); ++i) ASSERT_NEAR(model.pts.sigma_eff[i], 0.75 * law.A, 1e-9 * law.A) << i;
    const std::vector<double> short_theta(3, theta0);
    EXPECT_THROW(model.pts.set_temperature_field(&short_theta), std::invalid_argument);
}
