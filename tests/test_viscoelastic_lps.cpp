// Mitchell's ordinary viscoelastic model (models/viscoelastic_lps.hpp, spec/000c sec. 1.4, V4) and
// the history hook of Explicit (time/verlet.hpp), against closed forms:
//   uniform pure shear held after a step: t_d = alpha omega e_d0 (1 + gamma_b e^{-t/tau_b}) per bond,
//     e_d0 and theta computed here by hand-written sums (not by the model), theta = O(eps^2);
//   any held deformation: the force is the elastic LPS force with G (1 + gamma_b e^{-t/tau_b})
//     (e_d is constant, e_d - e_db = e_d e^{-t/tau_b}; the deviatoric force is linear in G);
//   a trial evaluation does not accumulate; dt >> tau_b at 100 % strain gives the elastic LPS, no NaN;
//   total dissipation of a relaxation = the drop of the stored energy; Explicit calls the hook.
#include "pd/bond_loop.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/viscoelastic_lps.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd;

namespace {
constexpr double dx = 1e-3, delta = 3.05e-3;          // lattice spacing, horizon [m]
const Elastic mat = Elastic::from_E_nu(70e9, 0.3);     // [Pa]
constexpr double gamma_b = 1.5, tau_b = 2e-4;          // [-], [s]

Body<3> block(int n) { return box<3>({{0, 0, 0}}, {{n * dx, n * dx, n * dx}}, dx); }

// y = x + (eps (x_y, x_x, 0)) (pure shear, engineering gamma = 2 eps) or a smooth non-affine field.
Field<3> deformed(const Body<3>& body, double eps, bool affine)
{
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i) {
        const double X = body.x.c[0][i], Y = body.x.c[1][i], Z = body.x.c[2][i];
        if (affine) {
            y.c[0][i] += eps * Y, y.c[1][i] += eps * X;
        } else {
            y.c[0][i] += eps * dx * std::sin(900 * X + 300 * Z);
            y.c[1][i] += eps * dx * std::cos(700 * Y - 500 * X);
            y.c[2][i] += eps * dx * std::sin(400 * Z + 800 * Y);
        }
    }
    return y;
}

int centre_node(const Body<3>& body, int n)
{
    const double c = 0.5 * n * dx;
    int best = 0;
    double d2 = 1e300;
    for (std::size_t i = 0; i < body.size(); ++i) {
        double s = 0;
        for (int d = 0; d < 3; ++d) s += std::pow(body.x.c[d][i] - c, 2);
        if (s < d2) d2 = s, best = static_cast<int>(i);
    }
    return best;
}

// Hand sums (4.8-4.9, 4.13) at node i: alpha = 15 G/m [Pa/m^5], theta [-], and e_d of bond k [m].
struct Hand {
    double alpha = 0, theta = 0;
    double ed(const Bonds& b, const Field<3>& y, std::size_t i, std::int64_t k) const
    {
        const double L = b.length[k];
        return norm(y[b.partner[k]] - y[i]) - L - theta * L / 3;
    }
};
Hand hand_sums(const Bonds& b, const Field<3>& y, std::size_t i)
{
    double m = 0, th = 0;
    for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
        const double L = b.length[k], e = norm(y[b.partner[k]] - y[i]) - L;
        m += b.omega[k] * L * L * b.volume[k];
        th += b.omega[k] * L * e * b.volume[k];
    }
    return {15 * mat.G / m, 3 * th / m};
}

ViscoelasticLPS make_model(const Bonds& b) { return ViscoelasticLPS({{mat}, gamma_b, tau_b}, b); }
}  // namespace

// V4: step pure shear eps = 1e-4 at t = 0 (dt = 0), held with dt = 0.3 tau_b for 15 steps. At the
// centre node (full family) every bond's t_d follows alpha omega e_d0 (1 + gamma_b e^{-t/tau_b}) to
// 1e-12 of its largest value (round-off of the recurrence). theta is O(eps^2) (|theta| < eps^2).
TEST(ViscoelasticLPS, PureShearRelaxationPerBond)
{
    const int n = 8;
    const Body<3> body = block(n);
    const Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    const double eps = 1e-4;
    const Field<3> y = deformed(body, eps, true);
    const int i = centre_node(body, n);
    const Hand h = hand_sums(b, y, i);
    EXPECT_LT(std::abs(h.theta), eps * eps);
    Field<3> f;
    internal_force(model, b, y, 0.0, f);
    model.commit();
    for (int s = 0; s <= 15; ++s) {
        if (s > 0) {
            internal_force(model, b, y, 0.3 * tau_b, f);
            model.commit();
        }
        double worst = 0, scale = 0;
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const double ref = h.alpha * b.omega[k] * h.ed(b, y, i, k) * (1 + gamma_b * std::exp(-0.3 * s));
            worst = std::max(worst, std::abs(model.deviatoric_force_state(i, k) - ref));
            scale = std::max(scale, std::abs(ref));
        }
        ASSERT_LT(worst, 1e-12 * scale) << "step " << s;
    }
}

// Any held deformation (non-affine, every node including the surface): after t the force equals the
// elastic LPS force with G_t = G (1 + gamma_b e^{-t/tau_b}); the step at dt = 0 gives G (1 + gamma_b).
// Tolerance 1e-11 of the largest force (sums of ~100 bonds, round-off only).
TEST(ViscoelasticLPS, HeldDeformationEqualsLpsWithRelaxingShearModulus)
{
    const int n = 6;
    const Body<3> body = block(n);
    const Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    const Field<3> y = deformed(body, 1e-3, false);
    Field<3> f, g;
    double t = 0;
    for (double dt : {0.0, 0.1 * tau_b, 0.7 * tau_b, 2.0 * tau_b, 5.0 * tau_b}) {
        internal_force(model, b, y, dt, f);
        model.commit();
        t += dt;
        const Elastic relaxed = Elastic{mat.K, mat.G * (1 + gamma_b * std::exp(-t / tau_b))};
        LPS lps({relaxed}, b);
        internal_force(lps, b, y, g);
        double worst = 0, scale = 0;
        for (int d = 0; d < 3; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) {
                worst = std::max(worst, std::abs(f.c[d][i] - g.c[d][i]));
                scale = std::max(scale, std::abs(g.c[d][i]));
            }
        EXPECT_LT(worst, 1e-11 * scale) << "t/tau_b = " << t / tau_b;
    }
}

// The trial state is evaluated from the committed history: evaluations at y, at another y', and at y
// again (all before commit) give bit-identical forces at y.
TEST(ViscoelasticLPS, TrialEvaluationDoesNotAccumulate)
{
    const Body<3> body = block(5);
    const Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    const Field<3> y = deformed(body, 1e-3, false), y2 = deformed(body, 3e-3, true);
    Field<3> f1, f2, tmp;
    internal_force(model, b, y, 0.4 * tau_b, f1);
    internal_force(model, b, y2, tmp);
    internal_force(model, b, y, f2);
    for (int d = 0; d < 3; ++d) EXPECT_EQ(f1.c[d], f2.c[d]);
}

// Extreme: 100 % stretch (y = 2x) reached in one step of dt = 1e12 tau_b: beta = 1 - 1e-12, the
// branch is relaxed (e_db = e_d to 1e-12): force = elastic LPS force (G) to 1e-9; finite everywhere.
TEST(ViscoelasticLPS, StepFarLongerThanTauAtFullStrainIsElastic)
{
    const Body<3> body = block(5);
    const Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    Field<3> y = body.x, f, g;
    for (int d = 0; d < 3; ++d)
        for (auto& v : y.c[d]) v *= 2;
    internal_force(model, b, y, 1e12 * tau_b, f);
    LPS lps({mat}, b);
    internal_force(lps, b, y, g);
    double worst = 0, scale = 0;
    for (int d = 0; d < 3; ++d)
        for (std::size_t i = 0; i < body.size(); ++i) {
            ASSERT_TRUE(std::isfinite(f.c[d][i]));
            worst = std::max(worst, std::abs(f.c[d][i] - g.c[d][i]));
            scale = std::max(scale, std::abs(g.c[d][i]));
        }
    EXPECT_GT(scale, 0.0);
    EXPECT_LT(worst, 1e-9 * scale);
}

// Dissipation: a step held until relaxed (40 steps of 0.5 tau_b) dissipates the drop of stored energy
// sum V_i (W_i(0+) - W_i(inf)) = sum V_i 1/2 alpha_b sum omega e_d^2 V_j (7.20), to 1e-9 (the branch
// energy left at t = 20 tau_b is e^{-40} of it). Every node's D_i >= 0 at every step.
TEST(ViscoelasticLPS, RelaxationDissipatesTheBranchEnergy)
{
    const Body<3> body = block(5);
    const Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    const Field<3> y = deformed(body, 2e-3, false);
    Field<3> f;
    auto stored = [&] {
        const auto W = model.energy_density(b, y);
        double s = 0;
        for (std::size_t i = 0; i < body.size(); ++i) s += W[i] * body.volume[i];
        return s;  // [J]
    };
    internal_force(model, b, y, 0.0, f);
    model.commit();
    const double W0 = stored();
    double dissipated = 0;
    for (int s = 0; s < 40; ++s) {
        internal_force(model, b, y, 0.5 * tau_b, f);
        model.commit();
        for (std::size_t i = 0; i < body.size(); ++i) {
            ASSERT_GE(model.dissipation[i], 0.0);
            dissipated += model.dissipation[i] * body.volume[i];
        }
    }
    const double drop = W0 - stored();
    EXPECT_GT(drop, 0.0);
    EXPECT_NEAR(dissipated, drop, 1e-9 * drop);
}

// The Explicit hook: every node held at the affine pure shear by prescribed displacements from t = 0;
// Explicit's scene must evaluate with dt = 0 + commit in start() and with dt + commit per step, so
// that after 10 steps of 0.25 tau_b the centre bond force follows the closed form of V4 (1e-12).
TEST(ViscoelasticLPS, ExplicitCallsTheHistoryHook)
{
    const int n = 6;
    const Body<3> body = block(n);
    Bonds b = build_bonds(body, delta);
    ViscoelasticLPS model = make_model(b);
    const double eps = 1e-4;
    const Field<3> y = deformed(body, eps, true);
    Explicit<3, ViscoelasticLPS> sim(body, b, model, 2700);
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int d = 0; d < 3; ++d) {
            const double u = y.c[d][i] - body.x.c[d][i];
            sim.u.c[d][i] = u;
            sim.boundary.prescribe({Prescribed::Kind::displacement, {static_cast<int>(i)}, d, TimeFunction::constant(u)});
        }
    sim.start();
    const int i = centre_node(body, n);
    const Hand h = hand_sums(b, y, i);
    for (int s = 1; s <= 10; ++s) {
        sim.step(0.25 * tau_b);
        double worst = 0, scale = 0;
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const double ref = h.alpha * b.omega[k] * h.ed(b, y, i, k) * (1 + gamma_b * std::exp(-0.25 * s));
            worst = std::max(worst, std::abs(model.deviatoric_force_state(i, k) - ref));
            scale = std::max(scale, std::abs(ref));
        }
        ASSERT_LT(worst, 1e-12 * scale) << "step " << s;
    }
}
