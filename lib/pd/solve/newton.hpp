// Quasi-static Newton-Raphson on the nodal balance R(u) = (f_int(u) + b) V = 0 (spec/000a sec. 3.5,
// eq. 3.26) over the free dofs, with the sparse tangent K = -dF_int/du of solve/tangent.hpp:
//   K(u^k) du = R(u^k),  u^{k+1} = u^k + du   (prescribed components held at g(t_load)).
// Boundary handling, force scale and convergence test are those of DynamicRelaxation
// (time/dynamic_relaxation.hpp): relative residual ||R||_free / scale <= tol, the scale being the
// larger of ||b V|| and the reaction norm over the constrained components (or a user value;
// ||f_int V|| when both vanish). Load stepping warm-starts each level from the previous one; the
// jump of the prescribed values enters through the residual of the first iteration.
// Linear solver: sparse Cholesky, CG or LU (solve/linear_solver.hpp). Modified Newton (`reuse_tangent`) keeps the tangent (and the
// factorisation) of the first iteration of a level while the residual falls by at least
// `reuse_ratio` per iteration, and re-assembles otherwise.
// Failure is never silent: max_iter reached, non-finite residual, a failed factorisation (singular
// tangent) or CG without convergence return converged = false with a message.
#pragma once
#include "pd/bc/boundary.hpp"
#include "pd/bond_loop.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/rate_form.hpp"
#include "pd/solve/linear_solver.hpp"
#include "pd/solve/tangent.hpp"


#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <vector>

namespace pd {

struct NewtonOptions {
    double tol = 1e-8;          // relative residual [-]
    int max_iter = 30;          // linear solves per load level
    LinearSolver linear = LinearSolver::cholesky;
    double cg_tol = 1e-12;      // CG: ||K du - R|| <= cg_tol ||R||
    int cg_max_iter = 0;        // 0: Eigen's default (2 x dofs)
    bool reuse_tangent = false; // modified Newton (header)
    double reuse_ratio = 0.1;   // residual must fall by this factor per iteration to keep the tangent
    double fd_step = 0;         // finite-difference step [m]; 0: tangent_step
    double force_scale = 0;     // [N]; > 0 overrides the automatic scale
    std::ostream* log = nullptr; // one line per iteration when set
};

struct NewtonResult {
    bool converged = false;
    int iterations = 0;            // linear solves
    int tangents = 0;              // tangent assemblies
    double residual = 0;           // final relative residual [-]
    double force_scale = 0;        // [N]
    std::vector<double> history;   // relative residual before each iteration and at the end [-]
    double wall_s = 0, tangent_s = 0, linear_s = 0;  // [s]
    std::string message;
};

template <int D, class Model>
class Newton {
public:
    const Body<D>& body;
    const Bonds& bonds;
    Model& model;

    Newton(const Body<D>& body, const Bonds& bonds, Model& model) : body(body), bonds(bonds), model(model)
    {
        if (bonds.nodes() != body.size()) throw std::invalid_argument("Newton: body and bonds sizes differ");
        reject_unwrapped_rate_form(model, "Newton");
    }

    // Solves for u (in/out: initial guess) at load level t_load.
    NewtonResult solve(Field<D>& u, const Boundary<D>& bc, double t_load, const NewtonOptions& opt)
    {
        if (!(opt.tol > 0)) throw std::invalid_argument("Newton: tolerance must be positive");
        if (opt.max_iter < 0) throw std::invalid_argument("Newton: max_iter must be >= 0");
        if (u.size() != body.size()) throw std::invalid_argument("Newton: displacement field size differs from the body");
        const io::Timer timer;
        setup(u, bc, t_load);
        NewtonResult r;
        double res = evaluate(u, opt, r);
        r.history.push_back(res);
        bool have_tangent = false;
        double prev = res;
        std::string failure;
        while (!(res <= opt.tol) && std::isfinite(res) && r.iterations < opt.max_iter) {
            if (!have_tangent || !opt.reuse_tangent || res > opt.reuse_ratio * prev) {
                const io::Timer tt;
                K_ = tangent(model, body, bonds, y_, dofs_, colouring(), opt.fd_step);
                ++r.tangents;
                r.tangent_s += tt.seconds();
                const io::Timer ft;
                if (!linear_.factorise(K_, opt.linear, opt.cg_tol, opt.cg_max_iter, failure)) { r.linear_s += ft.seconds(); break; }
                r.linear_s += ft.seconds();
                have_tangent = true;
            }
            const io::Timer st;
            Eigen::VectorXd du;
            const bool ok = linear_.solve(R_, du, failure);
            r.linear_s += st.seconds();
            if (!ok) break;
            for (std::size_t i = 0; i < body.size(); ++i)
                for (int d = 0; d < D; ++d)
                    if (const int q = dofs_.index[i * D + d]; q >= 0) u.c[d][i] += du[q];
            ++r.iterations;
            prev = res;
            res = evaluate(u, opt, r);
            r.history.push_back(res);
            if (opt.log) *opt.log << "newton it " << r.iterations << " residual " << res << "\n";
        }
        r.residual = res;
        r.converged = res <= opt.tol;
        std::ostringstream msg;
        if (r.converged) msg << "converged";
        else if (!failure.empty()) msg << failure << " at iteration " << r.iterations;
        else if (!std::isfinite(res)) msg << "residual became non-finite at iteration " << r.iterations;
        else msg << "not converged in " << opt.max_iter << " iterations (relative residual " << res << " > " << opt.tol << ")";
        r.message = msg.str();
        r.wall_s = timer.seconds();
        return r;
    }

    // Load stepping: solves at each t in t_levels in order; stops after the first failure.
    std::vector<NewtonResult> solve_steps(Field<D>& u, const Boundary<D>& bc, const std::vector<double>& t_levels,
                                          const NewtonOptions& opt)
    {
        std::vector<NewtonResult> out;
        for (double t : t_levels) {
            out.push_back(solve(u, bc, t, opt));
            if (!out.back().converged) break;
        }
        return out;
    }

    const Field<D>& internal_force_density() const { return f_; }  // at the last iterate [N/m^3]
    const Eigen::SparseMatrix<double>& last_tangent() const { return K_; }
    const DofMap& dofs() const { return dofs_; }
    // Reaction force [N] summed over the constrained components: -sum (f_int + b) V per component.
    Vec<D> reaction() const
    {
        Vec<D> R{};
        for (std::size_t i = 0; i < body.size(); ++i)
            for (int d = 0; d < D; ++d)
                if (dofs_.index[i * D + d] < 0) R[d] -= (f_.c[d][i] + b_.c[d][i]) * body.volume[i];
        return R;
    }
    // The colouring used by the finite-difference tangent (computed once per solver).
    const Colouring& colouring()
    {
        if (colouring_.colour.empty() && !std::is_same_v<Model, PMB>) colouring_ = colour_bond_graph(bonds, tangent_reach<Model>());
        return colouring_;
    }

private:
    Field<D> f_, b_, y_;
    Eigen::VectorXd R_;
    DofMap dofs_;
    Colouring colouring_;
    Eigen::SparseMatrix<double> K_;
    SparseSolver linear_;

    void setup(Field<D>& u, const Boundary<D>& bc, double t_load)
    {
        std::vector<std::uint8_t> constrained(body.size() * D, 0);
        for (const auto& p : bc.prescribed) {
            if (p.kind != Prescribed::Kind::displacement)
                throw std::invalid_argument("Newton: prescribed velocities have no quasi-static meaning; prescribe displacements");
            const double g = p.g(t_load);
            for (int i : p.nodes) {
                constrained[i * D + p.component] = 1;
                u.c[p.component][i] = g;
            }
        }
        if (dofs_.index.empty() || DofMap(constrained).index != dofs_.index) dofs_ = DofMap(constrained);
        b_.resize(body.size());
        bc.external(t_load, b_);
    }

    // R = (f_int + b) V on the free dofs; returns the relative residual (as DynamicRelaxation).
    double evaluate(const Field<D>& u, const NewtonOptions& opt, NewtonResult& r)
    {
        add_fields(body.x, u, y_);
        internal_force(model, bonds, y_, f_);
        R_.setZero(dofs_.free);
        double rr = 0, bb = 0, reac = 0, ff = 0;
        for (std::size_t i = 0; i < body.size(); ++i)
            for (int d = 0; d < D; ++d) {
                const double V = body.volume[i];
                const double Fi = (f_.c[d][i] + b_.c[d][i]) * V;
                bb += b_.c[d][i] * b_.c[d][i] * V * V;
                ff += f_.c[d][i] * f_.c[d][i] * V * V;
                if (const int q = dofs_.index[i * D + d]; q >= 0) {
                    R_[q] = Fi;
                    rr += Fi * Fi;
                } else {
                    reac += Fi * Fi;
                }
            }
        double scale = opt.force_scale > 0 ? opt.force_scale : std::sqrt(std::max(bb, reac));
        if (scale == 0) scale = std::sqrt(ff);
        r.force_scale = scale;
        return scale > 0 ? std::sqrt(rr) / scale : 0.0;
    }
};

}  // namespace pd
