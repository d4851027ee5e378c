// Influence functions omega(|xi|) (spec/000a sec. 2.4, eq. 2.35) and their horizon moments
//   M_p = integral over the horizon of omega(r) r^p dV,
// with dV = 4 pi r^2 dr (3D), 2 pi t r dr (2D, thickness t), 2 A dr (1D, cross-section A).
// The micromoduli of PMB are written with M_1 (energy matching), so any omega works.
#pragma once
#include <functional>
#include <string>

namespace pd {

struct Influence {
    enum class Kind { one, inv_xi, triangular, custom } kind = Kind::one;
    std::function<double(double r, double delta)> custom_fn;  // used when kind == custom

    double operator()(double r, double delta) const
    {
        switch (kind) {
        case Kind::one: return 1.0;
        case Kind::inv_xi: return delta / r;          // "inverse" of eq. 2.35
        case Kind::triangular: return 1.0 - r / delta;
        case Kind::custom: return custom_fn(r, delta);
        }
        return 1.0;
    }
    static Influence parse(const std::string& name);  // "one" | "inv_xi" | "triangular"; throws otherwise
    std::string name() const;
};

// Measure of the reduced dimensions: 1 in 3D, thickness t [m] in 2D, cross-section A [m^2] in 1D.
// M_p [m^(p+3)] by adaptive Gauss-Kronrod quadrature (GSL) on the radial integral.
double horizon_moment(const Influence& w, int p, double delta, int dim, double measure);

// The same moment summed over a full family of a simple cubic lattice of spacing dx (node
// volumes dx^D * measure, |xi| <= delta): what an interior node of a lattice actually sees.
double lattice_moment(const Influence& w, int p, double delta, double dx, int dim, double measure);

}  // namespace pd
