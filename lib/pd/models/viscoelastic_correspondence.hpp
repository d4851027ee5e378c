// Correspondence viscoelastic model: Flanagan-Taylor correspondence (models/correspondence.hpp,
// Law::flanagan_taylor) plus one Maxwell branch on the unrotated deviatoric stress (Biondani 2018
// sec. 7.3; spec/000c sec. 1.5 and erratum 4). Per node, each step:
//   1. Flanagan-Taylor elastic update from the committed state: sigma_hat^{n+1}, s_hat = dev(sigma_hat)
//   2. sigma_hat_0 = sigma_hat + gamma_b s_hat                                              (7.29)
//   3. q^{n+1} = e q^n + (1 - e) gamma_b s_hat^n + beta gamma_b (s_hat^{n+1} - s_hat^n)        (7.19)
//      (forcing gamma_b s_hat, the consistent Simo-Hughes form recommended by the spec, erratum 4),
//      e = exp(-dt/tau_b), beta = 1 - (tau_b/dt)(1 - e) (laws/maxwell.hpp: exact for s_hat linear in the step)
//   4. sigma = R (sigma_hat_0 - q) R^T                                                       (7.16)
//   5. P = J sigma F^-T and the force state by the wrapped model's point pass.
// So the deviatoric response relaxes from G (1 + gamma_b) to G with time tau_b, and the volumetric
// response is the elastic K. Thermal expansion (the wrapped model's set_thermal_expansion) enters step 1
// as the increment alpha (theta - theta^n) I of eq. 2.81 (LoadStep restores theta^n with sigma_hat, so
// repeated trials take it whole); isotropic, it leaves s_hat and the branch alone. In the strain form
// of laws/maxwell.hpp, x = s_hat/(2G) and the branch modulus is 2 G gamma_b (q = 2 G gamma_b h); the
// dissipated energy of the step per node [J/m^3] is (2 G gamma_b / tau_b) int (x - h):(x - h) dt,
// exact per step.
// History protocol (as models/viscoelastic_lps.hpp): point_pass(bonds, y, dt) = trial
// state at y from the committed state (sigma_hat, R, V, q, s_hat, configuration y_c; no accumulation),
// commit() after each accepted step (time/verlet.hpp calls both). The Flanagan-Taylor update runs over
// the step from y_c to y by models/load_step.hpp (LoadStep::advance): mid-step configuration
// (y_c + y)/2 and velocity (y - y_c) over a pseudo step 1 (the update depends on v dt only); dt
// enters only the Maxwell branch.
// Uses only the public members of Correspondence<3>; it does not copy its loops.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/laws/elastic.hpp"
#include "pd/laws/maxwell.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/load_step.hpp"
#include "pd/core/parallel.hpp"

#include <stdexcept>
#include <vector>

namespace pd {

class ViscoelasticCorrespondence {
public:
    static constexpr bool has_point_pass = true;
    static constexpr bool ordinary = false;
    using Model = Correspondence<3>;
    using Mat = Model::Mat;
    struct Params {
        double gamma_b = 1;  // G_b / G [-] (>= 0)
        double tau_b = 1;    // relaxation time [s] (> 0)
    };
    Model& model;                     // Law::flanagan_taylor; its sigma is overwritten by point_pass
    double gamma_b = 0, tau_b = 1;    // [-], [s]
    double dt = 0;                    // step of the trial state [s]
    std::vector<Mat> q, s_hat;        // trial internal stress q^{n+1}, elastic s_hat^{n+1} [Pa]
    std::vector<double> dissipation;  // energy dissipated in the trial step per node [J/m^3]

    // y0: the configuration the model's present state belongs to (usually the reference x) [m].
    ViscoelasticCorrespondence(Model& m, const Params& p, const Field<3>& y0)
        : model(m), gamma_b(p.gamma_b), tau_b(p.tau_b), q(m.F.size(), Mat::Zero()), s_hat(m.F.size(), Mat::Zero()),
          dissipation(m.F.size(), 0.0), step_(m, y0), y_t_(y0)
    {
        if (m.par.law != Model::Law::flanagan_taylor) throw std::invalid_argument("ViscoelasticCorrespondence: needs Law::flanagan_taylor");
        if (!(p.gamma_b >= 0)) throw std::invalid_argument("ViscoelasticCorrespondence: gamma_b must be >= 0");
        if (!(p.tau_b > 0)) throw std::invalid_argument("ViscoelasticCorrespondence: tau_b must be positive");
        if (y0.size() != m.F.size()) throw std::invalid_argument("ViscoelasticCorrespondence: configuration size differs from the model");
        q_c_ = q, s_hat_c_ = s_hat;
    }

    // The trial state over a step [s] (HistoryModel, kernel_concepts.hpp); without it: the last step given.
    void point_pass(const Bonds& b, const Field<3>& y, double step)
    {
        if (!(step >= 0)) throw std::invalid_argument("ViscoelasticCorrespondence: time step must be >= 0");
        dt = step;
        point_pass(b, y);
    }

    // Trial state at y (steps 1-5 of the header).
    void point_pass(const Bonds& b, const Field<3>& y)
    {
        step_.advance(b, y);  // step 1
        const laws::MaxwellCoefficients c = laws::maxwell_coefficients(dt, tau_b);
        const double k_b = 2 * model.par.material.G * gamma_b;  // branch modulus 2 G_b [Pa]
        parallel_for(y.size(), [&](std::size_t i) {
            const Mat& sh = model.sigma_hat[i];
            s_hat[i] = laws::deviator(sh);  // step 2: s_hat = dev(sigma_hat)
            q[i] = laws::maxwell_update<Mat>(q_c_[i], gamma_b * s_hat_c_[i], gamma_b * s_hat[i], c);  // (7.19)
            model.sigma[i] = model.R[i] * (sh + gamma_b * s_hat[i] - q[i]) * model.R[i].transpose();  // (7.16), (7.29)
            // Dissipation in stress units: (1/k_b) int r_sigma:r_sigma dt / tau_b, r_sigma = k_b (x - h).
            dissipation[i] = k_b > 0 ? laws::maxwell_dissipation<Mat>(1.0, q_c_[i], gamma_b * s_hat_c_[i], gamma_b * s_hat[i], c) / k_b : 0.0;
        });
        model.point_pass(b, y);
        y_t_ = y;
    }

    // The trial state becomes the committed one.
    double step_heat(std::size_t i) const { return dissipation[i]; }  // DissipativeModel: all of it becomes heat
    void commit()
    {
        step_.accept(y_t_);
        q_c_ = q, s_hat_c_ = s_hat;
    }

    // Its part of a checkpoint (core/state_archive.hpp): the committed and the trial state, and the
    // wrapped model's rate-form stress; rebuild() then redoes the wrapped model's point pass (F, P).
    void state(StateArchive& ar)
    {
        model.rate_state(ar), step_.state(ar, "viscoelastic.committed");
        ar("viscoelastic.dt", dt), ar("viscoelastic.y_t", y_t_), ar("viscoelastic.dissipation", dissipation);
        ar.blocks("viscoelastic.q", q), ar.blocks("viscoelastic.s_hat", s_hat);
        ar.blocks("viscoelastic.q_c", q_c_), ar.blocks("viscoelastic.s_hat_c", s_hat_c_);
    }
    void rebuild(const Bonds& b, const Field<3>& y) { model.point_pass(b, y); }
    // Thermal expansion of the wrapped model (header; its refusals are Correspondence's).
    void set_thermal_expansion(const ThermalExpansion& t) { model.set_thermal_expansion(t); }
    const ThermalExpansion& thermal_expansion() const { return model.thermal_expansion(); }

    template <class Pass>
    void with_kernel(Pass&& pass, const Bonds& b) const { model.with_kernel(pass, b); }
    void sync_node_matrices() const { model.sync_node_matrices(); }  // hourglass_forces (bond_loop.hpp)
    Vec<3> bond_force(std::size_t i, std::int64_t k, int j, const Vec<3>& Y) const { return model.bond_force(i, k, j, Y); }
    // The equilibrium part's energy (Correspondence, Flanagan-Taylor: its stress_work) plus the Maxwell
    // branch's, r : r / (4 G_b) with its stress r = gamma_b s_hat - q [J/m^3].
    template <int D>
    std::vector<double> energy_density(const Bonds& b, const Field<D>& y) const
    {
        std::vector<double> W = model.energy_density(b, y);
        const double Gb = gamma_b * model.par.material.G;
        if (Gb > 0)
            for (std::size_t i = 0; i < W.size(); ++i) {
                const Mat r = gamma_b * s_hat[i] - q[i];
                W[i] += (r.array() * r.array()).sum() / (4 * Gb);
            }
        return W;
    }

    // Viscous stress gamma_b s_hat - q of node i, unrotated [Pa].
    Mat viscous_stress(std::size_t i) const { return gamma_b * s_hat[i] - q[i]; }

private:
    LoadStep<Model, 3> step_;  // committed sigma_hat, R, V and configuration y_c
    Field<3> y_t_;             // configuration of the trial state [m]
    std::vector<Mat> q_c_, s_hat_c_;
};

}  // namespace pd
