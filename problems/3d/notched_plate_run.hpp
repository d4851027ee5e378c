// problems/3d/notched_plate_run.hpp -- one run of notched_plate_3d: the plate scene (Setup), the notch
// as cut bonds, the chosen damage rule (critical stretch, MO 3D s0, 000c eq. 8.11; critical
// micropotential, w_C = 4 J_C/(pi delta^4), 8.15) with the no-fail band, the clamped grips ramped apart,
// velocity Verlet to t_end, and the measurements: fracture start (first broken bond), end (the tip,
// the largest x of a node whose damage grew by >= 0.35, reaches the last node column), the top grip's
// reaction as a stress, history_<run>.csv.
#pragma once
#include "pd/damage/critical_stretch.hpp"
#include "pd/damage/micropotential.hpp"
#include "pd/damage/precrack.hpp"
#include "pd/io/csv.hpp"
#include "pd/io/timer.hpp"
#include "pd/models/correspondence.hpp"
#include "pd/time/verlet.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

namespace notched_plate {

using C3 = pd::Correspondence<3>;

struct Setup {
    pd::Body<3> body;
    double L = 0, thick = 0, a = 0, y_notch = 0, delta = 0, dx = 0, rho = 0, strain = 0, t_ramp = 0, t_end = 0, dt = 0;
    double no_fail = 0, gauge = 0;  // no-fail band, pulled length between the grips [m]
    long sample = 50;
    pd::NodeSet bottom, top, protect;
    pd::Elastic mat;
    double Gc = 0, C_hg = 0;
};

struct Result {
    std::string name;
    double t_start = NAN, t_end = NAN, wall = 0, peak_stress = 0;  // [s], [s], [s], [Pa]
    long broken_at_end = 0, broken_final = 0;
    bool unstable = false;
};

// One run: bonds with the notch, the model from make(bonds), the damage rule, integration to t_end.
template <class Make>
Result run_case(const Setup& s, const std::string& name, const std::string& damage, Make make, const std::string& out,
                double dt_divisor = 1)
{
    Result r{name};
    const pd::io::Timer timer;
    pd::Bonds bonds = pd::build_bonds(s.body, s.delta, {.keep = pd::cut_by_rectangle(s.body, {{-s.dx, s.y_notch, -s.dx}},
                                                                                      {{s.a + s.dx, 0, 0}}, {{0, 0, s.thick + 2 * s.dx}})});
    bonds.enable_damage();
    const std::vector<double> phi0 = pd::point_damage(bonds);
    auto holder = make(bonds);
    auto& model = *holder;
    using Model = std::remove_reference_t<decltype(model)>;
    pd::Explicit<3, Model> ex(s.body, bonds, model, s.rho);
    pd::CriticalStretch cs{.s0 = pd::s0_madenci_oterkus_3d(s.Gc, s.mat, s.delta), .s0_bond = {}, .no_fail = {}};
    pd::CriticalMicropotential<3> mp;
    mp.w_c = pd::w_critical(s.Gc, s.delta);
    cs.protect(s.protect, s.body.size()), mp.protect(s.protect, s.body.size());
    if (damage == "stretch") ex.damage = &cs;
    if (damage == "micro") ex.micropotential = &mp;
    const double stretch = 0.5 * s.strain * s.gauge;  // grip displacement at the end of the ramp [m]
    for (int d = 0; d < 3; ++d) {
        const double g = d == 1 ? stretch : 0;
        ex.boundary.prescribe({pd::Prescribed::Kind::displacement, s.bottom, d, pd::TimeFunction::ramp(-g, s.t_ramp)});
        ex.boundary.prescribe({pd::Prescribed::Kind::displacement, s.top, d, pd::TimeFunction::ramp(g, s.t_ramp)});
    }
    ex.start();
    pd::io::CsvWriter csv(out + "/history_" + name + ".csv", {"t_s", "stress_Pa", "broken_bonds", "tip_x_m"});
    const double dt = s.dt / dt_divisor;
    const long steps = std::lround(s.t_end / dt);
    try {
        for (long n = 1; n <= steps; ++n) {
            ex.step(dt);
            if (std::isnan(r.t_start) && ex.broken_bonds > 0) r.t_start = ex.t;
            if (n % (s.sample * static_cast<long>(dt_divisor)) != 0 && n != steps) continue;
            double reaction = 0;  // force on the top grip from the plate [N]
            for (int i : s.top) reaction -= ex.internal_force_density().c[1][i] * s.body.volume[i];
            const double stress = reaction / (s.L * s.thick);
            r.peak_stress = std::max(r.peak_stress, stress);
            double tip = 0;
            if (ex.broken_bonds > 0) {
                const std::vector<double> phi = pd::point_damage(bonds);
                for (std::size_t i = 0; i < phi.size(); ++i)
                    if (phi[i] - phi0[i] >= 0.35) tip = std::max(tip, s.body.x.c[0][i]);
            }
            if (std::isnan(r.t_end) && tip > s.L - 1.5 * s.dx) { r.t_end = ex.t; r.broken_at_end = ex.broken_bonds; }
            csv.row({ex.t, stress, static_cast<double>(ex.broken_bonds), tip});
        }
    } catch (const pd::Unstable& e) {
        std::printf("  %s: %s\n", name.c_str(), e.what());
        r.unstable = true;
    }
    r.broken_final = ex.broken_bonds;
    r.wall = timer.seconds();
    std::printf("  %-12s start %7.2f us, end %7.2f us, propagation %6.2f us, peak %.4g MPa, broken %ld (at end %ld), "
                "detached %ld, %.1f s\n", name.c_str(), r.t_start * 1e6, r.t_end * 1e6, (r.t_end - r.t_start) * 1e6,
                r.peak_stress * 1e-6, r.broken_final, r.broken_at_end, mp.detached_nodes + ex.detached_nodes, r.wall);
    return r;
}

}  // namespace notched_plate
