// Transient heat conduction on a peridynamic body (spec/000b sec. 3.3; spec/000a sec. 3.2.3,
// 3.5.2-3.5.4):
//   rho c_i(theta_i) dtheta_i/dt = Q_i(theta) + s_i - h_i (theta_i - T_inf)       (free nodes)
//   theta_i = held value                                                          (fixed nodes)
// Q from the heat loop (heat_loop.hpp) of any heat model; s the volumetric source [W/m^3] (a surface
// flux q [W/m^2] enters as q/depth on the boundary layer, add_surface_flux); h the convection
// coefficient per unit volume h_s/depth [W/(m^3 K)] (heat leaves where theta > T_inf). Nodes with
// neither are adiabatic (the default). Integrators:
//   explicit_euler   theta += dt (Q + s - h (theta - T_inf)) / (rho c(theta)); stable below
//                    thermal_critical_step (Gershgorin bound of the operator).
//   implicit_euler   (rho c/dt + h - A) theta^{n+1} = rho c/dt theta^n + s + h T_inf, A the linear
//                    heat operator of the model (Q = A theta); fixed rows are identity rows. The sparse LU
//                    factorisation is kept while dt and rho c do not change; rho c(theta) is taken at
//                    theta^n (lagged). Unconditionally stable.
// A nonlinear model (Model::nonlinear, e.g. the temperature-dependent conductivity of
// conductivity.hpp, Q = A(theta) theta) makes implicit_euler and steady_state iterate by Picard:
// theta^(m+1) solves the linear system with A(theta^(m)), until max_i |theta^(m+1) - theta^(m)| <=
// picard_tol max(1, max_i |theta^(m+1)|) (default 1e-10: with a contraction rate rho <= 1/2 the
// distance to the fixed point is at most that change); std::runtime_error after picard_max_iter.
// (CVODE BDF: time/heat_cvode.hpp.)
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/heat/heat_loop.hpp"
#include "pd/heat/temperature_field.hpp"

#include <Eigen/Sparse>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseLU>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace pd {

// A heat model whose heat flow is not linear in theta (declares `static constexpr bool nonlinear`).
template <class Model>
concept NonlinearHeat = requires { Model::nonlinear; } && Model::nonlinear;

struct HeatLoads {
    std::vector<double> source;        // s_i [W/m^3]; empty = none
    std::vector<double> h;             // convection per unit volume [W/(m^3 K)]; empty = none
    double T_inf = 0;                  // ambient temperature of the convection [K or C]
    std::vector<int> fixed;            // nodes held at a temperature
    std::vector<double> fixed_value;   // their temperatures [K or C]
    // Optional: the temperature of held node fixed[f] at time t [s] (replaces fixed_value; explicit and
    // implicit Euler take it at the end of each step, Conduction::time; CVODE refuses it).
    std::function<double(std::size_t f, double t)> fixed_at;
};

// Adds a surface flux q [W/m^2] (positive into the body) on a boundary layer of the given depth [m].
inline void add_surface_flux(HeatLoads& loads, std::size_t n, const std::vector<int>& layer, double q, double depth)
{
    if (!(depth > 0)) throw std::invalid_argument("add_surface_flux: layer depth must be positive");
    loads.source.resize(n, 0.0);
    for (int i : layer) loads.source[i] += q / depth;
}

// Rows of a bond-wise heat operator: A_ij = c(i, k) for every intact bond k = i-j and A_ii = -sum_k c(i, k),
// c(i, k) the conductance of bond k [W/(m^3 K)] (Agwai: coef_k; with k(theta): k_ij coef_k).
template <class Conductance>
void add_bond_operator(const Bonds& b, std::vector<Eigen::Triplet<double>>& t, Conductance&& c)
{
    for (std::size_t i = 0; i < b.nodes(); ++i) {
        double diag = 0;
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const double ck = c(i, k);
            t.emplace_back(int(i), j, ck);
            diag -= ck;
        });
        t.emplace_back(int(i), int(i), diag);
    }
}

// Linear heat operator A (Q = A theta) of a model: its own add_operator(bonds, triplets) when it has
// one (correspondence heat), else from per-bond conductances coef (Agwai).
template <class Model>
Eigen::SparseMatrix<double> heat_operator(const Model& model, const Bonds& b)
{
    std::vector<Eigen::Triplet<double>> t;
    if constexpr (requires { model.add_operator(b, t); }) {
        model.add_operator(b, t);
    } else {
        t.reserve(b.size() + b.nodes());
        add_bond_operator(b, t, [&](std::size_t, std::int64_t k) { return model.coef[k]; });
    }
    Eigen::SparseMatrix<double> A(int(b.nodes()), int(b.nodes()));
    A.setFromTriplets(t.begin(), t.end());
    return A;
}

template <class Model>
class Conduction {
public:
    // rho_c: volumetric heat capacity per node [J/(m^3 K)]. rho_c_of (optional): rho c as a
    // function of node and temperature, used instead when set.
    Conduction(Model& model, const Bonds& bonds, std::vector<double> rho_c, HeatLoads loads)
        : model_(model), bonds_(bonds), rho_c_(std::move(rho_c)), loads_(std::move(loads)), held_(bonds.nodes(), 0)
    {
        const std::size_t n = bonds.nodes();
        if (rho_c_.size() != n) throw std::invalid_argument("Conduction: one rho c per node");
        for (double v : rho_c_)
            if (!(v > 0)) throw std::invalid_argument("Conduction: rho c must be positive");
        if (!loads_.source.empty() && loads_.source.size() != n) throw std::invalid_argument("Conduction: source size");
        if (!loads_.h.empty() && loads_.h.size() != n) throw std::invalid_argument("Conduction: convection size");
        if (loads_.fixed.size() != loads_.fixed_value.size()) throw std::invalid_argument("Conduction: fixed values");
        for (int i : loads_.fixed) held_.at(i) = 1;
    }

    std::function<double(std::size_t, double)> rho_c_of;  // optional rho c(i, theta) [J/(m^3 K)]

    double rho_c(std::size_t i, double theta) const { return rho_c_of ? rho_c_of(i, theta) : rho_c_[i]; }
    double source(std::size_t i) const { return loads_.source.empty() ? 0.0 : loads_.source[i]; }
    double h(std::size_t i) const { return loads_.h.empty() ? 0.0 : loads_.h[i]; }
    bool held(std::size_t i) const { return held_[i]; }
    const HeatLoads& loads() const { return loads_; }
    Model& model() { return model_; }
    const Bonds& bonds() const { return bonds_; }

    double time = 0;  // [s] the time at which apply_fixed takes fixed_at (ConductingField: end of the step)
    double picard_tol = 1e-10;    // relative change that ends the Picard iteration [-] (nonlinear models)
    int picard_max_iter = 100;    // Picard iterations before giving up
    int picard_iterations = 0;    // iterations of the last implicit step or steady solve
    long picard_total = 0;        // iterations of all implicit steps and steady solves so far

    // Sets the held temperatures (at `time` when HeatLoads::fixed_at is given).
    void apply_fixed(std::vector<double>& theta) const
    {
        for (std::size_t f = 0; f < loads_.fixed.size(); ++f)
            theta[loads_.fixed[f]] = loads_.fixed_at ? loads_.fixed_at(f, time) : loads_.fixed_value[f];
    }

    // Net heating power density of every node [W/m^3] (0 on held nodes) and the heat flow Q into each.
    void heating(const std::vector<double>& theta, std::vector<double>& P)
    {
        heat_flow(model_, bonds_, theta, Q_);
        P.resize(theta.size());
        for (std::size_t i = 0; i < theta.size(); ++i)
            P[i] = held_[i] ? 0.0 : Q_[i] + source(i) - h(i) * (theta[i] - loads_.T_inf);
    }
    // Heat-flow density Q of the last heating() call [W/m^3] (on held nodes too: the reaction).
    const std::vector<double>& last_heat_flow() const { return Q_; }

    void explicit_euler(std::vector<double>& theta, double dt)
    {
        heating(theta, P_);
        for (std::size_t i = 0; i < theta.size(); ++i)
            if (!held_[i]) theta[i] += dt * P_[i] / rho_c(i, theta[i]);
        apply_fixed(theta);
    }

    void implicit_euler(std::vector<double>& theta, double dt)
    {
        if constexpr (NonlinearHeat<Model>) {
            implicit_euler_picard(theta, dt);
            return;
        }
        const std::size_t n = theta.size();
        std::vector<double> rc(n);
        for (std::size_t i = 0; i < n; ++i) rc[i] = rho_c(i, theta[i]);
        if (!lu_ || dt != lu_dt_ || rc != lu_rc_ || operator_may_have_changed()) factorise(dt, rc);
        apply_fixed(theta);
        Eigen::VectorXd rhs(n), held_values = Eigen::VectorXd::Zero(n);
        for (std::size_t i = 0; i < n; ++i) {
            rhs[i] = held_[i] ? theta[i] : rc[i] / dt * theta[i] + source(i) + h(i) * loads_.T_inf;
            if (held_[i]) held_values[i] = theta[i];
        }
        rhs += coupling_ * held_values;  // known held temperatures moved to the right-hand side
        const Eigen::VectorXd next = lu_->solve(rhs);
        if (lu_->info() != Eigen::Success) throw std::runtime_error("implicit Euler: sparse solve failed");
        for (std::size_t i = 0; i < n; ++i) theta[i] = next[i];
    }

    // Steady state: Q + s - h (theta - T_inf) = 0 on free nodes, held values on held nodes, by
    // BiCGSTAB with a diagonal preconditioner to a relative residual `tol` (the operator is
    // non-symmetric with the per-node thermal correction). Needs at least one held node or h > 0.
    // Returns the iterations; throws std::runtime_error when it does not converge.
    int steady_state(std::vector<double>& theta, double tol = 1e-12)
    {
        if constexpr (NonlinearHeat<Model>) {
            int krylov = 0;
            picard([&](std::vector<double>& next) { krylov += steady_linear(next, tol); }, theta, "steady state");
            return krylov;
        }
        return steady_linear(theta, tol);
    }

private:
    int steady_linear(std::vector<double>& theta, double tol)
    {
        const std::size_t n = theta.size();
        apply_fixed(theta);
        bool anchored = !loads_.fixed.empty();
        for (std::size_t i = 0; i < n && !anchored; ++i) anchored = h(i) > 0;
        if (!anchored) throw std::invalid_argument("steady state: no held temperature and no convection (singular)");
        std::vector<double> zero(n, 0.0);
        assemble(zero);  // rho c / dt = 0
        Eigen::VectorXd rhs(n), held_values = Eigen::VectorXd::Zero(n), x0(n);
        for (std::size_t i = 0; i < n; ++i) {
            rhs[i] = held_[i] ? theta[i] : source(i) + h(i) * loads_.T_inf;
            if (held_[i]) held_values[i] = theta[i];
            x0[i] = theta[i];
        }
        rhs += coupling_ * held_values;
        Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::DiagonalPreconditioner<double>> solver;
        solver.setTolerance(tol);
        solver.setMaxIterations(100000);
        solver.compute(M_);
        const Eigen::VectorXd x = solver.solveWithGuess(rhs, x0);
        if (solver.info() != Eigen::Success)
            throw std::runtime_error("steady state: BiCGSTAB did not converge (residual " + std::to_string(solver.error()) + ")");
        for (std::size_t i = 0; i < n; ++i) theta[i] = x[i];
        return int(solver.iterations());
    }

    // Picard iteration: solve(next) replaces next by the solution of the linear problem with the
    // model's operator at next (the model's point pass evaluates k there).
    template <class Solve>
    void picard(Solve&& solve, std::vector<double>& theta, const char* what)
    {
        std::vector<double> next = theta;
        double change = 0;
        for (picard_iterations = 1; picard_iterations <= picard_max_iter; ++picard_iterations) {
            model_.point_pass(bonds_, next);
            const std::vector<double> previous = next;
            solve(next);
            change = 0;
            double scale = 1;
            for (std::size_t i = 0; i < next.size(); ++i)
                change = std::max(change, std::abs(next[i] - previous[i])), scale = std::max(scale, std::abs(next[i]));
            if (change <= picard_tol * scale) {
                picard_total += picard_iterations;
                theta = next;
                return;
            }
        }
        throw std::runtime_error(std::string(what) + ": Picard iteration did not converge in " + std::to_string(picard_max_iter) +
                                 " iterations (last change " + std::to_string(change) + ")");
    }

    // Implicit Euler of a nonlinear model: rho c lagged at theta^n, A(theta) iterated.
    void implicit_euler_picard(std::vector<double>& theta, double dt)
    {
        const std::size_t n = theta.size();
        apply_fixed(theta);
        std::vector<double> diag(n);
        for (std::size_t i = 0; i < n; ++i) diag[i] = rho_c(i, theta[i]) / dt;
        Eigen::VectorXd rhs0(n), held_values = Eigen::VectorXd::Zero(n);
        for (std::size_t i = 0; i < n; ++i) {
            rhs0[i] = held_[i] ? theta[i] : diag[i] * theta[i] + source(i) + h(i) * loads_.T_inf;
            if (held_[i]) held_values[i] = theta[i];
        }
        picard(
            [&](std::vector<double>& next) {
                assemble(diag);
                Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(M_);
                if (lu.info() != Eigen::Success) throw std::runtime_error("implicit Euler: sparse LU failed");
                const Eigen::VectorXd x = lu.solve(rhs0 + coupling_ * held_values);
                if (lu.info() != Eigen::Success) throw std::runtime_error("implicit Euler: sparse solve failed");
                for (std::size_t i = 0; i < n; ++i) next[i] = x[i];
            },
            theta, "implicit Euler");
    }

    // Since the last factorisation: a bond broke, or the operator follows a deformation (correspondence
    // heat with set_deformation: F changes with every mechanical step).
    bool operator_may_have_changed() const
    {
        if (bonds_.intact != lu_intact_) return true;
        if constexpr (requires { model_.follows_deformation(); }) return model_.follows_deformation();
        else return false;
    }

    void factorise(double dt, const std::vector<double>& rc)
    {
        std::vector<double> diag(rc.size());
        for (std::size_t i = 0; i < rc.size(); ++i) diag[i] = rc[i] / dt;
        assemble(diag);
        lu_ = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>>>();
        lu_->compute(M_);
        if (lu_->info() != Eigen::Success) throw std::runtime_error("implicit Euler: sparse LU failed");
        lu_dt_ = dt;
        lu_rc_ = rc;
        lu_intact_ = bonds_.intact;
    }

    // M_ = diag(c + h) - A on the free rows, identity on the held rows; coupling_ = the free-row,
    // held-column block of A.
    void assemble(const std::vector<double>& c)
    {
        const Eigen::SparseMatrix<double> A = heat_operator(model_, bonds_);
        // Held nodes are eliminated: identity rows, and their columns of the free rows move to the
        // right-hand side (coupling_), so no row mixes the two scales and the free block keeps the
        // symmetry of A.
        std::vector<Eigen::Triplet<double>> t, c_t;
        t.reserve(A.nonZeros() + c.size());
        for (int col = 0; col < A.outerSize(); ++col)
            for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
                if (held_[it.row()]) continue;
                if (held_[it.col()]) c_t.emplace_back(it.row(), it.col(), it.value());
                else t.emplace_back(it.row(), it.col(), -it.value());
            }
        coupling_.resize(A.rows(), A.cols());
        coupling_.setFromTriplets(c_t.begin(), c_t.end());
        for (std::size_t i = 0; i < c.size(); ++i) t.emplace_back(int(i), int(i), held_[i] ? 1.0 : c[i] + h(i));
        M_.resize(A.rows(), A.cols());
        M_.setFromTriplets(t.begin(), t.end());
    }

    Model& model_;
    const Bonds& bonds_;
    std::vector<double> rho_c_;
    HeatLoads loads_;
    std::vector<char> held_;
    std::vector<double> Q_, P_;
    std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>>> lu_;
    Eigen::SparseMatrix<double> coupling_;  // free-row, held-column block of A
    Eigen::SparseMatrix<double> M_;         // matrix of the last implicit or steady system
    double lu_dt_ = 0;
    std::vector<double> lu_rc_;
    std::vector<std::uint8_t> lu_intact_;  // the bonds of the factorised operator (a break changes it)
};

// Thermal critical step of explicit Euler [s] (spec/000b sec. 3.7, eq. 3.20): the eigenvalues of
// A lie in the Gershgorin discs, |lambda_i| <= sum_j |A_ij| = 2 g_i, and explicit Euler needs
// dt |lambda| / (rho c) <= 2, so dt = min over free nodes of rho c_i / (g_i + h_i). For Agwai g_i is
// the sum of the bond conductances sum_j kappa_1 V_j/|xi| (eq. 3.20); with the thermal correction
// it includes TCF (the source's fork ignores it; ours bounds the actual operator).
template <class Model>
double thermal_critical_step(const Model& model, const Bonds& b, const Conduction<Model>& c,
                             const std::vector<double>& theta)
{
    const Eigen::SparseMatrix<double, Eigen::RowMajor> A = heat_operator(model, b);
    double dt = std::numeric_limits<double>::infinity();
    for (int i = 0; i < A.outerSize(); ++i) {
        if (c.held(i)) continue;
        double g = 0;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(A, i); it; ++it) g += 0.5 * std::abs(it.value());
        g += c.h(i);
        if (g > 0) dt = std::min(dt, c.rho_c(i, theta[i]) / g);
    }
    return dt;
}

// The temperature field (temperature_field.hpp) of a heat model (agwai.hpp, correspondence_heat.hpp,
// conductivity.hpp) under explicit or implicit Euler; CVODE: time/heat_cvode.hpp's CvodeField.
template <class Model>
class ConductingField : public TemperatureField {
public:
    // theta0: initial temperatures (held nodes start at their held values); dt may be set later
    // (e.g. from critical_step()). CVODE is CvodeField's (time/heat_cvode.hpp).
    ConductingField(Model model, const Bonds& bonds, std::vector<double> rho_c, HeatLoads loads, std::vector<double> theta0,
                    HeatIntegrator integrator, double dt_thermal = 0)
        : model_(std::move(model)), bonds_(bonds), integrator_(integrator), conduction_(model_, bonds, std::move(rho_c), std::move(loads))
    {
        if (theta0.size() != bonds.nodes()) throw std::invalid_argument("ConductingField: one initial temperature per node");
        theta = std::move(theta0);
        conduction_.apply_fixed(theta);
        dt = dt_thermal;
    }
    ConductingField(const ConductingField&) = delete;  // conduction_ refers to model_
    ConductingField& operator=(const ConductingField&) = delete;

    Conduction<Model>& conduction() { return conduction_; }
    const Model& model() const { return model_; }
    // Explicit Euler's critical step at the current theta [s] (conduction.hpp, Gershgorin bound).
    double critical_step() const { return thermal_critical_step(model_, bonds_, conduction_, theta); }

    const std::vector<double>& heat_flow() override
    {
        pd::heat_flow(model_, bonds_, theta, Q_);
        return Q_;
    }
    // theta_i += e_i / (rho c_i(theta_i)) on the free nodes (temperature_field.hpp).
    void deposit(const std::vector<double>& e) override
    {
        if (e.size() != theta.size()) throw std::invalid_argument("deposit: one energy density per node");
        for (std::size_t i = 0; i < theta.size(); ++i)
            if (!conduction_.held(i)) theta[i] += e[i] / conduction_.rho_c(i, theta[i]);
    }

protected:
    void take_step() override
    {
        conduction_.time = t() + dt;  // the held temperatures of the step's end
        if (integrator_ == HeatIntegrator::explicit_euler) conduction_.explicit_euler(theta, dt);
        else if (integrator_ == HeatIntegrator::implicit_euler) conduction_.implicit_euler(theta, dt);
        else throw std::logic_error("ConductingField: CVODE is time/heat_cvode.hpp's CvodeField");
    }
    const Bonds& bonds() const { return bonds_; }

private:
    Model model_;
    const Bonds& bonds_;
    HeatIntegrator integrator_;
    Conduction<Model> conduction_;
    std::vector<double> Q_;
};

}  // namespace pd
