// Adaptive refinement during a fracture run (time/adaptive_refinement.hpp, spec/002 sec. 4.1-4.8):
// V6d (the damage trigger's roll-back: no bond of a level-0 node breaks), the transfer of u and v onto
// new nodes (linear fields exactly, never across the pre-crack: V6c in the run), refine_around
// (Alg. A.3) and the per-horizon critical stretch of dual families. References: the pre-crack geometry
// and linear fields written out in the tests; the same run without the damage trigger, which does
// break level-0 bonds (so the V6d check can fail); s0(delta) of eq. 2.15b.
#include "pd/core/parallel.hpp"
#include "pd/core/refinement.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/time/adaptive_refinement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

namespace {
constexpr double h0 = 0.5e-3, L = 20e-3, H = 10e-3, m = 3;  // soda-lime plate of 40 x 20 cells
constexpr double E = 72e9, rho = 2440, Gc = 135;

pd::RefinedGrid<2> grid() { return pd::RefinedGrid<2>(pd::box<2>({{0, 0}}, {{L, H}}, h0), m * h0); }

// The plate with an edge pre-crack to its centre, pulled apart by sigma [Pa] on its top and bottom rows.
pd::AdaptiveScene<2> scene(double sigma)
{
    pd::AdaptiveScene<2> s;
    s.pmb = {.material = pd::Elastic::from_E_nu(E, 1.0 / 3), .dim = 2, .plane = pd::Plane::stress};
    s.rho = rho;
    s.s0 = [](double delta) { return pd::s0_pmb(Gc, E, delta, 2, pd::Plane::stress); };
    s.cut = pd::segment_crossing({{-h0, H / 2}}, {{L / 2, H / 2}});
    s.boundary = [sigma](const pd::Body<2>& b) {
        pd::Boundary<2> bc;
        bc.traction(pd::select(b, pd::in_box<2>({{-1, H - h0}}, {{1, 1}}), "top"), {{0, sigma}}, h0);
        bc.traction(pd::select(b, pd::in_box<2>({{-1, -1}}, {{1, h0}}), "bottom"), {{0, -sigma}}, h0);
        return bc;
    };
    return s;
}

// Broken bonds (other than the pre-crack's) with an end at a level below `levels`.
long coarse_breaks(const pd::AdaptiveFracture<2>& run, int levels)
{
    const pd::Bonds& b = run.bonds();
    const auto cut = pd::segment_crossing({{-h0, H / 2}}, {{L / 2, H / 2}});
    long n = 0;
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            if (b.intact[k] || cut(run.body().x[std::min<int>(i, j)], run.body().x[std::max<int>(i, j)])) continue;
            n += run.grid().level[run.ids()[i]] < levels || run.grid().level[run.ids()[j]] < levels;
        }
    return n;
}

// The windowed update gives the families of a whole-grid build, bit for bit.
void expect_whole_grid_families(const pd::AdaptiveFracture<2>& run)
{
    const pd::HorizonFamilies full = pd::build_variable_horizon_bonds(run.body(), run.grid().active_delta(), run.grid().active_h(),
                                                                     pd::HorizonCoupling::dual, pd::PartialVolume::pa_pdlammps);
    const pd::HorizonFamilies& f = run.families();
    EXPECT_EQ(f.bonds.offset, full.bonds.offset);
    EXPECT_EQ(f.bonds.partner, full.bonds.partner);
    EXPECT_EQ(f.bonds.reverse, full.bonds.reverse);
    EXPECT_EQ(f.bonds.length, full.bonds.length);
    EXPECT_EQ(f.bonds.volume, full.bonds.volume);
    EXPECT_EQ(f.share, full.share);
    EXPECT_EQ(f.delta, full.delta);
}

// The run for `steps` steps at a quarter of the finest grid's critical step; the largest coarse_breaks seen.
long run_crack(pd::AdaptiveFracture<2>& run, int levels, long steps)
{
    const double dt = 0.25 * run.critical_step() / (1 << levels);
    long worst = 0;
    for (long s = 0; s < steps; ++s) {
        run.step(dt);
        worst = std::max(worst, coarse_breaks(run, levels));
    }
    return worst;
}
}  // namespace

// V6d: with the damage trigger every bond that breaks has both ends at the finest level; without it
// the same crack breaks bonds of level-0 nodes (the check above is not vacuous). The families after
// the windowed updates are those of a whole-grid build.
TEST(AdaptiveRefinement, RollBackKeepsEveryBreakInTheFinestZone)
{
    for (int levels : {1, 2}) {
        pd::AdaptiveFracture<2> run(grid(), scene(60e6), {.levels = levels, .m_level = {}, .energy_fraction = 0});
        EXPECT_EQ(run_crack(run, levels, 900), 0) << levels << " levels";
        EXPECT_GT(run.broken_bonds(), 100) << "the crack must run for the test to mean anything";
        EXPECT_GT(run.stats().rollbacks, 0);
        EXPECT_GT(run.body().size(), run.stats().nodes_initial);
        EXPECT_GT(run.stats().updates, 2);
        expect_whole_grid_families(run);
    }
    pd::AdaptiveFracture<2> plain(grid(), scene(60e6), {.levels = 1, .m_level = {}, .energy_fraction = 0, .damage_trigger = false});
    EXPECT_GT(run_crack(plain, 1, 900), 0);
    EXPECT_EQ(plain.body().size(), plain.stats().nodes_initial);
}

// V6c in the run: u and v of new nodes are the linear fields of their side of the pre-crack exactly,
// though the two sides carry different fields; nodes that stay keep their u, v and broken bonds.
TEST(AdaptiveRefinement, TransferReproducesLinearFieldsWithoutCrossingTheCrack)
{
    pd::AdaptiveFracture<2> run(grid(), scene(0), {.levels = 2, .m_level = {}, .energy_fraction = 0});
    auto field = [](const pd::Vec<2>& x, int d, double scale) {  // a different linear field above and below
        const bool above = x[1] > H / 2;
        return scale * (above ? 1e-6 + 2e-4 * x[0] - 3e-4 * x[1] : -2e-6 + (d ? 5e-4 : -1e-4) * x[0] + 1e-4 * x[1]);
    };
    auto& sim = run.sim();
    for (std::size_t i = 0; i < run.body().size(); ++i)
        for (int d = 0; d < 2; ++d) sim.u.c[d][i] = field(run.body().x[i], d, 1), sim.v.c[d][i] = field(run.body().x[i], d, 1e3);
    pd::Bonds& bonds = run.sim().scene.bonds;  // a broken corner node, far from the refinement: stays broken
    for (std::int64_t k = bonds.begin(0); k < bonds.end(0); ++k) bonds.intact[k] = bonds.intact[bonds.reverse[k]] = 0;
    const std::size_t before = run.body().size();
    const int mid_crack = 20 * 40 / 2 + 10;  // row 10 (just above the pre-crack), column 10 (x = L/4 + h0/2)
    EXPECT_GT(run.refine({mid_crack}), 0);
    ASSERT_GT(run.body().size(), before);
    int near_crack = 0;
    for (std::size_t i = 0; i < run.body().size(); ++i) {
        const pd::Vec<2> x = run.body().x[i];
        near_crack += std::abs(x[1] - H / 2) < h0 && run.grid().level[run.ids()[i]] > 0;
        for (int d = 0; d < 2; ++d) {  // bounds: round-off of the least-squares fit, ~1e-12 of the fields (1e-6 m, 1e-3 m/s)
            EXPECT_NEAR(run.sim().u.c[d][i], field(x, d, 1), 1e-18) << i;
            EXPECT_NEAR(run.sim().v.c[d][i], field(x, d, 1e3), 1e-15) << i;
        }
    }
    EXPECT_GT(near_crack, 8);
    ASSERT_EQ(run.ids()[0], 0);
    EXPECT_EQ(run.damage()[0], 1.0);
}

// Alg. A.3: refine_around splits the level-0 zone of the given node and, for two levels, the level-1
// zone of its children only; a second call on the same node splits nothing (needs_refinement says
// so); a margin of one cell widens the zone to 4 h0; the interface horizon comes back to the nominal
// one on nodes that are no longer at an interface.
TEST(AdaptiveRefinement, RefineAroundIsTheNestedZoneOfTheNode)
{
    pd::RefinedGrid<2> g = grid();
    const int q = 10 * 40 + 20;  // an interior level-0 node (row 10, column 20)
    const int split = g.refine_around({q}, 2, pd::Refinement::delta);
    int level1 = 0, level0_split = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (g.level[i] == 0 && !g.active[i]) {
            ++level0_split;
            EXPECT_LE(norm(g.x[i] - g.x[q]), m * h0 * (1 + 1e-12));
        }
        if (g.level[i] == 1 && !g.active[i]) {
            ++level1;
            double d = 1e9;
            for (int c = 0; c < 4; ++c) d = std::min(d, norm(g.x[i] - g.x[g.first_child[q] + c]));
            EXPECT_LE(d, m * h0 / 2 * (1 + 1e-12));
        }
    }
    EXPECT_EQ(level0_split, 29);  // lattice points in a disc of radius 3 h0
    EXPECT_EQ(split, level0_split + level1);
    EXPECT_EQ(g.refine_around({q}, 2, pd::Refinement::delta), 0);
    EXPECT_FALSE(g.needs_refinement({q}, 2));
    EXPECT_TRUE(g.needs_refinement({q + 4}, 1));  // its zone reaches one column beyond the refined disc
    pd::RefinedGrid<2> wide = grid();  // a margin of one cell: the lattice points within 4 h0
    wide.refine_around({q}, 1, pd::Refinement::delta, {}, 1.0);
    EXPECT_EQ(static_cast<int>(wide.size() - 800) / 4, 49);
    g.interface_horizon(m);
    const std::vector<double> first = g.delta;
    g.refine_around({q + 3, q - 3}, 1, pd::Refinement::delta);  // the zone grows; old interface nodes become interior
    g.interface_horizon(m);
    int restored = 0;
    for (std::size_t i = 0; i < first.size(); ++i)
        if (g.active[i] && g.level[i] > 0 && first[i] != g.nominal[i] && g.delta[i] == g.nominal[i]) ++restored;
    EXPECT_GT(restored, 0);
}

// Dual families: the pair critical stretch is s0(delta) where every horizon is delta, and between the
// two horizons' s0 at a refined interface.
TEST(AdaptiveRefinement, PairCriticalStretchFollowsTheHorizons)
{
    pd::RefinedGrid<2> g = grid();
    g.refine_around({5 * 40 + 5}, 1, pd::Refinement::delta);
    const pd::Body<2> body = g.body();
    const pd::HorizonFamilies f = pd::build_variable_horizon_bonds(body, g.active_delta(), g.active_h(), pd::HorizonCoupling::dual,
                                                                  pd::PartialVolume::pa_pdlammps);
    const pd::PMB::Params p{.material = pd::Elastic::from_E_nu(E, 1.0 / 3), .dim = 2};
    auto c_of = [&](double d) { return pd::PMB::micromodulus(p, pd::Influence{}, d); };
    auto s0_of = [](double d) { return pd::s0_pmb(Gc, E, d, 2, pd::Plane::stress); };
    const std::vector<double> s0 = pd::pair_critical_stretch(f, c_of, s0_of);
    int mixed = 0;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (std::int64_t k = f.bonds.begin(i); k < f.bonds.end(i); ++k) {
            const double di = f.delta[i], dj = f.delta[f.bonds.partner[k]];
            EXPECT_EQ(s0[k], s0[f.bonds.reverse[k]]);
            if (di == dj) {  // bound: round-off of the weighted mean of two equal values (s0 ~ 1e-3)
                EXPECT_NEAR(s0[k], s0_of(di), 1e-15);
            }
            if (di != dj) {
                ++mixed;
                EXPECT_GE(s0[k], std::min(s0_of(di), s0_of(dj)) * (1 - 1e-14));
                EXPECT_LE(s0[k], std::max(s0_of(di), s0_of(dj)) * (1 + 1e-14));
            }
        }
    EXPECT_GT(mixed, 0);
}

// The run does not depend on the thread count: the same grid updates, nodes, broken bonds and
// displacements, bit for bit, with one and two threads.
TEST(AdaptiveRefinement, RunIsTheSameForAnyThreadCount)
{
    auto crack_run = [](int threads) {
        pd::set_threads(threads);
        pd::AdaptiveFracture<2> run(grid(), scene(60e6), {.levels = 1, .m_level = {}, .energy_fraction = 0.7});
        run_crack(run, 1, 300);
        return std::tuple{run.stats().updates, run.body().size(), run.broken_bonds(), run.sim().u.c[0], run.sim().u.c[1]};
    };
    const auto one = crack_run(1), two = crack_run(2);
    pd::set_threads(0);
    EXPECT_GT(std::get<0>(one), 1);
    EXPECT_EQ(one, two);
}

// Method B on a lattice rotated by 10 deg: the children sit at the sub-cell centres along the rotated
// axes, so a split block of cells is the rotated lattice of half the spacing (nearest neighbours at
// h/2 exactly, each child h/4 (sqrt 2) from its parent), with the volume kept.
TEST(AdaptiveRefinement, RotatedLatticeSplitsAlongItsAxes)
{
    const double theta = 10 * 3.14159265358979323846 / 180, c = std::cos(theta), s = std::sin(theta);
    pd::Body<2> body;
    body.dx = h0;
    for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i) body.push({{c * i * h0 - s * j * h0, s * i * h0 + c * j * h0}}, h0 * h0);
    pd::RefinedGrid<2> g(body, m * h0, theta);
    std::vector<int> all(36);
    for (int i = 0; i < 36; ++i) all[i] = i;
    g.split(all, pd::Refinement::delta);
    double volume = 0;  // bounds: round-off of lengths of 1e-4 m (a few ulps) and of the volume sum
    for (std::size_t i = 36; i < g.size(); ++i) {
        volume += g.volume[i];
        EXPECT_NEAR(norm(g.x[i] - g.x[g.parent[i]]), h0 / 4 * std::sqrt(2.0), 1e-15);
        const pd::Vec<2> d = g.x[i] - g.x[g.parent[i]];  // along the rotated diagonals: |d . axis| = h0/4
        EXPECT_NEAR(std::abs(c * d[0] + s * d[1]), h0 / 4, 1e-15);
        double nearest = 1e9;
        for (std::size_t j = 36; j < g.size(); ++j)
            if (j != i) nearest = std::min(nearest, norm(g.x[j] - g.x[i]));
        EXPECT_NEAR(nearest, h0 / 2, 1e-15);
    }
    EXPECT_NEAR(volume, 36 * h0 * h0, 1e-18);
    EXPECT_THROW(pd::RefinedGrid<3>(pd::box<3>({{0, 0, 0}}, {{2 * h0, 2 * h0, 2 * h0}}, h0), m * h0, 0.1), std::invalid_argument);
}
