// pd/models/plastic_points.hpp -- the per-node plastic state shared by the PD plasticity models
// (plastic_lps.hpp, plastic_correspondence.hpp): Johnson-Cook law, which nodes are plastic, the
// node temperatures, the committed and trial equivalent plastic strain, and the per-step outputs.
// History protocol (HistoryModel, kernel_concepts.hpp; also the viscoelastic models'): the models'
// point_pass(bonds, y, dt) evaluates the TRIAL state at y over the step dt from the COMMITTED history
// (idempotent: no accumulation over solver iterations; dt = 0: an instantaneous step, as Explicit::start
// takes: rate-independent return, no heat source; without dt: the last step given, quasi-static
// solvers); commit() makes the trial history the committed one.
// Dissipated power (spec/000b eqs. 5.22-5.23, 5.51): p_i = beta_TQ sigma_y dlambda / dt [W/m^3],
// the heat source of a thermo-mechanical scene (heat_source, after point_pass; step_heat, its energy
// over the step, is what a scene's heat component accumulates, scene.hpp).
// Node temperatures of the Johnson-Cook law: temperature_field when set (a scene's temperature field,
// read at each return: plastic heating then softens the law), else the vector temperature, else
// law.theta_ref.
// Also the trial deviatoric bond extension e_de of the two ordinary models (LPS, PALS).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/laws/j2.hpp"
#include "pd/laws/johnson_cook.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct PlasticPoints {
    laws::JohnsonCook law;
    double beta_TQ = 0.9;                 // Taylor-Quinney factor [-]
    double dt = 1;                        // step of the trial evaluation [s] (quasi-static: any, C = 0)
    std::vector<std::uint8_t> plastic;    // 1: J2 return at this node, 0: elastic; empty = all plastic
    std::vector<double> temperature;      // node temperature [law's unit]; empty = law.theta_ref
    const std::vector<double>* temperature_field = nullptr;  // header (set_temperature_field); must outlive the model's use
    std::vector<double> ep_c, ep;         // committed and trial equivalent plastic strain [-]
    std::vector<double> dlambda;          // trial plastic multiplier of the step [-]
    std::vector<double> sigma_eff;        // trial end-of-step von Mises stress [Pa]
    std::vector<double> heat_source;      // beta_TQ sigma_y dlambda / dt [W/m^3]
    std::vector<double> plastic_work;     // trial sigma_y dlambda of the step [J/m^3] (not checkpointed: the next pass sets it)

    PlasticPoints() = default;
    PlasticPoints(const laws::JohnsonCook& law, double beta_TQ, std::size_t n)
        : law(law), beta_TQ(beta_TQ), ep_c(n, 0.0), ep(n, 0.0), dlambda(n, 0.0), sigma_eff(n, 0.0), heat_source(n, 0.0),
          plastic_work(n, 0.0)
    {
        law.validate();
        if (!(beta_TQ >= 0 && beta_TQ <= 1)) throw std::invalid_argument("PlasticPoints: beta_TQ must lie in [0, 1]");
    }

    void set_time_step(double step)  // the models' point_pass(bonds, y, dt)
    {
        if (!(step >= 0)) throw std::invalid_argument("point_pass: time step dt must be >= 0");
        dt = step;
    }
    // Reads the node temperatures from t (null: back to `temperature`); throws for another length.
    void set_temperature_field(const std::vector<double>* t)
    {
        if (t && t->size() != ep_c.size())
            throw std::invalid_argument("PlasticPoints: " + std::to_string(t->size()) + " temperatures for " + std::to_string(ep_c.size()) + " nodes");
        temperature_field = t;
    }
    bool is_plastic(std::size_t i) const { return plastic.empty() || plastic[i]; }
    double theta(std::size_t i) const
    {
        return temperature_field ? (*temperature_field)[i] : temperature.empty() ? law.theta_ref : temperature[i];
    }

    // The scalar return (j2.hpp) of node i from its committed ep, recorded as the trial state;
    // an elastic node records sigma_eff_trial only.
    laws::ScalarReturn scalar_return(std::size_t i, double G, double trial)
    {
        laws::ScalarReturn r;
        r.sigma_eff = trial;
        if (is_plastic(i)) r = laws::radial_return(law, G, trial, ep_c[i], dt, theta(i));
        record(i, r);
        return r;
    }
    void record(std::size_t i, const laws::ScalarReturn& r)
    {
        dlambda[i] = r.dlambda;
        ep[i] = ep_c[i] + r.dlambda;
        sigma_eff[i] = r.sigma_eff;
        heat_source[i] = dt > 0 ? beta_TQ * r.dissipation / dt : 0.0;  // an instantaneous step: no power
        plastic_work[i] = r.dissipation;
    }
    void commit() { ep_c = ep; }
    // Heat of the last step at node i, beta_TQ sigma_y dlambda [J/m^3] (DissipativeModel).
    double step_heat(std::size_t i) const { return heat_source[i] * dt; }
    // All the plastic work of the last step at node i, sigma_y dlambda [J/m^3] (DissipativeModel;
    // 1 - beta_TQ of it is stored cold work, lost to the mechanics all the same).
    double step_dissipation(std::size_t i) const { return plastic_work[i]; }
    // Its part of a checkpoint (core/state_archive.hpp).
    void state(StateArchive& ar)
    {
        ar("plastic.dt", dt), ar("plastic.temperature", temperature), ar("plastic.ep_c", ep_c), ar("plastic.ep", ep);
        ar("plastic.dlambda", dlambda), ar("plastic.sigma_eff", sigma_eff), ar("plastic.heat_source", heat_source);
    }
};

// Trial deviatoric extension of bond k (i -> j) of the ordinary plastic models (plastic_lps.hpp,
// plastic_pals.hpp): e_de = |Y| - |xi| (1 + theta_i/3) - e_dp_c [m]; th = theta_i/3 [-].
inline double deviatoric_extension(const Bonds& b, const Field<3>& y, std::size_t i, std::int64_t k, double th,
                                   const std::vector<double>& edp_c)
{
    const int j = b.partner[k];
    double Y2 = 0;
    for (int d = 0; d < 3; ++d) { const double Yd = y.c[d][j] - y.c[d][i]; Y2 += Yd * Yd; }
    return std::sqrt(Y2) - b.length[k] * (1 + th) - edp_c[k];
}

}  // namespace pd
