// Surface correction of PMB by the energy method of Madenci & Oterkus (2014, "Peridynamic Theory
// and Its Applications", surface effects; spec/002 sec. 2.4 [EXTERNAL], steps 1-6):
//   1. for each axis k, probe with a uniform uniaxial extension u_k = zeta x_k (other components 0)
//      and compute the PD energy density W_k(i) with the model's own quadrature (PMB::energy_density);
//   2. W_k_inf = the bulk value for that strain (see Reference below);
//   3. node factor g_k(i) = W_k_inf / W_k(i);
//   4. bond factor G_k,ij = (g_k(i) + g_k(j)) / 2;
//   5. direction-combined G_ij = [sum_k (n_k / G_k,ij)^2]^(-1/2), n = xi/|xi|;
//   6. c_ij = G_ij c  (PMB::scale_bonds).
// Reference::full_family (default): W_k_inf is the PD energy density of a node whose family is the
//   full lattice family (spec/002: "equals the PD energy of a node with a full neighbourhood"), summed
//   over all integer offsets n with |n| dx <= delta using the model's own per-bond coefficients
//   (on a uniform lattice c omega beta V_j / |xi| depends on |n|^2 only). Interior nodes keep g = 1,
//   so the correction removes only the skin effect; the body need not contain a full-family node.
// Reference::classical: W_k_inf = (D^2/2) kappa_D <n_k^4> zeta^2, the continuum PMB energy under
//   uniaxial strain (W = 1/4 c zeta^2 integral omega |xi| n_k^4 dV, c M1 = 2 D^2 kappa_D), with the
//   spherical averages <n_k^4> = 1/5 (3D), 3/8 (2D), 1 (1D). 3D: 9/10 K zeta^2 = (lambda + 2G)/2
//   zeta^2 with nu = 1/4. It also absorbs the lattice quadrature error of interior nodes.
// LPS (same steps 1-5, the LPS energy density at the probe after its point pass): step 6 scales
//   omega V_j of bond k by G_ij (LPS::scale_bonds), in the dilatation and the deviatoric part alike,
//   with m_i kept (pair forces balance; the force is not the exact gradient of W, see
//   LPS::scale_bonds). Reference::classical only, W_k_inf = (kappa_D/2 + G (1 - 1/D)) zeta^2
//   (uniaxial strain: 3D (K + 4G/3)/2 zeta^2; 2D (kappa_2D + G)/2 zeta^2; 1D E/2 zeta^2). Unlike the
//   uncorrected LPS, the corrected one no longer gives theta = 3 eps exactly at surface nodes under
//   isotropic expansion (G_ij != 1 there).
// Nodes with W_k(i) = 0 (no bond stretched by the probe, e.g. an isolated node) keep g_k = 1.
// Compute the factors on the unscaled model, before any bond breaks (broken bonds are skipped).
#pragma once
#include "pd/models/lps.hpp"
#include "pd/models/pmb.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

enum class SurfaceCorrectionMethod { none, energy };

inline SurfaceCorrectionMethod parse_surface_correction(const std::string& name)  // "none" | "energy"
{
    if (name == "none") return SurfaceCorrectionMethod::none;
    if (name == "energy") return SurfaceCorrectionMethod::energy;
    throw std::invalid_argument("surface correction: unknown method '" + name + "' (none | energy)");
}

struct SurfaceCorrectionOptions {
    double zeta = 1e-6;  // probing uniaxial strain [-]: small, so s = zeta n_k^2 to O(zeta^2)
    enum class Reference { full_family, classical } reference = Reference::full_family;
    double kappa = 0;    // kappa_D [Pa] (kappa_dim of the material), only for Reference::classical
};

template <int D>
struct SurfaceFactors {
    std::array<double, D> W_inf{};         // reference energy density per probing axis [J/m^3]
    std::array<std::vector<double>, D> W;  // uncorrected PD energy density per axis and node [J/m^3]
    std::array<std::vector<double>, D> g;  // node factors g_k(i) [-]
    std::vector<double> G;                 // bond factors G_ij, one per bond, G[k] == G[reverse[k]] [-]
};

namespace detail {

// Positions y = x + zeta (x_a - x_a,mean) e_a: uniaxial extension along a (the shift is a rigid
// translation; it halves the round-off of |y_j - y_i| - |xi|).
template <int D>
Field<D> uniaxial_probe(const Body<D>& body, int a, double zeta)
{
    Field<D> y = body.x;
    double mean = 0;
    for (double v : body.x.c[a]) mean += v;
    mean /= static_cast<double>(body.size());
    for (std::size_t i = 0; i < body.size(); ++i) y.c[a][i] += zeta * (body.x.c[a][i] - mean);
    return y;
}

// Energy density of a full lattice family under each probe, W = 1/4 sum_n coef(|n|^2) |xi|^2 s^2
// (the PMB quadrature), coef taken from the model's bonds keyed by the integer |n|^2.
template <int D>
std::array<double, D> full_family_energy(const PMB& pmb, const Body<D>& body, const Bonds& bonds, double zeta)
{
    const double dx = body.dx;
    if (!(dx > 0))
        throw std::invalid_argument("surface correction: the full-family reference needs a lattice body (dx > 0); use Reference::classical");
    if (!families_within_horizon(bonds))
        throw std::invalid_argument("surface correction: the full-family reference counts the lattice within delta, these families reach "
                                    "beyond it (exact-area partial volumes); use Reference::classical");
    std::map<long, double> coef_of;  // |n|^2 -> c omega beta V_j / |xi|
    for (std::size_t i = 0; i < bonds.nodes(); ++i)
        for_family(bonds, i, [&](std::int64_t k, int j) {
            const Vec<D> xi = body.x[j] - body.x[i];
            const long key = std::lround(dot(xi, xi) / (dx * dx));
            const auto [it, fresh] = coef_of.emplace(key, pmb.coef[k]);
            // 1e-9: same |n|^2 gives the same coefficient up to the round-off of |xi| (~1e-15).
            if (!fresh && std::abs(it->second - pmb.coef[k]) > 1e-9 * std::abs(it->second))
                throw std::invalid_argument("surface correction: bond coefficients differ at equal |xi| (non-uniform lattice "
                                            "or already scaled model); use Reference::classical on the unscaled model");
        });
    std::array<double, D> W{};
    for (const auto& n : full_family_offsets(bonds.delta, dx, D)) {
        Vec<D> xi;
        long key = 0;
        for (int d = 0; d < D; ++d) {
            xi[d] = n[d] * dx;
            key += n[d] * n[d];
        }
        const double L = norm(xi);
        const auto it = coef_of.find(key);
        if (it == coef_of.end())
            throw std::invalid_argument("surface correction: the body has no bond with |xi|^2 = " + std::to_string(key) +
                                        " dx^2, so the full family cannot be assembled; use Reference::classical");
        for (int a = 0; a < D; ++a) {
            Vec<D> Y = xi;
            Y[a] *= 1 + zeta;
            const double s = (norm(Y) - L) / L;  // stretch under the probe
            W[a] += 0.25 * it->second * L * L * s * s;  // spec/002 eq. 2.14, discretised
        }
    }
    return W;
}

}  // namespace detail

namespace detail {

// Steps 1 and 3-5 from the reference energies W_inf and the model's energy density at a probe,
// energy(y) -> W per node [J/m^3].
template <int D, class Energy>
void energy_method_factors(SurfaceFactors<D>& out, const Body<D>& body, const Bonds& bonds, double zeta, Energy&& energy)
{
    for (int a = 0; a < D; ++a) {
        out.W[a] = energy(uniaxial_probe(body, a, zeta));
        out.g[a].resize(body.size());
        for (std::size_t i = 0; i < body.size(); ++i)
            out.g[a][i] = out.W[a][i] > 0 ? out.W_inf[a] / out.W[a][i] : 1.0;  // g_k = W_inf / W_k
    }
    out.G.resize(bonds.size());  // bond factors, symmetric in i and j term by term
    parallel_for(bonds.nodes(), [&](std::size_t i) {
        for_family(bonds, i, [&](std::int64_t k, int j) {
            const Vec<D> xi = body.x[j] - body.x[i];
            const double L2 = dot(xi, xi);
            double sum = 0;
            for (int a = 0; a < D; ++a) {
                const double Ga = 0.5 * (out.g[a][i] + out.g[a][j]);  // G_k,ij
                sum += xi[a] * xi[a] / L2 / (Ga * Ga);                  // (n_k / G_k,ij)^2
            }
            out.G[k] = 1.0 / std::sqrt(sum);  // G_ij = [sum_k (n_k / G_k,ij)^2]^(-1/2)
        });
    });
}

}  // namespace detail

template <int D>
SurfaceFactors<D> surface_correction(const PMB& pmb, const Body<D>& body, const Bonds& bonds,
                                     const SurfaceCorrectionOptions& opt = {})
{
    if (!(opt.zeta > 0)) throw std::invalid_argument("surface correction: zeta must be > 0");
    if (pmb.coef.size() != bonds.size() || body.size() != bonds.nodes())
        throw std::invalid_argument("surface correction: model, body and bonds do not match");
    SurfaceFactors<D> out;
    // Step 2: reference energy densities.
    if (opt.reference == SurfaceCorrectionOptions::Reference::full_family) {
        out.W_inf = detail::full_family_energy(pmb, body, bonds, opt.zeta);
    } else {
        if (!(opt.kappa > 0)) throw std::invalid_argument("surface correction: Reference::classical needs kappa > 0");
        const double n4 = D == 3 ? 1.0 / 5 : D == 2 ? 3.0 / 8 : 1.0;  // spherical average of n_k^4
        for (int a = 0; a < D; ++a) out.W_inf[a] = 0.5 * D * D * opt.kappa * n4 * opt.zeta * opt.zeta;
    }
    PMB probe = pmb;  // the reference body is isothermal
    probe.set_thermal_expansion({});
    detail::energy_method_factors(out, body, bonds, opt.zeta, [&](const Field<D>& y) { return probe.energy_density(bonds, y); });
    return out;
}

// LPS (header): Reference::classical with the model's own kappa_D and G (opt.kappa is not used).
template <int D>
SurfaceFactors<D> surface_correction(const LPS& lps, const Body<D>& body, const Bonds& bonds,
                                     const SurfaceCorrectionOptions& opt = {})
{
    if (!(opt.zeta > 0)) throw std::invalid_argument("surface correction: zeta must be > 0");
    if (opt.reference != SurfaceCorrectionOptions::Reference::classical)
        throw std::invalid_argument("surface correction: LPS takes Reference::classical only");
    if (lps.wV.size() != bonds.size() || body.size() != bonds.nodes() || lps.dim != D)
        throw std::invalid_argument("surface correction: model, body and bonds do not match");
    SurfaceFactors<D> out;
    for (int a = 0; a < D; ++a) out.W_inf[a] = (0.5 * lps.kappa + lps.G * (1.0 - 1.0 / D)) * opt.zeta * opt.zeta;
    LPS probe = lps;  // the point pass writes theta; the reference body is isothermal
    probe.set_thermal_expansion({});
    detail::energy_method_factors(out, body, bonds, opt.zeta, [&](const Field<D>& y) {
        probe.point_pass(bonds, y);
        return probe.energy_density(bonds, y);
    });
    return out;
}

template <int D, class Model>
std::vector<double> surface_correction_factors(const Model& model, const Body<D>& body, const Bonds& bonds,
                                               const SurfaceCorrectionOptions& opt = {})
{
    return surface_correction(model, body, bonds, opt).G;
}

// Step 6 for a scene (PMB or LPS): scales the bonds when `method` is energy; none leaves the model.
template <int D, class Model>
void apply_surface_correction(Model& model, const Body<D>& body, const Bonds& bonds, SurfaceCorrectionMethod method,
                              const SurfaceCorrectionOptions& opt = {})
{
    if (method == SurfaceCorrectionMethod::none) return;
    model.scale_bonds(surface_correction_factors(model, body, bonds, opt));
}

}  // namespace pd
