// pd/time/multirate.hpp -- the clocks of a multirate thermo-mechanical run (spec/000a sec. 3.3.4-3.3.5):
// N mechanical steps of dt_mech over the duration T, a thermal (conduction) step every N_sync(MK) of
// them and a heat-generation step every N_sync(MH), all sub-multiples of T.
//
// multirate_steps(T, dt_mech_max, dt_thermal_max, nsync_mh, nsync_mk) chooses them as the fork of the
// source does, mechanical step first (spec/000a sec. 3.3.4, ambiguity A10):
//   N  = ceil(T / dt_mech_max),  N_T = ceil(T / dt_thermal_max)
//   N_sync(MK) = max(1, floor(N / N_T))            unless given (nsync_mk > 0)
//   N rounded up to a multiple of N_sync(MK), or of lcm(N_sync(MK), N_sync(MH)) with heat generation
//   dt_mech = T / N,  dt_thermal = N_sync(MK) dt_mech,  dt_heat = N_sync(MH) dt_mech.
// Rounding N up keeps dt_mech <= dt_mech_max (to a relative 1e-12, so that a duration of a whole
// number of steps keeps that number) and, for the chosen N_sync(MK), dt_thermal <= T / N_T <=
// dt_thermal_max: both clocks stable. (The fork writes the rounding with an integer division inside
// the ceiling, which rounds N down and can exceed the mechanical bound; not copied.) Where the thermal
// bound is the smaller one, the fork stops with an error; here the mechanical step takes it (N_sync(MK)
// = 1), so that a run of any material has stable clocks. A given N_sync(MK) whose thermal step would
// exceed dt_thermal_max is refused (std::invalid_argument naming both steps).
#pragma once
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>

namespace pd {

struct MultirateSteps {
    long mech_steps = 0;   // N over the duration
    long nsync_mk = 1;     // mechanical steps per thermal step
    long nsync_mh = 0;     // mechanical steps per heat-generation step (0: no heat generation)
    double dt_mech = 0;    // [s]
    double dt_thermal = 0; // [s]
    double dt_heat = 0;    // [s] (0: no heat generation)
};

inline MultirateSteps multirate_steps(double duration, double dt_mech_max, double dt_thermal_max, long nsync_mh = 0,
                                      long nsync_mk = 0)
{
    if (!(duration > 0 && std::isfinite(duration))) throw std::invalid_argument("multirate_steps: the duration must be positive and finite");
    if (!(dt_mech_max > 0) || !(dt_thermal_max > 0))
        throw std::invalid_argument("multirate_steps: the stable mechanical and thermal steps must be positive");
    if (nsync_mh < 0 || nsync_mk < 0) throw std::invalid_argument("multirate_steps: N_sync must be >= 0 (0: none / chosen)");
    auto steps = [&](double dt) {
        const double n = std::ceil(duration / dt * (1 - 1e-12));  // a duration that is a whole number of steps stays so
        if (!(n < 1e15)) throw std::invalid_argument("multirate_steps: more than 1e15 steps over the duration");
        return std::max(1L, static_cast<long>(n));
    };
    MultirateSteps s;
    long n = steps(nsync_mk == 0 ? std::min(dt_mech_max, dt_thermal_max) : dt_mech_max);
    s.nsync_mk = nsync_mk > 0 ? nsync_mk : std::max(1L, n / steps(dt_thermal_max));
    s.nsync_mh = nsync_mh;
    const long multiple = nsync_mh > 0 ? std::lcm(s.nsync_mk, nsync_mh) : s.nsync_mk;
    n = (n + multiple - 1) / multiple * multiple;
    s.mech_steps = n;
    s.dt_mech = duration / double(n);
    s.dt_thermal = double(s.nsync_mk) * s.dt_mech;
    s.dt_heat = double(nsync_mh) * s.dt_mech;
    if (s.dt_thermal > dt_thermal_max * (1 + 1e-12))
        throw std::invalid_argument("multirate_steps: N_sync(MK) = " + std::to_string(s.nsync_mk) + " gives a thermal step of " +
                                    std::to_string(s.dt_thermal) + " s above the stable " + std::to_string(dt_thermal_max) + " s");
    return s;
}

}  // namespace pd
