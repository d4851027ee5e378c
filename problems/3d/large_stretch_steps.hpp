// problems/3d/large_stretch_steps.hpp -- step 5 of large_stretch_3d: the gripped V2 bar stretched in
// equal end-displacement steps, each solved by adaptive dynamic relaxation warm-started from the
// secant predictor 2 u_(k-1) - u_(k-2); after each converged step the model's commit (Flanagan-Taylor:
// pd::LoadStep) and the gauge measurement: P = F/(l1 l3) from the right-grip reaction, the gauge
// stretches (problems/common/measure/bar_stretch.hpp), true stress sigma = P/(mu_y mu_z), Hencky equivalent strain,
// beside the closed-form uniaxial curve of reference/uniaxial_stretch at the same gauge stretch.
#pragma once
#include "problems/common/grips.hpp"
#include "pd/core/timer.hpp"
#include "pd/io/checkpoints.hpp"
#include "problems/common/measure/bar_sections.hpp"
#include "problems/common/measure/bar_stretch.hpp"
#include "pd/time/dynamic_relaxation.hpp"
#include "reference/uniaxial_stretch.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace large_stretch {

using pd::ref::UniaxialLaw;

struct Point {  // one converged load step
    double strain = 0, P = 0, lambda = 1, mu_y = 1, mu_z = 1, sigma = 0, eps_eq = 0;
    double P_ref = 0, sigma_ref = 0, eps_eq_ref = 0;  // closed form at the same gauge stretch
    long iterations = 0;
    double residual = 0;
};

struct Run {
    std::vector<Point> curve;
    bool converged = true;
    std::string message;
    double wall_s = 0;
};

struct Loading {   // the load stepping (options)
    double strain;  // final end displacement / length [-]
    int steps;      // equal load steps
    double tol;     // ADR relative residual tolerance per step [-]
    long max_iter;  // ADR iterations per step
    double safety;  // ADR density safety factor over the reference-tangent bound [-]
};

using Bar = pd::GaugedBar;  // gauge layers at 0.5 l2 -+ delta

// Load stepping by ADR; `commit` ends each converged step (Flanagan-Taylor), no-op otherwise. The
// load steps are a restartable loop (io/checkpoints.hpp): its state is the converged fields of the
// last two steps, the curve so far and, for pd::LoadStep (Flanagan-Taylor), its committed state;
// each ADR solve starts afresh from u, so nothing else carries over between steps.
template <class Model, class Commit>
Run stretch(Model& model, const pd::Field<3>& bound, const Bar& s, pd::Bonds& bonds, const Loading& load, double nu,
            UniaxialLaw law, const pd::Elastic& mat, Commit commit, pd::io::Checkpoints& cp)
{
    const auto [strain, steps, tol, max_iter, safety] = load;
    pd::io::Timer timer;
    const pd::Body<3>& body = s.bar.body;
    pd::DynamicRelaxation<3, Model> adr(body, bonds, model, bound);
    adr.safety = safety * pd::ref::max_tangent_ratio(law, mat.K, mat.G, 1 + strain);  // cover the stiffening
    pd::Field<3> u(body.size()), u_old(body.size()), y(body.size());  // u_old: converged field of step k - 2 (0: unloaded)
    const double e = strain / steps;  // step 1 guess: uniform uniaxial field of the first step
    pd::uniaxial_bar_field(body, s.L, s.W, s.T, e * s.L, e, nu, pd::Grips::axial, u);
    Run run;
    auto state = [&](pd::StateArchive& ar) {
        ar("u", u), ar("u_old", u_old), ar.records("curve", run.curve), ar("converged", run.converged), ar("message", run.message);
        timer.state(ar, "wall");
        if constexpr (requires { model.state(ar, ""); }) model.state(ar, "load_step");
    };
    cp.loop(steps, state, [] {}, [&](long k) {
        const double U = strain * s.L * k / steps;
        pd::Boundary<3> bc;
        pd::grip_bar_ends(bc, s.bar.left, s.bar.right, pd::TimeFunction::constant(U), pd::Grips::axial);
        if (k > 1) {  // secant predictor from the converged fields of steps k - 1 and k - 2
            const pd::Field<3> u_km1 = u;
            for (int d = 0; d < 3; ++d)
                for (std::size_t i = 0; i < body.size(); ++i) u.c[d][i] = 2 * u.c[d][i] - u_old.c[d][i];
            u_old = u_km1;
        }
        const pd::RelaxationResult r = adr.solve(u, bc, 0, tol, max_iter);
        if (!r.converged) {
            run.converged = false;
            run.message = "step " + std::to_string(k) + ": " + r.message;
            return false;
        }
        pd::add_fields(body.x, u, y);
        commit(bonds, y);
        Point p{.strain = U / s.L, .iterations = r.iterations, .residual = r.residual};
        p.P = pd::grip_stress(adr.internal_force_density(), s);
        const pd::GaugeStretches g = pd::gauge_stretches(body.x, u, s.gauge);
        p.lambda = g.lambda, p.mu_y = g.mu_y, p.mu_z = g.mu_z;
        if (!(std::isfinite(p.lambda) && p.lambda > 0 && p.mu_y > 0 && p.mu_z > 0)) {  // e.g. a section turned inside out
            run.converged = false;
            run.message = "step " + std::to_string(k) + ": nonphysical gauge state (stretches " + std::to_string(p.lambda) + ", " +
                          std::to_string(p.mu_y) + ", " + std::to_string(p.mu_z) + ")";
            return false;
        }
        p.sigma = p.P / (p.mu_y * p.mu_z);
        p.eps_eq = pd::equivalent_strain(p.lambda, p.mu_y, p.mu_z);
        try {
            const pd::ref::UniaxialPoint c = pd::ref::uniaxial_stress(law, mat.K, mat.G, p.lambda);
            p.P_ref = c.P;
            p.sigma_ref = c.sigma;
            p.eps_eq_ref = pd::equivalent_strain(p.lambda, c.mu, c.mu);
        } catch (const std::domain_error&) {  // SVK beyond the collapse of its section: no closed form
            p.P_ref = p.sigma_ref = p.eps_eq_ref = NAN;
        }
        run.curve.push_back(p);
        return true;
    });
    run.wall_s = timer.seconds();
    return run;
}

}  // namespace large_stretch
