#include "reference/enthalpy.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pd::ref {

namespace {

constexpr double theta_min = 20, theta_max = 1200;  // validity of EN 1993-1-2 eq. 3.36 [C]
constexpr double t1 = 600, t2 = 735, t3 = 900;       // branch boundaries [C]

void check_range(double theta, const char* who)
{
    if (!(theta >= theta_min && theta <= theta_max))
        throw std::invalid_argument(std::string(who) + ": temperature " + std::to_string(theta) + " C outside 20..1200 C");
}

// Antiderivatives of the four branches (any constant; only differences are used).
double F1(double T, double a1) { return 425 * T + a1 * T * T / 2 - 1.69e-3 * T * T * T / 3 + 2.22e-6 * T * T * T * T / 4; }
double F2(double T) { return 666 * T - 13002 * std::log(738 - T); }
double F3(double T) { return 545 * T + 17820 * std::log(T - 731); }
double F4(double T) { return 650 * T; }

}  // namespace

double carbon_steel_specific_heat(double theta, const CarbonSteelCp& law)
{
    check_range(theta, "carbon_steel_specific_heat");
    if (theta < t1) return 425 + law.a1 * theta - 1.69e-3 * theta * theta + 2.22e-6 * theta * theta * theta;
    if (theta < t2) return 666 + 13002 / (738 - theta);
    if (theta < t3) return 545 + 17820 / (theta - 731);
    return 650;
}

double carbon_steel_enthalpy(double theta, const CarbonSteelCp& law)
{
    check_range(theta, "carbon_steel_enthalpy");
    // Sum of the branch integrals over [20, theta], each branch clipped to its interval.
    double q = F1(std::min(theta, t1), law.a1) - F1(theta_min, law.a1);
    if (theta > t1) q += F2(std::min(theta, t2)) - F2(t1);
    if (theta > t2) q += F3(std::min(theta, t3)) - F3(t2);
    if (theta > t3) q += F4(theta) - F4(t3);
    return q;
}

double carbon_steel_temperature_at_enthalpy(double q, const CarbonSteelCp& law)
{
    const double q_max = carbon_steel_enthalpy(theta_max, law);
    if (!(q >= 0 && q <= q_max)) throw std::invalid_argument("carbon_steel_temperature_at_enthalpy: q outside 0..q(1200)");
    if (q == 0) return theta_min;
    if (q == q_max) return theta_max;
    struct Args { double q; CarbonSteelCp law; } args{q, law};
    gsl_function f;
    f.function = [](double T, void* p) {
        const auto* a = static_cast<const Args*>(p);
        return carbon_steel_enthalpy(T, a->law) - a->q;
    };
    f.params = &args;
    gsl_root_fsolver* s = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
    gsl_root_fsolver_set(s, &f, theta_min, theta_max);  // q is increasing: one root in the bracket
    double T = 0.5 * (theta_min + theta_max);
    for (int it = 0; it < 200; ++it) {
        gsl_root_fsolver_iterate(s);
        T = gsl_root_fsolver_root(s);
        if (gsl_root_test_interval(gsl_root_fsolver_x_lower(s), gsl_root_fsolver_x_upper(s), 0, 1e-12) == GSL_SUCCESS) break;
    }
    gsl_root_fsolver_free(s);
    return T;
}

double adiabatic_heating_time(double rho, double s, double theta0, double theta, const CarbonSteelCp& law)
{
    if (!(rho > 0) || !(s > 0)) throw std::invalid_argument("adiabatic_heating_time: rho and s must be positive");
    return rho * (carbon_steel_enthalpy(theta, law) - carbon_steel_enthalpy(theta0, law)) / s;
}

}  // namespace pd::ref
