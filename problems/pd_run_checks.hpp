// problems/pd_run_checks.hpp -- input cross-checks of pd_run (problems/pd_run.cpp) that need more
// than one option: the elastic pair, and the point cloud against the physics of the run.
#pragma once
#include "pd/io/options.hpp"
#include "pd/io/point_cloud.hpp"
#include "pd/core/material.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/lattice.hpp"
#include "pd/io/csv.hpp"
#include "pd_run_integrate.hpp"  // pd_run::fail, program

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace pd_run {

inline constexpr double near_duplicate = 1e-3;  // closest pair / median nearest spacing below which pd_run warns

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
    if (!msg.empty()) fail(msg);
    return pd::Elastic::from_E_nu(E, nu);
}

// The options that depend on the dimension or the model: fail() names the first that does not apply.
inline void check_model_options(const pd::io::Options& opt, int dim, const std::string& model, const std::string& surface, const std::string& pv)
{
    if (opt.given("plane") && dim != 2) fail("option --plane applies to --dim 2 only");
    if (opt.given("thickness") && dim != 2) fail("option --thickness applies to --dim 2 only");
    if (opt.given("area") && dim != 1) fail("option --area applies to --dim 1 only");
    if (pv == "pa-pdlammps" && !opt.given("dx")) fail("option --partial-volume pa-pdlammps needs --dx (the lattice spacing)");
    if (model == "pals" && dim != 3) fail("option --model pals needs --dim 3");
    if (model == "correspondence" && dim == 1) fail("option --model correspondence needs --dim 2 or 3");
    if (surface == "energy" && model == "pmb" && !opt.given("dx")) fail("option --surface-correction energy needs --dx (the lattice spacing)");
    if (surface == "energy" && model != "pmb" && model != "lps") fail("option --surface-correction energy applies to --model pmb or lps only");
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

// Physically empty scenes (after the bonds): every point isolated is an error naming --delta; some
// isolated points, and points much nearer than the cloud's typical spacing (they set the automatic
// step: the stiffness of a bond grows as 1/|xi|), are a one-line warning each on stderr.
template <int D>
void warn_empty_scene(const pd::Body<D>& body, const pd::Bonds& bonds, long isolated)
{
    const std::size_t n = body.size();
    if (isolated == static_cast<long>(n))
        fail("option --delta: no point has a bond within delta = " + pd::io::format_shortest(bonds.delta) +
             " m (every point is isolated; --delta must exceed the spacing of the cloud)");
    if (isolated > 0)
        std::fprintf(stderr, "%s: warning: %ld of %zu points have no bond within --delta (they move freely)\n", program, isolated, n);
    // Nearest partner per point; the closest pair against the median nearest spacing.
    std::vector<double> nearest;
    double closest = std::numeric_limits<double>::infinity();
    std::size_t ci = 0;
    int cj = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double r = std::numeric_limits<double>::infinity();
        pd::for_intact_bonds(bonds, i, [&](std::int64_t k, int j) {
            if (bonds.length[k] < r) {
                r = bonds.length[k];
                if (r < closest) closest = r, ci = i, cj = j;
            }
        });
        if (std::isfinite(r)) nearest.push_back(r);
    }
    if (nearest.empty()) return;
    std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
    const double median = nearest[nearest.size() / 2];
    if (closest < near_duplicate * median)
        std::fprintf(stderr, "%s: warning: points %zu and %d are %.3g m apart, %.2g of the median nearest spacing %.3g m: "
                     "near-duplicates shrink the automatic step in proportion\n", program, ci, cj, closest, closest / median, median);
}

// Correspondence: points whose shape tensor is singular (fewer than D independent bonds) carry no
// stress force; all of them is an error (a flat cloud run with a larger --dim), some a warning.
template <class Model>
void warn_singular_shape_tensors(const Model& model, int dim)
{
    long singular = 0;
    for (const auto& K_inv : model.Kinv) singular += K_inv.isZero(0);
    const long n = static_cast<long>(model.Kinv.size());
    if (n > 0 && singular == n)
        fail("option --model correspondence: every shape tensor is singular (fewer than " + std::to_string(dim) +
             " independent bonds per point; is the cloud flat for --dim " + std::to_string(dim) + "?)");
    if (singular > 0)
        std::fprintf(stderr, "%s: warning: %ld of %ld points have a singular shape tensor (no correspondence stress force)\n", program,
                     singular, n);
}

}  // namespace pd_run
