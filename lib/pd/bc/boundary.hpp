// Boundary conditions on node sets (spec/000a sec. 3.6): prescribed displacement or velocity
// components with a time function (constant, ramp, table), fixed nodes, body forces, and
// surface tractions applied as body force on a boundary layer of thickness Delta,
// b = p / Delta (3.28).
#pragma once
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace pd {

// g(t): constant value; ramp value * min(t / t_ramp, 1); table linear interpolation, held
// constant outside its range.
struct TimeFunction {
    enum class Kind { constant, ramp, table } kind = Kind::constant;
    double value = 0;
    double t_ramp = 0;           // [s]
    std::vector<double> t, g;    // table abscissae [s] (increasing) and values

    static TimeFunction constant(double v) { return {Kind::constant, v, 0, {}, {}}; }
    static TimeFunction ramp(double v, double t_ramp)
    {
        if (!(t_ramp > 0)) throw std::invalid_argument("ramp time must be positive");
        return {Kind::ramp, v, t_ramp, {}, {}};
    }
    static TimeFunction table(std::vector<double> t, std::vector<double> g)
    {
        if (t.empty() || t.size() != g.size()) throw std::invalid_argument("time table needs matching, non-empty columns");
        if (!std::is_sorted(t.begin(), t.end())) throw std::invalid_argument("time table abscissae must increase");
        return {Kind::table, 0, 0, std::move(t), std::move(g)};
    }
    double operator()(double time) const
    {
        switch (kind) {
        case Kind::constant: return value;
        case Kind::ramp: return value * std::min(time / t_ramp, 1.0);
        case Kind::table: {
            if (time <= t.front()) return g.front();
            if (time >= t.back()) return g.back();
            const auto it = std::upper_bound(t.begin(), t.end(), time);
            const std::size_t hi = it - t.begin(), lo = hi - 1;
            const double w = (time - t[lo]) / (t[hi] - t[lo]);
            return (1 - w) * g[lo] + w * g[hi];
        }
        }
        return 0;
    }
};

struct Prescribed {
    enum class Kind { displacement, velocity } kind = Kind::displacement;
    NodeSet nodes;
    int component = 0;
    TimeFunction g;  // u [m] or v [m/s] as a function of time
};

template <int D>
struct BodyForce {
    NodeSet nodes;            // empty = every node
    Vec<D> b{};               // [N/m^3]
    TimeFunction scale = TimeFunction::constant(1.0);
};

template <int D>
struct Boundary {
    std::vector<Prescribed> prescribed;
    std::vector<BodyForce<D>> forces;

    void fix(const NodeSet& nodes)  // all components held at zero displacement
    {
        if (nodes.empty()) throw std::invalid_argument("fixed node set is empty");
        for (int d = 0; d < D; ++d) prescribed.push_back({Prescribed::Kind::displacement, nodes, d, TimeFunction::constant(0)});
    }
    void prescribe(Prescribed p)
    {
        if (p.nodes.empty()) throw std::invalid_argument("prescribed node set is empty");
        if (p.component < 0 || p.component >= D) throw std::invalid_argument("prescribed component out of range");
        prescribed.push_back(std::move(p));
    }
    // Surface traction p [Pa] on the layer `nodes` of thickness Delta [m]: b = p / Delta (3.28).
    void traction(const NodeSet& nodes, const Vec<D>& p, double Delta, TimeFunction scale = TimeFunction::constant(1.0))
    {
        if (nodes.empty()) throw std::invalid_argument("traction node set is empty");
        if (!(Delta > 0)) throw std::invalid_argument("traction layer thickness must be positive");
        forces.push_back({nodes, (1.0 / Delta) * p, scale});
    }
    void body_force(const Vec<D>& b, NodeSet nodes = {}, TimeFunction scale = TimeFunction::constant(1.0))
    {
        forces.push_back({std::move(nodes), b, scale});
    }
    // External body-force density at time t [N/m^3], added into b (sized n).
    void external(double t, Field<D>& b) const
    {
        b.fill(0.0);
        for (const auto& f : forces) {
            const double s = f.scale(t);
            if (f.nodes.empty())
                for (std::size_t i = 0; i < b.size(); ++i) b.add(i, s * f.b);
            else
                for (int i : f.nodes) b.add(i, s * f.b);
        }
    }
};

}  // namespace pd
