// problems/pd_run_checks.hpp -- input cross-checks of pd_run (problems/pd_run.cpp) that need more
// than one option: the elastic pair, and the point cloud against the physics of the run.
#pragma once
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/core/material.hpp"
#include "pd_run_integrate.hpp"  // pd_run::fail

#include <string>

namespace pd_run {

// The elastic constants: exactly one of the pairs --K --G and --E --nu (1D: --E alone).
inline pd::Elastic elastic_constants(const pd::io::Options& opt, int dim, pd::Plane plane)
{
    const bool kg = opt.given("K") || opt.given("G"), enu = opt.given("E") || opt.given("nu");
    if (kg && enu) fail("give the elastic constants as --K --G or as --E --nu (not both pairs, not mixed)");
    if (!kg && !enu) fail("elastic constants missing: give --E and --nu, or --K and --G");
    if (kg && !opt.given("K")) fail("option --G needs --K");
    if (kg && !opt.given("G")) fail("option --K needs --G");
    if (enu && !opt.given("E")) fail("option --nu needs --E");
    if (enu && !opt.given("nu") && dim != 1) fail("option --E needs --nu in " + std::to_string(dim) + "D");
    if (kg) return {opt.get("K"), opt.get("G")};
    const double E = opt.get("E"), nu = dim == 1 ? 0.0 : opt.get("nu");  // 1D: only E enters
    const std::string msg = pd::validate_elastic(E, nu, dim, plane);
    if (!msg.empty()) fail("option --" + msg);
    return pd::Elastic::from_E_nu(E, nu);
}

// The point cloud against the physics of the run: temperature columns need --heat, motion columns
// need the mechanics, and the initial temperature comes from the T0 column or --T0 (not both).
inline void check_cloud(const pd::io::PointCloud& pc, const pd::io::Options& opt, bool mechanics, bool heat)
{
    const std::string file = pc.path.string();
    for (const char* c : {"T0", "T_fixed"})
        if (!heat && pc.has_column(c)) fail(file + ": column '" + c + "' needs --heat agwai|correspondence");
    if (pc.has_column("no_fail") && !opt.given("s0")) fail(file + ": column 'no_fail' needs --s0 (bond breaking)");
    for (const char* c : {"ux", "uy", "uz", "vx", "vy", "vz", "fixed"})
        if (!mechanics && pc.has_column(c)) fail(file + ": column '" + c + "' needs the mechanics (not --mechanics off)");
    if (heat && !pc.has_column("T0") && !opt.given("T0")) fail("option --T0 is required: " + file + " has no T0 column");
    if (heat && pc.has_column("T0") && opt.given("T0")) fail("option --T0 is ambiguous: " + file + " has a T0 column");
}


}  // namespace pd_run
