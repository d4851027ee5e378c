// pd/models/dissipative_registry.hpp -- the inelastic models by name: an elastic choice of
// models/registry.hpp with a dissipation (J2 / Johnson-Cook plasticity, or a standard linear solid)
// turned into the constructed model and handed to the caller's code, as with_model does.
//
//     pd::with_dissipative_model(choice, pd::Dissipation{.kind = pd::Dissipation::Kind::plastic, .law = jc},
//                                body, bonds, [&](auto& model) { return simulate(model); });
//
// The models (each a DissipativeModel, kernel_concepts.hpp: its step heat feeds a scene's heat):
//   plastic       lps, lps-scf -> PlasticLPS (lps-scf: Peridigm's shear correction on the wrapped LPS);
//                 pals -> PlasticPALS; correspondence -> PlasticCorrespondence. 3D only; heat per step
//                 beta_TQ sigma_y dlambda (models/plastic_points.hpp).
//   viscoelastic  lps, lps-scf (2D, 3D) -> ViscoelasticLPS; correspondence (3D, the hypo-elastic
//                 Flanagan-Taylor law, ModelChoice::hypoelastic) -> ViscoelasticCorrespondence; the
//                 whole dashpot dissipation becomes heat.
// Any other pairing (pmb, kind none, plasticity in 2D) throws std::invalid_argument naming it; 1D has
// no dissipative model (not compiled).
#pragma once
#include "pd/laws/johnson_cook.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/plastic_lps.hpp"
#include "pd/models/plastic_pals.hpp"
#include "pd/models/registry.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/models/viscoelastic_lps.hpp"

#include <stdexcept>
#include <string>

namespace pd {

struct Dissipation {
    enum class Kind { none, plastic, viscoelastic };
    Kind kind = Kind::none;
    laws::JohnsonCook law{};  // plastic: the flow stress (5.64); J2 with linear hardening is C = 0, m = 0, n = 1
    double beta_TQ = 0.9;   // plastic: Taylor-Quinney fraction of the plastic work that becomes heat [-]
    double gamma_b = 1;     // viscoelastic: G_b / G of the Maxwell branch [-]
    double tau_b = 1;       // viscoelastic: relaxation time [s]
};

// Calls fn(model) with the inelastic model of (c, dis) built on the bonds (header). fn is compiled
// for the five model types, or for those listed in Only (as with_model), so its result type must be
// the same for each; a model outside Only throws.
template <class... Only, int D, class Fn>
    requires(D >= 2)  // no dissipative model is written for 1D
decltype(auto) with_dissipative_model(const ModelChoice& c, const Dissipation& dis, const Body<D>& body, const Bonds& bonds, Fn&& fn)
{
    using Kind = Dissipation::Kind;
    using detail::model_allowed;
    const bool lps = c.name == "lps" || c.name == "lps-scf", corr = c.name == "correspondence";
    if (dis.kind == Kind::plastic) {
        if (D != 3) throw std::invalid_argument("the plastic models are written for 3D");
        if constexpr (D == 3 && model_allowed<PlasticLPS, Only...>)
            if (lps) {
                PlasticLPS model({.material = c.material, .dim = 3}, bonds, dis.law, dis.beta_TQ);
                if (c.name == "lps-scf") model.lps.apply_shear_correction(body.x);
                return fn(model);
            }
        if constexpr (D == 3 && model_allowed<PlasticPALS, Only...>)
            if (c.name == "pals") {
                PlasticPALS model({.material = c.material, .base = c.pals_base}, body, bonds, dis.law, dis.beta_TQ);
                return fn(model);
            }
        if constexpr (D == 3 && model_allowed<PlasticCorrespondence, Only...>)
            if (corr) {
                PlasticCorrespondence model({.material = c.material, .C_hg = c.C_hg, .hourglass_direction = c.hourglass_direction,
                                             .rotation = c.rotation},
                                            body, bonds, dis.law, dis.beta_TQ);
                return fn(model);
            }
        throw std::invalid_argument("plasticity is written for models lps, lps-scf, pals and correspondence, not " + c.name);
    }
    if (dis.kind == Kind::viscoelastic) {
        if constexpr (model_allowed<ViscoelasticLPS, Only...>)
            if (lps) {
                ViscoelasticLPS model({{.material = c.material, .dim = D, .plane = c.plane}, dis.gamma_b, dis.tau_b}, bonds);
                if (c.name == "lps-scf") model.lps.apply_shear_correction(body.x);
                return fn(model);
            }
        if constexpr (D == 3 && model_allowed<ViscoelasticCorrespondence, Only...>)
            if (corr) {
                if (!c.hypoelastic) throw std::invalid_argument("viscoelastic correspondence needs the hypo-elastic (Flanagan-Taylor) law");
                using C3 = Correspondence<3>;
                C3 elastic({.material = c.material, .law = C3::Law::flanagan_taylor, .C_hg = c.C_hg,
                            .hourglass_direction = c.hourglass_direction, .rotation = c.rotation},
                           body, bonds);
                ViscoelasticCorrespondence model(elastic, {dis.gamma_b, dis.tau_b}, body.x);
                return fn(model);
            }
        throw std::invalid_argument("viscoelasticity is written for models lps, lps-scf and (3D) correspondence, not " + c.name + " in " +
                                    std::to_string(D) + "D");
    }
    throw std::invalid_argument("with_dissipative_model: no dissipation chosen (use with_model)");
}

}  // namespace pd
