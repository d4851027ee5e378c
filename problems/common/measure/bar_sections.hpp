// problems/common/measure/bar_sections.hpp -- cross-section measurements on the gripped bar specimens
// (pd::gripped_bar: x axial, bar [0, L] x [0, W] x [0, T], lattice dx, grips outside both ends).
//
// Gauge (seed 000b sec. 4.7, eq. 4.37; spec/000b sec. 5.2): the strain is measured between the two
// lattice layers nearest x = L/2 - delta and x = L/2 + delta, away from the grips' end effects:
//   layer(x) = round(x/dx - 1/2) (cell index of a node at the cell centre (k + 1/2) dx),
//   a = layer(L/2 - delta), b = layer(L/2 + delta), both clamped to [0, nx - 1], nx = round(L/dx),
//   gauge length dist = (b - a) dx, eps = (mean u_x over layer b - mean u_x over layer a) / dist.
// Stress: sigma = F / (W T), F = -sum_{i in grip} f_x,i V_i the axial reaction of a grip (f: the
// internal force density [N/m^3], so -f V is the force the grip holds the node with).
// Lateral stretch of a section: the least-squares slope of the deformed against the reference
// coordinate, mu_d = cov(x_d, x_d + u_d) / var(x_d).
// Axis variant (the source's "two points near the section centre", sec. 4.7): eps_axis from the mean
// u_x of the gauge layers' nodes within dx of the axis (y, z) = (W/2, T/2) in y and z.
// Node sets come in node order and every sum runs in that order (results reproducible bit for bit),
// but for AxisGauge's sections, which sum their axis nodes last.
#pragma once

#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace pd {

struct BarGauge {
    NodeSet sec_a, sec_b;  // nodes of the layers nearest L/2 - delta and L/2 + delta
    NodeSet mid;           // nodes of the mid-length layer(s): one for odd nx, the two central ones for even nx
    double dist = 0;       // gauge length (b - a) dx [m]; 0 when both gauge points fall in one layer
};

// Layer index of a node at axial coordinate x [m] on the lattice dx [m].
inline long bar_layer(double x, double dx) { return std::lround(x / dx - 0.5); }

// The gauge layers of a bar of length L [m] on lattice dx [m] for horizon delta [m] (nodes of
// `body` outside [0, L], the grips, belong to no layer).
inline BarGauge bar_gauge(const Body<3>& body, double L, double dx, double delta)
{
    BarGauge g;
    const long nx = std::lround(L / dx);
    const long a = std::clamp(bar_layer(L / 2 - delta, dx), 0L, nx - 1);
    const long b = std::clamp(bar_layer(L / 2 + delta, dx), 0L, nx - 1);
    g.dist = (b - a) * dx;
    for (std::size_t i = 0; i < body.size(); ++i) {
        const long layer = bar_layer(body.x.c[0][i], dx);
        if (layer == a) g.sec_a.push_back(static_cast<int>(i));
        if (layer == b) g.sec_b.push_back(static_cast<int>(i));
        if (layer == (nx - 1) / 2 || layer == nx / 2) g.mid.push_back(static_cast<int>(i));
    }
    return g;
}

// True when node i lies within `tol` [m] of the bar axis (y, z) = (W/2, T/2) in both y and z.
inline bool near_bar_axis(const Body<3>& body, int i, double W, double T, double tol)
{
    return std::abs(body.x.c[1][i] - W / 2) < tol && std::abs(body.x.c[2][i] - T / 2) < tol;
}

// Axial reaction of a grip [N]: F = -sum f_x V over its nodes (f: internal force density [N/m^3]).
inline double axial_reaction(const Field<3>& f, const Body<3>& body, const NodeSet& grip)
{
    double F = 0;
    for (int i : grip) F -= f.c[0][i] * body.volume[i];
    return F;
}

// The specimen of the bar drivers: a gripped bar (pd::gripped_bar, grip length `grip` outside each
// end) with its gauge. Throws std::invalid_argument (exit status 2 through guarded_main) when delta is
// so large that both gauge layers are one layer.
struct GaugedBar {
    double L, W, T, dx, delta;  // [m]
    GrippedBar bar;             // body, left and right grips
    BarGauge gauge;
};
inline GaugedBar gauged_bar(double L, double W, double T, double dx, double delta, double grip)
{
    GaugedBar s{L, W, T, dx, delta, gripped_bar(L, W, T, dx, grip), {}};
    s.gauge = bar_gauge(s.bar.body, L, dx, delta);
    if (!(s.gauge.dist > 0)) throw std::invalid_argument("option --m too large for the bar: the two gauge layers coincide");
    return s;
}

// Engineering stress sigma = F/(W T) [Pa], F the reaction of the pulled (right) grip (header).
inline double grip_stress(const Field<3>& f, const GaugedBar& s) { return axial_reaction(f, s.bar.body, s.bar.right) / (s.W * s.T); }

// Mean axial displacement u_x over a node set [m].
inline double mean_axial_displacement(const Field<3>& u, const NodeSet& set)
{
    double m = 0;
    for (int i : set) m += u.c[0][i];
    return m / set.size();
}

// The gauge layers of s split at the axis (header): sec_a, sec_b every node of the layer, the axis
// nodes moved to the end (the summation order pals_units_3d has always used: runs.csv depends on it
// in the last bits); axis_a, axis_b only the axis nodes.
struct AxisGauge {
    NodeSet sec_a, sec_b, axis_a, axis_b;
};
inline AxisGauge axis_gauge(const GaugedBar& s)
{
    AxisGauge g;
    auto axis = [&](int i) { return near_bar_axis(s.bar.body, i, s.W, s.T, s.dx); };
    for (int i : s.gauge.sec_a) (axis(i) ? g.axis_a : g.sec_a).push_back(i);
    for (int i : s.gauge.sec_b) (axis(i) ? g.axis_b : g.sec_b).push_back(i);
    g.sec_a.insert(g.sec_a.end(), g.axis_a.begin(), g.axis_a.end());
    g.sec_b.insert(g.sec_b.end(), g.axis_b.begin(), g.axis_b.end());
    return g;
}

// sigma and eps of (4.37) under the displacement u with internal force density f: eps from the
// section means, eps_axis from the axis nodes (units of the bar's lengths and of f).
struct GaugeSample {
    double sigma, eps, eps_axis;  // [Pa], [-], [-]
};
inline GaugeSample sample_gauge(const Field<3>& f, const Field<3>& u, const GaugedBar& s, const AxisGauge& g)
{
    auto mean = [&](const NodeSet& set) { return mean_axial_displacement(u, set); };
    const double dist = s.gauge.dist;
    return {grip_stress(f, s), (mean(g.sec_b) - mean(g.sec_a)) / dist, (mean(g.axis_b) - mean(g.axis_a)) / dist};
}

// Least-squares slope of the deformed coordinate x_d + u_d against x_d over `set` (lateral stretch).
inline double lateral_stretch(const Field<3>& x, const Field<3>& u, const NodeSet& set, int d)
{
    double xm = 0, ym = 0, sxx = 0, sxy = 0;
    for (int i : set) xm += x.c[d][i], ym += x.c[d][i] + u.c[d][i];
    xm /= set.size(), ym /= set.size();
    for (int i : set) sxx += (x.c[d][i] - xm) * (x.c[d][i] - xm), sxy += (x.c[d][i] - xm) * (x.c[d][i] + u.c[d][i] - ym);
    return sxy / sxx;
}

}  // namespace pd
