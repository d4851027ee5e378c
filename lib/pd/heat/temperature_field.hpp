// pd/heat/temperature_field.hpp -- a body's temperature field with its heat model and integrator,
// advanced on its own clock: the heat component of a scene (scene.hpp, set_heat) or a heat-only run.
//   TemperatureField    theta [K or C], the thermal step dt [s] and the count of thermal steps taken,
//                       whatever the heat model and integrator (type-erased):
//     advance()         one thermal step, then after_step(field) (a guard, a log row), if set;
//     follow(n, dt_m)   the thermal steps due on a mechanical clock of n steps of dt_m [s]: while
//                       (step + 1) dt <= n dt_m (relative slack 1e-12 for round-off). A thermal step of
//                       N_sync mechanical steps (dt = N_sync dt_m, spec/000a sec. 3.3.4) is thus taken
//                       every N_sync steps; any other ratio follows the clock as closely as it can;
//     heat_flow()       Q at the current theta [W/m^3];
//     deposit(e)        theta_i += e_i / (rho c_i) on the free nodes: heat released at once, e [J/m^3]
//                       (the dissipated heat of a scene, spec/000a eq. 3.23 with erratum E11);
//     state(ar)         theta and the step count (core/state_archive.hpp).
// The field of a heat model under explicit or implicit Euler is conduction.hpp's ConductingField; under
// CVODE BDF time/heat_cvode.hpp's CvodeField (make_temperature_field builds either).
#pragma once
#include "pd/core/state_archive.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

enum class HeatIntegrator { explicit_euler, implicit_euler, cvode };

inline HeatIntegrator parse_heat_integrator(const std::string& s)
{
    if (s == "explicit") return HeatIntegrator::explicit_euler;
    if (s == "implicit") return HeatIntegrator::implicit_euler;
    if (s == "cvode") return HeatIntegrator::cvode;
    throw std::invalid_argument("integrator must be explicit|implicit|cvode, got '" + s + "'");
}
inline const char* name(HeatIntegrator i)
{
    return i == HeatIntegrator::explicit_euler ? "explicit" : i == HeatIntegrator::implicit_euler ? "implicit" : "cvode";
}

class TemperatureField {
public:
    virtual ~TemperatureField() = default;
    std::vector<double> theta;  // [K or C]
    double dt = 0;              // thermal step [s]
    long step = 0;              // thermal steps taken
    std::function<void(const TemperatureField&)> after_step;  // optional: called after each thermal step

    double t() const { return double(step) * dt; }  // [s]

    void advance()
    {
        if (!(dt > 0)) throw std::invalid_argument("TemperatureField: the thermal step dt must be positive");
        take_step();
        ++step;
        if (after_step) after_step(*this);
    }
    // Thermal steps due after n mechanical steps of dt_mech [s] (header).
    long due(long n, double dt_mech) const { return static_cast<long>(std::floor(double(n) * dt_mech / dt * (1 + 1e-12))); }
    void follow(long n, double dt_mech)
    {
        const long target = due(n, dt_mech);
        while (step < target) advance();
    }
    virtual const std::vector<double>& heat_flow() = 0;  // Q at theta [W/m^3]
    virtual void deposit(const std::vector<double>& e) = 0;  // header [J/m^3]

    void state(StateArchive& ar) { ar("heat.T", theta), ar("heat.step", step); }

protected:
    virtual void take_step() = 0;
};

}  // namespace pd
