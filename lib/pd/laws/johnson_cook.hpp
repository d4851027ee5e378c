// pd/laws/johnson_cook.hpp -- Johnson-Cook flow stress (Johnson & Cook 1983; spec/000b sec. 2.7):
//   sigma_y = (A + B ep^n) (1 + C ln(rate/epdot0)) (1 - theta*^m)                      (5.64)
//   theta*  = (theta - theta_ref) / (theta_melt - theta_ref)                           (5.65)
// Conventions (each avoids a NaN or a singularity of the printed formula):
//   rate: the log is evaluated at max(rate, epdot0/1000): the source's floor epdot0/1000 for
//     rate <= 0 (sec. 2.7), extended continuously to 0 < rate < epdot0/1000 so that the return-map
//     residual stays continuous (identical above the floor, where all V7 rows lie). The rate factor
//     is clamped at >= 0 (it would turn negative only for C > 1/ln(1000) = 0.145).
//   temperature: softening off when m = 0 (the default; plain hardening); theta* <= 0 -> factor 1
//     (standard JC practice, no pow of a negative base); theta* >= 1 -> factor 0 (flow stress 0).
//   ep = 0 with n < 1: the hardening term is A and its slope n B ep^(n-1) is +inf; the J2 return
//     (j2.hpp) never takes a Newton step with an infinite slope (it bisects instead).
// Plain isotropic power hardening A + B ep^n is the special case C = 0, m = 0.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pd::laws {

struct JohnsonCook {
    double A = 0;           // quasi-static yield stress at theta_ref [Pa]
    double B = 0;           // hardening modulus [Pa]
    double n = 1;           // hardening exponent [-]
    double C = 0;           // rate sensitivity [-]; 0 = rate independent
    double epdot0 = 1;      // reference plastic strain rate [1/s]
    double m = 0;           // thermal softening exponent [-]; 0 = no softening
    double theta_ref = 0;   // reference temperature [K or C, as theta]
    double theta_melt = 1;  // melting temperature [same unit as theta_ref]

    void validate() const
    {
        if (!(A >= 0) || !(B >= 0) || !(n > 0) || !(C >= 0) || !(epdot0 > 0) || !(m >= 0))
            throw std::invalid_argument("JohnsonCook: need A, B, C, m >= 0, n > 0, epdot0 > 0");
        if (m > 0 && !(theta_melt > theta_ref)) throw std::invalid_argument("JohnsonCook: theta_melt must exceed theta_ref");
    }

    // theta* (5.65) [-].
    double homologous(double theta) const { return (theta - theta_ref) / (theta_melt - theta_ref); }
    // Thermal factor 1 - theta*^m, with the conventions of the header [-].
    double thermal_factor(double theta) const
    {
        if (m == 0) return 1;
        const double ts = homologous(theta);
        if (!(ts > 0)) return 1;
        if (ts >= 1) return 0;
        return 1 - std::pow(ts, m);
    }
    // Hardening A + B ep^n [Pa] (ep <= 0: A).
    double hardening(double ep) const { return ep > 0 ? A + B * std::pow(ep, n) : A; }
    // d(A + B ep^n)/d ep = n B ep^(n-1) [Pa]; +inf at ep = 0 for n < 1 (B > 0).
    double hardening_slope(double ep) const
    {
        if (B == 0) return 0;
        if (ep > 0) return n * B * std::pow(ep, n - 1);
        if (n < 1) return std::numeric_limits<double>::infinity();
        return n == 1 ? B : 0;
    }
    // The rate at which the log is evaluated, max(rate, epdot0/1000) [1/s].
    double floored_rate(double rate) const { return std::max(rate, 1e-3 * epdot0); }
    // Rate factor 1 + C ln(rate/epdot0), floored rate, clamped at >= 0 [-].
    double rate_factor(double rate) const
    {
        if (C == 0) return 1;
        return std::max(0.0, 1 + C * std::log(floored_rate(rate) / epdot0));
    }
    // d(rate factor)/d rate [s]: C / rate above the floor, 0 below it or where clamped.
    double rate_factor_slope(double rate) const
    {
        if (C == 0 || rate <= 1e-3 * epdot0 || rate_factor(rate) == 0) return 0;
        return C / rate;
    }
    // Flow stress (5.64) [Pa] at plastic strain ep [-], plastic strain rate [1/s], temperature theta.
    double flow_stress(double ep, double rate, double theta) const
    {
        return hardening(ep) * rate_factor(rate) * thermal_factor(theta);
    }
    // Flow stress of the start-of-step yield check: rate factor omitted (sec. 2.4 step 4) [Pa].
    double yield_check_stress(double ep, double theta) const { return hardening(ep) * thermal_factor(theta); }
};

}  // namespace pd::laws
