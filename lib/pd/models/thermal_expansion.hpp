// pd/models/thermal_expansion.hpp -- thermal expansion of the ordinary models (spec/000a sec. 2.11).
// The mechanical extension of bond k (i -> j) is the extension less the free thermal one,
//   e_mech = |Y| - |xi| - eps_i |xi|,   eps_i = alpha (theta_i - theta_ref)        (2.80, erratum E9)
// with theta_i the temperature of the bond's owner node i, as the source's code, or with bond_mean the
// mean of the bond's two ends, eps_ij = (eps_i + eps_j)/2 (a bond between a hot and a cold node then has
// one rest length seen from both ends; LPS and PALS); alpha is the linear
// coefficient (erratum E6: ~1e-5 1/K). Both the dilatation and the forces use e_mech, so a body free
// to expand by eps in every direction (y = (1 + eps) x) carries no force, and a body held at y = x is
// under the hydrostatic stress -3 K eps (spec/000a V7).
// A model holds one ThermalExpansion, set by set_thermal_expansion and read by thermal_expansion()
// (inactive by default: every result is then exactly the isothermal one, at no cost). The temperatures
// are the caller's (a TemperatureField's theta, a driver's vector), read at each force evaluation; they
// must outlive the model's use. 2D plane strain is refused: its free in-plane strain is (1 + nu) alpha
// dtheta (eps_zz = 0), a factor not written yet; 1D, 2D plane stress and 3D take alpha dtheta.
// Damage: the critical-stretch rule compares the mechanical stretch when given the same
// ThermalExpansion (damage/critical_stretch.hpp); the micropotential rule, given it by its
// set_thermal_expansion, takes the work along the mechanical displacement only (the thermal bond
// displacement alpha dtheta xi of each step subtracted, spec/000c sec. 2.3; damage/micropotential.hpp).
// Wrappers with their own deviatoric extension (viscoelastic LPS, plastic LPS and PALS) take it from the
// wrapped model's expansion; the lateral images of bc/lateral_images.hpp refuse an active one.
// Models with thermal expansion: PMB (whose pair force takes the mean of the two ends' eps, which is
// what the owner-node rule gives for a bond-based model: each end's half of the pair force uses its own
// node), LPS (with or without SCF: eps_i enters only per node, see lps.hpp), correspondence (the small
// strain less eps_i I, or the Flanagan-Taylor increment of eq. 2.81, see correspondence.hpp), its J2
// plasticity (plastic_correspondence.hpp), its viscoelastic wrapper (viscoelastic_correspondence.hpp: the
// Flanagan-Taylor increment, the branch sees only the deviator), PALS (per node, see pals.hpp) and the
// viscoelastic LPS and plastic LPS and PALS wrappers (their deviatoric extension).
#pragma once
#include "pd/simd/chunk_vector.hpp"

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace pd {

struct ThermalExpansion {
    double alpha = 0;                            // linear thermal expansion coefficient [1/K]
    double theta_ref = 0;                        // temperature of the stress-free reference state [K or C]
    const std::vector<double>* theta = nullptr;  // node temperatures [as theta_ref]; null: no thermal strain
    bool bond_mean = false;                      // bond i -> j takes (eps_i + eps_j)/2, not the owner's eps_i (header)

    bool active() const { return theta != nullptr; }
    // eps_i = alpha (theta_i - theta_ref) [-]; 0 when inactive.
    double strain(std::size_t i) const { return theta ? alpha * ((*theta)[i] - theta_ref) : 0.0; }
    // (eps_i + eps_j)/2, the mean of a pair's two ends (PMB's pair force, the critical stretch) [-].
    double pair_strain(std::size_t i, std::size_t j) const
    {
        return theta ? 0.5 * alpha * (((*theta)[i] - theta_ref) + ((*theta)[j] - theta_ref)) : 0.0;
    }
    // The free thermal strain of bond i -> j by the rule above: eps_i, or (eps_i + eps_j)/2 with bond_mean [-].
    double bond_strain(std::size_t i, std::size_t j) const { return bond_mean ? pair_strain(i, j) : strain(i); }
    // pair_strain for a bond formula written once for both paths of the bond loop (node_value,
    // simd/chunk_vector.hpp): the thermal kernels' (eps_i + eps_j)/2 of one node or of a chunk's lanes.
    struct PairStrain {
        const double* theta;      // node temperatures
        double half_alpha, theta_ref;  // alpha / 2 [1/K], reference temperature
        template <class V>
        V at(std::size_t i, int j) const
        {
            return half_alpha * ((node_value<V>(theta, i) - theta_ref) + (node_value<V>(theta, static_cast<std::size_t>(j)) - theta_ref));
        }
    };
    PairStrain pair_strains() const { return {theta->data(), 0.5 * alpha, theta_ref}; }  // active only
    // Throws std::invalid_argument naming what is wrong (a model calls it when attached).
    void validate(std::size_t nodes, bool plane_strain_2d = false) const
    {
        if (theta && plane_strain_2d)
            throw std::invalid_argument("thermal expansion: 2D plane strain is not written (its free strain is (1 + nu) alpha dtheta)");
        if (!std::isfinite(alpha)) throw std::invalid_argument("thermal expansion: alpha must be finite");
        if (!std::isfinite(theta_ref)) throw std::invalid_argument("thermal expansion: theta_ref must be finite");
        if (theta && nodes > 0 && theta->size() != nodes)
            throw std::invalid_argument("thermal expansion: " + std::to_string(theta->size()) + " temperatures for " +
                                        std::to_string(nodes) + " nodes");
    }
};

}  // namespace pd
