// pd/models/rate_form.hpp -- rate-form stress (Correspondence<3> with Law::flanagan_taylor) needs
// update_stress(bonds, y_mid, v, dt) once per step, from a committed state (models/correspondence.hpp).
// A model plays this role (RateFormModel) by supplying rate_form(), true when this instance's stress
// is in rate form, update_stress and reset_rate_state() (back to the reference state). A scene advances it each step (scene.hpp); for quasi-static
// solvers the model is wrapped in LoadStep (models/load_step.hpp), which is not a RateFormModel and
// so passes here. Solvers that do neither (Newmark, dynamic relaxation, Newton) call
// reject_unwrapped_rate_form in their constructor, so that such a model fails loudly instead of
// running with the zero stress of a state that is never updated.
#pragma once
#include <concepts>
#include <stdexcept>
#include <string>

namespace pd {

template <class M>
concept RateFormModel = requires(const M& m) {
    { m.rate_form() } -> std::convertible_to<bool>;
};

template <class Model>
void reject_unwrapped_rate_form(const Model& model, const std::string& solver)
{
    if constexpr (RateFormModel<Model>)
        if (model.rate_form())
            throw std::invalid_argument(solver + ": Law::flanagan_taylor needs update_stress every step; wrap the model in "
                                                 "pd::LoadStep (models/load_step.hpp) or use pd::Explicit");
}

}  // namespace pd
