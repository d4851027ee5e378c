// Horizon moments of influence functions by GSL adaptive quadrature (see influence.hpp).
#include "pd/core/influence.hpp"
#include "pd/core/bonds.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

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
    gsl_error_handler_t* handler = gsl_set_error_handler_off();  // a status, not GSL's abort()
    const int status = gsl_integration_qags(&f, 0.0, delta, 0.0, 1e-12, 200, ws, &result, &abserr);
    gsl_set_error_handler(handler);
    gsl_integration_workspace_free(ws);
    const double moment = factor * result;
    if (status != GSL_SUCCESS || !std::isfinite(moment)) {
        char what[160];
        std::snprintf(what, sizeof what, "horizon moment of order %d over delta = %g m failed (GSL: %s)", p, delta,
                      status != GSL_SUCCESS ? gsl_strerror(status) : "not finite");
        throw std::invalid_argument(what);
    }
    return moment;
}

double lattice_moment(const Influence& w, int p, double delta, double dx, int dim, double measure)
{
    const double volume = std::pow(dx, dim) * measure;
    double sum = 0;
    for (const auto& n : full_family_offsets(delta, dx, dim)) {
        const double r = dx * std::sqrt(double(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
        sum += w(r, delta) * std::pow(r, p) * volume;
    }
    return sum;
}

}  // namespace pd
