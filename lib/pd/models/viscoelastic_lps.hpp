// Mitchell's ordinary state-based viscoelastic model (Mitchell 2011, SAND2011-8064; Biondani 2018
// sec. 7.2; spec/000c sec. 1.4, errata 1-2, 5), built on LPS (models/lps.hpp, by composition: its
// dilatation theta_i, weighted volume m_i, alpha_i and bond force are reused, not copied).
// The deviatoric extension e_d = e - theta_i |xi| / D of each bond drives a standard linear solid:
//   W_d = 1/2 alpha_inf (omega e_d).e_d + 1/2 alpha_b (omega (e_d - e_db)).(e_d - e_db)     (7.20)
//   t_d = alpha_inf omega e_d + alpha_b omega (e_d - e_db)                                  (7.21, erratum 1)
//   alpha_inf = alpha_LPS = 15 G / m_w,  alpha_b = gamma_b alpha_inf  (thesis convention)    (7.22, erratum 5)
//   d e_db/dt + e_db / tau_b = e_d / tau_b,  e_db(-inf) = 0                                 (7.24-7.25)
//   e_db^{n+1} = e^{-dt/tau_b} e_db^n + (1 - e^{-dt/tau_b}) e_d^n + beta_b (e_d^{n+1} - e_d^n)  (7.27, erratum 2)
// (the update of laws/maxwell.hpp, exact for e_d linear in the step). Slow loading gives the elastic
// LPS, an instantaneous step the LPS with G (1 + gamma_b) on the deviatoric part.
// Force on i from bond k (i -> j): the LPS pair force plus (tv_ik + tv_ji) omega V_j Y/|Y|, with the
// viscous force-state scalar tv_ik = alpha_b,i (e_d - e_db) of bond k seen from i (tv_ji from the
// reverse bond, Bonds::reverse).
// History protocol (HistoryModel, kernel_concepts.hpp; shared with the plastic models): point_pass
// (bonds, y, dt) evaluates the TRIAL back extensions e_db^{n+1} at y over the step dt from the
// COMMITTED e_d^n, e_db^n (it does not accumulate: two calls at the same y give the same force);
// commit() makes the trial history the committed one (once per accepted time step: scene.hpp). The per-bond history
// (e_d, e_db, committed and trial) exists only in scenes that use this model.
// Thermal expansion (the wrapped LPS's set_thermal_expansion): lps.theta is the mechanical dilatation
// theta - D eps_i, so e_d = e - eps_i |xi| - theta_mech |xi|/D, the deviatoric extension of e_mech (the
// isotropic thermal strain does not load the branch); with ThermalExpansion::bond_mean each bond takes
// (eps_i + eps_j)/2 instead of eps_i (ThermalExpansion::bond_strain).
// Dissipation (7.10): the energy dissipated by the dashpots of node i over the trial step [J/m^3],
//   D_i = sum_k (alpha_b,i omega V_j / tau_b) int (e_d - e_db)^2 dt   (laws/maxwell.hpp, exact per step).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/core/field.hpp"
#include "pd/laws/maxwell.hpp"
#include "pd/models/lps.hpp"
#include "pd/core/parallel.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd {

struct ViscoelasticLPS {
    static constexpr bool has_point_pass = true;
    struct Params {
        LPS::Params lps;      // the elastic (equilibrium) LPS: alpha_inf = alpha_LPS
        double gamma_b = 1;   // alpha_b / alpha_inf = G_b / G [-] (>= 0)
        double tau_b = 1;     // relaxation time of the Maxwell branch [s] (> 0)
    };
    LPS lps;
    double gamma_b = 0;               // [-]
    double tau_b = 1;                 // [s]
    double dt = 0;                    // step of the trial state [s]
    std::vector<double> ed_c, edb_c;  // committed e_d^n, e_db^n per bond [m]
    std::vector<double> ed_t, edb_t;  // trial e_d^{n+1}, e_db^{n+1} per bond [m]
    std::vector<double> tv;           // alpha_b,i (e_d - e_db) per bond, trial [Pa/m^4 in 3D]
    std::vector<double> dissipation;  // D_i of the trial step per node [J/m^3]

    ViscoelasticLPS() = default;
    ViscoelasticLPS(const Params& p, const Bonds& b)
        : lps(p.lps, b), gamma_b(p.gamma_b), tau_b(p.tau_b), ed_c(b.size(), 0.0), edb_c(b.size(), 0.0), ed_t(b.size(), 0.0),
          edb_t(b.size(), 0.0), tv(b.size(), 0.0), dissipation(b.nodes(), 0.0)
    {
        if (p.lps.dim < 2) throw std::invalid_argument("ViscoelasticLPS: 1D LPS has no deviatoric part (alpha = 0)");
        if (!(p.gamma_b >= 0)) throw std::invalid_argument("ViscoelasticLPS: gamma_b must be >= 0");
        if (!(p.tau_b > 0)) throw std::invalid_argument("ViscoelasticLPS: tau_b must be positive");
        if (b.reverse.size() != b.size()) throw std::invalid_argument("ViscoelasticLPS: bonds need the reverse-bond index");
    }

    // The trial state over a step [s] (HistoryModel, kernel_concepts.hpp); without it: the last step given.
    template <int D>
    void point_pass(const Bonds& b, const Field<D>& y, double step)
    {
        if (!(step >= 0)) throw std::invalid_argument("ViscoelasticLPS: time step must be >= 0");
        dt = step;
        point_pass(b, y);
    }

    // The trial state becomes the committed history.
    double step_heat(std::size_t i) const { return dissipation[i]; }  // DissipativeModel: all of it becomes heat
    void commit()
    {
        ed_c = ed_t;
        edb_c = edb_t;
    }
    // Its part of a checkpoint (core/state_archive.hpp): the history and the last point pass.
    void state(StateArchive& ar)
    {
        ar("lps.theta", lps.theta), ar("lps.a_coef", lps.a_coef), ar("viscoelastic.dt", dt);
        ar("viscoelastic.ed_c", ed_c), ar("viscoelastic.edb_c", edb_c), ar("viscoelastic.ed_t", ed_t), ar("viscoelastic.edb_t", edb_t);
        ar("viscoelastic.tv", tv), ar("viscoelastic.dissipation", dissipation);
    }

    void recompute(const Bonds& b) { lps.recompute(b); }
    // Thermal expansion of the wrapped LPS (header; its refusals are LPS's).
    void set_thermal_expansion(const ThermalExpansion& t) { lps.set_thermal_expansion(t); }
    const ThermalExpansion& thermal_expansion() const { return lps.thermal_expansion(); }

    // theta_i by LPS, then e_d^{n+1}, the trial e_db^{n+1} (7.27), tv and D_i of every bond.
    template <int D>
    void point_pass(const Bonds& b, const Field<D>& y)
    {
        lps.point_pass(b, y);
        const laws::MaxwellCoefficients c = laws::maxwell_coefficients(dt, tau_b);
        const bool damaged = b.has_damage();
        const int dim = lps.dim;
        parallel_for(b.nodes(), [&](std::size_t i) {
            const double alpha_b = gamma_b * lps.alpha[i];  // (7.22) [Pa/m^5 in 3D]
            double Di = 0;
            for_family(b, i, [&](std::int64_t k, int j) {
                if (damaged && !b.intact[k]) {  // a broken bond keeps its history and carries no force
                    ed_t[k] = ed_c[k], edb_t[k] = edb_c[k], tv[k] = 0;
                    return;
                }
                const double L = b.length[k];
                const double ed = norm(y[j] - y[i]) - L - lps.theta[i] * L / dim - lps.thermal_expansion().bond_strain(i, j) * L;  // (4.9), header
                const double edb = laws::maxwell_update(edb_c[k], ed_c[k], ed, c);            // (7.27)
                ed_t[k] = ed, edb_t[k] = edb;
                tv[k] = alpha_b * (ed - edb);                                                  // (7.21), branch part
                Di += laws::maxwell_dissipation(alpha_b * lps.wV[k], edb_c[k], ed_c[k], ed, c);
            });
            dissipation[i] = Di;
        });
    }

    // LPS bond scalar plus the Maxwell branch from both ends, (tv_ik + tv_ji) omega V_j / |Y|.
    double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const
    {
        return lps.bond_scalar(i, k, j, ylen) + (tv[k] + tv[lps.bonds->reverse[k]]) * lps.wV[k] / ylen;
    }

    // Deviatoric force state t_d of bond k of node i at the trial state (7.21) [N/m^6 in 3D].
    double deviatoric_force_state(std::size_t i, std::int64_t k) const
    {
        const double omega = lps.bonds->omega[k];
        return omega * (lps.alpha[i] * ed_t[k] + tv[k]);
    }

    // W_i = LPS energy (alpha_inf part) + 1/2 alpha_b sum omega (e_d - e_db)^2 V_j (7.20) [J/m^3];
    // call after point_pass at the same y.
    template <int D>
    std::vector<double> energy_density(const Bonds& b, const Field<D>& y) const
    {
        const std::vector<double> W = lps.energy_density(b, y);
        auto bond = [&](std::size_t, std::int64_t k) {
            const double r = ed_t[k] - edb_t[k];
            return lps.wV[k] * r * r;
        };
        return node_sums(b, bond, [&](std::size_t i, double s) { return W[i] + 0.5 * gamma_b * lps.alpha[i] * s; });
    }
};

}  // namespace pd
