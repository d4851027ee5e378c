// pd/time/adaptive_refinement.hpp -- adaptive grid refinement and scaling (AGRS, spec/002 sec. 4.1-4.8)
// of an explicit bond-based PMB fracture run: a coarse grid (RefinedGrid, core/refinement.hpp) is
// refined during the run where a trigger fires, with the horizon scaled to the new spacing.
// Each step at t >= t_start (sec. 4.1):
//   1. damage trigger (sec. 4.3): the step is taken; if bonds broke, their end nodes are mapped to
//      their level-0 ancestors (V6f) and the zone around them is refined (refine_around, Alg. A.3).
//      If that split any node, the step is undone (u, v, bond states, t of the step before), the grid
//      updated on that state, and the step repeated; so bonds break only where the grid is already as
//      fine as the zone rule makes it: never a bond of a level-0 node when levels >= 1 (V6d).
//   2. energy trigger (sec. 4.2), every energy_every steps: the nodes with W >= alpha W_max (W the
//      strain energy density, W_max its current maximum) are mapped to level-0 ancestors and refined
//      around, on the current state.
// A grid update (sec. 4.6-4.8): the interface horizon m d_min (when interface_m > 0); the dual-horizon
// families with PA-PDLAMMPS (or the given) partial volumes (core/variable_horizon.hpp), so the
// refined interface has no ghost forces; c per horizon (PMB::micromodulus of delta_i, horizon_factors)
// and s0 per horizon (the caller's s0(delta), pair_critical_stretch); bond states: a pair that existed
// keeps its state, a new pair is intact unless it crosses the pre-crack (the caller's cut); u and v
// of a new node by linear moving least squares (core/mls.hpp) over its nearest ancestor that was a
// node, and that node's partners over intact bonds (never across a crack, V6c); a node that stays
// keeps its u and v. The acceleration is not interpolated: the integrator restarts on the new grid
// (Explicit::start at the same t), which computes a = (f(u) + b)/rho, the equation of motion at the
// transferred u (the source interpolates a as well); the damage rule is attached after that start, so a
// bond the transferred state over-stretches breaks in the next step, under the damage trigger.
// Bonds are rebuilt in a window (sec. 4.7 suggests it; the source rebuilt the whole grid): only the
// nodes within the largest reach of a node that appeared, disappeared or changed its horizon search
// their families again; every other family is copied with its bond states (FamilyReuse,
// core/variable_horizon.hpp), which gives the whole-grid families exactly. The update's cost is
// measured apart from stepping (stats().wall_update). Refinement is permanent (no coarsening).
// Initial damage phi0_i: the fraction of i's family volume cut by the pre-crack (the Delta phi of
// sec. 4.3 is read here as "a bond broke during the step", which is exact and needs no phi0).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/mls.hpp"
#include "pd/core/refinement.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/variable_horizon.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <stdexcept>
#include <vector>

namespace pd {

struct AdaptiveOptions {
    int levels = 1;                      // level_max (>= 1)
    Refinement rule = Refinement::delta; // horizon of a child (sec. 4.6)
    std::function<double(int)> m_level;  // delta_m: m of level l
    double t_start = 0;                  // t_st: the triggers act from here [s]
    double energy_fraction = 0.7;        // alpha_W of the energy trigger; 0: no energy trigger
    long energy_every = 1;               // steps between energy-trigger checks (>= 1)
    bool damage_trigger = true;          // the damage trigger with its roll-back
    double interface_m = 3;              // interface horizon m d_min; 0: none
    double zone_margin = 0;              // cells added to each refinement zone (ours; 0: the source's zone)
    PartialVolume partial_volume = PartialVolume::pa_pdlammps;
};

// What the caller supplies for every grid the run builds.
template <int D>
struct AdaptiveScene {
    PMB::Params pmb;                                           // material, dim, plane, measure
    double rho = 0;                                            // density [kg/m^3]
    std::function<double(double delta)> s0;                   // critical stretch of a horizon [-]
    std::function<bool(const Vec<D>&, const Vec<D>&)> cut;     // the bond p - q crosses the pre-crack (precrack.hpp; empty: none)
    std::function<Boundary<D>(const Body<D>&)> boundary;       // loads and constraints of a body (empty: free)
    std::function<NodeSet(const Body<D>&)> no_fail;            // nodes whose bonds never break (empty: none)
};

struct AdaptiveStats {
    long updates = 0;             // grid updates
    long rollbacks = 0;           // steps repeated after a damage-triggered update
    std::size_t nodes_initial = 0;
    double wall_update = 0;       // refining, rebuilding the bonds, transferring, restarting [s]
};

template <int D>
class AdaptiveFracture {
public:
    AdaptiveFracture(RefinedGrid<D> grid, AdaptiveScene<D> scene, AdaptiveOptions opt)
        : grid_(std::move(grid)), scene_(std::move(scene)), opt_(std::move(opt))
    {
        if (opt_.levels < 1) throw std::invalid_argument("adaptive refinement: at least one level");
        if (opt_.energy_every < 1) throw std::invalid_argument("adaptive refinement: energy_every must be >= 1");
        if (opt_.rule == Refinement::delta_m && !opt_.m_level) throw std::invalid_argument("adaptive refinement: delta_m needs m_level");
        if (!(scene_.rho > 0) || !scene_.s0) throw std::invalid_argument("adaptive refinement: a density and s0(delta) are needed");
        stats_.nodes_initial = grid_.ids().size();
        State none;
        rebuild(none);
    }

    // Refines around level-0 nodes now, on the current state (tests, a refinement known in advance).
    int refine(const std::vector<int>& level0)
    {
        io::Timer timer;
        const int split = refine_around(level0);
        if (split > 0) rebuild(save(true));
        stats_.wall_update += timer.seconds();
        return split;
    }

    // One step of dt [s] with the triggers (header).
    void step(double dt)
    {
        const bool armed = sim_->t + dt >= opt_.t_start;
        for (;;) {
            const State before = armed && opt_.damage_trigger ? save(true) : State{};
            const long broke_before = sim_->broken_bonds;
            sim_->step(dt);
            if (!armed || !opt_.damage_trigger || sim_->broken_bonds == broke_before) break;
            io::Timer timer;
            std::vector<int> hit;
            const Bonds& b = fam_.bonds;
            for (std::size_t i = 0; i < b.nodes(); ++i)
                for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
                    if (before.intact[k] && !b.intact[k]) {
                        hit.push_back(grid_.ancestor(ids_[i]));
                        break;
                    }
            const int split = refine_around(hit);
            if (split > 0) rebuild(before), ++stats_.rollbacks;
            stats_.wall_update += timer.seconds();
            if (split == 0) break;
        }
        if (armed && opt_.energy_fraction > 0 && sim_->step_count % opt_.energy_every == 0) energy_trigger();
    }

    const RefinedGrid<D>& grid() const { return grid_; }
    const Body<D>& body() const { return body_; }
    const Bonds& bonds() const { return fam_.bonds; }
    const HorizonFamilies& families() const { return fam_; }
    const std::vector<int>& ids() const { return ids_; }        // grid node of each body node
    const std::vector<double>& initial_damage() const { return phi0_; }
    std::vector<double> damage() const { return point_damage(fam_.bonds); }
    Explicit<D, PMB>& sim() { return *sim_; }
    const Explicit<D, PMB>& sim() const { return *sim_; }
    long broken_bonds() const { return broken_base_ + sim_->broken_bonds; }  // ordered bonds broken in the run
    double critical_step() const { return dt_crit_; }  // Silling-Askari, current families [s]
    // The broken bonds between two level-0 nodes of the current grid, the pre-crack's excluded
    // (ordered): none under the damage trigger with levels >= 1 (V6d); with the energy trigger alone,
    // the fracture that happened where no trigger refined.
    long coarse_bonds_broken() const
    {
        const Bonds& b = fam_.bonds;
        long n = 0;
        for (std::size_t i = 0; i < b.nodes(); ++i)
            if (grid_.level[ids_[i]] == 0)
                for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                    const int j = b.partner[k];
                    n += !b.intact[k] && grid_.level[ids_[j]] == 0 && !(scene_.cut && scene_.cut(body_.x[i], body_.x[j]));
                }
        return n;
    }
    const AdaptiveStats& stats() const { return stats_; }

private:
    struct State {  // of the current grid, between steps
        Field<D> u, v;
        std::vector<std::uint8_t> intact;
        double t = 0;
        long steps = 0, broken = 0;
        bool valid = false;
    };

    RefinedGrid<D> grid_;
    AdaptiveScene<D> scene_;
    AdaptiveOptions opt_;
    std::vector<int> ids_;
    Body<D> body_;
    HorizonFamilies fam_;
    PMB model_;
    CriticalStretch rule_;
    std::unique_ptr<Explicit<D, PMB>> sim_;
    std::vector<double> phi0_;
    std::vector<std::uint8_t> done_;  // per level-0 node: refined around already
    std::map<double, double> c_of_delta_;  // micromodulus per horizon [N/m^6 per unit thickness in 2D]
    long broken_base_ = 0;
    double dt_crit_ = 0;
    AdaptiveStats stats_;

    static std::vector<int> unique(std::vector<int> v)
    {
        std::sort(v.begin(), v.end());
        v.erase(std::unique(v.begin(), v.end()), v.end());
        return v;
    }

    // refine_around for the level-0 nodes not refined around before (it is idempotent: the grid only
    // gets finer), so a trigger that fires again where the grid is final costs no search. With a zone
    // margin, the zones are widened only when the source's zones need a split: the margin is then a
    // look-ahead that the next triggers find refined already.
    int refine_around(const std::vector<int>& level0)
    {
        done_.resize(stats_.nodes_initial, 0);
        std::vector<int> fresh;  // ancestors not refined around before
        for (int q : unique(level0))
            if (!done_.at(q)) fresh.push_back(q), done_[q] = 1;
        if (fresh.empty() || (opt_.zone_margin > 0 && !grid_.needs_refinement(fresh, opt_.levels))) return 0;
        return grid_.refine_around(fresh, opt_.levels, opt_.rule, opt_.m_level, opt_.zone_margin);
    }

    State save(bool with_bonds) const
    {
        State s{sim_->u, sim_->v, {}, sim_->t, sim_->step_count, broken_bonds(), true};
        if (with_bonds) s.intact = fam_.bonds.intact;
        return s;
    }

    void energy_trigger()
    {
        const std::vector<double> W = model_.energy_density(fam_.bonds, sim_->positions());
        const double W_max = *std::max_element(W.begin(), W.end());
        std::vector<int> hit;
        if (W_max > 0)
            for (std::size_t i = 0; i < W.size(); ++i)
                if (W[i] >= opt_.energy_fraction * W_max) hit.push_back(grid_.ancestor(ids_[i]));
        io::Timer update;
        if (refine_around(hit) > 0) rebuild(save(true));
        stats_.wall_update += update.seconds();
    }

    // The run on the grid's active nodes, from state s of the previous grid (invalid: the start).
    void rebuild(const State& s)
    {
        if (opt_.interface_m > 0) grid_.interface_horizon(opt_.interface_m);
        const std::vector<int> old_ids = std::exchange(ids_, grid_.ids());
        const Body<D> old_body = std::exchange(body_, grid_.body());
        const HorizonFamilies old = std::move(fam_);
        const std::vector<double> old_phi0 = std::move(phi0_);
        sim_.reset();
        std::vector<int> old_index(grid_.size(), -1);  // grid node -> index in the previous body
        for (std::size_t q = 0; q < old_ids.size(); ++q) old_index[old_ids[q]] = static_cast<int>(q);

        const std::vector<double> delta = grid_.active_delta();
        FamilyReuse reuse{&old, {}, {}};
        if (s.valid) window(reuse, old_ids, old_body, old.delta, old_index, delta);
        fam_ = build_variable_horizon_bonds(body_, delta, grid_.active_h(), HorizonCoupling::dual, opt_.partial_volume, s.valid ? &reuse : nullptr);
        Bonds& b = fam_.bonds;
        auto c_of = [this](double d) {  // memoised: one integral per horizon
            const auto it = c_of_delta_.find(d);
            return it != c_of_delta_.end() ? it->second : c_of_delta_[d] = PMB::micromodulus(scene_.pmb, Influence{}, d);
        };
        model_ = PMB(scene_.pmb, b);
        model_.scale_bonds(horizon_factors(fam_, c_of));
        rule_ = CriticalStretch::uniform(0);
        rule_.s0_bond = pair_critical_stretch(fam_, c_of, scene_.s0);
        if (scene_.no_fail) rule_.protect(scene_.no_fail(body_), body_.size());
        dt_crit_ = critical_step_silling_askari(b, scene_.rho, model_.coef).dt;

        // Bond states: kept pairs keep theirs, new pairs are cut by the pre-crack only; phi0: the cut
        // share (a kept family keeps both).
        b.enable_damage();
        phi0_.assign(body_.size(), 0.0);
        for (std::size_t i = 0; i < body_.size(); ++i) {
            const int oi = old_index[ids_[i]];
            if (s.valid && !reuse.affected[i]) {
                std::copy(s.intact.begin() + old.bonds.begin(oi), s.intact.begin() + old.bonds.end(oi), b.intact.begin() + b.begin(i));
                phi0_[i] = old_phi0[oi];
                continue;
            }
            double all = 0, cut = 0;
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                const int j = b.partner[k];
                const bool crosses = scene_.cut && scene_.cut(body_.x[std::min<int>(i, j)], body_.x[std::max<int>(i, j)]);  // one answer per pair
                all += b.volume[k], cut += crosses ? b.volume[k] : 0.0;
                b.intact[k] = !crosses;
                const int oj = old_index[ids_[j]];
                if (s.valid && oi >= 0 && oj >= 0) {
                    const auto first = old.bonds.partner.begin() + old.bonds.begin(oi), last = old.bonds.partner.begin() + old.bonds.end(oi);
                    const auto it = std::lower_bound(first, last, oj);
                    if (it != last && *it == oj) b.intact[k] = s.intact[it - old.bonds.partner.begin()];
                }
            }
            phi0_[i] = all > 0 ? cut / all : 0.0;
        }

        sim_ = std::make_unique<Explicit<D, PMB>>(body_, b, model_, scene_.rho);
        Explicit<D, PMB>& sim = *sim_;
        if (scene_.boundary) sim.boundary = scene_.boundary(body_);
        if (s.valid) transfer(s, old_body, old.bonds, old_index);
        broken_base_ = s.valid ? s.broken : 0;
        sim.t = s.t, sim.step_count = s.steps;
        sim.start();
        sim.scene.set_damage(rule_);  // after the start: every break happens in a step, where the damage trigger sees it
        ++stats_.updates;
    }

    // The window of an update (core/variable_horizon.hpp FamilyReuse): the nodes within the largest
    // reach of a node that appeared, disappeared or changed its horizon.
    void window(FamilyReuse& reuse, const std::vector<int>& old_ids, const Body<D>& old_body, const std::vector<double>& old_delta,
                const std::vector<int>& old_index, const std::vector<double>& delta)
    {
        const std::size_t n = body_.size();
        reuse.prev_index.assign(n, -1), reuse.affected.assign(n, 0);
        std::vector<Vec<D>> moved;  // where the node set or a horizon changed
        double reach = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const int oi = old_index[ids_[i]];
            reuse.prev_index[i] = oi;
            reach = std::max(reach, delta[i]);
            if (oi < 0 || old_delta[oi] != delta[i]) moved.push_back(body_.x[i]);
        }
        for (std::size_t q = 0; q < old_ids.size(); ++q) {
            reach = std::max(reach, old_delta[q]);
            if (!grid_.active[old_ids[q]]) moved.push_back(old_body.x[q]);
        }
        if (opt_.partial_volume == PartialVolume::exact_area)
            for (std::size_t i = 0; i < n; ++i) reach = std::max(reach, delta[i] + grid_.h[ids_[i]] * std::sqrt(0.5));
        reach *= 1 + 1e-6;
        const CellBins<D> bins(body_.x, reach);
        for (const Vec<D>& c : moved)
            bins.near(c, [&](int j) {
                if (norm(body_.x[j] - c) <= reach) reuse.affected[j] = 1;
            });
        for (std::size_t i = 0; i < n; ++i)
            if (reuse.prev_index[i] < 0) reuse.affected[i] = 1;
    }

    // u and v of the previous state onto the current nodes (header).
    void transfer(const State& s, const Body<D>& old_body, const Bonds& old_bonds, const std::vector<int>& old_index)
    {
        Explicit<D, PMB>& sim = *sim_;
        for (std::size_t i = 0; i < body_.size(); ++i) {
            int g = ids_[i];
            if (old_index[g] >= 0) {
                for (int d = 0; d < D; ++d) sim.u.c[d][i] = s.u.c[d][old_index[g]], sim.v.c[d][i] = s.v.c[d][old_index[g]];
                continue;
            }
            while (old_index[g] < 0) g = grid_.parent.at(g);  // the nearest ancestor that was a node
            const int p = old_index[g];
            std::vector<int> support{p};
            for (std::int64_t k = old_bonds.begin(p); k < old_bonds.end(p); ++k)
                if (s.intact[k]) support.push_back(old_bonds.partner[k]);
            double R = 0;
            for (int q : support) R = std::max(R, norm(old_body.x[q] - body_.x[i]));
            const std::vector<double> phi = mls_weights(old_body.x, support, body_.x[i], 1.25 * R + 1e-12 * grid_.h[g]);
            for (int d = 0; d < D; ++d) {
                double u = 0, v = 0;
                for (std::size_t q = 0; q < support.size(); ++q) u += phi[q] * s.u.c[d][support[q]], v += phi[q] * s.v.c[d][support[q]];
                sim.u.c[d][i] = u, sim.v.c[d][i] = v;
            }
        }
    }
};

}  // namespace pd
