// problems/pd_run_dissipation.hpp -- the inelastic part of pd_run (issue 20): its options, their
// checks, and the pd::Dissipation they choose (pd/models/dissipative_registry.hpp).
//   --plasticity johnson-cook   J2 radial return with the Johnson-Cook flow stress
//                               sigma_y = (A + B ep^n)(1 + C ln(rate/rate0))(1 - theta*^m) (laws/johnson_cook.hpp):
//                               --model lps, lps-scf, pals or correspondence, 3D. --jc-m > 0 softens with the
//                               run's temperatures (--heat), between --jc-T-ref and --jc-T-melt.
//   --viscoelastic sls          a standard linear solid (Maxwell branch G_b = --sls-gamma G, relaxation time
//                               --sls-tau): --model lps or lps-scf (2D, 3D), correspondence with --stress-law
//                               flanagan-taylor (3D).
// With --heat, the dissipated energy heats the points (plastic: --beta-tq of the plastic work; viscous:
// all of it), accumulated per point and released into the temperatures every --nsync-mh mechanical
// steps (spec/000a eqs. 3.22-3.24 with erratum E11; 0: never, the weak coupling); pd/scene.hpp.
#pragma once
#include "pd/io/options.hpp"
#include "pd/models/dissipative_registry.hpp"

#include <cmath>
#include <string>

namespace pd_run {

// The options as registered (references into pd::io::Options).
struct DissipationOptions {
    const std::string& plasticity;
    const double &A, &B, &n, &C, &rate0, &m, &T_ref, &T_melt, &beta;
    const std::string& viscoelastic;
    const double &gamma, &tau;
    const int& nsync_mh;
};

inline DissipationOptions add_dissipation_options(pd::io::Options& opt, double automatic)
{
    return {opt.add_string("plasticity", "none", "J2 plasticity with the Johnson-Cook flow stress (3D; lps, lps-scf, pals, correspondence)",
                           {"none", "johnson-cook"}),
            opt.add("jc-A", automatic, "Johnson-Cook yield stress A (required with --plasticity)", "Pa"),
            opt.add("jc-B", 0.0, "Johnson-Cook hardening modulus B", "Pa"),
            opt.add("jc-n", 1.0, "Johnson-Cook hardening exponent n"),
            opt.add("jc-C", 0.0, "Johnson-Cook rate sensitivity C (0: rate independent)"),
            opt.add("jc-rate0", 1.0, "Johnson-Cook reference plastic strain rate", "1/s"),
            opt.add("jc-m", 0.0, "Johnson-Cook thermal softening exponent m (0: none; > 0 needs --heat)"),
            opt.add("jc-T-ref", automatic, "Johnson-Cook reference (room) temperature (with --jc-m)", "K"),
            opt.add("jc-T-melt", automatic, "Johnson-Cook melting temperature (with --jc-m)", "K"),
            opt.add("beta-tq", 0.9, "Taylor-Quinney factor: fraction of the plastic work that becomes heat (with --heat)"),
            opt.add_string("viscoelastic", "none", "standard linear solid (lps, lps-scf; correspondence with --stress-law flanagan-taylor)",
                           {"none", "sls"}),
            opt.add("sls-gamma", 1.0, "Maxwell branch modulus over the shear modulus, G_b / G"),
            opt.add("sls-tau", automatic, "Maxwell branch relaxation time (required with --viscoelastic)", "s"),
            opt.add_int("nsync-mh", 1, "mechanical steps between releases of the dissipated heat, N_sync(MH) (0: never)")};
}

// The checks that need more than one option; fail() never returns. model: the canonical name
// (lps-scf for scf); heat: --heat is on; hypoelastic: correspondence takes the Flanagan-Taylor law.
template <class Fail>
pd::Dissipation dissipation_settings(const pd::io::Options& opt, const DissipationOptions& o, const std::string& model, int dim, bool mechanics,
                                     bool heat, bool hypoelastic, Fail fail)
{
    const bool plastic = o.plasticity != "none", viscous = o.viscoelastic != "none";
    for (const char* name : {"jc-A", "jc-B", "jc-n", "jc-C", "jc-rate0", "jc-m", "jc-T-ref", "jc-T-melt", "beta-tq"})
        if (opt.given(name) && !plastic) fail(std::string("option --") + name + " needs --plasticity johnson-cook");
    for (const char* name : {"sls-gamma", "sls-tau"})
        if (opt.given(name) && !viscous) fail(std::string("option --") + name + " needs --viscoelastic sls");
    if (opt.given("nsync-mh") && !(plastic || viscous)) fail("option --nsync-mh needs a dissipation (--plasticity or --viscoelastic)");
    if (opt.given("nsync-mh") && !heat) fail("option --nsync-mh needs --heat (it releases the dissipated heat into the temperatures)");
    if (o.nsync_mh < 0) fail("option --nsync-mh must be >= 0 (0: the dissipated heat is not released), got " + std::to_string(o.nsync_mh));
    pd::Dissipation d;
    if (!(plastic || viscous)) return d;
    if (!mechanics) fail(std::string("option --") + (plastic ? "plasticity" : "viscoelastic") + " applies to the mechanics (not --mechanics off)");
    if (plastic && viscous) fail("options --plasticity and --viscoelastic exclude each other (one dissipation per run)");
    if (opt.given("surface-correction"))
        fail("option --surface-correction applies to the elastic models (not with --plasticity or --viscoelastic)");
    if (plastic) {
        if (dim != 3) fail("option --plasticity needs --dim 3 (the plastic models are written for 3D)");
        if (model == "pmb") fail("option --plasticity applies to --model lps, lps-scf, pals or correspondence (PMB has no plastic form)");
        if (opt.given("beta-tq") && !heat) fail("option --beta-tq needs --heat (the plastic heat goes into the temperatures)");
        if (!opt.given("jc-A")) fail("option --jc-A is required with --plasticity johnson-cook");
        const bool softening = o.m != 0;
        for (const char* name : {"jc-T-ref", "jc-T-melt"})
            if (opt.given(name) != softening) fail(std::string("option --") + name + (softening ? " is required with --jc-m > 0" : " needs --jc-m > 0"));
        if (softening && !heat) fail("option --jc-m > 0 needs --heat (the softening reads the run's temperatures)");
        d.kind = pd::Dissipation::Kind::plastic;
        d.law = {.A = o.A, .B = o.B, .n = o.n, .C = o.C, .epdot0 = o.rate0, .m = o.m, .theta_ref = softening ? o.T_ref : 0.0,
                 .theta_melt = softening ? o.T_melt : 1.0};
        if (!(o.A >= 0 && o.B >= 0 && o.n > 0 && o.C >= 0 && o.rate0 > 0 && o.m >= 0))
            fail("options --jc-A, --jc-B, --jc-C, --jc-m must be >= 0 and --jc-n, --jc-rate0 > 0");
        if (softening && !(o.T_melt > o.T_ref)) fail("option --jc-T-melt must exceed --jc-T-ref");
        if (!(o.beta >= 0 && o.beta <= 1)) fail("option --beta-tq must lie in [0, 1], got " + pd::io::format_shortest(o.beta));
        d.beta_TQ = o.beta;
        return d;
    }
    if (dim == 1) fail("option --viscoelastic needs --dim 2 or 3 (1D LPS has no deviatoric part)");
    if (model != "lps" && model != "lps-scf" && model != "correspondence")
        fail("option --viscoelastic applies to --model lps, lps-scf or correspondence, not " + model);
    if (model == "correspondence" && !hypoelastic)
        fail("option --viscoelastic with --model correspondence needs --stress-law flanagan-taylor (the branch rotates with the stress)");
    if (!opt.given("sls-tau")) fail("option --sls-tau is required with --viscoelastic sls");
    if (!(o.gamma >= 0 && std::isfinite(o.gamma))) fail("option --sls-gamma must be >= 0, got " + pd::io::format_shortest(o.gamma));
    d.kind = pd::Dissipation::Kind::viscoelastic;
    d.gamma_b = o.gamma, d.tau_b = o.tau;
    return d;
}

}  // namespace pd_run
