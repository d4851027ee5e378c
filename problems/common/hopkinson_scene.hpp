// problems/common/hopkinson_scene.hpp -- the coupled scene of the 316L Hopkinson tension case (Biondani
// 2018 sec. 9.1; spec/000c sec. 3.2), shared by hopkinson_tension_3d (the 250 us run) and
// hopkinson_multirate_3d (the 30 us clock studies of sec. 9.1.3): its options, the dog-bone and the
// node sets of the measurements, the scene, and one sample of the measurements.
// Specimen (dog_bone.hpp): gauge 12 x 3.77 x 1.85 mm; the outline beyond the gauge is only in the
// source's Fig. 9.1, so ASSUMED here: fillets of radius 4 mm to grips 10 mm wide, body to x = +-30 mm
// plus constraint layers one horizon long outside (Fig. 9.9). Right layer fixed; left layer pulled at
// -V, V = rate x gauge length (1192 1/s: 14.30 m/s), the velocity ramped linearly over --t-rise
// (ASSUMED: the source gives no history); the lateral components of both layers held.
// Physics: correspondence J2 / Johnson-Cook (small-strain total form, models/plastic_correspondence.hpp;
// the source integrates Flanagan-Taylor) with plastic heating (beta_TQ 0.9, assumed by the source too),
// thermal expansion (alpha linear, spec/000c erratum 13) and the law softened by the temperature field;
// critical micropotential (J_C = G_C of Table 9.2) in the damage block only (the other nodes are
// no-fail; the default block, |x| <= 11 mm, holds the gauge, the fillets and one horizon of the grips:
// with its edge inside a fillet (8 mm) the fragments of the rupture stayed tied to no-fail bonds, melted
// (flow stress 0) and diverged 3 us after it); Agwai conduction on its own clock of N_sync(MK) steps when --conduction on (its bonds
// never break), the plastic heat released every N_sync(MH) steps (scene.hpp). dt = --dt-factor x the
// Silling-Askari step of PMB (the source: 0.5 x 0.0530 us at delta = 1 mm) unless a driver sets it.
// Sample: engineering force = mean of the two end reactions [N]; gauge strain from the mean axial
// displacements of the node sections nearest x = -+6 mm; on the surface centreline (top layer, y = 0,
// gauge and fillets) the temperature and the local axial strain (central difference between the two
// neighbours, 2 hx = 0.66 mm at delta = 1 mm); the mid-section (x = 0) mean temperature; the
// centre node's temperature (nearest the body's centre); the largest node damage in the damage block
// and the reference x of the (first) node that has it.
#pragma once
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/io/options.hpp"
#include "pd/models/plastic_correspondence.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/heat_cvode.hpp"
#include "pd/time/verlet.hpp"
#include "problems/common/dog_bone.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

namespace pd {

// The options of the case (SI, temperatures in degrees Celsius; defaults: Table 9.2, sec. 9.1.2).
inline void add_hopkinson_options(io::Options& opt)
{
    opt.add("E", 193e9, "Young's modulus", "Pa"), opt.add("nu", 0.3, "Poisson's ratio"), opt.add("rho", 7900, "density", "kg/m^3");
    opt.add("A", 310.8e6, "J-C yield stress A", "Pa"), opt.add("B", 881.38e6, "J-C hardening B", "Pa");
    opt.add("n", 0.178, "J-C hardening exponent"), opt.add("C", 0.19, "J-C rate sensitivity");
    opt.add("rate0", 1000, "J-C reference strain rate", "1/s"), opt.add("jc-m", 1.25, "J-C softening exponent");
    opt.add("T-ref", 20, "reference (and initial) temperature", "C"), opt.add("T-melt", 1387, "melting temperature", "C");
    opt.add("c", 500, "specific heat", "J/(kg K)"), opt.add("k", 16.2, "thermal conductivity", "W/(m K)");
    opt.add("alpha", 15.9e-6, "linear thermal expansion coefficient", "1/K");
    opt.add("Jc", 179288.86, "critical J-integral (G_C of Table 9.2)", "J/m^2"), opt.add("beta-tq", 0.9, "Taylor-Quinney factor");
    opt.add("delta", 1e-3, "horizon (quick: 2e-3)", "m"), opt.add("m", 3.05, "horizon ratio delta/dx");
    opt.add("C-hg", 0.02, "correspondence hourglass coefficient (assumed: not in the source)");
    opt.add("strain-rate", 1192, "gauge strain rate imposed through the end velocity", "1/s");
    opt.add("t-rise", 10e-6, "rise time of the end velocity (linear ramp, assumed; 0: at once)", "s");
    opt.add("fillet-radius", 4e-3, "fillet radius (assumed)", "m"), opt.add("grip-width", 10e-3, "grip width (assumed)", "m");
    opt.add("half-length", 30e-3, "half-length of the specimen between the constraint layers", "m");
    opt.add("damage-block", 11e-3, "half-length of the block that can fail (gauge, fillets and one horizon of the grips)", "m");
    opt.add("dt-factor", 0.5, "safety factor on the Silling-Askari step");
    for (const char* o : {"E", "rho", "A", "n", "rate0", "c", "k", "Jc", "delta", "m", "strain-rate", "dt-factor", "half-length", "damage-block",
                          "fillet-radius", "grip-width"})
        opt.require_positive(o);
    for (const char* o : {"B", "C", "jc-m", "alpha", "C-hg", "t-rise"}) opt.require_at_least(o, 0);
    opt.require_range("beta-tq", 0, 1, true, true);
    opt.require_range("nu", -1, 0.5, false, false);
}

struct HopkinsonParams {
    Elastic mat;
    double rho = 0, c = 0, k = 0, alpha = 0, Jc = 0, beta = 0, delta = 0, m = 0, C_hg = 0, rate = 0, t_rise = 0, x_grip = 0, block = 0;
    double dt_factor = 0;
    laws::JohnsonCook jc;
    DogBoneShape shape;
    bool conduction = false;
    long nsync_mk = 1, nsync_mh = 1;
    double dt = 0;  // > 0: the mechanical step [s] instead of dt_factor x Silling-Askari
};

// The parameters of the parsed options (one-line message and status 2 for an impossible set).
inline HopkinsonParams hopkinson_params(io::Options& opt)
{
    HopkinsonParams p;
    p.mat = Elastic::from_E_nu(opt.get("E"), opt.get("nu"));
    p.rho = opt.get("rho"), p.c = opt.get("c"), p.k = opt.get("k"), p.alpha = opt.get("alpha"), p.Jc = opt.get("Jc");
    p.beta = opt.get("beta-tq"), p.delta = opt.get("delta"), p.m = opt.get("m"), p.C_hg = opt.get("C-hg"), p.rate = opt.get("strain-rate");
    p.t_rise = opt.get("t-rise"), p.x_grip = opt.get("half-length"), p.block = opt.get("damage-block"), p.dt_factor = opt.get("dt-factor");
    p.jc = {.A = opt.get("A"), .B = opt.get("B"), .n = opt.get("n"), .C = opt.get("C"), .epdot0 = opt.get("rate0"), .m = opt.get("jc-m"),
            .theta_ref = opt.get("T-ref"), .theta_melt = opt.get("T-melt")};
    if (!(p.jc.theta_melt > p.jc.theta_ref)) opt.fail("option --T-melt must exceed --T-ref");
    p.shape = {.fillet_radius = opt.get("fillet-radius"), .grip_width = opt.get("grip-width"), .x_end = p.x_grip + p.delta};
    try {
        p.shape.validate();
    } catch (const std::invalid_argument& e) {
        opt.fail(std::string("options --fillet-radius, --grip-width, --half-length: ") + e.what());
    }
    return p;
}

struct HopkinsonSample {
    double t, F, eps_g, eps_c, T_mid, T_centre, T_line, eps_line, phi_max, x_phi_max;  // [s], [N], -, -, C, C, C, -, -, [m]
};

class HopkinsonScene {
public:
    HopkinsonParams p;
    DogBone d;
    NodeSet left, right, protect, line, mid, end_a, end_b;  // header
    int centre = 0;
    std::size_t q_centre = 0;  // line[q_centre]: the centreline node nearest x = 0
    double x_gauge = 0, section = 0, V = 0;  // gauge-end section position, gauge section [m], [m^2]; end velocity [m/s]
    Bonds bonds, heat_bonds;
    PlasticCorrespondence model;
    std::unique_ptr<TemperatureField> field;
    CriticalMicropotential<3> mp;
    double dt = 0;
    Explicit<3, PlasticCorrespondence> ex;

    explicit HopkinsonScene(const HopkinsonParams& par)
        : p(par), d(dog_bone(p.shape, p.delta / p.m)), bonds(build_bonds(d.body, p.delta)),
          heat_bonds(build_bonds(d.body, p.conduction ? p.delta : 0.25 * d.hx)),  // off: no bonds
          model({.material = p.mat, .C_hg = p.C_hg}, d.body, bonds, p.jc, p.beta),
          dt(p.dt > 0 ? p.dt : stable_step()),
          ex(d.body, bonds, model, p.rho)
    {
        const auto& X = d.body.x.c;
        const double z_top = *std::max_element(X[2].begin(), X[2].end());
        x_gauge = std::round(0.5 * p.shape.gauge_length / d.hx) * d.hx;
        double r_min = HUGE_VAL;
        for (std::size_t i = 0; i < d.body.size(); ++i) {
            const int n = static_cast<int>(i);
            const double x = X[0][i], y = X[1][i], r = std::hypot(x, y, X[2][i]);
            if (x < -p.x_grip) left.push_back(n);
            if (x > p.x_grip) right.push_back(n);
            if (std::abs(x) > p.block) protect.push_back(n);
            if (X[2][i] == z_top && std::abs(y) < 0.01 * d.hy && std::abs(x) <= 0.5 * p.shape.gauge_length + p.shape.fillet_length())
                line.push_back(n);
            if (std::abs(x) < 0.01 * d.hx) mid.push_back(n);
            if (std::abs(x + x_gauge) < 0.01 * d.hx) end_a.push_back(n);
            if (std::abs(x - x_gauge) < 0.01 * d.hx) end_b.push_back(n);
            if (r < r_min) r_min = r, centre = n;
        }
        for (std::size_t q = 0; q < line.size(); ++q) if (std::abs(X[0][line[q]]) < std::abs(X[0][line[q_centre]])) q_centre = q;
        section = p.shape.gauge_width * p.shape.thickness, V = p.rate * p.shape.gauge_length;
        const std::size_t N = d.body.size();
        field = make_temperature_field(Agwai({.k = p.k}, d.body, heat_bonds), heat_bonds, std::vector<double>(N, p.rho * p.c), HeatLoads{},
                                       std::vector<double>(N, p.jc.theta_ref), HeatIntegrator::explicit_euler, double(p.nsync_mk) * dt);
        model.set_thermal_expansion({p.alpha, p.jc.theta_ref, &field->theta});
        model.pts.set_temperature_field(&field->theta);
        mp.w_c = w_critical(p.Jc, p.delta);
        mp.protect(protect, N);
        mp.set_thermal_expansion(model.thermal_expansion(), d.body.x);
        ex.scene.set_damage(mp);
        ex.scene.set_heat(*field, p.nsync_mh);
        ex.boundary.fix(right);
        const TimeFunction pull = p.t_rise > 0 ? TimeFunction::ramp(-V, p.t_rise) : TimeFunction::constant(-V);  // 0: at once
        ex.boundary.prescribe({Prescribed::Kind::velocity, left, 0, pull});
        for (int c : {1, 2}) ex.boundary.prescribe({Prescribed::Kind::displacement, left, c, TimeFunction::constant(0)});
    }

    // dt_factor x the Silling-Askari step of PMB on these bonds [s].
    double stable_step() const
    {
        const double c = PMB::micromodulus({p.mat, 3}, Influence{}, p.delta);
        return p.dt_factor * critical_step_silling_askari(bonds, p.rho, c).dt;
    }

    void print() const
    {
        std::printf("dog bone: %zu nodes (%ld cut cells, %.3g mm^3 dropped), %zu bonds, cells %.4g x %.4g x %.4g mm, delta %.4g mm\n"
                    "dt %.4g us, end velocity %.4g m/s, damage block |x| <= %.3g mm, centreline %zu nodes, conduction %s (N_sync(MK) %ld), "
                    "N_sync(MH) %ld\n", d.body.size(), d.cut_cells, d.dropped_volume * 1e9, bonds.size(), d.hx * 1e3, d.hy * 1e3, d.hz * 1e3,
                    p.delta * 1e3, dt * 1e6, V, p.block * 1e3, line.size(), p.conduction ? "on" : "off", p.nsync_mk, p.nsync_mh);
    }

    double local_strain(std::size_t q) const  // along the centreline row (header)
    {
        const std::size_t a = q == 0 ? 0 : q - 1, b = std::min(q + 1, line.size() - 1);
        return (ex.u.c[0][line[b]] - ex.u.c[0][line[a]]) / (d.body.x.c[0][line[b]] - d.body.x.c[0][line[a]]);
    }

    // Are the two constraint layers still joined by intact bonds? (Breadth-first search from the left
    // layer; false: the specimen has separated.)
    bool ends_connected() const
    {
        std::vector<std::uint8_t> seen(d.body.size(), 0);
        std::vector<int> front(left.begin(), left.end());
        for (int i : left) seen[i] = 1;
        while (!front.empty()) {
            const int i = front.back();
            front.pop_back();
            for_intact_bonds(bonds, i, [&](std::int64_t, int j) {
                if (!seen[j]) seen[j] = 1, front.push_back(j);
            });
        }
        return std::any_of(right.begin(), right.end(), [&](int r) { return seen[r] != 0; });
    }

    // The measurements now; phi: the node damage (point_damage(bonds)).
    HopkinsonSample sample(const std::vector<double>& phi) const
    {
        const std::vector<double>& T = field->theta;
        const Field<3>& f = ex.internal_force_density();
        auto mean_ux = [&](const NodeSet& s) { double u = 0; for (int i : s) u += ex.u.c[0][i] / double(s.size()); return u; };
        HopkinsonSample s{ex.t, 0, (mean_ux(end_b) - mean_ux(end_a)) / (2 * x_gauge), local_strain(q_centre), 0, T[centre], -HUGE_VAL, -HUGE_VAL, 0,
                          NAN};
        for (int i : left) s.F += 0.5 * f.c[0][i] * d.body.volume[i];
        for (int i : right) s.F -= 0.5 * f.c[0][i] * d.body.volume[i];
        for (int i : mid) s.T_mid += T[i] / double(mid.size());
        for (std::size_t q = 0; q < line.size(); ++q) s.T_line = std::max(s.T_line, T[line[q]]), s.eps_line = std::max(s.eps_line, local_strain(q));
        for (std::size_t i = 0; i < d.body.size(); ++i)
            if (std::abs(d.body.x.c[0][i]) <= p.block && phi[i] > s.phi_max) s.phi_max = phi[i], s.x_phi_max = d.body.x.c[0][i];
        return s;
    }
};

}  // namespace pd
