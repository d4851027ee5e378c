// problems/common/stepped_bar_stretch.hpp -- the gripped V2 bar (pd::gauged_bar, axial grips:
// grips.hpp) stretched quasi-statically in equal end-displacement steps (large_stretch_3d; seed 000b
// sec. 4.8, spec/000b V5): step k prescribes U_k = strain l2 k/steps and is solved by adaptive
// dynamic relaxation (time/dynamic_relaxation.hpp) from the secant predictor u = 2 u_(k-1) - u_(k-2)
// (step 1: the uniform uniaxial field of U_1, grips.hpp), its density safety raised by the largest
// tangent ratio of the closed-form law up to the final stretch (the stiffening). After each converged
// step the model's commit (Flanagan-Taylor: pd::LoadStep) and the measured state of the bar
// (P, lambda, mu_y, mu_z, sigma, eps_eq: measure/bar_stretch.hpp) beside the closed-form uniaxial-stress
// curve at the same gauge stretch (reference/uniaxial_stretch.hpp: P, sigma and the equivalent strain of
// (lambda, mu, mu)). The stepping stops at the first unconverged step or nonphysical gauge state.
// The steps are a restartable loop (io/checkpoints.hpp): its state is the converged fields of the last
// two steps, the curve so far and, for pd::LoadStep, its committed state; each ADR solve starts afresh
// from u, so nothing else carries over between steps.
#pragma once
#include "problems/common/grips.hpp"
#include "problems/common/measure/bar_sections.hpp"
#include "problems/common/measure/bar_stretch.hpp"
#include "pd/core/timer.hpp"
#include "pd/io/checkpoints.hpp"
#include "pd/time/dynamic_relaxation.hpp"
#include "reference/uniaxial_stretch.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct StretchPoint {  // one converged load step
    double strain = 0, P = 0, lambda = 1, mu_y = 1, mu_z = 1, sigma = 0, eps_eq = 0;  // nominal strain, BarStretchState
    double P_ref = 0, sigma_ref = 0, eps_eq_ref = 0;  // closed form at the same gauge stretch [Pa], [Pa], [-]
    long iterations = 0;                              // ADR iterations of the step
    double residual = 0;                              // ADR relative residual at convergence [-]
};

struct StretchCurve {
    std::vector<StretchPoint> curve;
    bool converged = true;  // every step converged to a physical state
    std::string message;    // the first failure, if any
    double wall_s = 0;      // [s]
};

struct StretchLoading {  // the load stepping (options)
    double strain;       // final end displacement / length [-]
    int steps;           // equal load steps
    double tol;          // ADR relative residual tolerance per step [-]
    long max_iter;       // ADR iterations per step
    double safety;       // ADR density safety factor over the reference-tangent bound [-]
};

// Stretches bar s with `model` (ADR density bound `bound`); nu: Poisson's ratio of the step-1 guess;
// law, mat: the closed form compared with; commit(bonds, y) ends each converged step (no-op but for
// Flanagan-Taylor); cp: the restartable loop.
template <class Model, class Commit>
StretchCurve stretch_bar_in_steps(Model& model, const Field<3>& bound, const GaugedBar& s, Bonds& bonds, const StretchLoading& load,
                                  double nu, ref::UniaxialLaw law, const Elastic& mat, Commit commit, io::Checkpoints& cp)
{
    const auto [strain, steps, tol, max_iter, safety] = load;
    io::Timer timer;
    const Body<3>& body = s.bar.body;
    DynamicRelaxation<3, Model> adr(body, bonds, model, bound);
    adr.safety = safety * ref::max_tangent_ratio(law, mat.K, mat.G, 1 + strain);  // cover the stiffening
    Field<3> u(body.size()), u_old(body.size()), y(body.size());  // u_old: converged field of step k - 2 (0: unloaded)
    const double e = strain / steps;  // step 1 guess: uniform uniaxial field of the first step
    uniaxial_bar_field(body, s.L, s.W, s.T, e * s.L, e, nu, Grips::axial, u);
    StretchCurve run;
    auto state = [&](StateArchive& ar) {
        ar("u", u), ar("u_old", u_old), ar.records("curve", run.curve), ar("converged", run.converged), ar("message", run.message);
        timer.state(ar, "wall");
        if constexpr (requires { model.state(ar, ""); }) model.state(ar, "load_step");
    };
    cp.loop(steps, state, [] {}, [&](long k) {
        const double U = strain * s.L * k / steps;
        Boundary<3> bc;
        grip_bar_ends(bc, s.bar.left, s.bar.right, TimeFunction::constant(U), Grips::axial);
        if (k > 1) {  // secant predictor from the converged fields of steps k - 1 and k - 2
            const Field<3> u_km1 = u;
            for (int d = 0; d < 3; ++d)
                for (std::size_t i = 0; i < body.size(); ++i) u.c[d][i] = 2 * u.c[d][i] - u_old.c[d][i];
            u_old = u_km1;
        }
        const RelaxationResult r = adr.solve(u, bc, 0, tol, max_iter);
        if (!r.converged) {
            run.converged = false;
            run.message = "step " + std::to_string(k) + ": " + r.message;
            return false;
        }
        add_fields(body.x, u, y);
        commit(bonds, y);
        const BarStretchState b = measure_bar_stretch(adr.internal_force_density(), u, s);
        if (!b.physical()) {  // e.g. a section turned inside out
            run.converged = false;
            run.message = "step " + std::to_string(k) + ": nonphysical gauge state (stretches " + std::to_string(b.lambda) + ", " +
                          std::to_string(b.mu_y) + ", " + std::to_string(b.mu_z) + ")";
            return false;
        }
        StretchPoint p{.strain = U / s.L, .P = b.P, .lambda = b.lambda, .mu_y = b.mu_y, .mu_z = b.mu_z, .sigma = b.sigma,
                       .eps_eq = b.eps_eq, .iterations = r.iterations, .residual = r.residual};
        try {
            const ref::UniaxialPoint c = ref::uniaxial_stress(law, mat.K, mat.G, p.lambda);
            p.P_ref = c.P;
            p.sigma_ref = c.sigma;
            p.eps_eq_ref = equivalent_strain(p.lambda, c.mu, c.mu);
        } catch (const std::domain_error&) {  // SVK beyond the collapse of its section: no closed form
            p.P_ref = p.sigma_ref = p.eps_eq_ref = NAN;
        }
        run.curve.push_back(p);
        return true;
    });
    run.wall_s = timer.seconds();
    return run;
}

}  // namespace pd
