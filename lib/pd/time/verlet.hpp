// Explicit dynamics by velocity Verlet (spec/000a sec. 3.3.1), with kinematic boundary
// conditions imposed on the half-step velocity (so positions follow), energy bookkeeping and a
// stability guard.
//   v_{n+1/2} = v_n + dt/2 a_n;  BCs on v_{n+1/2};  u_{n+1} = u_n + dt v_{n+1/2};
//   a_{n+1} = (f(u_{n+1}) + b_{n+1}) / rho;  v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}.
// Energies [J], the books (Energies below): kinetic sum 1/2 rho v^2 V, stored (strain) sum W_i V_i,
// external work of body forces and of the constraints (reaction -f times displacement increment,
// trapezoidal in time, plus the change of kinetic energy of the constrained components, which the
// constraint supplies), the work of the scene's extra forces (contact, impactors) on its own, the
// work a DissipativeModel dissipated (plastic, viscous: step_dissipation after each commit), and with
// energy_books on: the work absorbed by hourglass forces, -sum (f_hg,n + f_hg,n+1)/2 . du V over every
// component (no gradient of an energy, so integrated from the force: one more pass each step), and
// the stored energy released by broken bonds (Scene::track_release: W before minus W after the break
// at the same positions; two more point passes in a step that breaks bonds). total = kinetic + stored
// + absorbed - supplied; its change since start() is the balance error, O(dt^2) for velocity Verlet
// on conservative forces (O(dt) with plasticity's backward-Euler return).
// A velocity-prescribed component ends the step at g(t_{n+1}).
// Forces come from the scene (scene.hpp): damage rule, bond-dependent constants, rate-form stress,
// history and bond work are its business. Explicit hands it u_n, u_{n+1} and dt each step, and 0 in
// start(): the history state is reached at once and a rate-form stress goes from the reference
// (u = 0) to the initial u in one pseudo step, as LoadStep from y0 = x does (so the model's state must
// belong to the reference then), or Peridigm's first evaluation with the initial velocity
// (Scene::rate_pairing); it commits the history once per step. The scene's extra_force (contact,
// impactors) adds to the boundary's body forces (v is the half-step velocity there); its work enters
// the external work like any body force. A heat component of the scene takes its thermal steps due
// after the positions' update and before the force evaluation. Explicit keeps its own copy of the scene (the rule and the
// model by reference): attach a damage rule before constructing it, or later through sim.scene.
// Guard: a NaN/Inf displacement, or a mechanical energy KE + SE above energy_limit times
// (initial energy + |external work| + |contact work|) and above a round-off floor (the whole mass moving at
// 1e-10 m/s: a scene at rest stays quiet), throws Unstable naming the step and the node.
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/core/errors.hpp"
#include "pd/scene.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct Energies {
    double kinetic = 0, strain = 0, external_work = 0;  // [J]
    double contact_work = 0;     // work of the scene's extra forces on the body [J]
    double hourglass_work = 0;   // work absorbed by the hourglass forces [J] (energy_books)
    double dissipated = 0;       // work dissipated by plasticity or viscosity [J]
    double damage_released = 0;  // stored energy released by broken bonds [J] (energy_books)
    double balance = 0;          // total() less its value at the start [J] (Explicit::energies)
    double total() const { return kinetic + strain + hourglass_work + dissipated + damage_released - external_work - contact_work; }
};

namespace detail {
// Kinetic and strain energy of a body [J] (the model's state must be at y); shared by the
// explicit (Explicit) and implicit (Newmark) integrators.
template <int D, class Model>
Energies body_energies(Model& model, const Bonds& bonds, const Body<D>& body, const Field<D>& y, const Field<D>& v,
                       const std::vector<double>& rho, double external_work)
{
    Energies e;
    e.strain = stored_energy(model, bonds, body, y);
    for (std::size_t i = 0; i < body.size(); ++i) {
        double v2 = 0;
        for (int d = 0; d < D; ++d) v2 += v.c[d][i] * v.c[d][i];
        e.kinetic += 0.5 * rho[i] * v2 * body.volume[i];
    }
    e.external_work = external_work;
    return e;
}

// The energy guard: KE + SE non-finite, or above limit x (initial + |W_ext| + |W_contact|) and the round-off floor.
inline bool energy_guard_tripped(const Energies& e, double limit, double initial, double floor)
{
    const double mech = e.kinetic + e.strain;
    return !std::isfinite(mech) || mech > std::max(limit * (initial + std::abs(e.external_work) + std::abs(e.contact_work)), floor);
}

// Kinetic energy of the constrained components [J]; constrained(i, d) says which.
template <int D, class Constrained>
double constrained_kinetic(const Body<D>& body, const Field<D>& v, const std::vector<double>& rho, Constrained&& constrained)
{
    double k = 0;
    for (int d = 0; d < D; ++d)
        for (std::size_t i = 0; i < body.size(); ++i)
            if (constrained(i, d)) k += 0.5 * rho[i] * v.c[d][i] * v.c[d][i] * body.volume[i];
    return k;
}
}  // namespace detail

template <int D, class Model>
class Explicit {
public:
    Scene<D, Model> scene;             // forces (header): body, bonds, model; set_damage, extra_force
    std::vector<double> rho;           // density per node [kg/m^3]
    Boundary<D> boundary;
    double energy_limit = 10;          // stability guard factor (see header)
    bool energy_books = false;         // hourglass work and damage release in the books (header); set before start()

    Field<D> u, v, a;                  // displacement [m], velocity [m/s], acceleration [m/s^2]
    double t = 0;                      // [s]
    long step_count = 0;
    long broken_bonds = 0;

    Explicit(const Scene<D, Model>& s, double density)
        : scene(s), rho(s.body.size(), density), u(s.body.size()), v(s.body.size()), a(s.body.size()), f_(s.body.size()),
          b_(s.body.size()), f_prev_(s.body.size()), u_old_(s.body.size()), b_prev_(s.body.size()), e_(s.body.size()),
          e_prev_(s.body.size())
    {
        if (!(density > 0)) throw std::invalid_argument("density rho must be positive");
    }
    Explicit(const Body<D>& body, Bonds& bonds, Model& model, double density) : Explicit(Scene<D, Model>(body, bonds, model), density) {}

    // Call after initial u, v and the boundary are set: forces and accelerations at t.
    void start()
    {
        prepare();
        evaluate(0.0, true);  // rate form: the pseudo step from the reference (header), or scene.rate_pairing
        scene.commit();
        add_dissipation();
        if (hourglass_) scene.hourglass_force(&fhg_);
        initial_total_ = 0;
        const Energies e = energies();
        initial_energy_ = e.kinetic + e.strain;
        initial_total_ = e.total();
    }

    // A checkpoint between steps (core/state_archive.hpp): state(ar) into a saving archive after any
    // step; state(ar) from a loading archive instead of start() on an Explicit set up
    // the same way (scene, damage rule, density, boundary) continues the run bit for bit as the
    // uninterrupted one.
    void state(StateArchive& ar)
    {
        if (!ar.saving()) prepare();
        ar("explicit.u", u), ar("explicit.v", v), ar("explicit.a", a);
        ar("explicit.f", f_), ar("explicit.b", b_);
        ar("explicit.t", t), ar("explicit.step", step_count), ar("explicit.broken_bonds", broken_bonds);
        ar("explicit.external_work", external_work_), ar("explicit.initial_energy", initial_energy_);
        ar("explicit.contact_work", contact_work_), ar("explicit.dissipated", dissipated_), ar("explicit.initial_total", initial_total_);
        if (scene.extra_force) ar("explicit.e", e_);
        if (energy_books) ar("explicit.hourglass_work", hourglass_work_), ar("explicit.f_hg", fhg_);
        scene.state(ar);
    }

    void step(double dt)
    {
        if (!(dt > 0)) throw std::invalid_argument("time step dt must be positive");
        const std::size_t n = scene.body.size();
        for (int d = 0; d < D; ++d) u_old_.c[d] = u.c[d];  // for the external work
        const double kinetic_constrained_old = constrained_kinetic();
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) v.c[d][i] += 0.5 * dt * a.c[d][i];
        for (const auto& p : boundary.prescribed)
            for (int i : p.nodes) {
                double& vh = v.c[p.component][i];
                if (p.kind == Prescribed::Kind::velocity) vh = p.g(t + 0.5 * dt);
                else vh = (p.g(t + dt) - u.c[p.component][i]) / dt;
            }
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) u.c[d][i] += dt * v.c[d][i];
        for (int d = 0; d < D; ++d) f_prev_.c[d] = f_.c[d];
        for (int d = 0; d < D; ++d) b_prev_.c[d] = b_.c[d];
        if (scene.extra_force) std::swap(e_prev_, e_);
        if (hourglass_) std::swap(fhg_prev_, fhg_);
        t += dt;
        ++step_count;
        scene.advance_heat(step_count, dt);  // theta^(n+1) before the forces (scene.hpp)
        evaluate(dt);
        scene.commit();
        add_dissipation();
        if (hourglass_) scene.hourglass_force(&fhg_);
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                if (constrained_[i * D + d]) continue;
                v.c[d][i] += 0.5 * dt * a.c[d][i];
            }
        for (const auto& p : boundary.prescribed)
            if (p.kind == Prescribed::Kind::velocity)
                for (int i : p.nodes) v.c[p.component][i] = p.g(t);
        // External work: body forces on every node, reactions on constrained components; the extra
        // forces' (contact) and the hourglass forces' work on their own.
        const bool contact = scene.extra_force != nullptr;
        double work = 0, work_contact = 0, work_hg = 0;
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                const double du = u.c[d][i] - u_old_.c[d][i], V = scene.body.volume[i];
                if (hourglass_) work_hg += 0.5 * (fhg_.c[d][i] + fhg_prev_.c[d][i]) * du * V;
                if (constrained_[i * D + d]) {
                    work += -0.5 * (f_.c[d][i] + f_prev_.c[d][i]) * du * V;  // reaction density
                    continue;
                }
                const double e_mid = contact ? 0.5 * (e_.c[d][i] + e_prev_.c[d][i]) : 0.0;
                work += (0.5 * (b_.c[d][i] + b_prev_.c[d][i]) - e_mid) * du * V;
                work_contact += e_mid * du * V;
            }
        external_work_ += work + constrained_kinetic() - kinetic_constrained_old;
        contact_work_ += work_contact;
        hourglass_work_ -= work_hg;
        check_finite();
    }

    Energies energies()
    {
        Energies e = detail::body_energies(scene.model, scene.bonds, scene.body, scene.positions(), v, rho, external_work_);
        e.contact_work = contact_work_, e.hourglass_work = hourglass_work_, e.dissipated = dissipated_;
        e.damage_released = scene.released_energy();
        e.balance = e.total() - initial_total_;
        return e;
    }

    // Energy check of the guard; call every k steps (costs one energy evaluation).
    Energies check_energy()
    {
        const Energies e = energies();
        const double mech = e.kinetic + e.strain;
        if (detail::energy_guard_tripped(e, energy_limit, initial_energy_, energy_floor_)) {
            std::ostringstream m;
            m << "unstable at step " << step_count << " (t = " << t << " s): mechanical energy " << mech
              << " J exceeds " << energy_limit << " x (initial + external work); fastest node " << fastest_node();
            throw Unstable(m.str(), step_count, fastest_node());
        }
        return e;
    }

    // Steps n times with dt; every `energy_every` steps (and after the last) runs the energy check
    // and calls report(energies). Unstable propagates to the caller, whose CSVs are already on disk.
    template <class Report>
    void advance(long n, double dt, long energy_every, Report&& report)
    {
        for (long k = 1; k <= n; ++k) {
            step(dt);
            if ((energy_every > 0 && k % energy_every == 0) || k == n) report(check_energy());
        }
    }

    const Field<D>& positions() const { return scene.positions(); }
    const Field<D>& internal_force_density() const { return f_; }
    double initial_energy() const { return initial_energy_; }

private:
    Field<D> f_, b_, f_prev_, u_old_, b_prev_;
    Field<D> e_, e_prev_;                                // the extra forces' part of b_ [N/m^3]
    Field<D> fhg_, fhg_prev_;                            // hourglass force density [N/m^3] (energy_books)
    bool hourglass_ = false;                             // energy_books and the model has hourglass forces
    std::vector<std::uint8_t> constrained_;
    double external_work_ = 0, contact_work_ = 0, hourglass_work_ = 0, dissipated_ = 0;  // [J]
    double initial_total_ = 0;                           // [J]
    double initial_energy_ = 0;
    double energy_floor_ = 0;                            // [J]
    static constexpr double roundoff_speed = 1e-10;      // [m/s], see header

    // What start() and a loading state() share: the constrained components and the energy guard's floor.
    void prepare()
    {
        constrained_.assign(scene.body.size() * D, 0);
        for (const auto& p : boundary.prescribed)
            for (int i : p.nodes) constrained_[i * D + p.component] = 1;
        double mass = 0;  // [kg]
        for (std::size_t i = 0; i < scene.body.size(); ++i) mass += rho[i] * scene.body.volume[i];
        energy_floor_ = 0.5 * mass * roundoff_speed * roundoff_speed;
        scene.track_release(energy_books);
        hourglass_ = energy_books && scene.hourglass_force(nullptr);
    }

    // The work the committed step dissipated (DissipativeModel), into the books.
    void add_dissipation()
    {
        if constexpr (DissipativeModel<Model>) {
            double w = 0;
            for (std::size_t i = 0; i < scene.body.size(); ++i) w += step_dissipation(scene.model, i) * scene.body.volume[i];
            dissipated_ += w;
        }
    }

    // Forces and accelerations at u; dt: the step from u_old_ to u (0 in start()).
    void evaluate(double dt, bool start = false)
    {
        const long broke = start ? scene.start_forces(u, v, f_) : scene.internal_forces(u_old_, u, dt, f_);
        broken_bonds += broke;
        if (energy_books) scene.book_release(dt, broke);
        boundary.external(t, b_);
        if (scene.extra_force) {  // kept apart for the books, then added
            for (int d = 0; d < D; ++d) std::fill(e_.c[d].begin(), e_.c[d].end(), 0.0);
            scene.extra_force(t, scene.positions(), v, e_);
            for (int d = 0; d < D; ++d)
                for (std::size_t i = 0; i < scene.body.size(); ++i) b_.c[d][i] += e_.c[d][i];
        }
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < scene.body.size(); ++i)
                a.c[d][i] = constrained_[i * D + d] ? 0.0 : (f_.c[d][i] + b_.c[d][i]) / rho[i];
    }

    double constrained_kinetic() const  // [J]
    {
        return detail::constrained_kinetic(scene.body, v, rho, [&](std::size_t i, int d) { return constrained_[i * D + d] != 0; });
    }

    int fastest_node() const
    {
        int best = 0;
        double vmax = -1;
        for (std::size_t i = 0; i < scene.body.size(); ++i) {
            double v2 = 0;
            for (int d = 0; d < D; ++d) v2 += v.c[d][i] * v.c[d][i];
            if (!std::isfinite(v2)) return static_cast<int>(i);
            if (v2 > vmax) { vmax = v2; best = static_cast<int>(i); }
        }
        return best;
    }

    void check_finite() const
    {
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < scene.body.size(); ++i)
                if (!std::isfinite(u.c[d][i]) || !std::isfinite(v.c[d][i])) {
                    std::ostringstream m;
                    m << "unstable at step " << step_count << " (t = " << t << " s): non-finite displacement or velocity at node " << i;
                    throw Unstable(m.str(), step_count, static_cast<int>(i));
                }
    }
};

}  // namespace pd
