// 3D crack tips on node slabs (problems/3d/crack_branching.cpp): the crack of a 3D plate run over
// time as damaged nodes connected in 3D to the pre-crack band, its tip taken with the 2D metrics of
// crack_metrics.hpp on the mid-thickness slab and both surface slabs. A slab k holds the nodes with
// k h0 <= z < (k + 1) h0 (h0: the spacing of the initial grid), so a grid refined during the run
// (time/adaptive_refinement.hpp: two sub-layers per slab) has its slabs too.
#pragma once
#include "problems/common/crack/crack_metrics.hpp"
#include "pd/core/state_archive.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace pd::crack {

// One slab of nodes as a 2D point set, for the 2D crack metrics.
struct Layer {
    std::vector<int> node;  // 3D node index of each layer point
    Field<2> x;         // in-plane reference positions [m]
    template <class T>
    std::vector<T> take(const std::vector<T>& f) const
    {
        std::vector<T> r(node.size());
        for (std::size_t l = 0; l < node.size(); ++l) r[l] = f[node[l]];
        return r;
    }
};

inline Layer layer(const Field<3>& x, double h0, long k)
{
    Layer L;
    for (std::size_t i = 0; i < x.size(); ++i)
        if (std::lround(std::floor(x.c[2][i] / h0)) == k) L.node.push_back(static_cast<int>(i));
    L.x.resize(L.node.size());
    for (std::size_t l = 0; l < L.node.size(); ++l) L.x.set(l, {{x.c[0][L.node[l]], x.c[1][L.node[l]]}});
    return L;
}

// A sample: the crack = damaged nodes connected in 3D to the pre-crack band (steps up to `step` through
// nodes with phi >= walk, within half_band of y_mid: away from the loaded rows), its tip along dir on
// the mid and both surface slabs; the last sample is kept for the final metrics.
struct SlabTips {
    Vec<2> origin{}, dir{};
    double threshold = 0, walk = 0, step = 0, h0 = 0, y_mid = 0, half_band = 0;
    long nz = 1;
    TipHistory tip_mid, tip_bot, tip_top;
    Field<3> x;
    std::vector<double> phi, phi0;
    Mask crack;
    double u_max = 0;  // largest displacement [m]

    void operator()(double t, const Field<3>& nodes, const Bonds& bonds, std::vector<double> p, const std::vector<double>* initial,
                    const Field<3>& u)
    {
        if (initial) phi0 = *initial;
        else if (phi0.empty()) phi0 = p;  // the pre-crack band at t = 0
        Mask seeds(p.size()), inner(p.size());
        for (std::size_t i = 0; i < p.size(); ++i) seeds[i] = phi0[i] >= threshold, inner[i] = std::abs(nodes.c[1][i] - y_mid) < half_band;
        crack = connected_damage(bonds, p, seeds, step, walk, inner);
        auto tip_on = [&](long k) {
            const Layer ly = layer(nodes, h0, k);
            return tip_along(ly.x, ly.take(p), origin, dir, threshold, ly.take(crack));
        };
        tip_mid.push(t, tip_on(nz / 2)), tip_bot.push(t, tip_on(0)), tip_top.push(t, tip_on(nz - 1));
        x = nodes, phi = std::move(p);
        u_max = 0;
        for (std::size_t i = 0; i < u.size(); ++i) u_max = std::max(u_max, norm(u[i]));
    }
    void state(StateArchive& ar)
    {
        tip_mid.state(ar, "tips_mid"), tip_bot.state(ar, "tips_bottom"), tip_top.state(ar, "tips_top");
        ar("x", x), ar("phi", phi), ar("seeds", phi0), ar("crack", crack), ar("u_max", u_max);
    }
};


}  // namespace pd::crack
