// Critical-micropotential damage (damage/micropotential.hpp), the work integral and the breaking
// test. Accuracy against an independent reference: correspondence on an affine loading path, w of
// every pair against its closed form (written out below from the bond list, no library call).
// Consistency (not an independent reference: both sides use the model under test): w of every
// mechanical model (elastic, plastic, viscoelastic; 3D correspondence on its AVX2 path with and
// without hourglass control, with the hourglass work left out, and with per-node J_C ratios), summed
// inside the force pass, against the trapezoidal sum of the model's own public per-bond force from
// both ends of each pair, pairs broken during the loading included; the same w for 1 and 2 threads;
// apply() breaks exactly the pairs at or above w_C (correspondence); a body without bonds runs.
// Closed forms of PMB and the constants: test_micropotential.cpp.
#include "pd/damage/micropotential.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/models/viscoelastic_lps.hpp"
#include "pd/time/verlet.hpp"

#include "damage_fixtures.hpp"

#include <algorithm>
#include <cstdio>
#include <random>
#include <utility>

using namespace pd;
using namespace pd_test;

namespace {
constexpr double step_s = 1e-6;  // [s]: the viscoelastic tau_b below, so the dashpot matters

struct Loading {
    std::vector<double> w, w_ref;  // per ordered bond: work(b, k), and the reference from bond k's own end
};

// Random loading: five random deformations in sequence, forces and increments after each; before
// the third, every 11th pair breaks (both halves), so its w must stay where it was. History models
// (viscoelastic, plastic) follow a scene's protocol (scene.hpp): the step dt in the force evaluation,
// commit() after the increments. The reference is the header's trapezoidal sum
// for every ordered bond from its own end, with g_k from the model's public per-bond force
// (bond_force, or bond_scalar times Y) at each deformation, not from the force pass; with
// `reference` given, from that model's instead, evaluated at the same deformations. b's intact
// flags are as before on return.
template <int D, class Model>
Loading random_loading(Model model, const Body<D>& body, Bonds& b, CriticalMicropotential<D>& mp, Correspondence<D>* reference = nullptr)
{
    const std::vector<std::uint8_t> intact = b.intact;
    Loading out{std::vector<double>(b.size()), std::vector<double>(b.size(), 0.0)};
    std::vector<Vec<D>> g_old(b.size()), Y_old(b.size());
    for (unsigned s = 0; s < 5; ++s) {
        if (s == 2) {
            for (std::size_t k = 0; k < b.size(); k += 11) b.break_pair(k);
            if constexpr (requires { model.recompute(b); }) model.recompute(b);
        }
        const Field<D> y = deformed(body, 100 + s);
        Field<D> f;
        if constexpr (HistoryModel<Model, D>) internal_force(model, b, y, step_s, f);
        else internal_force(model, b, y, f);
        mp.accumulate(model, b, y);
        if (reference) internal_force(*reference, b, y, f);
        for (std::size_t i = 0; i < body.size(); ++i)
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                const int j = b.partner[k];
                const Vec<D> Y = y[j] - y[i];
                Vec<D> fk;
                if (reference) fk = reference->bond_force(i, k, j, Y);
                else if constexpr (requires { model.bond_force(i, k, j, Y); }) fk = model.bond_force(i, k, j, Y);
                else fk = model.bond_scalar(i, k, j, norm(Y)) * Y;
                const Vec<D> g = (b.intact[k] / b.volume[k]) * fk;
                const double r = mp.jc_ratio.empty() ? 1.0 : 0.5 * (mp.jc_ratio[i] + mp.jc_ratio[j]);
                if (s > 0) out.w_ref[k] += b.intact[k] * r * 0.5 * dot(g_old[k] + g, Y - Y_old[k]);
                g_old[k] = g;
                Y_old[k] = Y;
            }
        if constexpr (requires { model.commit(); }) model.commit();
        if constexpr (requires { model.pts.ep_c; }) {  // the plastic models really flow
            EXPECT_GT(*std::max_element(model.pts.ep_c.begin(), model.pts.ep_c.end()), 0.0);
        }
    }
    for (std::size_t k = 0; k < b.size(); ++k) out.w[k] = mp.work(b, static_cast<std::int64_t>(k));
    b.intact = intact;
    return out;
}

// Largest |w_ref| and largest |w - w_ref| over the bonds of a loading.
std::pair<double, double> largest_and_error(const Loading& run)
{
    double wmax = 0, err = 0;
    for (std::size_t k = 0; k < run.w.size(); ++k) {
        wmax = std::max(wmax, std::abs(run.w_ref[k]));
        err = std::max(err, std::abs(run.w[k] - run.w_ref[k]));
    }
    return {wmax, err};
}

Body<3> loaded_box()  // above parallel_min_nodes, so that 2 threads really split the nodes
{
    return box<3>({{0, 0, 0}}, {{14 * dx, 13 * dx, 12 * dx}}, dx);
}

Bonds cut_bonds(const Body<3>& body)  // every 7th pair broken from the start
{
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(k);
    return b;
}
}  // namespace

// Consistency (header): every model's w from the force pass against the sum of its per-bond force
// from both ends of each pair (so w_ij = w_ji within round-off of the two ends' forces), and the same
// w for 1 and 2 threads, bit for bit. Tolerance
// 1e-12 of the largest w: the force pass and the public per-bond functions add the same terms in
// different orders (measured: 4e-16 for the correspondence models, up to 2.7e-13 for LPS, whose
// bond_scalar regroups the node terms; printed by the test).
TEST(Micropotential, MatchesTheWorkSumFromBothEndsAndIsThreadIndependent)
{
    const auto body = loaded_box();
    ASSERT_GE(body.size(), static_cast<std::size_t>(parallel_min_nodes));
    Bonds b = cut_bonds(body);
    std::vector<double> ratio(body.size());
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.5, 2.0);
    for (double& r : ratio) r = u(rng);
    auto check = [&](auto model, const char* name, bool scaled = false, Correspondence<3>* reference = nullptr) {
        Loading run[2];
        for (int t = 0; t < 2; ++t) {
            set_threads(t + 1);
            CriticalMicropotential<3> mp;
            if (scaled) mp.jc_ratio = ratio;
            mp.hourglass_work = reference == nullptr;
            run[t] = random_loading(model, body, b, mp, reference);
        }
        set_threads(0);
        EXPECT_EQ(run[0].w, run[1].w) << name;
        for (std::size_t k = 0; k < b.size(); ++k) {
            if (!b.intact[k]) {
                ASSERT_EQ(run[0].w[k], 0.0) << name << " broken bond " << k;
            }
        }
        const auto [wmax, err] = largest_and_error(run[0]);
        EXPECT_GT(wmax, 0.0) << name;
        EXPECT_LT(err, 1e-12 * wmax) << name;
        std::printf("%-28s largest w %.3e J/m^6, largest difference from the reference %.2e of it\n", name, wmax, err / wmax);
    };
    check(make_corr<3>(0.02)(body, b), "correspondence");
    check(make_corr<3>(0.0)(body, b), "correspondence, no hourglass");
    check(make_corr<3>(0.02)(body, b), "correspondence, J_C ratios", true);
    // Peridigm's w (hourglass_work = false): the work of the forces without the hourglass term, which
    // are the forces of the same model with C_hg = 0 at the same deformations.
    Correspondence<3> no_hourglass = make_corr<3>(0.0)(body, b);
    check(make_corr<3>(0.02)(body, b), "correspondence, w without hourglass", false, &no_hourglass);
    check(make_lps(3, LPS::Params::WeightedVolume::intact, false)(body, b), "LPS");
    check(make_lps(3, LPS::Params::WeightedVolume::intact, false)(body, b), "LPS, J_C ratios", true);
    check(make_pals(body, b), "PALS");
    // History models: yield at strain A/(3G) ~ 2e-7 (every node flows under the 1e-3 loading);
    // viscoelastic LPS with tau_b = the step, gamma_b = 1.
    const laws::JohnsonCook law{.A = 5e4, .B = 1e8, .n = 0.71};
    check(PlasticLPS({.material = steel, .dim = 3}, b, law), "plastic LPS");
    check(PlasticPALS({.material = steel}, body, b, law), "plastic PALS");
    check(PlasticCorrespondence({steel, Correspondence<3>::Law::linear, 0.02}, body, b, law), "plastic correspondence");
    check(ViscoelasticLPS({{.material = steel, .dim = 3}, 1.0, step_s}, b), "viscoelastic LPS");
}

// An independent reference (closed form, no call of the code under test): correspondence, linear law,
// on the affine path y(s) = (I + s H) x, s = 0 .. 1. F_i = I + s H exactly at every node whose K is
// regular, whatever its family, so P_i = sigma(s) = s sigma_H (sigma_H = lambda tr(sym H) I + 2 G sym H)
// and the hourglass term vanishes (Y = F xi). The force density on i from bond k, f_k = omega_k V_k
// s sigma_H (K_i^-1 + K_j^-1) xi, is linear in s and dY = H xi ds, so the work of the pair is
//   w_ij = int_0^1 f_k . H xi ds / V_k = omega_k/2 (sigma_H (K_i^-1 + K_j^-1) xi) . (H xi),
// and the trapezoidal sum of the header is exact for any number of steps. K_i = sum over i's intact
// bonds of omega xi (x) xi V is summed here from the bond list; broken pairs keep w = 0.
// Tolerance 1e-10 of the largest w: F from the family sums carries round-off ~1e-15 against s H ~ 1e-3,
// i.e. ~1e-12 of w (measured 1.1e-12, printed by the test).
TEST(Micropotential, CorrespondenceWorkOfAnAffinePathIsTheClosedForm)
{
    using Mat = Eigen::Matrix3d;
    const auto body = loaded_box();
    Bonds b = cut_bonds(body);
    Mat H;
    H << 1.0e-3, 0.4e-3, -0.2e-3, -0.3e-3, 0.5e-3, 0.6e-3, 0.1e-3, -0.7e-3, -0.8e-3;
    const double K = steel.K, G = steel.G, lambda = K - 2 * G / 3;
    const Mat eps_H = 0.5 * (H + H.transpose());
    const Mat sigma_H = lambda * eps_H.trace() * Mat::Identity() + 2 * G * eps_H;
    auto xi_of = [&](std::size_t i, int j) {
        return Eigen::Vector3d(body.x.c[0][j] - body.x.c[0][i], body.x.c[1][j] - body.x.c[1][i], body.x.c[2][j] - body.x.c[2][i]);
    };
    std::vector<Mat> Kinv(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) {
        Mat Ki = Mat::Zero();
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            if (b.intact[k]) Ki += b.omega[k] * b.volume[k] * xi_of(i, b.partner[k]) * xi_of(i, b.partner[k]).transpose();
        ASSERT_GT(std::abs(Ki.determinant()), 1e-6 * std::pow(Ki.trace() / 3, 3)) << "node " << i << ": the closed form needs a regular K";
        Kinv[i] = Ki.inverse();
    }
    Correspondence<3> model = make_corr<3>(0.02)(body, b);
    CriticalMicropotential<3> mp;
    const int steps = 4;
    Field<3> f;
    for (int m = 0; m <= steps; ++m) {
        const double s = double(m) / steps;
        Field<3> y = body.x;
        for (std::size_t i = 0; i < body.size(); ++i)
            for (int a = 0; a < 3; ++a)
                for (int c = 0; c < 3; ++c) y.c[a][i] += s * H(a, c) * body.x.c[c][i];
        internal_force(model, b, y, f, mp.bond_work<Correspondence<3>>(b));
        mp.accumulate(model, b, y);
    }
    double wmax = 0, err = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            const Eigen::Vector3d xi = xi_of(i, j);
            const double w_ref = b.intact[k] ? 0.5 * b.omega[k] * (sigma_H * (Kinv[i] + Kinv[j]) * xi).dot(H * xi) : 0.0;
            wmax = std::max(wmax, std::abs(w_ref));
            err = std::max(err, std::abs(mp.work(b, k) - w_ref));
        }
    EXPECT_GT(wmax, 0.0);
    EXPECT_LT(err, 1e-10 * wmax);
    std::printf("affine path: largest w %.3e J/m^6, largest difference from the closed form %.2e of it\n", wmax, err / wmax);
}

// 2D correspondence takes the generic bond pass (the AVX2 family kernel is 3D only): w with and
// without the hourglass work against the same references as above, tolerance as above.
TEST(Micropotential, TwoDimensionalCorrespondenceWithAndWithoutHourglassWork)
{
    const auto body = box<2>({{0, 0}}, {{9 * dx, 8 * dx}}, dx, 1e-3);
    Bonds b = build_bonds(body, m_ratio * dx);
    b.enable_damage();
    for (std::size_t k = 0; k < b.size(); k += 7) b.break_pair(k);
    Correspondence<2> no_hourglass = make_corr<2>(0.0)(body, b);
    for (bool hourglass_work : {true, false}) {
        CriticalMicropotential<2> mp;
        mp.hourglass_work = hourglass_work;
        const Loading run = random_loading(make_corr<2>(0.02)(body, b), body, b, mp, hourglass_work ? nullptr : &no_hourglass);
        const auto [wmax, err] = largest_and_error(run);
        EXPECT_GT(wmax, 0.0);
        EXPECT_LT(err, 1e-12 * wmax) << "hourglass work " << hourglass_work;
    }
}

// With w_C at the median w of the intact bonds, apply() breaks exactly the intact bonds whose pair
// has w >= w_C, both halves, and returns their number (correspondence: the per-node largest w that
// lets apply skip nodes comes from the AVX2 kernel and its scalar tail).
TEST(Micropotential, BreaksExactlyThePairsAtOrAboveCritical)
{
    const auto body = loaded_box();
    Bonds b = cut_bonds(body);
    CriticalMicropotential<3> mp;
    mp.w_c = 1e300;
    const Loading run = random_loading(make_corr<3>(0.02)(body, b), body, b, mp);
    std::vector<double> w;
    for (std::size_t k = 0; k < b.size(); ++k)
        if (b.intact[k]) w.push_back(run.w[k]);
    std::nth_element(w.begin(), w.begin() + w.size() / 2, w.end());
    mp.w_c = w[w.size() / 2];
    const std::vector<std::uint8_t> before = b.intact;
    long expected = 0;
    for (std::size_t k = 0; k < b.size(); ++k) expected += before[k] && run.w[k] >= mp.w_c;
    ASSERT_GT(expected, 0);
    EXPECT_EQ(mp.apply(b), expected);
    for (std::size_t k = 0; k < b.size(); ++k) {
        ASSERT_EQ(b.intact[k], before[k] && run.w[k] < mp.w_c) << "bond " << k;
    }
}

// A body whose horizon holds no partner: Explicit's first apply() (before any force pass) and the
// steps run without reading per-node data that does not exist yet (that read crashed), and the body
// counts as damaged although it has no bond to flag.
TEST(Micropotential, BodyWithoutBondsRuns)
{
    const auto body = box<3>({{0, 0, 0}}, {{2 * dx, 2 * dx, 2 * dx}}, dx);
    Bonds b = build_bonds(body, 0.5 * dx);
    ASSERT_EQ(b.size(), 0u);
    b.enable_damage();
    ExplicitPMBMicropotential run(body, b, 1.0);
    run.ex.start();
    for (int n = 0; n < 3; ++n) run.ex.step(1e-8);
    EXPECT_TRUE(b.has_damage());
}
