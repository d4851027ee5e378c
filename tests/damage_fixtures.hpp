// Fixtures of the damage tests (test_damage_models.cpp, test_damage_energy.cpp, test_micropotential*.cpp):
// the 1D/2D/3D blocks, broken-pair predicates, the random small deformation, round-off comparisons, the
// model makers, an Explicit PMB body with micropotential damage and the "damaged body equals the body
// built from scratch" checks. Round-off tolerance
// (all comparisons): 1e-12 of the largest value (reasons in test_damage_models.cpp).
#pragma once

#include "pd/bond_loop.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <random>

namespace pd_test {

using namespace pd;

inline constexpr double dx = 1e-3;       // lattice spacing [m]
inline constexpr double m_ratio = 3.05;  // delta / dx
inline constexpr double roundoff = 1e-12;
inline const Elastic steel = Elastic::from_E_nu(200e9, 0.3);
using Broken = std::function<bool(int, int)>;  // symmetric pair predicate

template <int D>
Body<D> block()
{
    if constexpr (D == 3) return box<3>({{0, 0, 0}}, {{7 * dx, 6 * dx, 5 * dx}}, dx);
    else if constexpr (D == 2) return box<2>({{0, 0}}, {{12 * dx, 10 * dx}}, dx, 1e-3);
    else return box<1>({{0}}, {{60 * dx}}, dx, 1e-6);
}

// About `percent` % of the pairs (hash of the unordered pair) plus every bond of node `lonely`.
inline Broken random_pairs(int lonely, int percent = 20)
{
    return [lonely, percent](int i, int j) {
        if (i == lonely || j == lonely) return true;
        std::uint64_t h = std::uint64_t(std::min(i, j)) * 1000003u + std::uint64_t(std::max(i, j));
        h ^= h >> 33; h *= 0xff51afd7ed558ccdULL; h ^= h >> 33; h *= 0xc4ceb9fe1a85ec53ULL; h ^= h >> 33;
        return static_cast<int>(h % 100) < percent;
    };
}
// Bonds crossing the plane x = cut.
template <int D>
Broken plane_cut(const Body<D>& body, double cut)
{
    return [&body, cut](int i, int j) { return (body.x.c[0][i] - cut) * (body.x.c[0][j] - cut) < 0; };
}

inline void mark(Bonds& b, const Broken& broken)
{
    b.enable_damage();
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            if (broken(static_cast<int>(i), b.partner[k])) b.intact[k] = 0;
}

// y = x + eps A x + noise: a random small deformation (eps = 1e-3, noise 1e-4 dx).
template <int D>
Field<D> deformed(const Body<D>& body, unsigned seed)
{
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> U(-1, 1);
    double A[3][3];
    for (auto& r : A) for (double& a : r) a = 1e-3 * U(gen);
    Field<D> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int a = 0; a < D; ++a) {
            for (int c = 0; c < D; ++c) y.c[a][i] += A[a][c] * body.x.c[c][i];
            y.c[a][i] += 1e-4 * dx * U(gen);
        }
    return y;
}

template <int D>
double max_abs(const Field<D>& f)
{
    double r = 0;
    for (int d = 0; d < D; ++d) for (double v : f.c[d]) r = std::max(r, std::abs(v));
    return r;
}
template <int D>
void expect_fields_near(const Field<D>& a, const Field<D>& b, const char* what)
{
    const double tol = roundoff * max_abs(b);
    for (int d = 0; d < D; ++d)
        for (std::size_t i = 0; i < b.size(); ++i) {
            ASSERT_TRUE(std::isfinite(a.c[d][i])) << what << " node " << i;
            ASSERT_NEAR(a.c[d][i], b.c[d][i], tol) << what << " node " << i << " component " << d;
        }
}
template <class V>
void expect_vectors_near(const V& a, const V& b, const char* what)
{
    ASSERT_EQ(a.size(), b.size());
    double scale = 0;
    for (double v : b) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < b.size(); ++i) ASSERT_NEAR(a[i], b[i], roundoff * scale) << what << " " << i;
}

template <class Model>
void after_damage(Model& model, const Bonds& b)
{
    if constexpr (requires { model.recompute(b); }) model.recompute(b);
}

// Rate form (Correspondence<3>, Law::flanagan_taylor): one update_stress from the reference x to y
// in a pseudo step dt = 1 (mid-step configuration, velocity y - x), as Explicit::start does; else nothing.
template <int D, class Model>
void advance_rate_form(Model& model, const Bonds& b, const Body<D>& body, const Field<D>& y)
{
    if constexpr (D == 3 && requires { model.par.law == Model::Law::flanagan_taylor; })
        if (model.par.law == Model::Law::flanagan_taylor) {
            Field<D> ym(body.size()), v(body.size());
            for (int d = 0; d < D; ++d)
                for (std::size_t i = 0; i < body.size(); ++i) {
                    ym.c[d][i] = 0.5 * (body.x.c[d][i] + y.c[d][i]);
                    v.c[d][i] = y.c[d][i] - body.x.c[d][i];
                }
            model.update_stress(b, ym, v, 1.0);
        }
}

// The model built on undamaged bonds, then the bonds marked broken (as in a run), against the model
// built on the bonds without them. extra(damaged_model, scratch_model) compares per-node state.
template <int D, class Make, class Extra>
void expect_same_as_scratch(const Body<D>& body, const Broken& broken, Make make, Extra extra, int lonely = -1)
{
    const double delta = m_ratio * dx;
    Bonds scratch = build_bonds(body, delta, BondOptions{.keep = [&](int i, int j) { return !broken(i, j); }});
    Bonds damaged = build_bonds(body, delta);
    auto md = make(body, damaged);
    mark(damaged, broken);
    after_damage(md, damaged);
    auto ms = make(body, scratch);
    const Field<D> y = deformed(body, 7);
    advance_rate_form(md, damaged, body, y);
    advance_rate_form(ms, scratch, body, y);
    Field<D> fd, fs;
    internal_force(md, damaged, y, fd);
    internal_force(ms, scratch, y, fs);
    expect_fields_near(fd, fs, "force");
    extra(md, ms);
    if (lonely >= 0) {
        for (int d = 0; d < D; ++d) EXPECT_EQ(fd.c[d][lonely], 0.0) << "isolated node";
    }
}

// A plane of broken bonds at x = 4 dx (between node layers): moving half B (x > cut) rigidly leaves the forces on half
// A bit-identical, and each half equals the half built alone (nodes renumbered in order).
template <int D, class Make>
void expect_cut_halves_independent(const Body<D>& body, Make make)
{
    const double delta = m_ratio * dx, cut = 4 * dx;
    Bonds b = build_bonds(body, delta);
    auto model = make(body, b);
    mark(b, plane_cut(body, cut));
    after_damage(model, b);
    const Field<D> y = deformed(body, 11);
    Field<D> y2 = y;  // half B rotated by 0.2 rad about the x3 axis and shifted by 0.3 dx
    const double c = std::cos(0.2), s = std::sin(0.2);
    for (std::size_t i = 0; i < body.size(); ++i)
        if (body.x.c[0][i] > cut) {
            const double a = y.c[0][i], q = y.c[1][i];
            y2.c[0][i] = c * a - s * q + 0.3 * dx;
            y2.c[1][i] = s * a + c * q;
        }
    Field<D> f, f2;
    internal_force(model, b, y, f);
    internal_force(model, b, y2, f2);
    for (int half = 0; half < 2; ++half) {
        Body<D> part;
        part.dx = body.dx;
        part.measure = body.measure;
        std::vector<int> nodes;
        for (std::size_t i = 0; i < body.size(); ++i)
            if ((body.x.c[0][i] > cut) == (half == 1)) { nodes.push_back(static_cast<int>(i)); part.push(body.x[i], body.volume[i]); }
        Bonds pb = build_bonds(part, delta);
        auto pm = make(part, pb);
        Field<D> py(nodes.size()), pf, sub(nodes.size());
        for (std::size_t n = 0; n < nodes.size(); ++n) {
            py.set(n, y[nodes[n]]);
            sub.set(n, f[nodes[n]]);
            if (half == 0) {
                for (int d = 0; d < D; ++d) {
                    ASSERT_EQ(f2.c[d][nodes[n]], f.c[d][nodes[n]]) << "half A node " << nodes[n];
                }
            }
        }
        internal_force(pm, pb, py, pf);
        expect_fields_near(sub, pf, half == 0 ? "half A alone" : "half B alone");
    }
}

inline auto make_pmb(int dim)
{
    return [dim](const auto& body, const Bonds& b) { return PMB({steel, dim, Plane::stress, body.measure}, b); };
}
inline auto make_lps(int dim, LPS::Params::WeightedVolume rule, bool scf)
{
    return [=](const auto& body, const Bonds& b) {
        LPS lps({steel, dim, Plane::strain, rule}, b);
        if (scf) lps.apply_shear_correction(body.x);
        return lps;
    };
}
inline auto lps_state = [](const LPS& d, const LPS& s) {
    expect_vectors_near(d.m, s.m, "m");
    expect_vectors_near(d.theta, s.theta, "theta");
    expect_vectors_near(d.alpha, s.alpha, "alpha");
    expect_vectors_near(d.scf, s.scf, "SCF");
};
inline auto make_pals = [](const Body<3>& body, const Bonds& b) { return PALS({steel}, body, b); };
template <int D>
auto make_corr(double C_hg)
{
    return [C_hg](const Body<D>& body, const Bonds& b) {
        return Correspondence<D>({steel, Correspondence<D>::Law::linear, C_hg, Plane::strain, body.measure}, body, b);
    };
}
template <int D>
void corr_state(const Correspondence<D>& d, const Correspondence<D>& s)
{
    for (std::size_t i = 0; i < s.F.size(); ++i) {
        ASSERT_LE((d.Kinv[i] - s.Kinv[i]).norm(), roundoff * s.Kinv[i].norm()) << "K^-1 node " << i;
        ASSERT_LE((d.F[i] - s.F[i]).norm(), roundoff) << "F node " << i;
    }
}
inline auto no_state = [](const auto&, const auto&) {};

// A steel PMB body in Explicit with critical-micropotential damage at w_C (test_micropotential*.cpp).
struct ExplicitPMBMicropotential {
    PMB pmb;
    CriticalMicropotential<3> mp;
    Explicit<3, PMB> ex;
    ExplicitPMBMicropotential(const Body<3>& body, Bonds& b, double w_c) : pmb({steel, 3}, b), ex(body, b, pmb, 7850)
    {
        mp.w_c = w_c;
        ex.scene.set_damage(mp);
    }
};

}  // namespace pd_test
