// pd/models/rate_form.hpp -- rate-form stress (Correspondence<3> with Law::flanagan_taylor) needs
// update_stress once per step, from a committed state (models/correspondence.hpp). Explicit drives
// it itself (time/verlet.hpp); for quasi-static solvers the model is wrapped in LoadStep
// (models/load_step.hpp), which has no `par` and so passes here. Solvers that do neither (Newmark,
// dynamic relaxation, Newton) call reject_unwrapped_rate_form in their constructor, so that such a
// model fails loudly instead of running with the zero stress of a state that is never updated.
#pragma once
#include <stdexcept>
#include <string>

namespace pd {

template <class Model>
void reject_unwrapped_rate_form(const Model& model, const std::string& solver)
{
    if constexpr (requires { model.par.law == Model::Law::flanagan_taylor; })
        if (model.par.law == Model::Law::flanagan_taylor)
            throw std::invalid_argument(solver + ": Law::flanagan_taylor needs update_stress every step; wrap the model in "
                                                 "pd::LoadStep (models/load_step.hpp) or use pd::Explicit");
}

}  // namespace pd
