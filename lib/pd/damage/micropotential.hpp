// Critical-micropotential damage (Foster et al. 2011; Biondani 2018 sec. 8.2; spec/000c sec. 2.3-2.5):
// a bond breaks for good when the work done on it, per unit volume of each end, reaches w_C:
//   w<xi> = w'<-xi> = int_0^t (T<xi> - T'<-xi>) . dY                     (000c eq. 8.16)
//   w >= w_C  =>  phi = 1                                                  (8.13)
//   3D  w_C = 4 J_C / (pi delta^4)   [J/m^6]                               (8.15)
//   2D  w_C = 3 J_C / (2 delta^3)    [J/m^5 per unit thickness]  [DERIVED here: the 2D analogue of
//       (8.14), J_C = w int_0^delta int_z^delta 2 xi acos(z/xi) dxi dz = 2 w delta^3 / 3]
// Increment of bond k = i->j over a step n -> n+1 (trapezoidal rule on the work integral):
//   d_k = 1/2 (g_k^n + g_k^{n+1}) . (Y_k^{n+1} - Y_k^n),   g_k = f_k / (beta V_j)  [N/m^6]
// with f_k the pair force density on i from bond k, both ends' states included, as the model's
// public bond_scalar(...) Y (ordinary: PMB, LPS, PALS, viscoelastic/plastic LPS) or bond_force(...)
// (non-ordinary: correspondence, with the hourglass term; Peridigm leaves hourglass forces out,
// 000c sec. 2.3 [CODE]). For PMB this integrates exactly to w = c omega s^2 |xi| / 2.
// Both halves get the same increment, 1/2 (d_k + d_rev(k)) (rev: the reverse-bond index): the
// floating-point sum is commutative, so w_ij == w_ji bit for bit, whatever the number of threads
// (Peridigm instead adds the owner's increment to the specular bond, sec. 3.7.1).
// Temperature-dependent J_C (000c sec. 2.4, eqs. 8.21-8.23, V9): with per-node ratios
// r_i = J_C(theta_ref) / J_C(theta_i) set in `jc_ratio`, the increment is scaled by (r_i + r_j)/2 and
// compared with w_C(theta_ref): each end weighted by its own temperature as in (8.23).
// Singular nodes (000c sec. 2.5, the thesis' rule for correspondence): when a model exposes K^-1 and F
// per node, a node whose K is singular (K^-1 = 0, correspondence.hpp) or with det F <= 0 loses all
// its bonds at the next breaking pass.
// Usage (Explicit in time/verlet.hpp does this): apply(bonds) before the force evaluation breaks bonds
// with w >= w_C; accumulate(model, bonds, y) after it adds the step's increments.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/bonds.hpp"
#include "pd/field.hpp"
#include "pd/lattice.hpp"
#include "pd/parallel.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

// Critical micropotential w_C from the critical J-integral J_C [J/m^2] and horizon delta [m].
inline double w_critical(double Jc, double delta, int dim = 3)
{
    if (dim == 3) return 4 * Jc / (std::numbers::pi * std::pow(delta, 4));  // 000c eq. 8.15
    if (dim == 2) return 1.5 * Jc / (delta * delta * delta);                // 2D analogue (header)
    throw std::invalid_argument("w_critical: dim must be 2 or 3");
}

template <int D>
struct CriticalMicropotential {
    double w_c = 0;                      // critical micropotential w_C(theta_ref) [J/m^6 in 3D]
    std::vector<std::uint8_t> no_fail;   // per node, 1 = bonds never break; empty = none
    std::vector<double> jc_ratio;        // per node J_C(theta_ref)/J_C(theta_i) [-]; empty = 1
    bool detach_singular = true;         // the singular-node rule (header), for models with Kinv and F
    std::vector<double> w;               // accumulated micropotential per bond [J/m^6 in 3D]
    std::vector<std::uint8_t> detached;  // per node, 1 = all bonds break at the next apply
    long detached_nodes = 0;             // nodes detached so far by the singular rule

    void protect(const NodeSet& set, std::size_t nodes)
    {
        if (no_fail.empty()) no_fail.assign(nodes, 0);
        for (int i : set) no_fail[i] = 1;
    }

    // Breaks the intact bonds with w >= w_C or touching a detached node (never a no-fail node's);
    // returns how many ordered bonds broke. Both tests are symmetric in i, j.
    long apply(Bonds& b)
    {
        if (w.size() != b.size()) return 0;  // nothing accumulated yet
        long broken = 0;
        const bool any_detached = !detached.empty();
        const long n = static_cast<long>(b.nodes());
#pragma omp parallel for schedule(static) reduction(+ : broken) if (n >= parallel_min_nodes)
        for (long i = 0; i < n; ++i) {
            if (!no_fail.empty() && no_fail[i]) continue;
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                if (!b.intact[k]) continue;
                const int j = b.partner[k];
                if (!no_fail.empty() && no_fail[j]) continue;
                if (w[k] >= w_c || (any_detached && (detached[i] || detached[j]))) { b.intact[k] = 0; ++broken; }
            }
        }
        return broken;
    }

    // Adds the increments of the step that ended at positions y; the model's state must be the one
    // of the force evaluation at y (call right after internal_force). The first call only records.
    template <class Model>
    void accumulate(const Model& model, const Bonds& b, const Field<D>& y)
    {
        if (!b.has_damage()) throw std::invalid_argument("CriticalMicropotential: call bonds.enable_damage() first");
        const std::size_t nb = b.size(), n = b.nodes();
        const bool first = g_.size() != nb * D;
        if (first) { w.assign(nb, 0.0); g_.assign(nb * D, 0.0); d_.assign(nb, 0.0); y_.resize(n); }
        parallel_for(n, [&](std::size_t i) {
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                if (!b.intact[k]) { d_[k] = 0; continue; }
                const int j = b.partner[k];
                const Vec<D> Y = y[j] - y[i];
                Vec<D> f;
                if constexpr (detail::is_ordinary<Model>()) f = model.bond_scalar(i, k, j, norm(Y)) * Y;
                else f = model.bond_force(i, k, j, Y);
                const double inv_v = 1 / b.volume[k];
                double* g = &g_[static_cast<std::size_t>(k) * D];
                const Vec<D> Y_n = y_[j] - y_[i];
                double d = 0;
                for (int a = 0; a < D; ++a) {
                    const double g_np1 = f[a] * inv_v;
                    d += 0.5 * (g[a] + g_np1) * (Y[a] - Y_n[a]);  // trapezoidal work increment (header)
                    g[a] = g_np1;
                }
                d_[k] = first ? 0.0 : d;
            }
        });
        const bool scaled = !jc_ratio.empty();
        parallel_for(n, [&](std::size_t i) {
            for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
                if (!b.intact[k]) continue;
                double dw = 0.5 * (d_[k] + d_[b.reverse[k]]);  // same value on both halves (header)
                if (scaled) dw *= 0.5 * (jc_ratio[i] + jc_ratio[b.partner[k]]);  // 000c eq. 8.23
                w[k] += dw;
            }
        });
        for (int a = 0; a < D; ++a) y_.c[a] = y.c[a];
        if constexpr (requires { model.Kinv; model.F; })
            if (detach_singular) mark_singular(model, n);
        if constexpr (requires { model.model.Kinv; model.model.F; })  // wrappers (viscoelastic correspondence)
            if (detach_singular) mark_singular(model.model, n);
    }

private:
    std::vector<double> g_;  // g_k^n per bond, D components [N/m^6 in 3D]
    std::vector<double> d_;  // this step's one-sided increment per bond [J/m^6 in 3D]
    Field<D> y_;             // positions at the previous call [m]

    template <class Model>
    void mark_singular(const Model& model, std::size_t n)
    {
        if (detached.size() != n) detached.assign(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
            if (detached[i]) continue;
            if (model.Kinv[i].isZero(0.0) || !(model.F[i].determinant() > 0)) { detached[i] = 1; ++detached_nodes; }
        }
    }
};

}  // namespace pd
