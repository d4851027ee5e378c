// problems/common/meteorite_scene.hpp -- the basalt meteorite entering the atmosphere (Biondani 2018
// sec. 9.2; spec/000c sec. 4, Table 9.5, V16, V17): its options, the sphere with its loading shell, the
// heat input and the measurements, shared by the two studies of meteorite_entry_3d.
// Geometry (cut_sphere.hpp): a 1 cm sphere on cubic cells of side dx = delta/m with cut surface cells,
// covered by the shell R_c of thickness Delta = --shell-factor x dx. Shell-shell bonds are cut (for
// conduction and mechanics alike: the source's mitigation, sec. 9.2.3); shell nodes do not expand
// (alpha = 0 on the shell, realised by giving the expansion of shell nodes the temperature T0).
// Heat input (eqs. 3.29): r(x_v) = Q(phi)/Delta_eff on the shell nodes, phi the angle of the node from
// the flight direction +x (its nearest surface point has the same phi), held constant in time (the
// source: the flux depends only weakly on the surface temperature). Delta_eff = V_shell/(4 pi R^2), the
// thickness that makes the shell's volume that of a layer on the sphere, so that a uniform Q delivers
// exactly Q 4 pi R^2 (r is then Q/Delta less 3 % at delta = 0.5 mm and 7 % at 1 mm: Delta_eff/Delta =
// 1.033, 1.067, the shell lying outside R). Q(phi): the CFD table of the source exists only as figures
// (ambiguity 21), so a SURROGATE: the free-molecular (hyperthermal) heating law Q = Q_s max(cos phi, 0),
// whose total power is Q_s pi R^2, or any table given by --flux-table (CSV angle_deg,Q_W_m2, values
// >= 0; periodic cubic spline with the mirror symmetry, pd/bc/angle_table.hpp; an undershoot of the
// spline below 0 is cut at 0). Q_s is not in the source either: the default 6.7e5 W/m^2
// is the flux under which a semi-infinite solid of basalt gains 1070 K at its surface in 10 s
// (dT = 2 Q sqrt(t/(pi k rho c))), i.e. the source's surface temperature is an input of the
// surrogate, not a prediction.
// Conduction: Agwai (no thermal correction: heat is conserved to round-off), explicit Euler.
#pragma once
#include "pd/io/angle_table_file.hpp"
#include "pd/damage/critical_stretch.hpp"
#include "pd/heat/agwai.hpp"
#include "pd/io/options.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/viscoelastic_correspondence.hpp"
#include "pd/models/viscoelastic_numerical.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"
#include "pd/heat/conduction.hpp"
#include "problems/common/cut_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

namespace pd {

inline void add_meteorite_options(io::Options& opt)
{
    opt.add("E", 70e9, "Young's modulus", "Pa"), opt.add("nu", 0.25, "Poisson's ratio"), opt.add("rho", 3000, "density", "kg/m^3");
    opt.add("c", 1000, "specific heat", "J/(kg K)"), opt.add("k", 1.6736, "thermal conductivity", "W/(m K)");
    opt.add("alpha", 5.4e-6, "linear thermal expansion coefficient (Table 9.5's alpha_V, erratum 13)", "1/K");
    opt.add("Gc", 53.57, "Griffith energy", "J/m^2"), opt.add("radius", 5e-3, "sphere radius", "m");
    opt.add("delta", 0, "horizon (by study: thermal 0.5 mm, spall 1 mm; quick 2 mm)", "m");
    opt.add("m", 3.05, "horizon ratio delta/dx"), opt.add("T0", 30, "initial temperature", "C");
    opt.add("shell-factor", 1, "shell thickness Delta / dx (the source: 1, then 0.1)");
    opt.add("q-stag", 6.7e5, "stagnation heat flux of the surrogate law (header)", "W/m^2");
    opt.add_string("flux-table", "", "CSV angle_deg,Q_W_m2 instead of the surrogate law (cubic in angle, symmetric)");
    opt.add("scale", 0, "factor on k and on the flux (by study: thermal 1, spall 1000)");
    opt.add("dt-factor-heat", 0.5, "safety factor on the explicit thermal critical step");
    for (const char* o : {"E", "rho", "c", "k", "Gc", "radius", "shell-factor"}) opt.require_positive(o);
    opt.require_range("m", 1, 20, false, true), opt.require_range("dt-factor-heat", 0, 1, false, true);
    opt.require_at_least("alpha", 0), opt.require_positive("q-stag");
    opt.require_range("nu", -1, 0.5, false, false);
}

struct MeteoriteParams {
    Elastic mat;
    double rho = 0, c = 0, k = 0, alpha = 0, Gc = 0, R = 0, delta = 0, m = 0, T0 = 0, shell_factor = 0, q_stag = 0, scale = 1, dt_factor_heat = 0;
    std::string flux_table;
};

inline MeteoriteParams meteorite_params(io::Options& opt, double delta, double scale)
{
    MeteoriteParams p{Elastic::from_E_nu(opt.get("E"), opt.get("nu")), opt.get("rho"), opt.get("c"), opt.get("k"), opt.get("alpha"), opt.get("Gc"),
                      opt.get("radius"), delta, opt.get("m"), opt.get("T0"), opt.get("shell-factor"), opt.get("q-stag"), scale,
                      opt.get("dt-factor-heat"), opt.get_string("flux-table")};
    if (!(p.delta / p.m <= 0.25 * p.R)) opt.fail("options --delta, --m, --radius: the cell side delta/m must be at most a quarter of the radius");
    if (!(p.shell_factor < p.m)) opt.fail("option --shell-factor must be below --m (a thicker shell has nodes without bonds to the body)");
    return p;
}

// The sphere, its shell, the heat input and the conduction of a run.
struct MeteoriteScene {
    MeteoriteParams p;
    CutSphere s;
    Bonds heat_bonds;
    double delta_eff = 0, power = 0;  // shell thickness of the heat input [m], total heat input [W]
    int centre = 0;                   // the node at the centre
    std::unique_ptr<ConductingField<Agwai>> field;

    MeteoriteScene(const MeteoriteParams& par, const std::optional<AngleTable>& table)
        : p(par), s(cut_sphere(p.R, p.delta / p.m, p.shell_factor * p.delta / p.m)), heat_bonds(build_bonds(s.body, p.delta, shell_cut()))
    {
        const std::size_t N = s.body.size();
        HeatLoads loads;
        std::vector<double>& r = loads.source;  // heat input per node [W/m^3]
        r.assign(N, 0.0);
        double v_shell = 0;
        for (std::size_t i = s.n_body; i < N; ++i) v_shell += s.body.volume[i];
        delta_eff = v_shell / (4 * std::numbers::pi * p.R * p.R);
        for (std::size_t i = s.n_body; i < N; ++i) {
            const double phi = angle(i);
            r[i] = p.scale * std::max(table ? (*table)(phi) : p.q_stag * std::cos(phi), 0.0) / delta_eff;
            power += r[i] * s.body.volume[i];
        }
        for (std::size_t i = 0; i < s.n_body; ++i) if (norm(s.body.x[i]) < norm(s.body.x[centre])) centre = static_cast<int>(i);
        field = std::make_unique<ConductingField<Agwai>>(Agwai({.k = p.scale * p.k}, s.body, heat_bonds), heat_bonds,
                                                         std::vector<double>(N, p.rho * p.c), loads, std::vector<double>(N, p.T0),
                                                         HeatIntegrator::explicit_euler, 1.0);
    }

    // Shell-shell bonds are not created (header).
    BondOptions shell_cut() const
    {
        const std::size_t nb = s.n_body;
        return {.keep = [nb](int i, int j) { return std::size_t(i) < nb || std::size_t(j) < nb; }};
    }
    double angle(std::size_t i) const { return std::acos(std::clamp(s.body.x.c[0][i] / norm(s.body.x[i]), -1.0, 1.0)); }  // from +x [rad]
    // dt_factor_heat x the explicit critical step of the conduction [s].
    double thermal_step() const
    {
        return p.dt_factor_heat * field->critical_step();
    }
    // Heat content above T0 of the body or of the shell [J].
    double heat_content(bool shell) const
    {
        double e = 0;
        for (std::size_t i = shell ? s.n_body : 0; i < (shell ? s.body.size() : s.n_body); ++i)
            e += p.rho * p.c * (field->theta[i] - p.T0) * s.body.volume[i];
        return e;
    }
    struct Temperatures {
        double body_max, surface_max, shell_max, centre;  // [C]
    };
    Temperatures temperatures() const
    {
        const std::vector<double>& T = field->theta;
        Temperatures t{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL, T[centre]};
        for (std::size_t i = 0; i < s.body.size(); ++i) {
            if (s.in_shell(i)) t.shell_max = std::max(t.shell_max, T[i]);
            else t.body_max = std::max(t.body_max, T[i]);
            if (!s.in_shell(i) && s.surface[i]) t.surface_max = std::max(t.surface_max, T[i]);
        }
        return t;
    }
    void print() const
    {
        std::printf("sphere R %.4g mm: %zu body nodes (%ld cut cells) + %zu shell nodes (Delta %.4g mm, Delta_eff %.4g mm), %zu heat bonds, "
                    "delta %.4g mm, dx %.4g mm; heat input %.6g W (k, flux x %g)\n", p.R * 1e3, s.n_body, s.cut_cells, s.body.size() - s.n_body,
                    s.shell * 1e3, delta_eff * 1e3, heat_bonds.size(), p.delta * 1e3, s.dx * 1e3, power, p.scale);
    }
};

// The mechanics of the weakly coupled study (sec. 9.2.5): Flanagan-Taylor correspondence with the
// numerical viscosity of sec. 8.4.2 (eta, one Maxwell branch on the deviator; weak coupling, sec. 9.2.2:
// its dissipation is not released as heat, N_sync(MH) = 0), hourglass control C_hg (assumed: not in
// the source), thermal
// expansion from the scene's temperatures (shell nodes held at T0), critical stretch s0 of PMB 3D (the
// source does not state its formula; PMB and MO 3D coincide at nu = 1/4) on the mechanical stretch,
// the singular-node rule; a free body (the CFD pressure, rho_inf V^2 ~ 3 kPa, is not applied). Heat
// bonds are the scene's and never break. dt: dt_factor x the Silling-Askari step of PMB with the elastic
// moduli (the branch's instantaneous 9 G relaxes within tau_b, a quarter of the step at delta = 1 mm; a
// run that becomes unstable stops with the step and node).
struct MeteoriteMechanics {
    MeteoriteScene& sc;
    Bonds bonds;
    Correspondence<3> model;
    ViscoelasticCorrespondence visco;
    CriticalStretch rule;
    std::vector<double> theta_mech;  // the temperatures the expansion sees [C]
    Explicit<3, ViscoelasticCorrespondence> ex;

    MeteoriteMechanics(MeteoriteScene& scene, double eta, double C_hg)
        : sc(scene), bonds(build_bonds(sc.s.body, sc.p.delta, sc.shell_cut())),
          model({.material = sc.p.mat, .law = Correspondence<3>::Law::flanagan_taylor, .C_hg = C_hg}, sc.s.body, bonds),
          visco(model, params(numerical_viscosity(sc.p.mat.G, sc.p.rho, sc.s.dx, eta)), sc.s.body.x),
          rule(CriticalStretch::uniform(s0_pmb_3d(sc.p.Gc, sc.p.mat.K, sc.p.delta))), theta_mech(sc.field->theta),
          ex(sc.s.body, bonds, visco, sc.p.rho)
    {
        const ThermalExpansion te{sc.p.alpha, sc.p.T0, &theta_mech};
        model.set_thermal_expansion(te);
        rule.thermal = te;
        sc.field->after_step = [this](const TemperatureField& f) { refresh(f.theta); };
        ex.scene.set_damage(rule);
        ex.scene.set_heat(*sc.field, 0);  // weak coupling: no heat from the mechanics
    }
    static ViscoelasticCorrespondence::Params params(const MaxwellShear& m) { return {m.gamma_b, m.tau_b}; }
    void refresh(const std::vector<double>& theta)
    {
        std::copy(theta.begin(), theta.begin() + long(sc.s.n_body), theta_mech.begin());  // the shell stays at T0
    }
    double stable_step(double dt_factor) const
    {
        const double c = PMB::micromodulus({sc.p.mat, 3}, Influence{}, sc.p.delta);
        return dt_factor * critical_step_silling_askari(bonds, sc.p.rho, c).dt;
    }
    // Damage of body node i over its bonds to body nodes only (the shell's bonds, which may tear as the
    // shell detaches, left out): 1 - intact V / all V.
    double body_damage(std::size_t i) const
    {
        double all = 0, kept = 0;
        for_family(bonds, i, [&](std::int64_t k, int j) {
            if (std::size_t(j) >= sc.s.n_body) return;
            all += bonds.volume[k], kept += bonds.intact[k] ? bonds.volume[k] : 0.0;
        });
        return all > 0 ? 1 - kept / all : 0.0;
    }
    // Mean body_damage of the body nodes within `cone` [rad] of the stagnation direction, in bins of
    // depth R - |x| of width dx (bin b: [b dx, (b + 1) dx)), down to half the radius (at least one bin).
    std::vector<double> front_damage_profile(double cone) const
    {
        const std::size_t bins = std::max<std::size_t>(1, static_cast<std::size_t>(0.5 * sc.p.R / sc.s.dx));
        std::vector<double> sum(bins, 0.0), cnt(bins, 0.0);
        for (std::size_t i = 0; i < sc.s.n_body; ++i) {
            const std::size_t b = static_cast<std::size_t>((sc.p.R - norm(sc.s.body.x[i])) / sc.s.dx);
            if (sc.angle(i) <= cone && b < bins) sum[b] += body_damage(i), cnt[b] += 1;
        }
        for (std::size_t b = 0; b < bins; ++b) sum[b] = cnt[b] > 0 ? sum[b] / cnt[b] : 0.0;
        return sum;
    }
};

}  // namespace pd
