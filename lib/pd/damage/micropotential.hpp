// Critical-micropotential damage (Foster et al. 2011; Biondani 2018 sec. 8.2; spec/000c sec. 2.3-2.5):
// a bond breaks for good when the work done on it, per unit volume of each end, reaches w_C:
//   w<xi> = w'<-xi> = int_0^t (T<xi> - T'<-xi>) . dY                     (000c eq. 8.16)
//   w >= w_C  =>  phi = 1                                                  (8.13)
//   3D  w_C = 4 J_C / (pi delta^4)   [J/m^6]                               (8.15)
//   2D  w_C = 3 J_C / (2 delta^3)    [J/m^5 per unit thickness]  [DERIVED here: the 2D analogue of
//       (8.14), J_C = w int_0^delta int_z^delta 2 xi acos(z/xi) dxi dz = 2 w delta^3 / 3]
// Increment of bond k = i->j over a step n -> n+1 (trapezoidal rule on the work integral):
//   d_k = 1/2 (g_k^n + g_k^{n+1}) . (Y_k^{n+1} - Y_k^n),   g_k = f_k / (beta V_j)  [N/m^6]
// with f_k the pair force density on i from bond k, both ends' states included (non-ordinary
// models such as correspondence: with the hourglass term; Peridigm leaves hourglass forces out,
// 000c sec. 2.3 [CODE]). For PMB this integrates exactly to w = c omega s^2 |xi| / 2.
// f_k is handed out by the model's own force pass (bond_loop.hpp, per-bond output: the bond_scalar
// t_k of ordinary models, f_k = t_k Y_k, or the D components of f_k), so no force is evaluated
// twice; accumulate keeps the previous call's per-bond values and positions. Since
// f_ji / (beta V_i) = -f_ij / (beta V_j) and Y_ji = -Y_ij, d_ij = d_ji up to round-off: each pair is
// done once, by its lower node (i < j), and the same double is added to w_ij and w_ji, so
// w_ij == w_ji bit for bit whatever the number of threads (each entry of w has one writer).
// (Peridigm instead adds the owner's increment to the specular bond, sec. 3.7.1.)
// Cost (issue 6; reports/3d/notched_plate.md, bench/damage_cost.cpp): per step, the force pass stores
// 1 (ordinary) or D doubles per bond, and one pass over the pairs reads them with the positions;
// the breaking test reads w only. Correspondence, notched plate, per step before bonds break: 1.25x
// the stretch rule on the driver's grid (36k bonds; was 2.1x), 1.63x on the published grid (544k
// bonds, memory-bound: the per-bond arrays leave the caches; was 2.5x).
// Temperature-dependent J_C (000c sec. 2.4, eqs. 8.21-8.23, V9): with per-node ratios
// r_i = J_C(theta_ref) / J_C(theta_i) set in `jc_ratio`, the increment is scaled by (r_i + r_j)/2 and
// compared with w_C(theta_ref): each end weighted by its own temperature as in (8.23).
// Singular nodes (000c sec. 2.5, the thesis' rule for correspondence): when a model exposes K^-1 and F
// per node, a node whose K is singular (K^-1 = 0, correspondence.hpp) or with det F <= 0 loses all
// its bonds at the next breaking pass.
// Usage (Explicit in time/verlet.hpp does this): apply(bonds) before the force evaluation breaks bonds
// with w >= w_C; internal_force(model, bonds, y, f, mp.bond_output<Model>(bonds)) evaluates the forces
// and hands out the per-bond values; accumulate(model, bonds, y) then adds the step's increments
// (without the bond_output call it runs the model's bond pass once more itself).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/bonds.hpp"
#include "pd/damage/singular_nodes.hpp"
#include "pd/field.hpp"
#include "pd/lattice.hpp"
#include "pd/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <utility>
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

    // Per-bond force buffers for the force evaluation at the positions of the next accumulate:
    // internal_force(model, b, y, f, mp.bond_output<Model>(b)) fills them (bond_loop.hpp), and
    // accumulate then uses them instead of evaluating the bond forces again.
    template <class Model>
    const BondForces* bond_output(const Bonds& b)
    {
        out_.components = detail::is_ordinary<Model>() ? 1 : D;
        for (int c = 0; c < out_.components; ++c) {
            g_new_[c].resize(b.size());
            out_.c[c] = g_new_[c].data();
        }
        handed_out_ = true;
        return &out_;
    }

    // Adds the increments of the step that ended at positions y; the model's state must be the one
    // of the force evaluation at y (call right after internal_force). The first call only records.
    // When that force evaluation did not fill bond_output, the bond pass is run again here.
    template <class Model>
    void accumulate(const Model& model, const Bonds& b, const Field<D>& y)
    {
        if (!b.has_damage()) throw std::invalid_argument("CriticalMicropotential: call bonds.enable_damage() first");
        if (!handed_out_) {
            Field<D> f;
            bond_forces(model, b, y, f, bond_output<Model>(b));
        }
        handed_out_ = false;
        const std::size_t nb = b.size(), n = b.nodes();
        if (w.size() != nb || y_.size() != n) {  // first call: record only
            w.assign(nb, 0.0);
            y_ = y;
            for (int c = 0; c < out_.components; ++c) std::swap(g_new_[c], g_old_[c]);
        } else if (out_.components == 1) {
            const double *t_old = g_old_[0].data(), *t_new = g_new_[0].data();
            pair_pass(b, y, [=](std::int64_t k, const Vec<D>& Y, const Vec<D>& Yn, const Vec<D>& dY) {
                return 0.5 * (t_old[k] * dot(Yn, dY) + t_new[k] * dot(Y, dY));  // g = t Y (ordinary)
            });
        } else {
            const double *go[3] = {}, *gn[3] = {};
            for (int a = 0; a < D; ++a) { go[a] = g_old_[a].data(); gn[a] = g_new_[a].data(); }
            pair_pass(b, y, [=](std::int64_t k, const Vec<D>&, const Vec<D>&, const Vec<D>& dY) {
                double d = 0;
                for (int a = 0; a < D; ++a) d += (go[a][k] + gn[a][k]) * dY[a];
                return 0.5 * d;
            });
        }
        if (detach_singular) detached_nodes += mark_singular_nodes(model, n, detached);  // also wrappers (.model)
    }

private:
    std::vector<double> g_old_[3], g_new_[3];  // per-bond forces at the previous and this call (bond_loop.hpp)
    BondForces out_;
    bool handed_out_ = false;  // bond_output was called since the last accumulate
    Field<D> y_;               // positions at the previous call [m]

    // Trapezoidal increment of each intact pair, computed once by its lower node i < j; the new w_ij
    // is written to both halves (the same double: w_ij == w_ji bit for bit; each w entry has one
    // writer, so no race and no dependence on the threads); then this call's forces and positions
    // become the old ones.
    template <class Work>
    void pair_pass(const Bonds& b, const Field<D>& y, Work work)
    {
        const bool scaled = !jc_ratio.empty();
        const int* partner = b.partner.data();
        const std::int64_t* reverse = b.reverse.data();
        const std::uint8_t* intact = b.intact.data();
        const double* volume = b.volume.data();
        double* wk = w.data();
        const double *yc[3] = {}, *ync[3] = {};
        for (int a = 0; a < D; ++a) { yc[a] = y.c[a].data(); ync[a] = y_.c[a].data(); }
        parallel_for(b.nodes(), [&](std::size_t i) {
            double yi[D], yni[D];
            for (int a = 0; a < D; ++a) { yi[a] = yc[a][i]; yni[a] = ync[a][i]; }
            const std::int64_t ke = b.end(i);
            for (std::int64_t k = b.begin(i); k < ke; ++k) {
                const int j = partner[k];
                if (static_cast<std::size_t>(j) < i || !intact[k]) continue;
                Vec<D> Y, Yn;
                for (int a = 0; a < D; ++a) { Y[a] = yc[a][j] - yi[a]; Yn[a] = ync[a][j] - yni[a]; }
                double d = work(k, Y, Yn, Y - Yn) / volume[k];  // g_k = f_k / (beta V_j) (header)
                if (scaled) d *= 0.5 * (jc_ratio[i] + jc_ratio[j]);  // 000c eq. 8.23
                const double w_new = wk[k] + d;  // w_ji == w_ij before (induction), so it needs no load
                wk[k] = w_new;
                wk[reverse[k]] = w_new;
            }
        });
        for (int a = 0; a < D; ++a) y_.c[a] = y.c[a];
        for (int c = 0; c < out_.components; ++c) std::swap(g_new_[c], g_old_[c]);
    }
};

}  // namespace pd
