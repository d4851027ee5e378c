// PD plasticity models (models/plastic_lps.hpp, plastic_pals.hpp, plastic_correspondence.hpp) against the
// classical small-strain J2 radial return of reference/j2_plasticity.hpp (the Johnson-Cook flow stress
// typed from spec/000b (5.64) and the scalar equation (5.21) solved by plain bisection; it calls
// nothing of the library), spec/000b V7 identity test:
//  - ordinary LPS J2: a node whose family is the 12 vertices of an icosahedron (a spherical
//    5-design, so the 4th moments sum_k n n n n are isotropic and the PD deviatoric energy equals
//    G dev(eps):dev(eps) for affine deformation) under a non-proportional affine history with a
//    volumetric part: per step dl, ep and sigma_eff equal the classical return; PALS: the same at
//    the centre node of a lattice block (full family, cubic symmetry);
//  - correspondence J2: interior nodes of a lattice block (full family, F exact for affine y)
//    under uniaxial strain then shear reproduce the point law;
//  - the history protocol: point_pass twice at one y gives the same force (no accumulation), and
//    commit() then re-evaluation at the same y adds no plastic strain; heat source
//    beta_TQ sigma_y dl / dt;
//  - explicit dynamics (Explicit: dt = 0 at start, dt per step): a free block stretched by
//    an initial velocity field yields; kinetic + stored energy never rises above the initial
//    kinetic energy by more than the elastic run's integration error and ends clearly below it
//    (dissipation); below yield the stored energy is the elastic model's.
#include "pd/bond_loop.hpp"
#include "pd/core/lattice.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/time/verlet.hpp"
#include "reference/j2_plasticity.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace pd;
using laws::Mat3;

namespace {
const Elastic al = Elastic::from_E_nu(71.7e9, 0.33);  // Al 7075-T6 [Pa]

Field<3> affine(const Body<3>& body, const Mat3& F)
{
    Field<3> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) y.c[a][i] += F(a, b) * body.x.c[b][i];
    return y;
}

// Centre node 0 plus the 12 icosahedron vertices at radius r [m]; delta between r and the edge
// length 1.0515 r: the centre's family is the 12 directions.
Body<3> icosahedron(double r)
{
    Body<3> b;
    const double g = (1 + std::sqrt(5.0)) / 2, s = r / std::sqrt(1 + g * g);
    b.push({{0, 0, 0}}, 1e-9);
    for (double p : {-1.0, 1.0})
        for (double q : {-1.0, 1.0}) {
            b.push({{0, p * s, q * g * s}}, 1e-9);
            b.push({{p * s, q * g * s, 0}}, 1e-9);
            b.push({{q * g * s, 0, p * s}}, 1e-9);
        }
    return b;
}

// The classical reference (reference/j2_plasticity.hpp) with the constants of a law.
ref::Hardening hardening_of(const laws::JohnsonCook& jc) { return {jc.A, jc.B, jc.n, jc.C, jc.epdot0}; }

// Strain of step k of a non-proportional history: uniaxial-type deviator, then shear, plus a
// volumetric part [-]; amplitudes ~1e-6 (see the tolerance of the LPS test).
Mat3 history_strain(int k)
{
    const double a = 1e-6 * std::min(k, 6), c = 1e-6 * std::max(0, k - 6), v = 2e-7 * k;
    Mat3 e = Mat3::Zero();
    e.diagonal() << a + v, -0.5 * a + v, -0.5 * a + v;
    e(0, 1) = e(1, 0) = c;
    return e;
}
}  // namespace

// Non-proportional affine history at node c with a symmetric family: the PD return of `model`
// against the classical one, step by step.
template <class Model>
void expect_classical_return(Model& model, const Body<3>& body, const Bonds& bonds, const laws::JohnsonCook& jc, std::size_t c = 0)
{
    ref::ClassicalJ2 h;
    Field<3> f;
    int plastic_steps = 0;
    for (int k = 1; k <= 12; ++k) {
        const Mat3 eps = history_strain(k);
        internal_force(model, bonds, affine(body, Mat3::Identity() + eps), f);
        const ref::ClassicalJ2 u = ref::classical_j2(al.K, al.G, hardening_of(jc), eps, h, 1.0);
        // Tolerance: the PD extension |Y| - |xi| equals the linear n.eps.n |xi| only to O(eps)
        // (strains <= 1.4e-5; measured relative difference of sigma_eff <= 5e-7), which carries
        // into sigma_eff_trial and into dl (~1e-6).
        EXPECT_NEAR(model.pts.sigma_eff[c], ref::von_mises(u.stress), 5e-6 * ref::von_mises(u.stress)) << "step " << k;
        EXPECT_NEAR(model.pts.dlambda[c], u.dl, 5e-6 * 1e-6) << "step " << k;
        EXPECT_NEAR(model.pts.ep[c], u.ep, 5e-6 * (1e-6 + u.ep)) << "step " << k;
        plastic_steps += u.dl > 0;
        model.commit();
        h = u;
    }
    EXPECT_GE(plastic_steps, 8);  // the history is mostly plastic, in both loading directions
    EXPECT_GT(h.ep, 5e-6);
}

// Small yield stress so that plasticity starts at strains ~1e-6 (G 27 GPa): A/(3G) = 6e-7.
const laws::JohnsonCook tiny_yield{.A = 5e4, .B = 1e8, .n = 0.71};

TEST(PlasticLPS, IcosahedronNodeGivesTheClassicalReturn)
{
    const double r = 1e-3;
    const Body<3> body = icosahedron(r);
    const Bonds bonds = build_bonds(body, 1.02 * r);
    ASSERT_EQ(bonds.end(0) - bonds.begin(0), 12);
    PlasticLPS model({.material = al, .dim = 3}, bonds, tiny_yield);
    expect_classical_return(model, body, bonds, tiny_yield);
}

// PALS: the icosahedron is degenerate for PALS (the six matching functions take only three
// distinct value sets on its 12 bonds, the systems are singular). Instead the centre node of a
// lattice block with its full family: cubic symmetry leaves two deviatoric moduli (normal and
// shear), both fixed by the matching constraints, so W_d = G dev(eps):dev(eps) and theta = tr eps
// for every affine eps (linearised).
TEST(PlasticPALS, FullLatticeFamilyGivesTheClassicalReturn)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{-3.5 * dx, -3.5 * dx, -3.5 * dx}}, {{3.5 * dx, 3.5 * dx, 3.5 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    std::size_t c = 0;  // the centre node (0, 0, 0)
    while (norm(Vec<3>{{body.x.c[0][c], body.x.c[1][c], body.x.c[2][c]}}) > 1e-9) ++c;
    ASSERT_EQ(bonds.end(c) - bonds.begin(c), 122);  // the full family of delta = 3.05 dx
    PlasticPALS model({.material = al}, body, bonds, tiny_yield);
    expect_classical_return(model, body, bonds, tiny_yield, c);
}

TEST(PlasticLPS, TrialEvaluationDoesNotAccumulate)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{0, 0, 0}}, {{6 * dx, 6 * dx, 6 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    const laws::JohnsonCook jc{.A = 300e6, .B = 500e6, .n = 0.5};
    PlasticLPS model({.material = al, .dim = 3}, bonds, jc);
    Mat3 F = Mat3::Identity();
    F(0, 0) += 0.02;
    F(0, 1) += 0.01;
    const Field<3> y = affine(body, F);
    Field<3> f1, f2, f3;
    internal_force(model, bonds, y, f1);
    const std::vector<double> ep1 = model.pts.ep;
    internal_force(model, bonds, y, f2);
    double emax = 0;
    for (double e : ep1) emax = std::max(emax, e);
    EXPECT_GT(emax, 1e-3);  // it yielded
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f1.c[d], f2.c[d]);  // bit-identical: no accumulation
    EXPECT_EQ(model.pts.ep, ep1);
    model.commit();
    internal_force(model, bonds, y, f3);
    // Re-evaluating the committed state: on the yield surface, no further flow beyond round-off
    // (residual 4 eps sigma / 3G ~ 1e-17).
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_LE(model.pts.dlambda[i], 1e-14);
}

TEST(PlasticCorrespondence, InteriorNodesReproduceThePointLaw)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{0, 0, 0}}, {{8 * dx, 8 * dx, 8 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    const laws::JohnsonCook jc{.A = 546e6, .B = 678e6, .n = 0.71, .C = 0.024, .epdot0 = 1};
    PlasticCorrespondence model({.material = al, .C_hg = 0.02}, body, bonds, jc);
    // Interior nodes: the full family fits (distance >= delta from every face).
    std::vector<int> interior;
    for (std::size_t i = 0; i < body.size(); ++i) {
        bool in = true;
        for (int d = 0; d < 3; ++d) in = in && body.x.c[d][i] > 3.05 * dx && body.x.c[d][i] < 5 * dx;
        if (in) interior.push_back(static_cast<int>(i));
    }
    ASSERT_FALSE(interior.empty());
    ref::ClassicalJ2 h;
    Field<3> f;
    for (int k = 1; k <= 10; ++k) {
        Mat3 eps = Mat3::Zero();
        eps(0, 0) = 2e-3 * std::min(k, 5);             // uniaxial strain, then
        eps(1, 2) = eps(2, 1) = 2e-3 * std::max(0, k - 5);  // shear
        internal_force(model, bonds, affine(body, Mat3::Identity() + eps), 1e-4, f);
        const ref::ClassicalJ2 u = ref::classical_j2(al.K, al.G, hardening_of(jc), eps, h, 1e-4);  // at theta_ref (jc.m = 0: no softening)
        for (int i : interior) {
            // F exact for affine y on a full family: round-off of the family sums (1e-13 of F).
            EXPECT_LE((model.model.sigma[i] - u.stress).norm(), 1e-9 * u.stress.norm()) << "step " << k;
            EXPECT_NEAR(model.pts.ep[i], u.ep, 1e-9 * (1e-6 + u.ep));
            EXPECT_DOUBLE_EQ(model.pts.heat_source[i], 0.9 * model.pts.sigma_eff[i] * model.pts.dlambda[i] / 1e-4);
        }
        model.commit();
        h = u;
    }
    EXPECT_GT(h.ep, 5e-3);  // both parts of the path flowed
}

namespace {
struct ExplicitRun {
    double ep_max = 0;      // largest equivalent plastic strain [-]
    double rise = -1e300;   // max over the steps of (KE + SE) / KE_0 - 1 [-]
    double final = 0;       // (KE + SE) / KE_0 - 1 at the end [-]
};

// A 5^3 block with v_x = rate (x - x_c), rate 1e5 1/s (uniaxial strain rate; yield strain near
// 4e-3 is reached after 40 ns), free faces, 40 steps of 2e-8 s (the critical step is about 1e-7 s).
template <class Model>
ExplicitRun stretch_block_explicitly(Model& model, const Body<3>& body, Bonds& bonds, double dx)
{
    Explicit<3, Model> ex(body, bonds, model, 2700);
    for (std::size_t i = 0; i < body.size(); ++i) ex.v.c[0][i] = 1e5 * (body.x.c[0][i] - 2 * dx);
    ex.start();
    const double e0 = ex.energies().kinetic;
    ExplicitRun r;
    for (int n = 0; n < 40; ++n) {
        ex.step(2e-8);
        const Energies e = ex.energies();
        r.final = (e.kinetic + e.strain) / e0 - 1;
        r.rise = std::max(r.rise, r.final);
    }
    if constexpr (requires { model.pts; })
        for (std::size_t i = 0; i < body.size(); ++i) {
            r.ep_max = std::max(r.ep_max, model.pts.ep[i]);
            EXPECT_TRUE(std::isfinite(model.pts.heat_source[i]));
        }
    return r;
}
}  // namespace

// The elastic LPS run of the same block gives the integrator's own energy error at this dt (no
// dissipation, no external work): |rise| and |final| of the elastic run bound it. A plastic run
// must never rise above the initial energy by more than twice that, and must end lower by more
// than ten times it (the plastic dissipation is real, not integration error).
TEST(PlasticModels, RunInExplicitDynamicsAndDissipate)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{0, 0, 0}}, {{4 * dx, 4 * dx, 4 * dx}}, dx);
    Bonds bonds = build_bonds(body, 3.05 * dx);
    LPS elastic({.material = al, .dim = 3}, bonds);
    const ExplicitRun el = stretch_block_explicitly(elastic, body, bonds, dx);
    const double err = std::max(std::abs(el.rise), std::abs(el.final));
    ASSERT_LT(err, 0.05);  // a sane integration at this dt
    const laws::JohnsonCook jc{.A = 300e6, .B = 500e6, .n = 0.5, .C = 0.02, .epdot0 = 1};
    PlasticLPS lps({.material = al, .dim = 3}, bonds, jc);
    PlasticPALS pals({.material = al}, body, bonds, jc);
    PlasticCorrespondence corr({.material = al, .C_hg = 0.02}, body, bonds, jc);
    const ExplicitRun runs[] = {stretch_block_explicitly(lps, body, bonds, dx), stretch_block_explicitly(pals, body, bonds, dx),
                                stretch_block_explicitly(corr, body, bonds, dx)};
    for (const ExplicitRun& r : runs) {
        EXPECT_GT(r.ep_max, 1e-3);
        EXPECT_LE(r.rise, 2 * err);
        EXPECT_LT(r.final, -10 * err);
        std::printf("elastic error %.3g; plastic: ep_max %.3g, rise %.3g, final %.3g\n", err, r.ep_max, r.rise, r.final);
    }
}

TEST(PlasticModels, StoredEnergyBelowYieldIsTheElasticModels)
{
    const double dx = 1e-3;
    const Body<3> body = box<3>({{0, 0, 0}}, {{5 * dx, 5 * dx, 5 * dx}}, dx);
    const Bonds bonds = build_bonds(body, 3.05 * dx);
    const laws::JohnsonCook jc{.A = 300e6, .B = 500e6, .n = 0.5};
    Mat3 F = Mat3::Identity();
    F(0, 0) += 1e-4;
    F(0, 1) += 5e-5;  // strains of 1e-4: far below yield (about 4e-3)
    const Field<3> y = affine(body, F);
    Field<3> f;
    PlasticLPS p({.material = al, .dim = 3}, bonds, jc);
    LPS e({.material = al, .dim = 3}, bonds);
    internal_force(p, bonds, y, f);
    internal_force(e, bonds, y, f);
    const std::vector<double> Wp = p.energy_density(bonds, y), We = e.energy_density(bonds, y);
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_NEAR(Wp[i], We[i], 1e-12 * We[i]) << i;
}
