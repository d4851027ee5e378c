// problems/pd_run_conventions.hpp -- pd_run's choice between this library's conventions and
// Peridigm's, one option each, and --conventions peridigm that sets them all (an option given
// explicitly wins). Peridigm's forms are read from its source (reference/peridigm_cloud/README.md);
// with all of them pd_run reproduces Peridigm's four models on that point cloud to round-off
// (tests/test_pd_run_peridigm.cpp; the effect of each: reports/3d/peridigm_cloud.md).
//   --stress-law linear|flanagan-taylor       correspondence: small-strain law, or hypo-elastic (3D; Peridigm)
//   --hourglass-direction unit|bond           hourglass force along Y/|Y|, or along Y (Peridigm: times |Y|)
//   --rotation-increment rodrigues|peridigm   Flanagan-Taylor: exact Q, or the minus before (1 - cos)
//   --rate-configuration mid-step|end-of-step Flanagan-Taylor: v_(n+1/2) with F at mid step, or at the end
//   --start-stress reference|initial-velocity Flanagan-Taylor: a0 from the stress at rest, or from one
//                                             update with the initial velocity, then reset (Peridigm)
//   --pals-base normalised|unit               PALS: omega0, sigma0 normalised on the sphere, or 1 in SI
#pragma once
#include "pd/io/options.hpp"
#include "pd/laws/flanagan_taylor.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/pals.hpp"
#include "pd/scene.hpp"

#include <string>

namespace pd_run {

// The options as given (references into the Options object).
struct ConventionOptions {
    const std::string *conventions, *law, *hourglass, *rotation, *rate, *start, *pals;
};

inline ConventionOptions add_convention_options(pd::io::Options& opt)
{
    ConventionOptions c;
    c.conventions = &opt.add_string("conventions", "ours", "peridigm: every choice below as Peridigm makes it (an option given wins)",
                                    {"ours", "peridigm"});
    c.law = &opt.add_string("stress-law", "linear", "correspondence stress law (flanagan-taylor: hypo-elastic, 3D)",
                            {"linear", "flanagan-taylor"});
    c.hourglass = &opt.add_string("hourglass-direction", "unit", "correspondence hourglass force along Y/|Y| (unit) or Y (bond)",
                                  {"unit", "bond"});
    c.rotation = &opt.add_string("rotation-increment", "rodrigues", "flanagan-taylor rotation increment Q", {"rodrigues", "peridigm"});
    c.rate = &opt.add_string("rate-configuration", "mid-step", "flanagan-taylor: configuration paired with v_(n+1/2)",
                             {"mid-step", "end-of-step"});
    c.start = &opt.add_string("start-stress", "reference", "flanagan-taylor: stress of the first acceleration",
                              {"reference", "initial-velocity"});
    c.pals = &opt.add_string("pals-base", "normalised", "PALS base influence functions (unit: 1 in SI)", {"normalised", "unit"});
    return c;
}

// The resolved choices.
struct Conventions {
    bool hypoelastic = false;
    pd::HourglassDirection hourglass = pd::HourglassDirection::unit;
    pd::laws::RotationIncrement rotation = pd::laws::RotationIncrement::rodrigues;
    bool end_of_step = false, initial_velocity = false;
    pd::PALS::Base pals_base = pd::PALS::Base::normalised;
};

// Resolves the options for `model` in `dim` dimensions; fail(message) for a choice that does not
// apply (given explicitly with another model, or a hypo-elastic law outside 3D).
template <class Fail>
Conventions resolve_conventions(const pd::io::Options& opt, const ConventionOptions& c, const std::string& model, int dim, Fail&& fail)
{
    const bool peridigm = *c.conventions == "peridigm";
    auto pick = [&](const char* name, const std::string& value, const char* theirs) {  // true: Peridigm's form
        return opt.given(name) ? value == theirs : peridigm;
    };
    Conventions r;
    const bool corr = model == "correspondence";
    r.hypoelastic = corr && pick("stress-law", *c.law, "flanagan-taylor");
    r.hourglass = pick("hourglass-direction", *c.hourglass, "bond") ? pd::HourglassDirection::bond : pd::HourglassDirection::unit;
    r.rotation = pick("rotation-increment", *c.rotation, "peridigm") ? pd::laws::RotationIncrement::peridigm : pd::laws::RotationIncrement::rodrigues;
    r.end_of_step = pick("rate-configuration", *c.rate, "end-of-step");
    r.initial_velocity = pick("start-stress", *c.start, "initial-velocity");
    r.pals_base = pick("pals-base", *c.pals, "unit") ? pd::PALS::Base::unit : pd::PALS::Base::normalised;
    for (const char* name : {"stress-law", "hourglass-direction"})
        if (opt.given(name) && !corr) fail(std::string("option --") + name + " applies to --model correspondence only");
    for (const char* name : {"rotation-increment", "rate-configuration", "start-stress"})
        if (opt.given(name) && !r.hypoelastic) fail(std::string("option --") + name + " applies to --stress-law flanagan-taylor only");
    if (opt.given("pals-base") && model != "pals") fail("option --pals-base applies to --model pals only");
    if (r.hypoelastic && dim != 3)
        fail(std::string("option --") + (opt.given("stress-law") ? "stress-law flanagan-taylor" : "conventions peridigm") +
             " with --model correspondence needs --dim 3 (the hypo-elastic law is written for 3D)");
    return r;
}

}  // namespace pd_run
