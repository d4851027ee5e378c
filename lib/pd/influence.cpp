// Horizon moments of influence functions by GSL adaptive quadrature (see influence.hpp).
#include "pd/influence.hpp"
#include "pd/bonds.hpp"

#include <gsl/gsl_integration.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace pd {

Influence Influence::parse(const std::string& name)
{
    Influence w;
    if (name == "one") w.kind = Kind::one;
    else if (name == "inv_xi") w.kind = Kind::inv_xi;
    else if (name == "triangular") w.kind = Kind::triangular;
    else throw std::invalid_argument("unknown influence function '" + name + "' (one, inv_xi, triangular)");
    return w;
}

std::string Influence::name() const
{
    switch (kind) {
    case Kind::one: return "one";
    case Kind::inv_xi: return "inv_xi";
    case Kind::triangular: return "triangular";
    case Kind::custom: return "custom";
    }
    return "?";
}

namespace {
struct MomentArgs { const Influence* w; int power; double delta; };
double radial_integrand(double r, void* p)
{
    auto* a = static_cast<MomentArgs*>(p);
    return (*a->w)(r, a->delta) * std::pow(r, a->power);
}
}  // namespace

double horizon_moment(const Influence& w, int p, double delta, int dim, double measure)
{
    // dV = 4 pi r^2 dr, 2 pi t r dr, 2 A dr  ->  shell factor and extra power of r.
    const double pi = std::numbers::pi;
    const double factor = dim == 3 ? 4 * pi : dim == 2 ? 2 * pi * measure : 2 * measure;
    MomentArgs args{&w, p + dim - 1, delta};
    gsl_function f{&radial_integrand, &args};
    gsl_integration_workspace* ws = gsl_integration_workspace_alloc(200);
    double result = 0, abserr = 0;
    gsl_integration_qags(&f, 0.0, delta, 0.0, 1e-12, 200, ws, &result, &abserr);
    gsl_integration_workspace_free(ws);
    return factor * result;
}

double lattice_moment(const Influence& w, int p, double delta, double dx, int dim, double measure)
{
    const long reach = static_cast<long>(std::floor(delta / dx * (1 + horizon_roundoff)));
    const double volume = std::pow(dx, dim) * measure;
    double sum = 0;
    for (long a = -reach; a <= reach; ++a)
        for (long b = (dim > 1 ? -reach : 0); b <= (dim > 1 ? reach : 0); ++b)
            for (long c = (dim > 2 ? -reach : 0); c <= (dim > 2 ? reach : 0); ++c) {
                const double r = dx * std::sqrt(double(a * a + b * b + c * c));
                if (r == 0 || r > delta * (1 + horizon_roundoff)) continue;
                sum += w(r, delta) * std::pow(r, p) * volume;
            }
    return sum;
}

}  // namespace pd
