// problems/common/bar_options.hpp -- the options of the gripped V2 bar (seed 000b sec. 4.6, Figs. 4.2-4.3;
// spec/000b sec. 5.2 T2, V2), shared by the quasi-static 3D bar drivers (bar_stiffness_3d,
// large_stretch_3d): material, bar l2 x l1 x l3 = 10 x 2 x 1 mm (x axial), end strain, horizon
// ratio, and the length of the grips added outside each end. Registers them in this order with the
// source's defaults (only the end strain differs between the cases) and their validation: positive
// sizes, strain and grip, m >= 1, and (validate(), after parse) an admissible 3D E, nu.
#pragma once
#include "pd/io/options.hpp"
#include "pd/core/material.hpp"

#include <string>

namespace pd::io {

struct BarOptions {
    double& E;       // Young's modulus [Pa]
    double& nu;      // Poisson's ratio [-]
    double& L;       // bar length l2 (axial) [m]
    double& W;       // bar width l1 [m]
    double& T;       // bar thickness l3 [m]; dx = T/n
    double& strain;  // end displacement / length [-]
    double& m;       // horizon ratio delta/dx [-]
    double& grip;    // grip length outside each end, in delta [-]

    // After opt.parse(): ends with the option message (exit 2) unless E, nu are admissible in 3D.
    void validate(Options& opt) const
    {
        if (const std::string msg = validate_elastic(E, nu, 3, Plane::strain); !msg.empty()) opt.fail(msg);
    }
};

// Registers the bar options; `strain` and `strain_help`: the case's end strain and its description.
inline BarOptions add_bar_options(Options& opt, double strain, const std::string& strain_help)
{
    BarOptions b{opt.add("E", 100e9, "Young's modulus", "Pa"),
                 opt.add("nu", 0.33, "Poisson's ratio (PMB uses only K: nu = 1/4 implied)"),
                 opt.add("length", 10e-3, "bar length l2 (axial)", "m"),
                 opt.add("width", 2e-3, "bar width l1", "m"),
                 opt.add("thickness", 1e-3, "bar thickness l3 (dx = l3/n)", "m"),
                 opt.add("strain", strain, strain_help),
                 opt.add("m", 3.05, "horizon ratio delta/dx"),
                 opt.add("grip", 2, "grip length outside each end, in delta (source: 2)")};
    for (const char* o : {"E", "length", "width", "thickness", "strain", "grip"}) opt.require_positive(o);
    opt.require_at_least("m", 1);
    return b;
}

}  // namespace pd::io
