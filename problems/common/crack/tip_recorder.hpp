// The crack tip of a 2D fracture run over time, on any grid the run has at the sample (uniform, or
// refined during the run: time/adaptive_refinement.hpp): the farthest node along dir (dir = 0: from
// origin) with phi >= threshold among those connected to the pre-crack band (crack_metrics.hpp
// connected_damage: steps up to `step` through nodes with phi >= walk inside `region`, e.g. away
// from the loaded rows), and among those inside `beyond` (e.g. not the notch band itself).
// The pre-crack band: the nodes whose initial damage phi0 (the pre-crack's share of the family) is at
// least the threshold; phi0 is the damage of the first sample when the run does not give it.
// Keeps the last sample (grid, phi, connected crack) for the final metrics; write() saves the history.
#pragma once
#include "problems/common/crack/crack_run.hpp"
#include "pd/core/state_archive.hpp"

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace pd::crack {

struct TipRecorder {
    Vec<2> origin{}, dir{};            // reference line of the advance [m], unit direction
    double threshold = tip_threshold;  // phi of a tip node [-]
    double walk = 0.2;                 // phi of the nodes the connection walks through [-]
    double step = 0;                   // longest bond walked [m]
    std::function<bool(const Vec<2>&)> region;  // where the walk goes (empty: everywhere)
    std::function<bool(const Vec<2>&)> beyond;  // where a connected node counts as crack (empty: everywhere)

    TipHistory tips;
    Field<2> x;                        // the last sample's nodes [m]
    std::vector<double> phi, phi0;     // its damage and initial damage [-]
    Mask crack;                        // its nodes connected to the pre-crack

    // A sample at t [s]; phi0: the initial damage of these nodes (null: the first sample's phi).
    void operator()(double t, const Field<2>& nodes, const Bonds& bonds, std::vector<double> p, const std::vector<double>* initial = nullptr)
    {
        if (initial) phi0 = *initial;
        else if (phi0.empty()) phi0 = p;
        Mask seeds(p.size()), inner(p.size(), 1);
        for (std::size_t i = 0; i < p.size(); ++i) seeds[i] = phi0[i] >= threshold, inner[i] = !region || region(nodes[i]);
        crack = connected_damage(bonds, p, seeds, step, walk, inner);
        if (beyond)
            for (std::size_t i = 0; i < p.size(); ++i) crack[i] = crack[i] && beyond(nodes[i]);
        tips.push(t, dir[0] == 0 && dir[1] == 0 ? tip_farthest(nodes, p, origin, threshold, crack) : tip_along(nodes, p, origin, dir, threshold, crack));
        x = nodes, phi = std::move(p);
    }

    // tip_history<suffix>.csv, speed<suffix>.csv (over `window` [s]), damage<suffix>.csv of the last
    // sample, and on a lattice crack_path<suffix>.csv (the phi = 0.41 level curve).
    void write(const std::filesystem::path& out, const std::string& suffix, double window, const Body<2>* lattice) const
    {
        io::CsvWriter th(out / ("tip_history" + suffix + ".csv"), {"t_s", "x_m", "y_m", "advance_m"}, false);
        for (std::size_t l = 0; l < tips.size(); ++l) th.row({tips.t[l], tips.x[l][0], tips.x[l][1], tips.advance[l]});
        io::CsvWriter sp(out / ("speed" + suffix + ".csv"), {"t_s", "v_m_per_s"});
        for (const auto& s : tips.speed(window)) sp.row({s.t, s.v});
        write_damage_csv(out / ("damage" + suffix + ".csv"), x, phi);
        if (lattice) write_crack_path_csv(out / ("crack_path" + suffix + ".csv"), *lattice, phi);
    }

    // Its part of a checkpoint (entries named with `prefix`: one recorder per crack).
    void state(StateArchive& ar, const std::string& prefix = "")
    {
        tips.state(ar, prefix + "tips"), ar(prefix + "x", x), ar(prefix + "phi", phi), ar(prefix + "seeds", phi0), ar(prefix + "crack", crack);
    }
};

}  // namespace pd::crack
