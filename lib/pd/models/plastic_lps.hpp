// pd/models/plastic_lps.hpp -- ordinary (LPS) J2 / Johnson-Cook plasticity with radial return
// (Biondani 2018 sec. 5.3; spec/000b sec. 2.4-2.5), composed with models/lps.hpp (public members
// only). Per node i, from the committed plastic back extension e_dp per bond and ep_i:
//   e    = |Y| - |xi|,  e_de = e - theta_i |xi|/3 - e_dp                      (sec. 2.4 step 2)
//   W_d  = (alpha_i/2) sum_j omega e_de^2 V_j,  sigma_eff_trial = sqrt(6 G W_d)   (5.33), (5.36)
//   scalar return (laws/j2.hpp): sigma_eff_trial - 3 G dl - sigma_y(ep + dl, dl/dt, theta) = 0  (5.48)
//   t_d  = alpha_i omega e_de sigma_y / sigma_eff_trial (radial return, 5.46)
//   e_dp += 3 G dl e_de / sigma_eff_trial                                       (5.40)
// The flow rule (5.40), (m/5) t_d/(omega sigma_eff) dl with t_d the returned state, equals
// 3 G dl e_de_trial/sigma_eff_trial for alpha = 15 G/m; written with alpha_i it stays consistent
// with a shear correction alpha_i = SCF 15 G/m (the [RECON] m/(5 SCF) of sec. 2.4), so the return
// factor is 3 G in both cases. Pair force on i: (t_i<xi> + t_j<-xi>) V_j Y/|Y| with
// t = omega (3 K theta |xi| / m + t_d) (4.11); t_j<-xi> reads the twin bond's t_d.
// 3D. Damage: the family sums skip broken bonds (as LPS), recompute(bonds) refreshes m_i and
// alpha_i (LPS intact rule), so a damaged body equals the body built without the broken bonds
// (tests/test_plastic_models.cpp); a broken bond keeps its committed e_dp and carries no force.
// Thermal expansion (the wrapped LPS's set_thermal_expansion): lps.theta is the mechanical dilatation
// theta - 3 eps_i, and e_de = e - eps_i |xi| - theta_mech |xi|/3 - e_dp (the isotropic thermal strain
// leaves the deviatoric extension, hence the yield, untouched: a free or clamped heated body does
// not flow); eps_i = 0 without it, exactly the isothermal result. With ThermalExpansion::bond_mean each
// bond takes (eps_i + eps_j)/2 instead of eps_i (ThermalExpansion::bond_strain).
// History protocol: plastic_points.hpp.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/models/lps.hpp"
#include "pd/models/plastic_points.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/stiffness_bound.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pd {

struct PlasticLPS {
    static constexpr bool has_point_pass = true;
    LPS lps;                         // elastic LPS: m, theta, alpha, p_coef, wV
    PlasticPoints pts;               // law, ep, outputs
    std::vector<double> edp_c, edp;  // committed and trial plastic back extension per bond [m]
    std::vector<double> tdev;        // trial deviatoric force scalar alpha_i e_de scale (no omega) [Pa/m^4]
    const std::int64_t* reverse = nullptr;

    PlasticLPS(const LPS::Params& p, const Bonds& b, const laws::JohnsonCook& law, double beta_TQ = 0.9)
        : lps(p, b), pts(law, beta_TQ, b.nodes()), edp_c(b.size(), 0.0), edp(b.size(), 0.0), tdev(b.size(), 0.0),
          reverse(b.reverse.data())
    {
        if (p.dim != 3) throw std::invalid_argument("PlasticLPS: written for 3D");
    }

    void recompute(const Bonds& b) { lps.recompute(b); }  // after bonds broke (header)
    // Thermal expansion of the wrapped LPS (header; its refusals are LPS's).
    void set_thermal_expansion(const ThermalExpansion& t) { lps.set_thermal_expansion(t); }
    const ThermalExpansion& thermal_expansion() const { return lps.thermal_expansion(); }
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
        ar("lps.theta", lps.theta), ar("lps.a_coef", lps.a_coef);
        ar("plastic_lps.edp_c", edp_c), ar("plastic_lps.edp", edp), ar("plastic_lps.tdev", tdev);
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
        lps.point_pass(b, y);
        const double G = lps.G;
        const bool damaged = b.has_damage();
        parallel_for(b.nodes(), [&](std::size_t i) {
            double sum = 0;  // sum omega e_de^2 V [m^5] over intact bonds
            for_family(b, i, [&](std::int64_t k, int j) {
                if (damaged && !b.intact[k]) { tdev[k] = 0; return; }
                const double th = lps.theta[i] / 3 + lps.thermal_expansion().bond_strain(i, j);  // header
                const double e = deviatoric_extension(b, y, i, k, th, edp_c);
                tdev[k] = e;  // e_de until the return below
                sum += lps.wV[k] * e * e;
            });
            const double trial = std::sqrt(6 * G * 0.5 * lps.alpha[i] * sum);  // sqrt(6 G W_d) (5.36)
            const laws::ScalarReturn r = pts.scalar_return(i, G, trial);
            const double scale = r.plastic ? r.sigma_eff / trial : 1.0;             // (5.46)
            const double flow = r.plastic ? 3 * G * r.dlambda / trial : 0.0;        // (5.40)
            for_family(b, i, [&](std::int64_t k, int) {
                if (damaged && !b.intact[k]) { edp[k] = edp_c[k]; return; }
                const double e = tdev[k];
                tdev[k] = lps.alpha[i] * scale * e;
                edp[k] = edp_c[k] + flow * e;
            });
        });
    }

    // Stored (elastic) energy density [J/m^3], call after point_pass at y: the LPS energy (4.10) of
    // the elastic deviatoric extension e_de - (e_dp - e_dp_c) = e - theta |xi|/3 - e_dp (trial e_dp).
    std::vector<double> energy_density(const Bonds& b, const Field<3>& y) const
    {
        auto bond = [&](std::size_t i, std::int64_t k) {
            const double e = deviatoric_extension(b, y, i, k, lps.theta[i] / 3 + lps.thermal_expansion().bond_strain(i, b.partner[k]), edp);
            return b.omega[k] * e * e * b.volume[k];
        };
        return node_sums(b, bond, [&](std::size_t i, double dev) {
            return 0.5 * lps.kappa * lps.theta[i] * lps.theta[i] + 0.5 * lps.alpha[i] * dev;
        });
    }

    // (t_i + t_j) V_j / |Y| with t = omega (p_coef theta |xi| + t_d); omega V_j = wV.
    double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const
    {
        const double L = lps.bonds->length[k];
        const double t = L * (lps.p_coef[i] * lps.theta[i] + lps.p_coef[j] * lps.theta[j]) + tdev[k] + tdev[reverse[k]];
        return t * lps.wV[k] / ylen;
    }
};

// ADR density: the elastic LPS bound (the plastic tangent is softer).
inline Field<3> stiffness_bound(const PlasticLPS& model, const Bonds& b, const Field<3>& x) { return stiffness_bound(model.lps, b, x); }

}  // namespace pd
