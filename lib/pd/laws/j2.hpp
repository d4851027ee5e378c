// pd/laws/j2.hpp -- J2 (von Mises) plasticity with isotropic hardening, radial return (Ottosen;
// spec/000b sec. 2.1, 2.2, 2.7), flow stress from laws/johnson_cook.hpp. Point law: no bonds.
//   trial         sigma_trial = sigma_n + D : d eps, sigma_eff_trial = sqrt(3/2 s:s)  (5.15)
//   yield check   sigma_eff_trial <= (A + B ep_n^n)(1 - theta*^m): elastic step     (5.16; sec. 2.4 step 4,
//                 the start-of-step flow stress without the rate factor)
//   scalar eq.    r(dl) = sigma_eff_trial - 3 G dl - sigma_y(ep_n + dl, dl/dt, theta) = 0   (5.21)/(5.48)
//   update        s = s_trial sigma_y / sigma_eff_trial, sigma_H unchanged, ep_np1 = ep_n + dl  (5.18)-(5.19)
//   plastic flow  d eps_p = dl 3 s_trial / (2 sigma_eff_trial)                                  (5.9)
//   dissipation   sigma_y dl per unit volume over the step [J/m^3]; power sigma_y dl/dt      (5.22)
// Solver: r is continuous and strictly decreasing in dl (sigma_y non-decreasing in ep and rate),
// r(0) >= 0 after a failed yield check (the floored rate factor is <= 1) and r(sigma_eff_trial/(3G))
// = -sigma_y <= 0: the root is bracketed in [0, sigma_eff_trial/(3G)]. Newton on (5.66)-(5.69),
// starting from the perfect-plasticity estimate; a Newton step leaving the current bracket, or an
// infinite slope (ep = 0 with n < 1), is replaced by bisection, so the iteration always converges.
// Stops when |r| <= 4 eps sigma_eff_trial (round-off of r) or the bracket is 2 ulps wide.
#pragma once
#include "pd/laws/elastic.hpp"
#include "pd/laws/johnson_cook.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace pd::laws {

struct ScalarReturn {
    bool plastic = false;
    double dlambda = 0;      // plastic multiplier = equivalent plastic strain increment [-]
    double sigma_eff = 0;    // end-of-step equivalent stress: sigma_y (plastic) or sigma_eff_trial [Pa]
    double dissipation = 0;  // sigma_y dlambda [J/m^3]
    int iterations = 0;      // residual evaluations
    int bisections = 0;      // of which bisection steps
};

// Solves (5.21) for dl; trial = sigma_eff_trial [Pa], G [Pa], ep_n [-], dt [s], theta as law's.
// dt = 0 is an instantaneous step (the initial state of an explicit run, time/verlet.hpp start):
// no rate is defined, so the return is rate-independent (rate factor 1, the yield-check stress).
inline ScalarReturn radial_return(const JohnsonCook& law, double G, double trial, double ep_n, double dt, double theta)
{
    if (!(dt >= 0)) throw std::invalid_argument("radial_return: dt must be >= 0");
    const bool rated = dt > 0;
    ScalarReturn r;
    r.sigma_eff = trial;
    if (!(trial > law.yield_check_stress(ep_n, theta))) return r;  // elastic (also trial = sigma_y0 = 0)
    r.plastic = true;
    const double tf = law.thermal_factor(theta);
    auto sigma_y = [&](double dl) { return rated ? law.flow_stress(ep_n + dl, dl / dt, theta) : law.yield_check_stress(ep_n + dl, theta); };
    double lo = 0, hi = trial / (3 * G);  // r(lo) >= 0 >= r(hi)
    double dl = std::min(hi, (trial - law.yield_check_stress(ep_n, theta)) / (3 * G));
    const double tol = 4 * std::numeric_limits<double>::epsilon() * trial;
    for (int it = 0; it < 400; ++it) {
        ++r.iterations;
        const double res = trial - 3 * G * dl - sigma_y(dl);
        if (res > 0) lo = dl;
        else hi = dl;
        if (std::abs(res) <= tol || hi - lo <= 2 * std::numeric_limits<double>::epsilon() * hi) break;
        // (5.66)-(5.67): dr/ddl = -3G - [h'(ep) R(rate) + h(ep) R'(rate)/dt] T(theta)
        const double ep = ep_n + dl, rate = rated ? dl / dt : 0;
        const double slope = rated ? -3 * G - (law.hardening_slope(ep) * law.rate_factor(rate)
                                               + law.hardening(ep) * law.rate_factor_slope(rate) / dt) * tf
                                   : -3 * G - law.hardening_slope(ep) * tf;
        double next = std::isfinite(slope) ? dl - res / slope : NAN;
        if (!(next > lo && next < hi)) {
            next = 0.5 * (lo + hi);
            ++r.bisections;
        }
        dl = next;
    }
    r.dlambda = dl;
    r.sigma_eff = sigma_y(dl);
    r.dissipation = r.sigma_eff * dl;
    return r;
}

struct StressReturn {
    Mat3 stress = Mat3::Zero();  // end-of-step Cauchy stress [Pa]
    Mat3 flow = Mat3::Zero();    // plastic strain increment dl 3 s_trial/(2 sigma_eff_trial) [-]
    double ep_np1 = 0;           // equivalent plastic strain [-]
    ScalarReturn scalar;
};

// Radial return of a trial stress [Pa] (5.15)-(5.21).
inline StressReturn j2_return(const JohnsonCook& law, double G, const Mat3& sigma_trial, double ep_n, double dt, double theta)
{
    StressReturn out;
    const Mat3 s = deviator(sigma_trial);
    const double trial = std::sqrt(1.5 * (s.array() * s.array()).sum());
    out.scalar = radial_return(law, G, trial, ep_n, dt, theta);
    out.stress = sigma_trial;
    out.ep_np1 = ep_n;
    if (!out.scalar.plastic) return out;
    const double scale = out.scalar.sigma_eff / trial;                             // (5.19)
    out.stress = sigma_trial - (1 - scale) * s;                                    // sigma_H unchanged (5.18)
    out.flow = 1.5 * out.scalar.dlambda / trial * s;                               // (5.9)
    out.ep_np1 = ep_n + out.scalar.dlambda;                                        // (5.11)
    return out;
}

// Small-strain, strain-driven J2 with the committed plastic strain as history:
//   sigma_trial = K tr(eps) I + 2 G dev(eps - eps_p_n), return, eps_p_np1 = eps_p_n + flow.
struct J2History {
    Mat3 eps_p = Mat3::Zero();  // plastic strain tensor (deviatoric) [-]
    double ep = 0;              // equivalent plastic strain [-]
};
struct J2Update {
    Mat3 stress = Mat3::Zero();  // [Pa]
    J2History history;           // trial history at the end of the step
    ScalarReturn scalar;
};
inline J2Update j2_strain_update(const IsotropicElastic& el, const JohnsonCook& law, const Mat3& eps,
                                 const J2History& h_n, double dt, double theta)
{
    const StressReturn r = j2_return(law, el.G, el.stress(eps - h_n.eps_p), h_n.ep, dt, theta);
    return {r.stress, {h_n.eps_p + r.flow, r.ep_np1}, r.scalar};
}

}  // namespace pd::laws
