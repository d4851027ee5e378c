// The bond-mean thermal strain of the ordinary models (ThermalExpansion::bond_mean,
// models/thermal_expansion.hpp): bond i -> j takes (eps_i + eps_j)/2 instead of its owner's eps_i.
// - A free body under a linear temperature field is stress-free in classical thermoelasticity (the
//   thermal strain a x is compatible); at the exact compatible displacement every bond's mechanical
//   extension is zero up to the rotation's second-order term, so LPS and PALS with the bond mean carry
//   no force at any node, surfaces included, while the owner rule leaves forces at the surfaces;
// - the LPS dilatation at y = x against its definition summed here bond by bond;
// - a uniform temperature gives the owner rule's forces; the force is minus the gradient of the energy;
//   the chunk path agrees with the per-node path; the LPS wrappers take the bond's strain;
// - the correspondence models, whose thermal strain is a node's, refuse it.
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/models/viscoelastic_lps.hpp"

#include <gtest/gtest.h>

#include "energy_gradient.hpp"
#include "thermal_expansion_fixtures.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace pd;
using namespace pd_test::thermal_expansion_fixtures;

namespace {
std::vector<double> random_temperatures(std::size_t n, unsigned seed, double spread)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> T(-spread, spread);
    std::vector<double> theta(n);
    for (auto& t : theta) t = theta_ref + 50 + T(gen);
    return theta;
}
Field<3> perturbed(const Body<3>& body, unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> U(-1e-7, 1e-7);
    Field<3> y = body.x;
    for (int d = 0; d < 3; ++d) for (auto& v : y.c[d]) v += U(gen);
    return y;
}
// eps(X) = eps0 + a X_1 about the bar's centre (2 K over the bar): u_1 = eps0 X_1 + a (X_1^2 - X_2^2 - X_3^2)/2,
// u_2 = (eps0 + a X_1) X_2, u_3 = (eps0 + a X_1) X_3 has sym grad u = eps I (a compatible thermal strain).
// For this quadratic u, Y = (1 + eps_m) xi + W_m xi exactly (eps_m at the bond's midpoint =
// (eps_i + eps_j)/2, W_m skew, |W_m| <= a |X| = 1.2e-5), so the bond-mean extension is
// |xi| O(|W_m|^2) = 7e-11 |xi|, against the owner rule's surface dilatation of order a delta / 2 = 2e-6:
// a force ratio of order 4e-5 (4e-6 measured), below the tests' bound 1e-3.
Field<3> linear_temperature_field(const Body<3>& body, std::vector<double>& theta)
{
    const double c[3] = {10 * dx, 2.5 * dx, 2 * dx}, eps0 = alpha * 50, a = alpha * 2 / (20 * dx);  // [m], [-], [1/m]
    theta.resize(body.size());
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) {
        const double X[3] = {body.x.c[0][i] - c[0], body.x.c[1][i] - c[1], body.x.c[2][i] - c[2]};
        const double eps = eps0 + a * X[0];
        theta[i] = theta_ref + eps / alpha;
        y.c[0][i] += eps0 * X[0] + 0.5 * a * (X[0] * X[0] - X[1] * X[1] - X[2] * X[2]);
        y.c[1][i] += eps * X[1];
        y.c[2][i] += eps * X[2];
    }
    return y;
}
// LPS (with SCF) and PALS with thermal expansion from theta by the owner or the bond-mean rule.
template <class Fn>
void for_each_ordinary_model(const Bonds& b, const Body<3>& body, const std::vector<double>& theta, bool mean, Fn&& fn)
{
    ThermalExpansion t{alpha, theta_ref, &theta};
    t.bond_mean = mean;
    LPS lps({mat, 3}, b), scf({mat, 3}, b);
    PALS pals({.material = mat}, body, b);
    scf.apply_shear_correction(body.x);
    lps.set_thermal_expansion(t), scf.set_thermal_expansion(t), pals.set_thermal_expansion(t);
    fn("LPS", lps);
    fn("LPS+SCF", scf);
    fn("PALS", pals);
}
}  // namespace

// Classical thermoelasticity: a free body under a linear temperature field is stress-free. With the
// bond mean every node's force vanishes to the rotation's second-order term (linear_temperature_field),
// while the owner rule leaves forces at the surfaces.
TEST(ThermalBondMean, LinearTemperatureFieldLeavesAFreeBodyForceFree)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta;
    const Field<3> y = linear_temperature_field(body, theta);
    std::vector<double> owner_max;
    for_each_ordinary_model(b, body, theta, false, [&](const char*, auto& model) {
        Field<3> f;
        internal_force(model, b, y, f);
        owner_max.push_back(max_norm(f));
    });
    int q = 0;
    for_each_ordinary_model(b, body, theta, true, [&](const char* name, auto& model) {
        Field<3> f;
        internal_force(model, b, y, f);
        EXPECT_GT(owner_max[q], 0) << name;
        EXPECT_LE(max_norm(f), 1e-3 * owner_max[q]) << name << ": bond mean " << max_norm(f) << ", owner " << owner_max[q];
        ++q;
    });
}

// theta_i = (3/m_i) sum_j omega |xi| (|Y| - |xi| (1 + eps_ij)) V_j, m_i = sum_j omega |xi|^2 V_j, summed
// here from the bonds (y = x: |Y| = |xi|); 1e-12: the same terms in another order.
TEST(ThermalBondMean, LPSDilatationIsTheSumOfTheBondsMechanicalExtensions)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta = random_temperatures(body.size(), 5, 40);
    ThermalExpansion t{alpha, theta_ref, &theta};
    t.bond_mean = true;
    LPS lps({mat, 3}, b);
    lps.set_thermal_expansion(t);
    lps.point_pass(b, body.x);
    for (std::size_t i = 0; i < body.size(); ++i) {
        double m = 0, s = 0;
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            const double L = b.length[k], eps = 0.5 * alpha * ((theta[i] - theta_ref) + (theta[j] - theta_ref));
            m += b.omega[k] * L * L * b.volume[k];
            s += b.omega[k] * L * (-eps * L) * b.volume[k];
        }
        EXPECT_NEAR(lps.theta[i], 3 * s / m, 1e-12 * std::abs(3 * s / m)) << "node " << i;
    }
}

// A uniform temperature has eps_ij = eps_i: the owner rule's forces, to round-off (1e-10 of the largest:
// (eps_i + eps_j)/2 and eps_i differ in the last bits, and PALS regroups the thermal terms). For PALS
// this holds where m_omega = 3, the owner rule's own premise (pals.hpp), i.e. at every node of this bar.
TEST(ThermalBondMean, UniformTemperatureGivesTheOwnerRulesForces)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref + 50);
    const Field<3> y = perturbed(body, 3);
    std::vector<Field<3>> owner;
    for_each_ordinary_model(b, body, theta, false, [&](const char*, auto& model) { internal_force(model, b, y, owner.emplace_back()); });
    int q = 0;
    for_each_ordinary_model(b, body, theta, true, [&](const char* name, auto& model) {
        Field<3> f;
        internal_force(model, b, y, f);
        expect_forces_near(f, owner[q++], 1e-10, name);
    });
}

// Also with one pair in seven broken (C_i and the sums over the intact bonds, m_i and the PALS
// multipliers formed from them at construction).
TEST(ThermalBondMean, ForceIsEnergyGradientUnderATemperatureField)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    const std::vector<double> theta = random_temperatures(body.size(), 11, 10);
    const Field<3> y = perturbed(body, 12);
    for (bool damaged : {false, true}) {
        Bonds b = build_bonds(body, 3 * dx);
        if (damaged) {
            b.enable_damage();
            for (std::size_t i = 0; i < body.size(); ++i)
                for_family(b, i, [&](std::int64_t k, int j) {
                    if (static_cast<int>(i) < j && (31 * i + j) % 7 == 0) b.intact[k] = b.intact[b.reverse[k]] = 0;
                });
        }
        for_each_ordinary_model(b, body, theta, true, [&](const char* name, auto& model) {
            pd_test::expect_force_is_energy_gradient(model, b, body, y, {0, 2 + 2 * 6, 2 + 2 * 6 + 3 * 36}, 1e-9, 1e-6,
                                                     std::string(name) + (damaged ? ", damaged" : ""));
        });
    }
}

// The chunk path against the per-node path (expect_chunk_path_matches_per_node: 1e-12 of the largest force).
TEST(ThermalBondMean, ChunkedAndPerNodePathsAgree)
{
    const Body<3> body = bar();
    const std::vector<double> theta = random_temperatures(body.size(), 7, 10);
    const Field<3> y = perturbed(body, 8);
    expect_chunk_path_matches_per_node(body, y, [&](const Bonds& b, auto&& fn) { for_each_ordinary_model(b, body, theta, true, fn); });
}

// The LPS wrappers take the bond's strain in their deviatoric extension: under the linear field of
// linear_temperature_field the viscoelastic LPS (its branch loaded by the step's deviatoric extension) and
// the plastic LPS (never yielding) carry no force with the bond mean, and surface forces with the owner
// rule (the same bound as the elastic models).
TEST(ThermalBondMean, LPSWrappersTakeTheBondsStrain)
{
    const Body<3> body = bar();
    Bonds b = build_bonds(body, 3 * dx);
    std::vector<double> theta;
    const Field<3> y = linear_temperature_field(body, theta);
    const laws::JohnsonCook hard{.A = 1e12, .B = 0, .n = 1};  // [Pa]: never yields
    const double dt = 1e-7;                                    // [s]
    double f_max[2][2] = {};                                   // [owner, mean][visco, plastic]
    for (bool mean : {false, true}) {
        ThermalExpansion t{alpha, theta_ref, &theta};
        t.bond_mean = mean;
        ViscoelasticLPS visco({{mat, 3}, 2.0, 1e-6}, b);
        PlasticLPS plps({.material = mat, .dim = 3}, b, hard);
        visco.lps.set_thermal_expansion(t), plps.lps.set_thermal_expansion(t);
        Field<3> f;
        internal_force(visco, b, y, dt, f);
        f_max[mean][0] = max_norm(f);
        internal_force(plps, b, y, dt, f);
        f_max[mean][1] = max_norm(f);
    }
    for (int w = 0; w < 2; ++w) {
        EXPECT_GT(f_max[0][w], 0) << (w ? "plastic LPS" : "viscoelastic LPS");
        EXPECT_LE(f_max[1][w], 1e-3 * f_max[0][w]) << (w ? "plastic LPS" : "viscoelastic LPS");
    }
}

// The correspondence models' thermal strain is a node's, and PlasticPALS's deviatoric extension takes
// the owner's: they refuse the bond mean rather than ignore it.
TEST(ThermalBondMean, ModelsWithoutItRefuseIt)
{
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds b = build_bonds(body, 3 * dx);
    const std::vector<double> theta(body.size(), theta_ref);
    ThermalExpansion t{alpha, theta_ref, &theta};
    t.bond_mean = true;
    Correspondence<3> corr({.material = mat}, body, b);
    EXPECT_THROW(corr.set_thermal_expansion(t), std::invalid_argument);
    const laws::JohnsonCook hard{.A = 1e12, .B = 0, .n = 1};
    PlasticCorrespondence pcorr({.material = mat, .law = Correspondence<3>::Law::flanagan_taylor}, body, b, hard);
    EXPECT_THROW(pcorr.set_thermal_expansion(t), std::invalid_argument);
    PlasticPALS ppals({.material = mat}, body, b, hard);
    ppals.pals.set_thermal_expansion(t);
    Field<3> f;
    EXPECT_THROW(internal_force(ppals, b, body.x, 1e-7, f), std::invalid_argument);
}
