// pd/models/registry.hpp -- the elastic models by name, for drivers and pd_run: one place that
// turns `--model NAME` into a constructed model and hands it to the caller's code.
//
//     pd::with_model(pd::ModelChoice{.name = "lps", .material = mat}, body, bonds,
//                    [&](auto& model) { return simulate(model, bonds); });
//
// Names (model_names): pmb (Silling-Askari 2005; only kappa enters, nu = 1/4 implied in 3D), lps
// (Silling et al. 2007), lps-scf (LPS with Peridigm's shear correction factor, spec/000b sec. 1.3,
// eq. 4.14), pals (3D only, spec/000b sec. 1.4), correspondence (2D/3D, linear small-strain law, or
// in 3D the hypo-elastic Flanagan-Taylor law, Littlewood hourglass control C_hg). fn receives the model as a non-const reference and is
// compiled once per model type, so its result type must be the same for every model; a call may
// name the model types it needs (with_model<PMB, LPS>(...)) so that fn is compiled for those only.
// An unknown
// name, or a model that does not exist in dimension D, throws std::invalid_argument naming it
// (exit status 2 through guarded_main).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/influence.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/material.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace pd {

// The names with_model accepts, in the order of the reports' tables.
inline const std::vector<std::string>& model_names()
{
    static const std::vector<std::string> names{"pmb", "lps", "lps-scf", "pals", "correspondence"};
    return names;
}

struct ModelChoice {
    std::string name;              // one of model_names()
    Elastic material;              // K and G [Pa]
    Plane plane = Plane::strain;   // 2D reduction
    double measure = 1;            // 2D thickness [m] / 1D cross-section [m^2]
    double C_hg = 0;               // correspondence: Littlewood hourglass coefficient [-] (source 0.02)
    // correspondence (3D): law flanagan_taylor instead of the small-strain linear law, and Peridigm's forms
    bool hypoelastic = false;
    HourglassDirection hourglass_direction = HourglassDirection::unit;
    laws::RotationIncrement rotation = laws::RotationIncrement::rodrigues;
    PALS::Base pals_base = PALS::Base::normalised;  // pals: scale of the base influence functions
};

namespace detail {
// True when the model type M is in the list Only (an empty list allows every model).
template <class M, class... Only>
inline constexpr bool model_allowed = sizeof...(Only) == 0 || (std::is_same_v<M, Only> || ...);
}  // namespace detail

// Calls fn(model) with the model named by c.name, built on the bonds. Only: the model types this
// call may build (default: all); fn is compiled for those only, and a name outside them throws.
template <class... Only, int D, class Fn>
decltype(auto) with_model(const ModelChoice& c, const Body<D>& body, const Bonds& bonds, Fn&& fn)
{
    if (c.name == "pmb") {
        if constexpr (detail::model_allowed<PMB, Only...>) {
            PMB model({.material = c.material, .dim = D, .plane = c.plane, .measure = c.measure}, bonds);
            return fn(model);
        }
    } else if (c.name == "lps" || c.name == "lps-scf") {
        if constexpr (detail::model_allowed<LPS, Only...>) {
            LPS model({.material = c.material, .dim = D, .plane = c.plane}, bonds);
            if (c.name == "lps-scf") model.apply_shear_correction(body.x);  // Peridigm's SCF from the reference positions
            return fn(model);
        }
    } else if (c.name == "pals") {
        if constexpr (D != 3) throw std::invalid_argument("model pals exists in 3D only");
        else if constexpr (detail::model_allowed<PALS, Only...>) {
            PALS model({.material = c.material, .base = c.pals_base}, body, bonds);
            return fn(model);
        }
    } else if (c.name == "correspondence") {
        if constexpr (D == 1) throw std::invalid_argument("model correspondence exists in 2D and 3D only");
        else if constexpr (detail::model_allowed<Correspondence<D>, Only...>) {
            if (D != 3 && c.hypoelastic) throw std::invalid_argument("the hypo-elastic correspondence law exists in 3D only");
            using Law = typename Correspondence<D>::Law;
            Correspondence<D> model({.material = c.material, .law = c.hypoelastic ? Law::flanagan_taylor : Law::linear, .C_hg = c.C_hg,
                                     .plane = c.plane, .measure = c.measure, .hourglass_direction = c.hourglass_direction,
                                     .rotation = c.rotation},
                                    body, bonds);
            return fn(model);
        }
    } else {
        throw std::invalid_argument("unknown model '" + c.name + "'");
    }
    throw std::invalid_argument("model " + c.name + " is not available in this case");
}

}  // namespace pd
