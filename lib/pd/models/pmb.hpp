// PMB, prototype microelastic brittle (Silling & Askari 2005; spec/000b sec. 1.1, spec/002 sec. 2.3).
//   stretch s = (|Y| - |xi|)/|xi|;  pair force density f = c omega s V_j Y/|Y|  (both ends).
//   micropotential w = c omega s^2 |xi| / 2;  W_i = 1/2 sum_j w V_j  (eq. 2.14 of spec/002).
// Micromodulus by energy matching under isotropic stretch, W = (D^2/2) kappa_D s^2:
//   c = 2 D^2 kappa_D / M1,  M1 = integral over the horizon of omega |xi| dV.
// With omega = 1: 3D 18K/(pi delta^4); 2D 12 kappa/(pi delta^3 t) (plane stress, nu = 1/3:
// 9E/(pi delta^3 t)); 1D 2E/(A delta^2). Calibration `lattice` replaces the continuum M1 by the
// sum over a full lattice family (influence.hpp), so an interior node of a simple cubic lattice
// reproduces W = (D^2/2) kappa_D s^2 exactly; `continuum` (default) is the published constant.
// Damage: a broken bond carries no force (bond_loop.hpp) and PMB has no per-node constant, so a
// damaged body is exactly the body built without the broken bonds (tests/test_damage_models.cpp).
// Thermal expansion (models/thermal_expansion.hpp, set_thermal_expansion): s = (|Y| - |xi| (1 + eps_ij))/|xi|
// with eps_ij = (eps_i + eps_j)/2, the mean of the two ends' free thermal strains (each end's half of
// the pair force with its owner node's eps, spec/000a eq. 2.80); the bond pass then takes
// ThermalKernel, which also gathers theta_j.
// Cost: nodes with translated families (translated_families.hpp: same |xi| and coef bond by bond) take
// the chunk path of the bond loop, W nodes at a time (bond_scalar in detail::vchunk). Change coef only through
// scale_bonds, which finds the runs again.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/core/field.hpp"
#include "pd/core/material.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/thermal_expansion.hpp"
#include "pd/simd/translated_families.hpp"

#include <stdexcept>
#include <vector>

namespace pd {

// c [N/m^6 in 3D] for a dimension-D bulk modulus kappa_D [Pa] and horizon moment M1 [m^4].
inline double pmb_micromodulus(double kappa_D, int dim, double M1) { return 2.0 * dim * dim * kappa_D / M1; }

struct PMB {
    static constexpr bool has_point_pass = false;
    struct Params {
        Elastic material;              // only kappa_D enters (PMB fixes nu)
        int dim = 3;
        Plane plane = Plane::stress;   // 2D reduction
        double measure = 1;            // 2D thickness [m] / 1D area [m^2]
        enum class Calibration { continuum, lattice } calibration = Calibration::continuum;
        double dx = 0;                 // lattice spacing for Calibration::lattice [m]
    };
    static double micromodulus(const Params& p, const Influence& w, double delta)
    {
        const double M1 = p.calibration == Params::Calibration::lattice
                              ? lattice_moment(w, 1, delta, p.dx, p.dim, p.measure)
                              : horizon_moment(w, 1, delta, p.dim, p.measure);
        return pmb_micromodulus(kappa_dim(p.material, p.dim, p.plane), p.dim, M1);
    }
    double c = 0;                  // micromodulus (see header) [N/m^6 in 3D]
    std::vector<double> coef;      // c omega beta V_j / |xi| per bond [N/m^4 in 3D]
    const double* length = nullptr;  // |xi| of the bonds the model was built on [m]

    PMB() = default;
    PMB(const Params& p, const Bonds& bonds)
        : c(micromodulus(p, bonds.influence, bonds.delta)),
          coef(bonds.size()), length(bonds.length.data()), plane_strain_2d_(p.dim == 2 && p.plane == Plane::strain)
    {
        for (std::size_t k = 0; k < bonds.size(); ++k) coef[k] = c * bonds.omega[k] * bonds.volume[k] / bonds.length[k];
        find_runs(bonds);
    }

    // Bond-wise micromodulus c_ij = factor[k] c (surface correction, models/surface_correction.hpp);
    // factor has one entry per bond (bonds.size()). Not calling it leaves the model unchanged.
    void scale_bonds(const std::vector<double>& factor)
    {
        if (factor.size() != coef.size()) throw std::invalid_argument("PMB::scale_bonds: one factor per bond expected");
        for (std::size_t k = 0; k < coef.size(); ++k) coef[k] *= factor[k];
        if (bonds_ && bonds_->size() == coef.size()) find_runs(*bonds_);
        else runs = {};  // bonds unknown: no chunks rather than stale ones
    }

    // c omega V s / |Y| with s = (|Y| - |xi|)/|xi|: force on i is this times Y. T = double, or the lanes
    // of a chunk (detail::vchunk; bond_loop.hpp).
    template <class T>
    T bond_scalar(std::size_t, std::int64_t k, int, const T& ylen) const
    {
        return coef[k] * (ylen - length[k]) / ylen;
    }

    // Thermal expansion (header); inactive by default.
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        t.validate(bonds_ ? bonds_->nodes() : 0, plane_strain_2d_);
        thermal = t;
    }
    const ThermalExpansion& thermal_expansion() const { return thermal; }
    // Free thermal strain of bond k (i -> j): (eps_i + eps_j)/2 [-].
    double bond_thermal_strain(std::size_t i, int j) const { return thermal.pair_strain(i, static_cast<std::size_t>(j)); }

    // Bond kernel with thermal expansion (header): bond_scalar with |xi| (1 + eps_ij) for |xi| in e.
    struct ThermalKernel {
        const PMB* pmb;
        ThermalExpansion::PairStrain eps;
        template <class T>
        T bond_scalar(std::size_t i, std::int64_t k, int j, const T& ylen) const
        {
            const T rest = pmb->length[k] * (1 + eps.at<T>(i, j));
            return pmb->coef[k] * (ylen - rest) / ylen;
        }
        const TranslatedRuns* chunks(const Bonds& b) const { return pmb->chunks(b); }
    };
    // The bond pass's kernel: this model, or ThermalKernel when thermal expansion is active.
    template <class Pass>
    void with_kernel(Pass&& pass) const
    {
        if (thermal.active()) pass(ThermalKernel{this, thermal.pair_strains()});
        else pass(*this);
    }

    // Chunk hook of the bond loop (bond_loop.hpp): the runs whose W nodes take bond_scalar at once.
    TranslatedRuns runs;
    const TranslatedRuns* chunks(const Bonds& b) const { return runs.fits(b) && !runs.chunk_start.empty() ? &runs : nullptr; }

    // Strain energy density W_i = 1/4 sum_j c omega s^2 |xi| V_j [J/m^3] (intact bonds; s mechanical).
    template <int D>
    std::vector<double> energy_density(const Bonds& bonds, const Field<D>& y) const
    {
        auto bond = [&](std::size_t i, std::int64_t k) {
            const double L = bonds.length[k];
            const double s = (norm(y[bonds.partner[k]] - y[i]) - L * (1 + bond_thermal_strain(i, bonds.partner[k]))) / L;
            return 0.25 * coef[k] * L * L * s * s;
        };
        return node_sums(bonds, bond, [](std::size_t, double sum) { return sum; });
    }

private:
    const Bonds* bonds_ = nullptr;  // the bonds the model was built on (as `length`)
    bool plane_strain_2d_ = false;
    ThermalExpansion thermal;
    void find_runs(const Bonds& b)
    {
        bonds_ = &b;
#ifdef PD_CHUNK_WIDTH
        runs = find_translated_runs(b, detail::chunk_width, {&b.length, &coef});
#endif
    }
};

}  // namespace pd
