// Time at which a probe of the temperature field (e.g. the centre temperature) first reaches a
// target value, with any of the three heat integrators (conduction.hpp, heat_cvode.hpp):
//   explicit / implicit Euler: fixed step dt, the crossing linearly interpolated between the two
//     steps around it (the source's metric, spec/000b T7);
//   CVODE: one internal step at a time, the crossing located on CVODE's own interpolant by
//     bisection to 1e-12 of the step or to the spacing of doubles at t, whichever is larger (so its error is the integrator's, not the interpolation's).
// Returns reached = false when the target is not met before t_max.
#pragma once
#include "pd/heat/conduction.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/core/timer.hpp"
#include "pd/core/errors.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct ReachResult {
    bool reached = false;
    double t = NAN;       // crossing time [s]
    long steps = 0;       // time steps (CVODE: internal steps)
    double wall_s = 0;    // run time [s]
};

using Probe = std::function<double(const std::vector<double>& theta)>;

// step: dt [s] for the Euler schemes; for CVODE opt is used instead.
template <class Model>
ReachResult time_to_reach(Conduction<Model>& heat, const Model& model, const Bonds& bonds, std::vector<double> theta,
                          HeatIntegrator scheme, double dt, const CvodeOptions& opt, double t_max, const Probe& probe,
                          double target)
{
    io::Timer timer;
    ReachResult r;
    heat.apply_fixed(theta);
    const double sign = probe(theta) < target ? 1.0 : -1.0;  // direction of approach
    double t = 0, before = probe(theta);
    if (scheme == HeatIntegrator::cvode) {
        HeatCvode<Model> cv(heat, model, bonds, theta, 0.0, opt);
        std::vector<double> y;
        while (t < t_max) {
            const double t_prev = t;
            t = cv.cvode().step(t_max);
            ++r.steps;
            if (sign * (probe(cv.cvode().y()) - target) < 0) continue;
            double lo = t_prev, hi = t;  // bisection on the interpolant of the last step
            while (hi - lo > 1e-12 * (t - t_prev)) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;  // no double between: a tiny step far from t = 0
                cv.cvode().dense_output(mid, y);
                (sign * (probe(y) - target) < 0 ? lo : hi) = mid;
            }
            r.reached = true, r.t = 0.5 * (lo + hi);
            break;
        }
    } else {
        if (!(dt > 0)) throw std::invalid_argument("time_to_reach: dt must be positive");
        while (t < t_max) {
            scheme == HeatIntegrator::implicit_euler ? heat.implicit_euler(theta, dt) : heat.explicit_euler(theta, dt);
            t += dt;
            if (++r.steps == step_limit()) {  // t_max only caps the run: the limit applies to the steps it takes
                char what[128];
                std::snprintf(what, sizeof what, "the heat run to its target (not reached at t = %.3g s, dt = %.3g s)", t, dt);
                require_steps(double(r.steps) + 1, what);
            }
            for (std::size_t i = 0; i < theta.size(); ++i)
                if (!std::isfinite(theta[i]))
                    throw Unstable("heat run unstable: non-finite temperature at step " + std::to_string(r.steps) +
                                       ", node " + std::to_string(i), r.steps, int(i));
            const double now = probe(theta);
            if (sign * (now - target) >= 0) {
                r.reached = true, r.t = t - dt + dt * (target - before) / (now - before);
                break;
            }
            before = now;
        }
    }
    r.wall_s = timer.seconds();
    return r;
}

}  // namespace pd
