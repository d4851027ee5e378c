// reference/j2_plasticity.hpp -- classical small-strain J2 plasticity with Johnson-Cook hardening at
// the reference temperature, written out independently of the library's laws (the references of
// tests/test_plastic_models.cpp and problems/3d/jc_bar.cpp). Flow stress (spec/000b (5.64), no
// softening) sigma_y = (A + B ep^n) max(0, 1 + C ln(max(rate, epdot0/1000)/epdot0)).
//   classical_j2        one strain-driven step with the plastic strain as history:
//                       sigma_trial = K tr(e) I + 2 G dev(e), e = eps - eps_p; yield check against
//                       A + B ep^n (no rate factor, sec. 2.4 step 4); the multiplier dl solves
//                       q_trial - 3 G dl = sigma_y(ep + dl, dl/dt) (5.21); s = s_trial (1 - 3 G dl /
//                       q_trial) (5.18)-(5.19), eps_p += dl 3 s_trial / (2 q_trial) (5.9);
//   uniaxial_j2_stress  the stress of a uniaxial bar at total strain eps, rate-independent: E eps
//                       below A, else the root of sigma/E + ((sigma - A)/B)^(1/n) = eps.
//   adiabatic_uniaxial_jc  a uniform bar in uniaxial stress pulled at the constant axial strain rate
//                       `rate` with Johnson-Cook rate and temperature dependence, heated by beta of its
//                       plastic work, no conduction (the Hopkinson gauge before necking, spec/000c
//                       sec. 3.2): eps = sigma/E + ep + alpha (theta - theta_0), sigma = sigma_y(ep,
//                       dep/dt, theta) while it flows, rho c dtheta = beta sigma dep; lateral strain
//                       eps_t = -nu sigma/E - ep/2 + alpha (theta - theta_0); the force per reference
//                       area of the small-strain total form with y = F x, F = diag(1 + eps, 1 + eps_t,
//                       1 + eps_t): P = J sigma F^-T, P_xx = (1 + eps_t)^2 sigma. S equal strain steps,
//                       each solved for dep by bisection with theta of the step's start (explicit heat).
// Both roots by plain bisection (no Newton: nothing shared with laws/j2.hpp), to the last bit and to
// 1e-15 relative respectively.
#pragma once

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <vector>

namespace pd::ref {

struct Hardening {  // Johnson-Cook constants [Pa], [Pa], [-], [-], [1/s]
    double A = 0, B = 0, n = 1, C = 0, epdot0 = 1;
};

// The root of a monotone function in [lo, hi]: low_side(x) is true for x below the root. Bisection
// until hi - lo <= rel_tol hi, or (rel_tol = 0) until no double lies between lo and hi.
template <class LowSide>
double bisect(double lo, double hi, LowSide&& low_side, double rel_tol = 0)
{
    for (int it = 0; it < 2000 && hi - lo > rel_tol * hi; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (low_side(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

struct ClassicalJ2 {
    Eigen::Matrix3d stress = Eigen::Matrix3d::Zero();  // [Pa]
    Eigen::Matrix3d eps_p = Eigen::Matrix3d::Zero();   // plastic strain after the step [-]
    double ep = 0, dl = 0;                              // equivalent plastic strain after the step, its increment [-]
};

inline ClassicalJ2 classical_j2(double K, double G, const Hardening& h, const Eigen::Matrix3d& eps, const ClassicalJ2& n, double dt)
{
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d e = eps - n.eps_p;
    const Eigen::Matrix3d s_tr = 2 * G * (e - e.trace() / 3 * I);
    const double q_tr = std::sqrt(1.5 * (s_tr.array() * s_tr.array()).sum());
    ClassicalJ2 out{K * e.trace() * I + s_tr, n.eps_p, n.ep, 0};
    auto hardening = [&](double ep) { return h.A + h.B * std::pow(ep, h.n); };
    if (!(q_tr > hardening(n.ep))) return out;
    out.dl = bisect(0, q_tr / (3 * G), [&](double dl) {  // the residual of (5.21) is positive below the root
        const double rate = std::max(dl / dt, 1e-3 * h.epdot0);
        return q_tr - 3 * G * dl - hardening(n.ep + dl) * std::max(0.0, 1 + h.C * std::log(rate / h.epdot0)) > 0;
    });
    out.stress -= 3 * G * out.dl / q_tr * s_tr;
    out.eps_p += 1.5 * out.dl / q_tr * s_tr;
    out.ep += out.dl;
    return out;
}

inline double von_mises(const Eigen::Matrix3d& sigma)
{
    const Eigen::Matrix3d s = sigma - sigma.trace() / 3 * Eigen::Matrix3d::Identity();
    return std::sqrt(1.5 * (s.array() * s.array()).sum());
}

inline double uniaxial_j2_stress(double E, const Hardening& h, double eps)
{
    if (!(E * eps > h.A)) return E * eps;
    return bisect(h.A, E * eps, [&](double s) { return !(s / E + std::pow((s - h.A) / h.B, 1 / h.n) > eps); }, 1e-15);
}

struct Softening {  // Johnson-Cook temperature factor 1 - theta*^m; m = 0: none
    double m = 0, theta_ref = 0, theta_melt = 1;
    double factor(double theta) const
    {
        if (m == 0) return 1;
        const double ts = (theta - theta_ref) / (theta_melt - theta_ref);
        return ts <= 0 ? 1.0 : ts >= 1 ? 0.0 : 1 - std::pow(ts, m);
    }
};

struct UniaxialState {
    double eps = 0, sigma = 0, P = 0, ep = 0, theta = 0;  // [-], [Pa], [Pa], [-], [as theta_0]
};

// States after each of the S steps from 0 to eps_end (header); theta_0 the start temperature.
inline std::vector<UniaxialState> adiabatic_uniaxial_jc(double E, double nu, const Hardening& h, const Softening& soft, double beta,
                                                        double rho_c, double alpha, double theta_0, double rate, double eps_end, int S)
{
    std::vector<UniaxialState> out;
    UniaxialState s{0, 0, 0, 0, theta_0};
    const double dt = eps_end / rate / S;
    auto flow = [&](double ep, double dep, double theta) {
        const double r = std::max(dep / dt, 1e-3 * h.epdot0);
        return (h.A + h.B * std::pow(ep, h.n)) * std::max(0.0, 1 + h.C * std::log(r / h.epdot0)) * soft.factor(theta);
    };
    for (int k = 1; k <= S; ++k) {
        const double eps = eps_end * k / S, thermal = alpha * (s.theta - theta_0);
        const double trial = E * (eps - s.ep - thermal);
        double dep = 0;
        if (trial > flow(s.ep, 0, s.theta))
            dep = bisect(0, trial / E, [&](double x) { return E * (eps - s.ep - x - thermal) - flow(s.ep + x, x, s.theta) > 0; });
        s.eps = eps, s.ep += dep;
        s.sigma = E * (eps - s.ep - thermal);
        s.theta += beta * s.sigma * dep / rho_c;
        const double eps_t = -nu * s.sigma / E - 0.5 * s.ep + alpha * (s.theta - theta_0);
        s.P = (1 + eps_t) * (1 + eps_t) * s.sigma;
        out.push_back(s);
    }
    return out;
}

}  // namespace pd::ref
