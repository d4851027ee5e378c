// pd/scene.hpp -- what the forces on a body are made of, composed: the bonds (the single owner of
// delta, the influence function and the volumes), a mechanical model, and only what the case uses of
//   a damage rule      any type with the DamageRule protocol below (damage/critical_stretch.hpp,
//                      damage/micropotential.hpp), attached by set_damage(rule);
//   extra body forces  contact and impactors (bc/contact.hpp): extra_force(t, y, v, b) adds a force
//                      density [N/m^3] to b;
//   heat               a temperature field on its own clock (heat/temperature_field.hpp), attached by
//                      set_heat(field): before the force evaluation of mechanical step n the integrator
//                      calls advance_heat(n, dt), which takes the thermal steps due by then (the order of
//                      spec/000a sec. 3.3.5: theta^(n+1) first, so that a coupled force sees it).
//                      With a DissipativeModel (kernel_concepts.hpp) the heat of each committed step is
//                      accumulated per node, e_abs += step_heat (eq. 3.24), and released into the field
//                      every N_sync(MH) mechanical steps after the thermal steps, theta += e_abs/(rho c),
//                      e_abs = 0 (eqs. 3.22-3.23 with erratum E11): set_heat(field, nsync_mh);
//                      N_sync(MH) = 0: the dissipation is not released (weak coupling: the temperature
//                      acts on the mechanics, the mechanics not on the temperature).
// The scene refers to the body, bonds, model, rule and field (kept by reference) but owns its own
// state (the last positions, e_abs): an integrator built from a scene (Explicit) keeps a copy, so read
// that state from the integrator's `scene` member.
// The model's optional roles (kernel_concepts.hpp) are served here, so that an integrator asks the
// scene for forces and commits and knows no model or rule by name:
//   internal_forces(u_old, u, dt, f)  one force evaluation at y = x + u after a step dt [s] from u_old:
//     1. the damage rule breaks bonds (a BondDependentModel then recomputes its per-node constants);
//     2. a rate-form stress (RateFormModel) is advanced over the step at the mid-step configuration
//        x + (u_old + u)/2 with v = (u - u_old)/dt (models/rate_form.hpp; dt = 0, a start, takes the
//        pseudo step 1: the update depends on v dt only);
//     3. the force f at y, a HistoryModel's trial state over dt from its committed history, with the
//        rule's bond work when it integrates one (bond_loop.hpp, BondWork);
//     4. the rule records the evaluation (micropotential positions, singular nodes).
//   It returns the ordered bonds broken in 1.
//   start_forces(u, v, f)  the first evaluation of a run (the integrator's start): internal_forces from
//     u_old = 0 with dt = 0, or, with rate_pairing.initial_velocity_step = dt > 0 (Peridigm's first
//     evaluation), a rate-form stress advanced once by dt at y = x + u with the initial velocity v;
//     the force of that stress is returned and the stress goes back to the reference state.
//   rate_pairing.end_of_step  the rate-form update pairs v with the end-of-step configuration x + u
//     (Peridigm) instead of the mid-step one; then L = Fdot F^-1 is not skew for a rigid rotation.
//   commit()  the trial history becomes the committed one (HistoryModel).
//   track_release(true)  the energy books (time/verlet.hpp): an evaluation that breaks bonds adds the
//     stored energy they release at its positions y, sum (W_i(y, bonds before) - W_i(y, bonds after)) V_i,
//     to released_energy() [J]: after the force, the model's state is formed once more with the bonds
//     before the break (recompute, point pass) for their energy, and again with the bonds after it
//     (the same arithmetic: the state the force saw). A rate-form stress keeps its stress of the step.
//   hourglass_force(&f)  the hourglass part of the last evaluation's force (bond_loop.hpp
//     hourglass_forces); false when the model has none (null: only that answer).
//   advance_heat(n, dt)  the heat component's thermal steps due after n mechanical steps of dt, then
//     the release of the dissipated heat when n is a multiple of N_sync(MH) (none: no-op).
// DamageRule protocol: long break_bonds(Bonds&, const Field<D>& y); template <class Model> const
// BondWork* bond_work(const Bonds&) (null: none); template <class Model> void record(const Model&,
// const Bonds&, const Field<D>& y); optionally state(StateArchive&), its part of a checkpoint.
//   state(ar)  the scene's part of a checkpoint (core/state_archive.hpp), see below.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/heat/temperature_field.hpp"
#include "pd/kernel_concepts.hpp"
#include "pd/models/rate_form.hpp"

#include <algorithm>
#include <functional>
#include <stdexcept>

namespace pd {

template <class R, class Model, int D>
concept DamageRule = requires(R& r, Bonds& b, const Field<D>& y, const Model& m) {
    { r.break_bonds(b, y) } -> std::convertible_to<long>;
    r.template bond_work<Model>(b);
    r.template record<Model>(m, b, y);
};

// A model with a stored-energy density, energy_density(bonds, y) [J/m^3 per node].
template <class M, int D>
concept HasEnergyDensity = requires(const M& m, const Bonds& b, const Field<D>& y) { m.energy_density(b, y); };

// The stored energy of a body at y, sum W_i V_i [J] (the model's state must be at y).
template <int D, class Model>
double stored_energy(const Model& model, const Bonds& bonds, const Body<D>& body, const Field<D>& y)
{
    const std::vector<double> W = model.energy_density(bonds, y);
    double e = 0;
    for (std::size_t i = 0; i < W.size(); ++i) e += W[i] * body.volume[i];
    return e;
}

// A part with its own checkpoint state: state(ar) visits it (core/state_archive.hpp).
template <class T>
concept HasState = requires(T& t, StateArchive& ar) { t.state(ar); };

// How the scene feeds a rate-form stress (header); the defaults are this library's choice, the
// alternatives Peridigm's (reference/peridigm_cloud/README.md).
struct RateFormPairing {
    bool end_of_step = false;           // false: mid-step configuration; true: end of step
    double initial_velocity_step = 0;   // [s] > 0: Peridigm's first evaluation; 0: the pseudo step from rest
};

template <int D, class Model>
class Scene {
public:
    const Body<D>& body;
    Bonds& bonds;
    Model& model;
    std::function<void(double t, const Field<D>& y, const Field<D>& v, Field<D>& b)> extra_force;  // see header; empty: none
    RateFormPairing rate_pairing;  // header; used by a RateFormModel only

    Scene(const Body<D>& body, Bonds& bonds, Model& model) : body(body), bonds(bonds), model(model), y_(body.size()) {}

    // Attaches a damage rule (kept by reference); bonds.enable_damage() is called if needed.
    template <class Rule>
        requires DamageRule<Rule, Model, D>
    void set_damage(Rule& rule)
    {
        if (!bonds.has_damage()) bonds.enable_damage();
        break_bonds_ = [&rule](Bonds& b, const Field<D>& y) { return rule.break_bonds(b, y); };
        bond_work_ = [&rule](const Bonds& b) { return rule.template bond_work<Model>(b); };
        record_ = [&rule, &m = model, &b = bonds](const Field<D>& y) { rule.template record<Model>(m, b, y); };
        if constexpr (HasState<Rule>) rule_state_ = [&rule](StateArchive& ar) { rule.state(ar); };
        else rule_state_ = nullptr;
    }

    bool has_damage_rule() const { return static_cast<bool>(break_bonds_); }

    // Attaches the heat component (kept by reference) with N_sync(MH) >= 1, or 0: no release (header).
    void set_heat(TemperatureField& field, long nsync_mh = 1)
    {
        if (nsync_mh < 0) throw std::invalid_argument("Scene: N_sync(MH) must be >= 1 (or 0: the dissipation is not released)");
        if (field.theta.size() != body.size()) throw std::invalid_argument("Scene: the temperature field is not of this body");
        heat_ = &field, nsync_mh_ = nsync_mh;
        if constexpr (DissipativeModel<Model>) e_abs_.assign(nsync_mh > 0 ? body.size() : 0, 0.0);
    }
    void advance_heat(long n, double dt)
    {
        if (!heat_) return;
        heat_->follow(n, dt);
        if constexpr (DissipativeModel<Model>)
            if (nsync_mh_ > 0 && n % nsync_mh_ == 0) {
                heat_->deposit(e_abs_);
                std::fill(e_abs_.begin(), e_abs_.end(), 0.0);
            }
    }
    // Heat accumulated since the last release [J/m^3] (empty without a heat component or dissipation).
    const std::vector<double>& accumulated_heat() const { return e_abs_; }

    // One force evaluation (header); returns the bonds broken before it.
    long internal_forces(const Field<D>& u_old, const Field<D>& u, double dt, Field<D>& f)
    {
        if (!(dt >= 0)) throw std::invalid_argument("Scene: time step dt must be >= 0");
        return evaluate(u_old, u, dt, f, nullptr);
    }

    // The first evaluation of a run (header).
    long start_forces(const Field<D>& u, const Field<D>& v, Field<D>& f)
    {
        const Field<D> rest(body.size());  // u_old = 0: the pseudo step from the reference
        if (!(rate_pairing.initial_velocity_step >= 0)) throw std::invalid_argument("Scene: initial_velocity_step must be >= 0");
        return evaluate(rest, u, 0.0, f, rate_pairing.initial_velocity_step > 0 ? &v : nullptr);
    }

    void commit()
    {
        if constexpr (HistoryModel<Model, D>) model.commit();
        if constexpr (DissipativeModel<Model>)
            for (std::size_t i = 0; i < e_abs_.size(); ++i) e_abs_[i] += model.step_heat(i);  // eq. 3.24
    }

    const Field<D>& positions() const { return y_; }  // y = x + u of the last evaluation [m]

    // After an evaluation that broke `broke` bonds (the integrator calls it with track_release on): the
    // energy the breaks released, and the intact flags for the next one. Out of line, so that the force
    // evaluation compiles as without the books.
    [[gnu::noinline]] void book_release(double dt, long broke)
    {
        if constexpr (HasEnergyDensity<Model, D>)
            if (broke > 0 && intact_before_.size() == bonds.intact.size()) released_ += release(dt);
        intact_before_ = bonds.intact;
    }
    void track_release(bool on)
    {
        if constexpr (!HasEnergyDensity<Model, D>)
            if (on) throw std::invalid_argument("Scene: the energy books need a model with an energy density");
        track_release_ = on;
        if (on) intact_before_ = bonds.intact;  // the flags before the next evaluation's breaks
    }
    double released_energy() const { return released_; }  // [J] (track_release)
    bool hourglass_force(Field<D>* f) const { return hourglass_forces(model, bonds, y_, f); }  // null f: whether there is one

    // The scene's part of a checkpoint: the intact flags, the positions of the last evaluation, the
    // damage rule's state, the heat component's and the model's. A model with history keeps its own
    // by state(ar) (and may rebuild(bonds, y) what its last evaluation derived from it); a rate-form
    // stress keeps its history by rate_state(ar); any other model is rebuilt on loading from the
    // restored bonds and positions by the functions that built it (recompute after breaks, the point
    // pass): bit for bit the same.
    void state(StateArchive& ar)
    {
        ar("bonds.intact", bonds.intact);
        ar("scene.y", y_);
        ar("scene.y_mid", y_mid_);
        ar("scene.v_step", v_step_);
        if (track_release_) ar("scene.released", released_);
        if (track_release_ && !ar.saving()) intact_before_ = bonds.intact;
        if (rule_state_) rule_state_(ar);
        if (heat_) heat_->state(ar);
        if (!e_abs_.empty()) ar("heat.e_abs", e_abs_);
        if constexpr (BondDependentModel<Model>)
            if (!ar.saving() && std::find(bonds.intact.begin(), bonds.intact.end(), std::uint8_t{0}) != bonds.intact.end())
                model.recompute(bonds);
        if constexpr (HasState<Model>) {
            model.state(ar);  // after recompute: the model's own state is the newer one
            if constexpr (requires { model.rebuild(bonds, y_); })
                if (!ar.saving()) model.rebuild(bonds, y_);  // what its last evaluation derived from the state
        } else {
            if constexpr (HistoryModel<Model, D>) throw std::logic_error("checkpoint: this history model has no state(ar): not checkpointable");
            if constexpr (D == 3 && RateFormModel<Model>)
                if (model.rate_form()) model.rate_state(ar);  // the stress the point pass below takes
            if constexpr (!HistoryModel<Model, D> && Model::has_point_pass)
                if (!ar.saving()) model.point_pass(bonds, y_);
        }
    }

private:
    // internal_forces, and start_forces with v_start: Peridigm's first evaluation (header).
    long evaluate(const Field<D>& u_old, const Field<D>& u, double dt, Field<D>& f, const Field<D>* v_start)
    {
        add_fields(body.x, u, y_);
        long broke = 0;
        if (break_bonds_) {
            broke = break_bonds_(bonds, y_);
            if constexpr (BondDependentModel<Model>)
                if (broke > 0) model.recompute(bonds);  // correspondence recomputes K in its point pass
        }
        bool reset = false;
        if constexpr (D == 3 && RateFormModel<Model>)
            if (model.rate_form()) {
                reset = v_start != nullptr;
                if (reset) model.update_stress(bonds, y_, *v_start, rate_pairing.initial_velocity_step);
                else advance_rate_form(u_old, u, dt > 0 ? dt : 1.0);
            }
        const BondWork* work = bond_work_ ? bond_work_(bonds) : nullptr;
        if constexpr (HistoryModel<Model, D>) internal_force(model, bonds, y_, dt, f, work);
        else internal_force(model, bonds, y_, f, work);
        if (record_) record_(y_);
        if constexpr (D == 3 && RateFormModel<Model>)
            if (reset) model.reset_rate_state();
        return broke;
    }

    // The stored energy the last break released at y_ [J] (track_release, header).
    double release(double dt)
        requires HasEnergyDensity<Model, D>
    {
        const double after = stored_energy();
        std::swap(bonds.intact, intact_before_);
        form_state(dt);
        const double before = stored_energy();
        std::swap(bonds.intact, intact_before_);
        form_state(dt);
        return before - after;
    }
    void form_state(double dt)
    {
        if constexpr (BondDependentModel<Model>) model.recompute(bonds);
        if constexpr (HistoryModel<Model, D>) model.point_pass(bonds, y_, dt);
        else if constexpr (Model::has_point_pass) model.point_pass(bonds, y_);
    }
    double stored_energy() const
        requires HasEnergyDensity<Model, D>
    {
        return pd::stored_energy(model, bonds, body, y_);
    }

    Field<D> y_;
    Field<D> y_mid_, v_step_;  // rate form only, else empty: the configuration and velocity of its update
    std::function<long(Bonds&, const Field<D>&)> break_bonds_;
    std::function<const BondWork*(const Bonds&)> bond_work_;
    std::function<void(const Field<D>&)> record_;
    std::function<void(StateArchive&)> rule_state_;
    TemperatureField* heat_ = nullptr;
    bool track_release_ = false;
    double released_ = 0;                     // [J] (track_release)
    std::vector<std::uint8_t> intact_before_;  // the intact flags before the last break (track_release)
    long nsync_mh_ = 1;          // N_sync(MH)
    std::vector<double> e_abs_;  // dissipated heat not yet released [J/m^3] (DissipativeModel with heat)

    void advance_rate_form(const Field<D>& u_old, const Field<D>& u, double dt)
    {
        if (y_mid_.size() != body.size()) {
            y_mid_.resize(body.size());
            v_step_.resize(body.size());
        }
        const double w_old = rate_pairing.end_of_step ? 0.0 : 0.5;  // weight of u_old in the configuration
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) {
                y_mid_.c[d][i] = body.x.c[d][i] + (w_old * u_old.c[d][i] + (1 - w_old) * u.c[d][i]);  // [m]
                v_step_.c[d][i] = (u.c[d][i] - u_old.c[d][i]) / dt;                  // [m/s]
            }
        model.update_stress(bonds, y_mid_, v_step_, dt);
    }
};

}  // namespace pd
