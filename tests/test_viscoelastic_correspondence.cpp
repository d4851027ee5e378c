// Correspondence viscoelastic model (models/viscoelastic_correspondence.hpp; spec/000c sec. 1.5, V5)
// against hand-derived closed forms. Pure shear y = x + eps (x_y, x_x, 0) reached in one step from the
// reference: the mid-step Flanagan-Taylor update has L dt = eps S (I + eps S/2)^-1 (S = e_x e_y + e_y e_x,
// eigenvalues 1, -1, 0), symmetric, so R = I and
//   s_hat_xy = 2 G eps / (1 - eps^2/4),  tr(sigma) = 3 K tr(L dt) = -3 K eps^2 / (1 - eps^2/4),
// and held afterwards (v = 0) the elastic state is frozen while q relaxes towards gamma_b s_hat:
//   sigma_xy(t) = s_hat_xy (1 + gamma_b e^{-t/tau_b})  (= G gamma0 (1 + gamma_b e^{-t/tau_b}), gamma0 = 2 eps,
//   to O(eps^2)); the mean stress does not change. A ramp followed by a hold matches the convolution
// (7.18); a step of dt >> tau_b at 100 % stretch is the elastic Flanagan-Taylor response; the total
// dissipation of a relaxation is the stored branch energy gamma_b s_hat:s_hat/(4 G); trials do not accumulate;
// Explicit (time/verlet.hpp) drives the model through its history hook.
#include "pd/bond_loop.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd;
using C3 = Correspondence<3>;
using M3 = C3::Mat;

namespace {
constexpr double dx = 1e-3, delta = 3.05e-3;       // [m]
const Elastic mat = Elastic::from_E_nu(3e9, 0.35);  // a polymer [Pa]
constexpr double gamma_b = 2.0, tau_b = 1e-3;       // [-], [s]

Body<3> block() { return box<3>({{0, 0, 0}}, {{5 * dx, 5 * dx, 5 * dx}}, dx); }

Field<3> affine(const Body<3>& body, const M3& F)
{
    Field<3> y(body.size());
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) y.c[a][i] += F(a, b) * body.x.c[b][i];
    return y;
}
M3 shear(double eps)
{
    M3 F = M3::Identity();
    F(0, 1) = F(1, 0) = eps;
    return F;
}
// One step of the model: time step, force evaluation, commit.
void advance(ViscoelasticCorrespondence& vc, const Bonds& b, const Field<3>& y, double dt)
{
    Field<3> f;
    internal_force(vc, b, y, dt, f);
    vc.commit();
}
}  // namespace

// V5 step and hold: every node (F is exact for an affine field at every node) follows the closed form
// of the header to 1e-12 of G eps (round-off); the mean stress stays -K eps^2/(1 - eps^2/4).
TEST(ViscoelasticCorrespondence, PureShearStepRelaxes)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    const double eps = 1e-3;
    const Field<3> y = affine(body, shear(eps));
    const double s_xy = 2 * mat.G * eps / (1 - eps * eps / 4), mean = -mat.K * eps * eps / (1 - eps * eps / 4);
    advance(vc, b, y, 0.0);
    for (int s = 0; s <= 12; ++s) {
        if (s > 0) advance(vc, b, y, 0.4 * tau_b);
        const double ref = s_xy * (1 + gamma_b * std::exp(-0.4 * s));
        for (std::size_t i = 0; i < body.size(); ++i) {
            ASSERT_NEAR(model.sigma[i](0, 1), ref, 1e-12 * mat.G * eps) << "node " << i << " step " << s;
            ASSERT_NEAR(model.sigma[i].trace() / 3, mean, 1e-12 * mat.G * eps) << "node " << i;
        }
    }
}

// Ramp of eps from 0 to 1e-4 in 25 steps of 0.08 tau_b, then 25 steps of hold. Reference (7.18) for a
// linear s_hat = 2 G eps(t): sigma_xy = 2 G [eps + gamma_b (eps - h)], h = rate (r(t) - r(t - t1)),
// r(s) = s - tau_b (1 - e^{-s/tau_b}) for s > 0. Tolerance 1e-7 of 2 G eps_max: the Flanagan-Taylor
// strain of the path is eps (1 + O(eps^2)) = 1e-8 relative, and the integrator is exact for linear input.
TEST(ViscoelasticCorrespondence, RampAndHoldMatchesTheConvolution)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    const double eps_max = 1e-4, dt = 0.08 * tau_b, t1 = 25 * dt, rate = eps_max / t1;  // [-], [s], [s], [1/s]
    auto r = [&](double s) { return s > 0 ? s - tau_b * (1 - std::exp(-s / tau_b)) : 0.0; };
    const std::size_t i = body.size() / 2;
    for (int n = 1; n <= 50; ++n) {
        const double t = n * dt, eps = rate * std::min(t, t1);
        advance(vc, b, affine(body, shear(eps)), dt);
        const double h = rate * (r(t) - r(t - t1));
        const double ref = 2 * mat.G * (eps + gamma_b * (eps - h));
        ASSERT_NEAR(model.sigma[i](0, 1), ref, 1e-7 * 2 * mat.G * eps_max) << "step " << n;
    }
}

// 100 % uniaxial stretch reached in one step of dt = 1e12 tau_b: beta = 1 - 1e-12, q = gamma_b s_hat,
// so sigma = the elastic Flanagan-Taylor stress of the same step to 1e-9; finite. That stress by hand:
// F = diag(2, 1, 1), mid-step F_m = diag(3/2, 1, 1), L dt = (F - I) F_m^-1 = diag(2/3, 0, 0), symmetric,
// so R = I and sigma = K (2/3) I + 2 G dev(diag(2/3, 0, 0)) = diag(2K/3 + 8G/9, 2K/3 - 4G/9, 2K/3 - 4G/9).
TEST(ViscoelasticCorrespondence, StepFarLongerThanTauAtFullStretchIsElastic)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    M3 F = M3::Identity();
    F(0, 0) = 2;
    const Field<3> y = affine(body, F);
    advance(vc, b, y, 1e12 * tau_b);
    M3 elastic = M3::Zero();  // [Pa]
    elastic(0, 0) = 2 * mat.K / 3 + 8 * mat.G / 9;
    elastic(1, 1) = elastic(2, 2) = 2 * mat.K / 3 - 4 * mat.G / 9;
    for (std::size_t i = 0; i < body.size(); ++i) {
        ASSERT_TRUE(model.sigma[i].allFinite());
        EXPECT_LT((model.sigma[i] - elastic).cwiseAbs().maxCoeff(), 1e-9 * elastic.norm()) << "node " << i;
    }
    EXPECT_GT(model.sigma[0](0, 0), 0.0);
}

// A step held until relaxed (40 steps of 0.5 tau_b) dissipates per node the branch energy stored at
// 0+, gamma_b s_hat:s_hat / (4 G) (the branch spring 2 G_b carries the strain s_hat/(2 G)), to 1e-9
// (e^{-40} left); every step's dissipation >= 0.
TEST(ViscoelasticCorrespondence, RelaxationDissipatesTheBranchEnergy)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    const double eps = 1e-3;
    advance(vc, b, affine(body, shear(eps)), 0.0);
    // dev(L dt) of the header: xy = eps/Dn, xx = yy = -eps^2/(6 Dn), zz = eps^2/(3 Dn), Dn = 1 - eps^2/4.
    const double Dn = 1 - eps * eps / 4, l_xy = eps / Dn, l_xx = -eps * eps / (6 * Dn), l_zz = eps * eps / (3 * Dn);
    const double ss = 4 * mat.G * mat.G * (2 * l_xy * l_xy + 2 * l_xx * l_xx + l_zz * l_zz);  // s_hat:s_hat [Pa^2]
    const double stored = gamma_b * ss / (4 * mat.G);                                         // 4444 J/m^3
    std::vector<double> total(body.size(), 0.0);
    for (int s = 0; s < 40; ++s) {
        advance(vc, b, affine(body, shear(eps)), 0.5 * tau_b);
        for (std::size_t i = 0; i < body.size(); ++i) {
            ASSERT_GE(vc.dissipation[i], 0.0);
            total[i] += vc.dissipation[i];
        }
    }
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_NEAR(total[i], stored, 1e-9 * stored) << "node " << i;
}

// Trial evaluations at y, at another y', at y again (no commit in between): identical forces.
TEST(ViscoelasticCorrespondence, TrialEvaluationDoesNotAccumulate)
{
    const Body<3> body = block();
    const Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    advance(vc, b, affine(body, shear(1e-3)), 0.0);
    Field<3> f1, f2, tmp;
    M3 F = shear(2e-3);
    F(2, 2) = 1.01;
    internal_force(vc, b, affine(body, F), 0.3 * tau_b, f1);
    internal_force(vc, b, affine(body, shear(-4e-3)), tmp);
    internal_force(vc, b, affine(body, F), f2);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f1.c[d], f2.c[d]);
    double fmax = 0;
    for (int d = 0; d < 3; ++d)
        for (double v : f1.c[d]) fmax = std::max(fmax, std::abs(v));
    EXPECT_GT(fmax, 0.0);  // surface nodes carry a force: the comparison is not of zeros
}

// Explicit with every node held at the pure shear by prescribed displacements: start() evaluates the
// step at dt = 0 and commits, each step(dt) relaxes the branch: sigma_xy follows the step closed form
// of PureShearStepRelaxes (1e-12 of G eps) at every node after each of 8 steps of 0.5 tau_b.
TEST(ViscoelasticCorrespondence, ExplicitCallsTheHistoryHook)
{
    const Body<3> body = block();
    Bonds b = build_bonds(body, delta);
    C3 model({mat, C3::Law::flanagan_taylor}, body, b);
    ViscoelasticCorrespondence vc(model, {gamma_b, tau_b}, body.x);
    const double eps = 1e-3;
    const Field<3> y = affine(body, shear(eps));
    Explicit<3, ViscoelasticCorrespondence> sim(body, b, vc, 1200);
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int d = 0; d < 3; ++d) {
            const double u = y.c[d][i] - body.x.c[d][i];
            sim.u.c[d][i] = u;
            sim.boundary.prescribe({Prescribed::Kind::displacement, {static_cast<int>(i)}, d, TimeFunction::constant(u)});
        }
    sim.start();
    const double s_xy = 2 * mat.G * eps / (1 - eps * eps / 4);
    for (int s = 1; s <= 8; ++s) {
        sim.step(0.5 * tau_b);
        const double ref = s_xy * (1 + gamma_b * std::exp(-0.5 * s));
        for (std::size_t i = 0; i < body.size(); ++i) ASSERT_NEAR(model.sigma[i](0, 1), ref, 1e-12 * mat.G * eps) << "node " << i << " step " << s;
    }
}
