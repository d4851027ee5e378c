// Validation of elastic constants (see material.hpp).
#include "pd/core/material.hpp"

#include <cmath>
#include <sstream>

namespace pd {

std::string validate_elastic(double E, double nu, int dim, Plane)
{
    std::ostringstream msg;
    if (!(E > 0) || !std::isfinite(E)) {
        msg << "option --E must be positive and finite, got " << E;
        return msg.str();
    }
    if (dim == 1) return "";
    if (!(nu > -1.0 && nu < 0.5)) {
        msg << "option --nu must lie in (-1, 0.5) in " << dim << "D, got " << nu;
        return msg.str();
    }
    return "";
}

}  // namespace pd
