// Generalised Maxwell solid (standard linear solid for one branch), a point law that knows nothing
// of bonds (spec/000c sec. 1.1-1.3, Biondani 2018 eqs. 7.1-7.19; Simo & Hughes 1998 ch. 10):
//   a spring E_inf in parallel with N branches, branch i a spring E_i in series with a dashpot
//   eta_i = E_i tau_i. With x the total strain and h_i the dashpot strain of branch i (alpha_i):
//     sigma = E_inf x + sum_i E_i (x - h_i)                                     (7.7)
//     dh_i/dt + h_i / tau_i = x / tau_i,  h_i(-inf) = 0                        (7.8, 7.24)
//     D = sum_i eta_i (dh_i/dt)^2 = sum_i (E_i / tau_i) (x - h_i)^2 >= 0       (7.10)
//   Exact exponential integrator over a step dt in which x is linear (7.19, 7.27, errata 2-3):
//     h^{n+1} = e h^n + (1 - e) x^n + beta (x^{n+1} - x^n),
//     e = exp(-dt/tau),  beta = 1 - (tau/dt)(1 - e)   (beta -> dt/(2 tau) for dt << tau, -> 1 for dt >> tau).
//   The internal-stress form of the source, q_i = E_i h_i with forcing gamma_i s_0 (7.13, 7.19),
//   is this update times E_i: q^{n+1} = e q^n + (1 - e) E_i x^n + beta E_i dx.
//   Dissipated energy of the step, exact for x linear in the step: with r = x - h, c = dx/dt and
//   s = t/tau, r(s) = r_n e^{-s} + c tau (1 - e^{-s}), so, with a = dt/tau,
//     D_step = (E/tau) int r^2 dt = E [ r_n^2 g2 + r_n c tau g1^2 + (c tau)^2 g3 ],
//     g1 = 1 - e^{-a}, g2 = (1 - e^{-2a})/2, g3 = int_0^a (1 - e^{-s})^2 ds
//   (g3 by its Taylor series below a = 0.1, where the closed form a - 2 g1 + g2 cancels).
// One template serves a scalar x (1D bar, or a per-bond extension with E = alpha omega V) and a
// deviatoric tensor x = e (Eigen 3x3, "E" then being 2 G_i so that the branch stress is 2 G_i (e - h)).
// Products of tensors are the full contraction A:B.
#pragma once
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd::laws {

// One Maxwell branch.
struct MaxwellBranch {
    double E = 0;    // branch modulus (E_i in 1D; 2 G_i for a deviatoric tensor) [Pa]
    double tau = 0;  // relaxation time tau_i = eta_i / E_i [s]
};

// Coefficients of the exponential integrator (7.19) for a step dt [s] and relaxation time tau [s].
struct MaxwellCoefficients {
    double decay = 1;  // e = exp(-dt/tau) [-]
    double beta = 0;   // 1 - (tau/dt)(1 - e) [-]
    double x = 0;      // dt / tau [-]
};

inline MaxwellCoefficients maxwell_coefficients(double dt, double tau)
{
    if (!(tau > 0)) throw std::invalid_argument("Maxwell: relaxation time tau must be positive");
    if (!(dt >= 0)) throw std::invalid_argument("Maxwell: time step dt must be >= 0");
    MaxwellCoefficients c;
    c.x = dt / tau;
    c.decay = std::exp(-c.x);
    const double g1 = -std::expm1(-c.x);  // 1 - e without cancellation [-]
    // beta = 1 - g1/x; below x = 1e-3 the series x/2 - x^2/6 + x^3/24 - x^4/120 (error < x^5/720 < 2e-18).
    c.beta = c.x < 1e-3 ? c.x * (0.5 - c.x * (1.0 / 6 - c.x * (1.0 / 24 - c.x / 120))) : 1 - g1 / c.x;
    return c;
}

// g3(a) = int_0^a (1 - e^{-s})^2 ds [-] (header), a = dt/tau passed as x.
inline double maxwell_g3(double x)
{
    if (x >= 0.1) return x + 2 * std::expm1(-x) - 0.5 * std::expm1(-2 * x);  // x - 2 g1 + g2
    // Series: (1 - e^{-s})^2 = sum_{n>=2} a_n s^n, a_n = (-2 (-1)^n + (-2)^n)/n!; integrated term by
    // term to n = 12 (next term < 0.1^14 relative to x^3/3: round-off level).
    double sum = 0, fact = 1, pm = 1, p2 = 1, xp = x;
    for (int n = 1; n <= 12; ++n) {
        fact *= n, pm = -pm, p2 *= -2, xp *= x;  // n!, (-1)^n, (-2)^n, x^{n+1}
        if (n >= 2) sum += (-2 * pm + p2) / fact * xp / (n + 1);
    }
    return sum;
}

namespace detail {
inline double contract(double a, double b) { return a * b; }
template <class T>
double contract(const T& a, const T& b) { return (a.array() * b.array()).sum(); }
}  // namespace detail

// Dashpot strain of one branch at n+1 (7.19): exact when x is linear in the step, any dt >= 0.
template <class T>
T maxwell_update(const T& h_n, const T& x_n, const T& x_np1, const MaxwellCoefficients& c)
{
    return T(c.decay * h_n + (1 - c.decay) * x_n + c.beta * (x_np1 - x_n));
}

// Energy dissipated by the dashpot of a branch of modulus E [Pa] over the step [J/m^3] (header).
template <class T>
double maxwell_dissipation(double E, const T& h_n, const T& x_n, const T& x_np1, const MaxwellCoefficients& c)
{
    const T r_n = x_n - h_n;                          // spring strain at t_n [-]
    const T ctau = c.x > 0 ? T((x_np1 - x_n) / c.x) : T(0 * r_n);  // c tau = dx tau / dt [-]
    const double g1 = -std::expm1(-c.x), g2 = -0.5 * std::expm1(-2 * c.x);
    return E * (detail::contract(r_n, r_n) * g2 + detail::contract(r_n, ctau) * g1 * g1 + detail::contract(ctau, ctau) * maxwell_g3(c.x));
}

// Result of one step of the law.
template <class T>
struct MaxwellStep {
    T stress;                // sigma^{n+1} (7.7) [Pa]
    std::vector<T> h;        // dashpot strains h_i^{n+1} [-]
    double dissipation = 0;  // energy dissipated in the step [J/m^3] (>= 0)
};

// The generalised Maxwell solid: E_inf plus the branches.
struct Maxwell {
    double E_inf = 0;                    // equilibrium modulus (E_inf in 1D; 2 G_inf for a deviatoric tensor) [Pa]
    std::vector<MaxwellBranch> branches;

    // Standard linear solid: E_inf, one branch (E_b, tau_b).
    static Maxwell sls(double E_inf, double E_b, double tau_b) { return {E_inf, {{E_b, tau_b}}}; }

    double instantaneous_modulus() const  // E_0 = E_inf + sum E_i [Pa]
    {
        double E0 = E_inf;
        for (const auto& b : branches) E0 += b.E;
        return E0;
    }

    // d sigma^{n+1} / d x^{n+1} over a step dt [Pa]: E_inf + sum E_i (1 - beta_i) (the update is linear).
    double tangent(double dt) const
    {
        double Et = E_inf;
        for (const auto& b : branches) Et += b.E * (1 - maxwell_coefficients(dt, b.tau).beta);
        return Et;
    }

    // One step from (x_n, h_n) to x_np1 over dt [s] (dt = 0: instantaneous response, h unchanged).
    template <class T>
    MaxwellStep<T> step(const std::vector<T>& h_n, const T& x_n, const T& x_np1, double dt) const
    {
        if (h_n.size() != branches.size()) throw std::invalid_argument("Maxwell::step: one internal variable per branch expected");
        MaxwellStep<T> s{T(E_inf * x_np1), h_n, 0.0};
        for (std::size_t i = 0; i < branches.size(); ++i) {
            const MaxwellCoefficients c = maxwell_coefficients(dt, branches[i].tau);
            s.h[i] = maxwell_update(h_n[i], x_n, x_np1, c);
            s.stress += branches[i].E * (x_np1 - s.h[i]);  // (7.7)
            s.dissipation += maxwell_dissipation(branches[i].E, h_n[i], x_n, x_np1, c);
        }
        return s;
    }
};

}  // namespace pd::laws
