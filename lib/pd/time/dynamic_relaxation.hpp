// Adaptive dynamic relaxation (ADR): the quasi-static balance f_int(u) + b = 0 (spec/000a
// sec. 3.5, eq. 3.26) solved matrix-free by damped fictitious dynamics (Kilic & Madenci 2010,
// "An adaptive dynamic relaxation method for quasi-static simulations using the peridynamic
// theory", Theor. Appl. Fract. Mech. 53, 194-204; Underwood 1983):
//   fictitious time step       dt = 1
//   diagonal density           lambda_ia >= 1/4 dt^2 sum_(j,b) |K_(ia)(jb)|   (K&M eq. 17, Gershgorin)
//   start-up                   v^{1/2} = dt F^0 / (2 lambda)                  (K&M eq. 14)
//   local stiffness            K^n_ia = -(F^n_ia - F^{n-1}_ia) / (lambda_ia dt v^{n-1/2}_ia)   (eq. 16)
//   damping (Rayleigh)         c_n = 2 sqrt(u^T K^n u / u^T u), 0 if negative  (eq. 15)
//   central difference         v^{n+1/2} = ((2 - c_n dt) v^{n-1/2} + 2 dt F^n / lambda) / (2 + c_n dt)
//                              u^{n+1} = u^n + dt v^{n+1/2}                   (eq. 13)
// with F = f_int + b on the free components; a prescribed displacement component is held at its
// value g(t_load) and is not integrated. The diagonal density is the Gershgorin row sum of the
// stiffness linearised at the reference configuration (stiffness_bound below: exact row sums for
// PMB, triangle-inequality bounds for LPS, PALS and correspondence with its hourglass springs;
// the PMB formula with a stand-in micromodulus c for any other model) times `safety` (default
// 1.2: covers the geometric stiffness of finite stretches).
// Convergence: ||F V|| over the free components <= tol * force scale, the scale being the larger
// of ||b V|| (all components) and the reaction norm ||(f_int + b) V|| over the constrained ones
// (or a user value; ||f_int V|| when both are zero). A solve that reaches max_iter, or whose residual turns non-finite, returns
// converged = false with a message: never silently. Round-off floor: y = x + u is rounded at the
// scale of the coordinates, so a bond extension |Y| - |xi| carries an error ~ 1e-16 max|x| and the
// relative residual cannot go much below 1e-16 max|x| / (strain dx) (1D bar, 400 nodes, strain
// 5e-4: stalls at 4e-10); a tighter tol ends as not converged. Iterations grow ~ linearly with
// the nodes across the body per decade of residual (1D PMB to 1e-8: 365, 750, 1501, 2976
// iterations for 50, 100, 200, 400 nodes).
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/bond_loop.hpp"
#include "pd/io/timer.hpp"
#include "pd/lattice.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/pmb.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {

namespace detail {
// Unit bond direction n = xi / |xi| from the reference positions.
template <int D>
inline Vec<D> bond_direction(const Field<D>& x, std::size_t i, int j, double L)
{
    Vec<D> n;
    for (int d = 0; d < D; ++d) n[d] = (x.c[d][j] - x.c[d][i]) / L;
    return n;
}
template <int D>
inline double norm1(const Vec<D>& n)
{
    double s = 0;
    for (int d = 0; d < D; ++d) s += std::abs(n[d]);
    return s;
}
}  // namespace detail

// Gershgorin row sums G_ia = sum_(j,b) |K_(ia)(jb)| [N/m^4 per m of displacement, in 3D N/m^5] of
// a pair-spring stiffness with spring constant k_k = c omega V_j / |xi| per bond (the linearised
// PMB: K_ij = -k n n^T, K_ii = sum_j k n n^T), so G_ia = 2 sum_j k_j |n_a| ||n||_1.
template <int D>
Field<D> stiffness_bound_springs(const Bonds& b, const Field<D>& x, const std::vector<double>& spring)
{
    Field<D> G(b.nodes());
    for (std::size_t i = 0; i < b.nodes(); ++i)
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const Vec<D> n = detail::bond_direction(x, i, b.partner[k], b.length[k]);
            const double w = 2 * spring[k] * detail::norm1(n);
            for (int d = 0; d < D; ++d) G.c[d][i] += w * std::abs(n[d]);
        }
    return G;
}

// PMB: exact Gershgorin row sums of the stiffness at the reference configuration (k = PMB::coef).
template <int D>
Field<D> stiffness_bound(const PMB& model, const Bonds& b, const Field<D>& x)
{
    return stiffness_bound_springs(b, x, model.coef);
}

// Stand-in for any model: the PMB formula with micromodulus c [N/m^6 in 3D] (as the critical step).
template <int D>
Field<D> stiffness_bound_micromodulus(const Bonds& b, const Field<D>& x, double c)
{
    std::vector<double> spring(b.size());
    for (std::size_t k = 0; k < b.size(); ++k) spring[k] = c * b.omega[k] * b.volume[k] / b.length[k];
    return stiffness_bound_springs(b, x, spring);
}

// LPS linearised at the reference (lps.hpp, with beta = p - alpha/D):
//   df_i = sum_k wV_k n_k [ L_k (beta_i dtheta_i + beta_j dtheta_j) + (alpha_i + alpha_j) n_k.(du_j - du_i) ]
//   dtheta_i = (D/m_i) sum_l wV_l L_l n_l.(du_(j_l) - du_i)
// Row bound by the triangle inequality, with T_i = (D/m_i) sum_l wV_l L_l 2 ||n_l||_1 (row sum of dtheta_i):
//   G_ia = sum_k wV_k (alpha_i + alpha_j) |n_a| 2 ||n||_1 + |beta_i| |sum_k wV_k L_k n_a| T_i
//          + sum_k wV_k L_k |n_a| |beta_j| T_j.
template <int D>
Field<D> stiffness_bound(const LPS& model, const Bonds& b, const Field<D>& x)
{
    const std::size_t nn = b.nodes();
    std::vector<double> T(nn, 0.0), beta(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        beta[i] = model.p_coef[i] - model.alpha[i] / model.dim;
        double s = 0;
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            s += model.wV[k] * b.length[k] * 2 * detail::norm1(detail::bond_direction(x, i, b.partner[k], b.length[k]));
        T[i] = model.m[i] > 0 ? model.dim * s / model.m[i] : 0.0;
    }
    Field<D> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        Vec<D> first{};  // sum_k wV_k L_k n_k: zero for a symmetric (interior) family
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            const int j = b.partner[k];
            const double L = b.length[k];
            const Vec<D> n = detail::bond_direction(x, i, j, L);
            const double pair = model.wV[k] * (model.alpha[i] + model.alpha[j]) * 2 * detail::norm1(n);
            for (int d = 0; d < D; ++d) {
                G.c[d][i] += (pair + model.wV[k] * L * std::abs(beta[j]) * T[j]) * std::abs(n[d]);
                first[d] += model.wV[k] * L * n[d];
            }
        }
        for (int d = 0; d < D; ++d) G.c[d][i] += std::abs(beta[i]) * std::abs(first[d]) * T[i];
    }
    return G;
}

// PALS linearised at the reference (pals.hpp; t = 0 there, so only d t along n contributes):
//   d t_k = L_k [a_ik dtheta_i - (w_ik/3) dq_i + a_jk dtheta_j - (w_jk/3) dq_j] + (s_ik + s_jk) de_k,
//   a_ik = w_ik A_i - s_ik/3,  A_i = K + 2G m_sigma_i/9,  de_l = n_l.(du_(j_l) - du_i),
//   dtheta_i = sum_l w_il L_l de_l,  dq_i = sum_l s_il L_l de_l  (q = (2G sigma x)•e, p = A theta - q/3),
// with w = omega V_j and s = 2G sigma V_j of either end (negative values allowed). Row bound by
// the triangle inequality (a functional sum_l c_l de_l has row sum <= sum_l |c_l| 2 ||n_l||_1):
//   G_ia = sum_k |s_ik + s_jk| |n_a| 2 ||n||_1                                    (pair term)
//        + sum_l |X_a w_il + Y_a s_il| L_l 2 ||n_l||_1,  X_a = sum_k n_a L a_ik, Y_a = -sum_k n_a L w_ik/3
//        + sum_k |n_a| L_k (|a_jk| Tw_j + |w_jk| Ts_j / 3),  Tw_j = sum_l |w_jl| L_l 2 ||n_l||_1 (Ts: s).
inline Field<3> stiffness_bound(const PALS& model, const Bonds& b, const Field<3>& x)
{
    const std::size_t nn = b.nodes();
    auto intact = [&](std::int64_t k) { return !b.has_damage() || b.intact[k]; };
    std::vector<double> A(nn), Tw(nn, 0.0), Ts(nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i) {
        A[i] = model.K + 2 * model.G * model.m_sigma[i] / 9;
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const double r = b.length[k] * 2 * detail::norm1(detail::bond_direction(x, i, b.partner[k], b.length[k]));
            Tw[i] += std::abs(model.w_i[k]) * r;
            Ts[i] += std::abs(model.s_i[k]) * r;
        }
    }
    Field<3> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        Vec<3> X{}, Y{};
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const int j = b.partner[k];
            const double L = b.length[k];
            const Vec<3> n = detail::bond_direction(x, i, j, L);
            const double a_i = model.w_i[k] * A[i] - model.s_i[k] / 3, a_j = model.w_j[k] * A[j] - model.s_j[k] / 3;
            const double pair = std::abs(model.s_i[k] + model.s_j[k]) * 2 * detail::norm1(n);
            const double far = L * (std::abs(a_j) * Tw[j] + std::abs(model.w_j[k]) * Ts[j] / 3);
            for (int d = 0; d < 3; ++d) {
                G.c[d][i] += (pair + far) * std::abs(n[d]);
                X[d] += n[d] * L * a_i;
                Y[d] -= n[d] * L * model.w_i[k] / 3;
            }
        }
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const double L = b.length[k];
            const double r = L * 2 * detail::norm1(detail::bond_direction(x, i, b.partner[k], L));
            for (int d = 0; d < 3; ++d) G.c[d][i] += std::abs(X[d] * model.w_i[k] + Y[d] * model.s_i[k]) * r;
        }
    }
    return G;
}

// Correspondence linearised at the reference (F = I, P = 0; the same tangent for every Law:
// dP = C : sym(dF) with Lame lambda, G), from the model's Params and the bonds only:
//   dF_i = sum_l (du_(j_l) - du_i) (x) g_il,  g_il = omega V_l K_i^-1 xi_l,  h_i = sum_l g_il,
//   df_i = dP_i h_i + sum_k dP_j r_k,  r_k = omega V_k K_j^-1 xi_k  (j = partner of bond k),
//   dP_i h = sum_l C(h, g_il) (du_(j_l) - du_i),  C_ac(h, g) = lambda h_a g_c + G delta_ac g.h + G g_a h_c.
// Row bound (each difference counted twice, |g.h| <= sum_b |g_b||h_b|), S1_i = sum_l ||g_il||_1,
// S_ib = sum_l |g_il,b|:
//   G_ia = 2 [lambda |h_a| S1_i + G sum_b |h_b| S_ib + G ||h||_1 S_ia]
//        + 2 sum_k [lambda |r_ka| S1_j + G sum_b |r_kb| S_jb + G ||r_k||_1 S_ja]
// plus the Littlewood term linearised, c_hg V_k/|xi| ((2 d eta - (dF_i + dF_j) xi).n) n, with
// |g_il.xi_k| <= |g_il| |xi_k| and Sg_i = sum_l |g_il|:
//        + sum_k c_hg V_k |n_a| ||n||_1 (4/|xi_k| + 2 (Sg_i + Sg_j)).
// K_i^-1 = 0 where K_i is singular, with the model's rule (|det| <= 1e-12 (tr K / D)^D).
template <int D>
Field<D> stiffness_bound(const Correspondence<D>& model, const Bonds& b, const Field<D>& x)
{
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    const auto& par = model.par;
    const double Gs = par.material.G;
    double lam = par.material.K - 2 * Gs / 3;
    if (D == 2 && par.plane == Plane::stress) lam = 2 * lam * Gs / (lam + 2 * Gs);
    const double c_hg = par.C_hg * pmb_micromodulus(kappa_dim(par.material, D, par.plane), D,
                                                    horizon_moment(Influence{}, 1, b.delta, D, par.measure));
    const std::size_t nn = b.nodes();
    auto intact = [&](std::int64_t k) { return !b.has_damage() || b.intact[k]; };
    auto xi = [&](std::size_t i, int j) {
        Col e;
        for (int d = 0; d < D; ++d) e(d) = x.c[d][j] - x.c[d][i];
        return e;
    };
    std::vector<Mat> Kinv(nn, Mat::Zero());
    std::vector<Col> h(nn, Col::Zero()), S(nn, Col::Zero());
    std::vector<double> S1(nn, 0.0), Sg(nn, 0.0);
    for (std::size_t i = 0; i < nn; ++i) {
        Mat K = Mat::Zero();
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k)
            if (intact(k)) K += b.omega[k] * b.volume[k] * xi(i, b.partner[k]) * xi(i, b.partner[k]).transpose();
        const double scale = K.trace() / D;
        if (!(scale > 0) || !(std::abs(K.determinant()) > 1e-12 * std::pow(scale, D))) continue;
        Kinv[i] = K.inverse();
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const Col g = b.omega[k] * b.volume[k] * (Kinv[i] * xi(i, b.partner[k]));
            h[i] += g;
            S[i] += g.cwiseAbs();
            S1[i] += g.template lpNorm<1>();
            Sg[i] += g.norm();
        }
    }
    Field<D> G(nn);
    for (std::size_t i = 0; i < nn; ++i) {
        const Col ha = h[i].cwiseAbs();
        Col row = 2 * (lam * S1[i] * ha + Gs * ha.dot(S[i]) * Col::Ones() + Gs * ha.sum() * S[i]);
        for (std::int64_t k = b.begin(i); k < b.end(i); ++k) {
            if (!intact(k)) continue;
            const int j = b.partner[k];
            const Col e = xi(i, j);
            const Col ra = (b.omega[k] * b.volume[k] * (Kinv[j] * e)).cwiseAbs();
            row += 2 * (lam * S1[j] * ra + Gs * ra.dot(S[j]) * Col::Ones() + Gs * ra.sum() * S[j]);
            if (c_hg != 0) {
                const double L = e.norm();
                const Col na = e.cwiseAbs() / L;
                row += c_hg * b.volume[k] * na.sum() * (4 / L + 2 * (Sg[i] + Sg[j])) * na;
            }
        }
        for (int d = 0; d < D; ++d) G.c[d][i] = row(d);
    }
    return G;
}

struct RelaxationResult {
    bool converged = false;
    long iterations = 0;                         // force evaluations after the initial one
    double residual = 0;                         // final ||F V||_free / force_scale [-]
    double force_scale = 0;                      // [N]
    std::vector<std::pair<long, double>> history;  // (iteration, relative residual) every history_every
    double wall_s = 0;                           // [s]
    std::string message;                         // why it stopped
};

template <int D, class Model>
class DynamicRelaxation {
public:
    const Body<D>& body;
    const Bonds& bonds;
    Model& model;
    double safety = 1.2;       // lambda = safety * dt^2/4 * G (see header) [-]
    long history_every = 100;  // residual history stride [iterations]
    double force_scale = 0;    // [N]; > 0 overrides the automatic scale

    // Density from stiffness_bound(model, bonds, x) (PMB, LPS, PALS, correspondence).
    DynamicRelaxation(const Body<D>& body, const Bonds& bonds, Model& model)
        : DynamicRelaxation(body, bonds, model, stiffness_bound(model, bonds, body.x)) {}
    // Density from given Gershgorin row sums G [N/m^5 in 3D], e.g. stiffness_bound_micromodulus.
    DynamicRelaxation(const Body<D>& body, const Bonds& bonds, Model& model, Field<D> row_sum)
        : body(body), bonds(bonds), model(model), G_(std::move(row_sum))
    {
        if (G_.size() != body.size() || bonds.nodes() != body.size())
            throw std::invalid_argument("DynamicRelaxation: body, bonds and stiffness bound sizes differ");
    }

    // Relaxes u (in/out: the initial guess, e.g. the previous load level) to the equilibrium at
    // t_load: prescribed displacements g(t_load), body forces at t_load.
    RelaxationResult solve(Field<D>& u, const Boundary<D>& bc, double t_load, double tol, long max_iter)
    {
        if (!(tol > 0)) throw std::invalid_argument("DynamicRelaxation: tolerance must be positive");
        if (max_iter < 0) throw std::invalid_argument("DynamicRelaxation: max_iter must be >= 0");
        if (u.size() != body.size()) throw std::invalid_argument("DynamicRelaxation: displacement field size differs from the body");
        const io::Timer timer;
        const std::size_t n = body.size();
        constexpr double dt = 1;  // fictitious time step (K&M: any value, lambda scales with dt^2)
        setup(u, bc, t_load);
        for (int d = 0; d < D; ++d) v_.c[d].assign(n, 0.0);
        RelaxationResult r;
        double res = evaluate(r);
        r.history.push_back({0, res});
        // Start-up, K&M eq. 14: v^{1/2} = dt F^0 / (2 lambda).
        for_free([&](int d, std::size_t i) { v_.c[d][i] = dt * F_.c[d][i] / (2 * lambda_.c[d][i]); });
        long it = 0;
        while (!(res <= tol) && std::isfinite(res) && it < max_iter) {
            for_free([&](int d, std::size_t i) { u.c[d][i] += dt * v_.c[d][i]; });  // eq. 13
            for (int d = 0; d < D; ++d) F_prev_.c[d] = F_.c[d];
            ++it;
            add_fields(body.x, u, y_);
            res = evaluate(r);
            if (history_every > 0 && it % history_every == 0) r.history.push_back({it, res});
            // Rayleigh quotient with the diagonal local stiffness (eqs. 15, 16).
            double num = 0, den = 0;
            for_free([&](int d, std::size_t i) {
                const double ud = u.c[d][i], vd = v_.c[d][i];
                den += ud * ud;
                if (vd != 0) num += ud * ud * (-(F_.c[d][i] - F_prev_.c[d][i]) / (lambda_.c[d][i] * dt * vd));
            });
            double c = (num > 0 && den > 0) ? 2 * std::sqrt(num / den) : 0.0;
            c = std::min(c, 2 / dt);  // c dt <= 2 keeps 2 - c dt >= 0: the old velocity is never reversed
            for_free([&](int d, std::size_t i) {  // eq. 13
                v_.c[d][i] = ((2 - c * dt) * v_.c[d][i] + 2 * dt * F_.c[d][i] / lambda_.c[d][i]) / (2 + c * dt);
            });
        }
        r.iterations = it;
        r.residual = res;
        r.converged = res <= tol;
        if (r.history.back().first != it) r.history.push_back({it, res});
        std::ostringstream msg;
        if (r.converged) msg << "converged";
        else if (!std::isfinite(res)) msg << "residual became non-finite at iteration " << it;
        else msg << "not converged in " << max_iter << " iterations (relative residual " << res << " > " << tol << ")";
        r.message = msg.str();
        r.wall_s = timer.seconds();
        return r;
    }

    // Load stepping: solves at each t in t_levels in order, warm-starting from the previous u.
    // Stops after the first level that does not converge (its result is the last one returned).
    std::vector<RelaxationResult> solve_steps(Field<D>& u, const Boundary<D>& bc, const std::vector<double>& t_levels,
                                              double tol, long max_iter)
    {
        std::vector<RelaxationResult> out;
        for (double t : t_levels) {
            out.push_back(solve(u, bc, t, tol, max_iter));
            if (!out.back().converged) break;
        }
        return out;
    }

    const Field<D>& density() const { return lambda_; }             // lambda [kg/m^3 per unit fictitious time^2]
    const Field<D>& internal_force_density() const { return f_; }  // f_int at the last iterate [N/m^3]
    // Reaction force [N] summed over the constrained components: -sum (f_int + b) V per component.
    Vec<D> reaction() const
    {
        Vec<D> R{};
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body.size(); ++i)
                if (constrained_[i * D + d]) R[d] -= (f_.c[d][i] + b_.c[d][i]) * body.volume[i];
        return R;
    }

private:
    Field<D> G_, lambda_, v_, F_, F_prev_, f_, b_, y_;
    std::vector<std::uint8_t> constrained_;

    template <class Fn>
    void for_free(Fn&& fn) const
    {
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body.size(); ++i)
                if (!constrained_[i * D + d]) fn(d, i);
    }

    void setup(Field<D>& u, const Boundary<D>& bc, double t_load)
    {
        const std::size_t n = body.size();
        constrained_.assign(n * D, 0);
        for (const auto& p : bc.prescribed) {
            if (p.kind != Prescribed::Kind::displacement)
                throw std::invalid_argument("DynamicRelaxation: prescribed velocities have no quasi-static meaning; prescribe displacements");
            const double g = p.g(t_load);
            for (int i : p.nodes) {
                constrained_[i * D + p.component] = 1;
                u.c[p.component][i] = g;
            }
        }
        lambda_.resize(n);
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < n; ++i) {
                // K&M eq. 17 with dt = 1; an unconnected node (G = 0) keeps unit density.
                const double g = safety * 0.25 * G_.c[d][i];
                lambda_.c[d][i] = g > 0 ? g : 1.0;
            }
        v_.resize(n);
        F_.resize(n);
        F_prev_.resize(n);
        b_.resize(n);
        bc.external(t_load, b_);
        add_fields(body.x, u, y_);
    }

    // F = f_int(y) + b on free components (0 on constrained ones); returns the relative residual.
    double evaluate(RelaxationResult& r)
    {
        internal_force(model, bonds, y_, f_);
        double rr = 0, bb = 0, reac = 0, ff = 0;
        for (int d = 0; d < D; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) {
                const double V = body.volume[i];
                const double Fi = f_.c[d][i] + b_.c[d][i];
                bb += b_.c[d][i] * b_.c[d][i] * V * V;
                ff += f_.c[d][i] * f_.c[d][i] * V * V;
                if (constrained_[i * D + d]) {
                    F_.c[d][i] = 0;
                    reac += Fi * Fi * V * V;
                } else {
                    F_.c[d][i] = Fi;
                    rr += Fi * Fi * V * V;
                }
            }
        double scale = force_scale > 0 ? force_scale : std::sqrt(std::max(bb, reac));
        if (scale == 0) scale = std::sqrt(ff);  // unloaded and unconstrained: relative to ||f_int V||
        r.force_scale = scale;
        return scale > 0 ? std::sqrt(rr) / scale : 0.0;
    }
};

}  // namespace pd
