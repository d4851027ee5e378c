// Load-step wrapper for a rate-form (hypoelastic) model driven by a quasi-static solver
// (adaptive dynamic relaxation, load stepping; spec/000b sec. 5.5 T5, spec/000a sec. 2.7).
// A rate model (Correspondence<3> with Law::flanagan_taylor) advances its state sigma_hat, R, V
// by update_stress(bonds, y, v, dt) once per physical step. Under load stepping the step is the
// whole load increment, from the configuration y_c committed at the end of the previous load step
// to the current iterate y; the solver evaluates forces at many trial iterates, and the stress of
// each must come from the committed state, not from the previous trial (no accumulation over
// iterations). At every force evaluation (point_pass) the wrapper therefore
//   1. restores sigma_hat, R, V to their committed values,
//   2. calls update_stress with the mid-step configuration y_m = (y_c + y)/2 and the velocity
//      v = (y - y_c)/dt over a pseudo step dt = 1 (the update depends on v dt only:
//      L dt = (F(y) - F(y_c)) F(y_m)^-1, exactly skew for a rigid rotation of the step (Cayley),
//      and d dt = mid-point approximation of the logarithmic strain increment, error O(de^3)),
//   3. calls the model's point_pass at y (F, P = J sigma F^-T, P K^-1);
// (with thermal expansion, the model's theta^n is restored with sigma_hat: each trial takes the
// temperature increment of the whole step, eq. 2.81);
// commit(bonds, y) at convergence evaluates at y and stores the state as the new committed one.
// advance (steps 1-2) and accept (store) serve a model that acts between steps 2 and 3
// (models/viscoelastic_correspondence.hpp).
// Uses only the model's public interface: update_stress, point_pass, bond_force / bond_scalar and
// the state vectors sigma_hat, R, V. Works with any Model exposing these (D = 3 for Flanagan-Taylor).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/state_archive.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace pd {

template <class Model, int D = 3>
class LoadStep {
public:
    static constexpr bool has_point_pass = true;
    static constexpr bool ordinary = false;
    Model& model;

    // y0: the configuration the model's present state belongs to (usually the reference x) [m].
    LoadStep(Model& model, const Field<D>& y0) : model(model), y_c_(y0) { store(); }

    // Trial evaluation at y (steps 1-3 of the header).
    void point_pass(const Bonds& b, const Field<D>& y)
    {
        advance(b, y);
        model.point_pass(b, y);
    }

    // Steps 1-2 only: the model's sigma_hat, R, V (and sigma) advanced from the committed state to y.
    void advance(const Bonds& b, const Field<D>& y)
    {
        if (y.size() != y_c_.size()) throw std::invalid_argument("LoadStep: configuration size differs from the committed one");
        model.sigma_hat = sigma_hat_c_;
        model.R = R_c_;
        model.V = V_c_;
        if constexpr (has_theta_n) {
            if (theta_n_c_.size() != model.theta_n.size()) theta_n_c_ = model.theta_n;  // expansion attached since the last commit
            model.theta_n = theta_n_c_;
        }
        if constexpr (has_stress_work) model.stress_work = stress_work_c_;
        y_m_.resize(y.size());
        v_.resize(y.size());
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < y.size(); ++i) {
                y_m_.c[d][i] = 0.5 * (y_c_.c[d][i] + y.c[d][i]);  // mid-step configuration [m]
                v_.c[d][i] = y.c[d][i] - y_c_.c[d][i];            // velocity over dt = 1 [m per unit pseudo time]
            }
        model.update_stress(b, y_m_, v_, 1.0);
    }

    // Ends the load step at y: the state evaluated at y becomes the committed state.
    void commit(const Bonds& b, const Field<D>& y)
    {
        point_pass(b, y);
        accept(y);
    }

    // The model's present state (last evaluated at y) becomes the committed state.
    void accept(const Field<D>& y)
    {
        y_c_ = y;
        store();
    }

    const Field<D>& committed_configuration() const { return y_c_; }
    // The committed state for a checkpoint (core/state_archive.hpp), entries "<name>.*".
    void state(StateArchive& ar, const std::string& name)
    {
        ar(name + ".y_c", y_c_);
        ar.blocks(name + ".sigma_hat_c", sigma_hat_c_), ar.blocks(name + ".R_c", R_c_), ar.blocks(name + ".V_c", V_c_);
        if constexpr (has_theta_n) ar(name + ".theta_n_c", theta_n_c_);  // empty without thermal expansion
        if constexpr (has_stress_work) ar(name + ".stress_work_c", stress_work_c_);
    }

    Vec<D> bond_force(std::size_t i, std::int64_t k, int j, const Vec<D>& Y) const { return model.bond_force(i, k, j, Y); }

private:
    // A model with thermal expansion in its rate form keeps theta^n, the temperature of its last update
    // (Correspondence::theta_n): committed and restored with the stress, so that every trial of a step
    // takes the whole increment theta - theta^n of the committed state.
    static constexpr bool has_theta_n = requires(Model& m) { m.theta_n; };
    // Its stored energy as the integrated stress power (Correspondence::stress_work): committed and
    // restored with the stress as well.
    static constexpr bool has_stress_work = requires(Model& m) { m.stress_work; };
    Field<D> y_c_, y_m_, v_;
    std::decay_t<decltype(std::declval<Model&>().sigma_hat)> sigma_hat_c_, R_c_, V_c_;
    std::vector<double> theta_n_c_, stress_work_c_;

    void store()
    {
        sigma_hat_c_ = model.sigma_hat;
        R_c_ = model.R;
        V_c_ = model.V;
        if constexpr (has_theta_n) theta_n_c_ = model.theta_n;
        if constexpr (has_stress_work) stress_work_c_ = model.stress_work;
    }
};

// The ADR density of the wrapped model is the wrapped model's (dynamic_relaxation.hpp): the
// tangent at the reference is the same.
template <class Model, int D>
Field<D> stiffness_bound(const LoadStep<Model, D>& ls, const Bonds& b, const Field<D>& x)
{
    return stiffness_bound(ls.model, b, x);
}

}  // namespace pd
