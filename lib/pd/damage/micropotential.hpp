// Critical-micropotential damage (Foster et al. 2011; Biondani 2018 sec. 8.2; spec/000c sec. 2.3-2.5):
// a bond breaks for good when the work done on it, per unit volume of each end, reaches w_C:
//   w<xi> = w'<-xi> = int_0^t (T<xi> - T'<-xi>) . dY                     (000c eq. 8.16)
//   w >= w_C  =>  phi = 1                                                  (8.13)
//   3D  w_C = 4 J_C / (pi delta^4)   [J/m^6]                               (8.15)
//   2D  w_C = 3 J_C / (2 delta^3)    [J/m^5 per unit thickness]  [DERIVED here: the 2D analogue of
//       (8.14), J_C = w int_0^delta int_z^delta 2 xi acos(z/xi) dxi dz = 2 w delta^3 / 3]
// Increment of bond k = i->j over a step n -> n+1 (trapezoidal rule on the work integral):
//   d_k = 1/2 (g_k^n + g_k^{n+1}) . (Y_k^{n+1} - Y_k^n),   g_k = f_k / (beta V_j)  [N/m^6]
// with f_k the pair force density on i from bond k, both ends' states included (non-ordinary
// models such as correspondence: with the hourglass term by default; `hourglass_work = false`
// leaves it out, as Peridigm does, 000c sec. 2.3 [CODE]). For PMB this integrates exactly to
// w = c omega s^2 |xi| / 2.
// Since f_ji / (beta V_i) = -f_ij / (beta V_j) and Y_ji = -Y_ij, d_ij = d_ji up to round-off: each
// pair has ONE w, computed by its lower node i < j and kept on the bond i -> j (work(b, k) reads it
// from either half), so w_ij == w_ji by construction, whatever the number of threads (each entry
// has one writer). (Peridigm instead adds the owner's increment to the specular bond, sec. 3.7.1.)
// The increments are made inside the model's force pass (bond_loop.hpp, BondWork: the pass has f_k
// in registers and reads the previous pass's g_k and positions), so no force is evaluated twice and
// no second pass reads the bonds again.
// Cost (reports/3d/notched_plate.md, bench/damage_cost.cpp): per step, for the bonds i -> j
// with j > i, the record (g, w) of 1 + 1 or D + 1 doubles is read and written (one stream: with g
// and w in separate arrays the notched plate's step cost 10 % more); the breaking test reads the
// records of the nodes whose largest w (from the pass) reached w_C only. Correspondence, notched
// plate, per step before bonds break: 1.27-1.30x the stretch rule on the published grid.
// Temperature-dependent J_C (000c sec. 2.4, eqs. 8.21-8.23, V9): with per-node ratios
// r_i = J_C(theta_ref) / J_C(theta_i) set in `jc_ratio`, the increment is scaled by (r_i + r_j)/2 and
// compared with w_C(theta_ref): each end weighted by its own temperature as in (8.23).
// Thermal expansion (set_thermal_expansion with the model's ThermalExpansion and the reference
// positions): the work is that of the mechanical displacement, dY less the thermal bond displacement
// alpha dtheta_pair xi of the step, dtheta_pair the mean of the two ends' temperature changes since the
// previous pass (000c sec. 2.3 [CODE]: the thermal-expansion bond velocity is subtracted first), so a
// heated clamped bar stores its compression energy as w and a freely expanding one none.
// Singular nodes (000c sec. 2.5, the thesis' rule for correspondence): when a model exposes K^-1 and F
// per node, a node whose K is singular (K^-1 = 0, correspondence.hpp) or with det F <= 0 loses all
// its bonds at the next breaking pass.
// Usage (a scene, scene.hpp, does this): apply(bonds) before the force evaluation breaks bonds
// with w >= w_C; internal_force(model, bonds, y, f, mp.bond_work<Model>(bonds)) evaluates the forces
// and adds the step's increments; accumulate(model, bonds, y) then records y for the next step
// (without the bond_work call it runs the model's bond pass once more itself).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/damage/singular_nodes.hpp"
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/thermal_expansion.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

// Critical micropotential w_C from the critical J-integral J_C [J/m^2] and horizon delta [m].
inline double w_critical(double Jc, double delta, int dim = 3)
{
    if (dim == 3) return 4 * Jc / (std::numbers::pi * std::pow(delta, 4));  // 000c eq. 8.15
    if (dim == 2) return 1.5 * Jc / (delta * delta * delta);                // 2D analogue (header)
    throw std::invalid_argument("w_critical: dim must be 2 or 3");
}

template <int D>
struct CriticalMicropotential {
    double w_c = 0;                      // critical micropotential w_C(theta_ref) [J/m^6 in 3D]
    std::vector<std::uint8_t> no_fail;   // per node, 1 = bonds never break; empty = none
    std::vector<double> jc_ratio;        // per node J_C(theta_ref)/J_C(theta_i) [-]; empty = 1
    bool detach_singular = true;         // the singular-node rule (header), for models with Kinv and F
    bool hourglass_work = true;          // w includes the work of hourglass forces (false: Peridigm's w)
    std::vector<std::uint8_t> detached;  // per node, 1 = all bonds break at the next apply
    long detached_nodes = 0;             // nodes detached so far by the singular rule

    // Thermal expansion of the model (header), with the reference positions x of the body (both must
    // outlive the rule's use); ThermalExpansion{} switches it off.
    void set_thermal_expansion(const ThermalExpansion& t, const Field<D>& x)
    {
        t.validate(x.size());
        thermal_ = t, x_ = &x;
        theta_old_.clear();
    }

    // The micropotential of bond k's pair, w_ij = w_ji, from whichever half holds it [J/m^6 in 3D].
    double work(const Bonds& b, std::int64_t k) const
    {
        if (rec_.size() != stride() * b.size()) return 0;
        const std::int64_t r = b.reverse[k];
        return w_of(b.partner[k] > b.partner[r] ? k : r);  // partner[r] is the owner of bond k
    }

    void protect(const NodeSet& set, std::size_t nodes)
    {
        if (no_fail.empty()) no_fail.assign(nodes, 0);
        for (int i : set) no_fail[i] = 1;
    }

    // Breaks the pairs with w >= w_C or touching a detached node (never a no-fail node's), both
    // halves at once; returns how many ordered bonds broke. The w test is symmetric in i, j, so each
    // pair is visited once, from its lower node, and only in the nodes whose largest w reached w_C
    // in the last force pass (w_max, bond_loop.hpp); detached nodes as for critical stretch.
    long apply(Bonds& b)
    {
        if (w_max_.size() != b.nodes() || rec_.size() != stride() * b.size()) return 0;  // no pass yet
        long broken = break_detached_bonds(b, detached, no_fail);
        const long n = static_cast<long>(b.nodes());
#pragma omp parallel for schedule(static) reduction(+ : broken) if (n >= parallel_min_nodes)
        for (long i = 0; i < n; ++i) {
            if (w_max_[i] < w_c || (!no_fail.empty() && no_fail[i])) continue;
            for_family(b, i, [&](std::int64_t k, int j) {
                if (j < i || (!no_fail.empty() && no_fail[j]) || w_of(k) < w_c) return;
                broken += b.break_pair(k);  // the reverse half lies in node j's range, whose thread writes only its bonds to j' > j
            });
        }
        return broken;
    }

    // The damage rule of a scene (scene.hpp): apply before a force evaluation that takes bond_work,
    // accumulate after it.
    long break_bonds(Bonds& b, const Field<D>&) { return apply(b); }
    template <class Model>
    void record(const Model& model, const Bonds& b, const Field<D>& y) { accumulate(model, b, y); }

    // The bond work for the force evaluation at the positions of the next accumulate:
    // internal_force(model, b, y, f, mp.bond_work<Model>(b)) adds the increments of the step
    // (bond_loop.hpp), and accumulate then only records the positions.
    template <class Model>
    const BondWork* bond_work(const Bonds& b)
    {
        work_.components = detail::is_ordinary<Model>() ? 1 : D;
        const bool first = rec_.size() != stride() * b.size() || y_.size() != b.nodes();
        if (first) {  // the first pass only stores the forces
            rec_.assign(stride() * b.size(), 0.0);
            w_max_.assign(b.nodes(), 0.0);
            y_ = Field<D>();
        }
        work_.w_max = w_max_.data();
        work_.rec = rec_.data();
        for (int a = 0; a < D; ++a) work_.y_old[a] = first ? nullptr : y_.c[a].data();
        work_.volume = b.volume.data();
        work_.ratio = jc_ratio.empty() ? nullptr : jc_ratio.data();
        work_.hourglass = hourglass_work;
        thermal_step_ = thermal_.active() && !first && theta_old_.size() == b.nodes();
        if (thermal_step_) {  // de = alpha (theta - theta at the last pass); the old force's half of the correction
            increment_.resize(b.nodes());
            touched_.assign(b.nodes(), 0);
            for (std::size_t i = 0; i < b.nodes(); ++i) {
                increment_[i] = thermal_.alpha * ((*thermal_.theta)[i] - theta_old_[i]);
                if (increment_[i] != 0) {  // node i and its family have pairs to correct
                    touched_[i] = 1;
                    for_family(b, i, [&](std::int64_t, int j) { touched_[j] = 1; });
                }
            }
            thermal_correction(b, y_);
        }
        handed_out_ = true;
        return &work_;
    }

    // Records the positions y of the force evaluation just made for the next step's increments; the
    // model's state must be the one of that evaluation (call right after internal_force). When that
    // evaluation did not take bond_work, the bond pass is run again here to add the increments.
    template <class Model>
    void accumulate(const Model& model, const Bonds& b, const Field<D>& y)
    {
        if (!b.has_damage()) throw std::invalid_argument("CriticalMicropotential: call bonds.enable_damage() first");
        if (!handed_out_) {
            Field<D> f;
            bond_forces(model, b, y, f, bond_work<Model>(b));
        }
        handed_out_ = false;
        if (thermal_step_) thermal_correction(b, y, true);  // the new force's half, and w_max again
        thermal_step_ = false;
        y_ = y;
        if (thermal_.active()) theta_old_ = *thermal_.theta;
        if (detach_singular) detached_nodes += mark_singular_nodes(model, b.nodes(), detached);  // also wrappers (.model)
    }

    // Its part of a checkpoint (core/state_archive.hpp), taken between steps: the accumulated bond
    // work, the positions of the last pass and the singular-node marks.
    void state(StateArchive& ar)
    {
        long components = work_.components;
        ar("micropotential.components", components);
        work_.components = static_cast<int>(components);
        ar("micropotential.rec", rec_);
        ar("micropotential.w_max", w_max_);
        ar("micropotential.y", y_);
        ar("micropotential.detached", detached);
        ar("micropotential.detached_nodes", detached_nodes);
        if (thermal_.active()) ar("micropotential.theta_old", theta_old_);
    }

private:
    std::vector<double> rec_;  // per bond (g, w) (bond_loop.hpp, BondWork); w of pair i < j on bond i -> j
    std::vector<double> w_max_;  // per node, the largest w of its bonds with j > i in the last pass
    BondWork work_;
    bool handed_out_ = false;  // bond_work was called since the last accumulate
    Field<D> y_;               // positions at the last accumulate [m]
    ThermalExpansion thermal_;            // header; inactive by default
    const Field<D>* x_ = nullptr;         // reference positions (thermal expansion) [m]
    std::vector<double> theta_old_;       // temperatures at the last accumulate
    std::vector<double> increment_;       // alpha (theta - theta_old) per node, for the pass [-]
    std::vector<std::uint8_t> touched_;   // 1: the node or one of its family has a non-zero increment

    bool thermal_step_ = false;           // this pass takes the thermal correction
    std::size_t stride() const { return static_cast<std::size_t>(work_.components) + 1; }

    // The thermal part of the step's increment, taken out of w (header): the pass added
    // 1/2 (g_old + g_new).dY / (beta V) (bond_loop.hpp); this subtracts the same with dY replaced by the
    // thermal bond displacement de_ij xi, de_ij = (de_i + de_j)/2, one half per call: before the pass with
    // the stored g_old at the old positions y, after it with g_new at the new ones (then w_max is
    // recomputed). Ordinary models store g = t (force t Y), so g.xi = t Y.xi. Kept out of the force pass
    // so that a run without temperature pays nothing; only the families with a pair whose temperature
    // changed are read (in a run heated by plastic work: the plastic zone and one horizon around it).
    void thermal_correction(const Bonds& b, const Field<D>& y, bool after_pass = false)
    {
        const int C = work_.components;
        const std::size_t st = stride();
        parallel_for(b.nodes(), [&](std::size_t i) {
            if (!touched_[i]) return;  // no pair of node i changed temperature: nothing to take out, w_max as the pass left it
            double wm = std::numeric_limits<double>::lowest();
            for_family(b, i, [&](std::int64_t k, int j) {
                if (j < static_cast<int>(i)) return;
                double* r = rec_.data() + st * static_cast<std::size_t>(k);
                if (b.intact[k]) {
                    double gxi = 0, Yxi = 0;
                    for (int a = 0; a < D; ++a) {
                        const double xi = x_->c[a][j] - x_->c[a][i];
                        if (C == 1) Yxi += (y.c[a][j] - y.c[a][i]) * xi;
                        else gxi += r[a] * xi;
                    }
                    if (C == 1) gxi = r[0] * Yxi;
                    double d = 0.5 * 0.5 * (increment_[i] + increment_[j]) * gxi / b.volume[k];
                    if (!jc_ratio.empty()) d *= 0.5 * (jc_ratio[i] + jc_ratio[j]);
                    r[C] -= d;
                }
                wm = std::max(wm, r[C]);
            });
            if (after_pass) w_max_[i] = wm;
        });
    }
    double w_of(std::int64_t k) const { return rec_[stride() * k + work_.components]; }
};

}  // namespace pd
