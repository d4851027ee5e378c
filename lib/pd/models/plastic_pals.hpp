// pd/models/plastic_pals.hpp -- PALS J2 / Johnson-Cook plasticity with radial return (Biondani
// 2018 sec. 5.3.2; spec/000b sec. 2.6), composed with models/pals.hpp (public members only:
// point_pass, theta, K, G, w_i = omega_i V_j, s_i = 2 G sigma_i V_j). Per node i, from the committed
// plastic back extension e_dp per bond and ep_i:
//   e_de = e - theta_i |xi|/3 - e_dp,  W_d = G (sigma_i e_de)•e_de,  sigma_eff_trial = sqrt(6 G W_d)  (5.53)-(5.55)
//   scalar return (laws/j2.hpp, eq. 5.48), scale = sigma_y / sigma_eff_trial
//   t_d  = 2 G sigma_i e_de scale                                                (5.59)-(5.63)
//   e_dp += (3/(2 sigma_y)) (t_d/sigma_i) dl = 3 G dl e_de / sigma_eff_trial      (5.58), with sigma_i
//   t    = (K theta_i - (2G/3)(sigma_i x)•e_de_np1) omega_i |xi| + t_d,  e_de_np1 = e_de scale   (4.21)
// This avoids both problems of the fork's jc_pals.cxx (spec/000b sec. 2.6 [CODE]): the flow uses
// the deviatoric influence state sigma_i (not omega_i), and the isotropic part uses e_de after the
// update (the plastic extension enters (sigma x)•e_de). Elastic (e_dp = 0, no flow): identical to
// models/pals.hpp. A negative W_d (possible where sigma_i < 0 on some bonds) is clamped at 0.
// Pair force on i: (t_i<xi> + t_j<-xi>) V_j Y/|Y|; t_j<-xi> is read from the twin bond.
// 3D. Damage: the family sums skip broken bonds, recompute(bonds) recomputes the multipliers
// (PALS), so a damaged body equals the body built without the broken bonds
// (tests/test_plastic_models.cpp); a broken bond keeps its committed e_dp and carries no force.
// Thermal expansion (the wrapped PALS's set_thermal_expansion): pals.theta is the total dilatation, so
// e_de is already the mechanical deviatoric extension (pals.hpp header); the isotropic part takes the
// mechanical dilatation theta_i - eps_i m_omega_i (mechanical_dilatation). The bond mean
// (ThermalExpansion::bond_mean) is refused by point_pass (energy_density and mechanical_dilatation
// assume the owner rule).
// History protocol: plastic_points.hpp.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/core/field.hpp"
#include "pd/models/pals.hpp"
#include "pd/models/plastic_points.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/stiffness_bound.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd {

struct PlasticPALS {
    static constexpr bool has_point_pass = true;
    PALS pals;
    PlasticPoints pts;
    std::vector<double> edp_c, edp;  // committed and trial plastic back extension per bond [m]
    std::vector<double> t;           // trial force state t_i<xi> per bond [N/m^6]
    const Bonds* bonds = nullptr;

    // body and bonds must outlive the model (as PALS).
    PlasticPALS(const PALS::Params& p, const Body<3>& body, const Bonds& b, const laws::JohnsonCook& law, double beta_TQ = 0.9)
        : pals(p, body, b), pts(law, beta_TQ, b.nodes()), edp_c(b.size(), 0.0), edp(b.size(), 0.0), t(b.size(), 0.0), bonds(&b)
    {
    }

    void recompute(const Bonds& b) { pals.recompute(b); }  // after bonds broke (header)
    // Thermal expansion of the wrapped PALS (header): the owner rule only, so bond_mean is refused here
    // as well as by point_pass (a PALS set directly).
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        if (t.active() && t.bond_mean)
            throw std::invalid_argument("PlasticPALS: the bond-mean thermal strain is not written for its deviatoric extension (owner rule only)");
        pals.set_thermal_expansion(t);
    }
    const ThermalExpansion& thermal_expansion() const { return pals.thermal_expansion(); }
    double step_heat(std::size_t i) const { return pts.step_heat(i); }  // DissipativeModel (plastic_points.hpp)
    double step_dissipation(std::size_t i) const { return pts.step_dissipation(i); }
    void commit()
    {
        edp_c = edp;
        pts.commit();
    }
    // Its part of a checkpoint (core/state_archive.hpp): the plastic history and the last point pass.
    void state(StateArchive& ar)
    {
        ar("pals.theta", pals.theta), ar("pals.p", pals.p);
        ar("plastic_pals.edp_c", edp_c), ar("plastic_pals.edp", edp), ar("plastic_pals.t", t);
        pts.state(ar);
    }

    // Trial state at y from the committed history (header).
    // The trial state over a step dt [s] (HistoryModel, kernel_concepts.hpp); without dt: the last step given.
    void point_pass(const Bonds& b, const Field<3>& y, double dt)
    {
        pts.set_time_step(dt);
        point_pass(b, y);
    }
    void point_pass(const Bonds& b, const Field<3>& y)
    {
        if (pals.thermal_expansion().active() && pals.thermal_expansion().bond_mean)
            throw std::invalid_argument("PlasticPALS: the bond-mean thermal strain is not written for its deviatoric extension (owner rule only)");
        pals.point_pass(b, y);
        const double G = pals.G;
        const bool damaged = b.has_damage();
        parallel_for(b.nodes(), [&](std::size_t i) {
            const double th = pals.theta[i] / 3;
            double wd = 0, sx = 0;  // 2 W_d = sum 2G sigma e_de^2 V [Pa]; sum 2G sigma |xi| e_de V [Pa] (intact bonds)
            for_family(b, i, [&](std::int64_t k, int) {
                if (damaged && !b.intact[k]) { t[k] = 0; return; }
                const double e = deviatoric_extension(b, y, i, k, th, edp_c);
                t[k] = e;  // e_de until the return below
                wd += pals.s_i[k] * e * e;
                sx += pals.s_i[k] * b.length[k] * e;
            });
            const double trial = std::sqrt(6 * G * 0.5 * std::max(wd, 0.0));  // sqrt(6 G W_d) (5.55)
            const laws::ScalarReturn r = pts.scalar_return(i, G, trial);
            const double scale = r.plastic ? r.sigma_eff / trial : 1.0;
            const double flow = r.plastic ? 3 * G * r.dlambda / trial : 0.0;   // (5.58)
            const double P = pals.K * mechanical_dilatation(i) - scale * sx / 3;  // K theta - (2G/3)(sigma x)•e_de_np1
            for_family(b, i, [&](std::int64_t k, int) {
                if (damaged && !b.intact[k]) { edp[k] = edp_c[k]; return; }
                const double e = t[k];
                t[k] = (P * pals.w_i[k] * b.length[k] + scale * pals.s_i[k] * e) / b.volume[k];  // (4.21)
                edp[k] = edp_c[k] + flow * e;
            });
        });
    }

    // Stored (elastic) energy density [J/m^3], call after point_pass at y: the PALS energy (4.15)
    // of the elastic deviatoric extension e - theta |xi|/3 - e_dp (trial e_dp).
    std::vector<double> energy_density(const Bonds& b, const Field<3>& y) const
    {
        auto bond = [&](std::size_t i, std::int64_t k) {
            const double e = deviatoric_extension(b, y, i, k, pals.theta[i] / 3, edp);
            return pals.s_i[k] * e * e;
        };
        return node_sums(b, bond, [&](std::size_t i, double dev) {
            const double th = mechanical_dilatation(i);
            return 0.5 * pals.K * th * th + 0.5 * dev;
        });
    }
    // theta_i - eps_i m_omega_i: the dilatation less the free thermal one (theta_i without thermal expansion).
    double mechanical_dilatation(std::size_t i) const { return pals.theta[i] - pals.thermal_expansion().strain(i) * pals.m_omega[i]; }

    // (t_i<xi> + t_j<-xi>) V_j / |Y|.
    double bond_scalar(std::size_t, std::int64_t k, int, double ylen) const
    {
        return (t[k] + t[bonds->reverse[k]]) * bonds->volume[k] / ylen;
    }
};

// ADR density: the elastic PALS bound.
inline Field<3> stiffness_bound(const PlasticPALS& model, const Bonds& b, const Field<3>& x) { return stiffness_bound(model.pals, b, x); }

}  // namespace pd
