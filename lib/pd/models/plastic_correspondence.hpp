// pd/models/plastic_correspondence.hpp -- correspondence J2 / Johnson-Cook plasticity (spec/000b
// sec. 2.1, 2.3, 2.7), a wrapper around Correspondence<3> (models/correspondence.hpp; public
// members point_pass, stress_from_sigma, F, sigma, with_kernel, bond_force only).
// Kinematics (documented choice): small-strain TOTAL form, history = committed plastic strain
// tensor eps_p and ep per node (laws/j2.hpp j2_strain_update):
//   eps = sym(F) - I,  sigma_trial = K tr(eps) I + 2 G dev(eps - eps_p_c),  radial return (5.15)-(5.21),
//   eps_p = eps_p_c + dl 3 s_trial/(2 sigma_eff_trial),  ep = ep_c + dl.
// The Cauchy stress sigma of the return is handed to the wrapped model (Law::flanagan_taylor, whose
// point_pass maps a given sigma to P = J sigma F^-T, P K^-1 and the bond forces); so each
// point_pass runs the model's point pass for F, then, after the return, model.stress_from_sigma for P
// (no second family traversal). At small strain P = sigma (1 + O(eps)). Not objective under large
// rotations (small-strain form; the source's Flanagan-Taylor variant would be, sec. 2.7); the T6 bar
// has no rotation.
// Thermal expansion (set_thermal_expansion, models/thermal_expansion.hpp): eps less the free thermal
// strain eps_i I of node i, the total-form equivalent of spec/000a eq. 2.81.
// Hourglass control (C_hg) acts as in the elastic model. History protocol: plastic_points.hpp.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/laws/elastic.hpp"
#include "pd/laws/j2.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/models/plastic_points.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/stiffness_bound.hpp"
#include "pd/models/thermal_expansion.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct PlasticCorrespondence {
    static constexpr bool has_point_pass = true;
    static constexpr bool ordinary = false;
    using C3 = Correspondence<3>;
    C3 model;                                 // Law::flanagan_taylor: P from the sigma set here
    laws::IsotropicElastic el;
    PlasticPoints pts;
    std::vector<laws::J2History> hist_c, hist;  // committed and trial plastic strain per node

    // p.law is overridden (see header); p.material gives K and G.
    PlasticCorrespondence(C3::Params p, const Body<3>& body, const Bonds& b, const laws::JohnsonCook& law, double beta_TQ = 0.9)
        : model(with_given_stress(p), body, b), el{p.material.K, p.material.G}, pts(law, beta_TQ, b.nodes()),
          hist_c(b.nodes()), hist(b.nodes())
    {
    }

    // Thermal expansion (header); ThermalExpansion{} switches it off. Throws std::invalid_argument for a
    // temperature vector of another length.
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        t.validate(hist.size());
        if (t.active() && t.bond_mean)
            throw std::invalid_argument("PlasticCorrespondence: its thermal strain is a node's (bond_mean is for the ordinary models)");
        thermal = t;
    }
    const ThermalExpansion& thermal_expansion() const { return thermal; }

    double step_heat(std::size_t i) const { return pts.step_heat(i); }  // DissipativeModel (plastic_points.hpp)
    double step_dissipation(std::size_t i) const { return pts.step_dissipation(i); }
    void commit()
    {
        hist_c = hist;
        pts.commit();
    }

    // Its part of a checkpoint (core/state_archive.hpp): the committed and trial plastic history and the
    // stress of the last point pass; rebuild() then redoes the wrapped model's pass (F, P from that
    // stress), not the return, which from the committed history would take the step's flow again.
    void state(StateArchive& ar)
    {
        for (auto* h : {&hist_c, &hist}) {
            const std::string name = h == &hist_c ? "plastic_correspondence.committed" : "plastic_correspondence.trial";
            std::vector<laws::Mat3> eps_p(h->size());
            std::vector<double> ep(h->size());
            for (std::size_t i = 0; i < h->size(); ++i) eps_p[i] = (*h)[i].eps_p, ep[i] = (*h)[i].ep;
            ar.blocks(name + ".eps_p", eps_p), ar(name + ".ep", ep);
            for (std::size_t i = 0; i < h->size(); ++i) (*h)[i] = {eps_p[i], ep[i]};
        }
        ar.blocks("plastic_correspondence.sigma", model.sigma);
        pts.state(ar);
    }
    void rebuild(const Bonds& b, const Field<3>& y) { model.point_pass(b, y); }

    // Trial state at y from the committed history (header).
    // The trial state over a step dt [s] (HistoryModel, kernel_concepts.hpp); without dt: the last step given.
    void point_pass(const Bonds& b, const Field<3>& y, double dt)
    {
        pts.set_time_step(dt);
        point_pass(b, y);
    }
    void point_pass(const Bonds& b, const Field<3>& y)
    {
        model.point_pass(b, y);  // F at y
        parallel_for(b.nodes(), [&](std::size_t i) {
            const laws::Mat3 eps = mechanical_strain(i);
            if (pts.is_plastic(i)) {
                const laws::J2Update u = laws::j2_strain_update(el, pts.law, eps, hist_c[i], pts.dt, pts.theta(i));
                model.sigma[i] = u.stress;
                hist[i] = u.history;
                pts.record(i, u.scalar);
            } else {
                model.sigma[i] = el.stress(eps);
                laws::ScalarReturn r;
                r.sigma_eff = laws::von_mises(model.sigma[i]);
                pts.record(i, r);
            }
        });
        model.stress_from_sigma();  // P = J sigma F^-T, P K^-1 at y
    }

    // Stored (elastic) energy density 1/2 sigma : (eps - eps_p) [J/m^3] (trial eps_p), call after
    // point_pass; hourglass energy not included (as Correspondence).
    std::vector<double> energy_density(const Bonds& b, const Field<3>&) const
    {
        std::vector<double> W(b.nodes(), 0.0);
        for (std::size_t i = 0; i < b.nodes(); ++i) {
            const laws::Mat3 eps = mechanical_strain(i) - hist[i].eps_p;
            W[i] = 0.5 * (model.sigma[i].array() * eps.array()).sum();
        }
        return W;
    }

    template <class Pass>
    void with_kernel(Pass&& pass, const Bonds& b) const { model.with_kernel(pass, b); }
    Vec<3> bond_force(std::size_t i, std::int64_t k, int j, const Vec<3>& Y) const { return model.bond_force(i, k, j, Y); }
    void sync_node_matrices() const { model.sync_node_matrices(); }  // hourglass_forces (bond_loop.hpp)

private:
    ThermalExpansion thermal;  // header; inactive by default

    // sym(F_i) - I - eps_i I [-].
    laws::Mat3 mechanical_strain(std::size_t i) const
    {
        laws::Mat3 eps = 0.5 * (model.F[i] + model.F[i].transpose()) - laws::Mat3::Identity();
        if (thermal.active()) eps.diagonal().array() -= thermal.strain(i);
        return eps;
    }

    static C3::Params with_given_stress(C3::Params p)
    {
        p.law = C3::Law::flanagan_taylor;
        return p;
    }
};

// ADR density: the elastic correspondence bound (the plastic tangent is softer).
inline Field<3> stiffness_bound(const PlasticCorrespondence& w, const Bonds& b, const Field<3>& x) { return stiffness_bound(w.model, b, x); }

}  // namespace pd
