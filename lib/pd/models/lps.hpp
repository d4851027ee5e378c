// LPS, linear peridynamic solid (Silling et al. 2007; spec/000b sec. 1.2, spec/002 sec. 2.2),
// written once for D = 1, 2, 3 with the dimension-D bulk modulus kappa_D (material.hpp):
//   weighted volume  m_i = sum_j omega |xi|^2 V_j                                   (4.8)
//   dilatation       theta_i = (D/m_i) sum_j omega |xi| e V_j,  e = |Y| - |xi|      (4.8)
//   deviatoric ext.  e_d = e - theta_i |xi| / D                                     (4.9)
//   energy           W_i = kappa_D theta_i^2 / 2 + (alpha_i/2) sum_j omega e_d^2 V_j  (4.10)
//   force state      t_i = D kappa_D theta_i omega |xi| / m_i + alpha_i omega e_d   (4.11)
//   shear constant   alpha_i = a_D G / m_i, a_3 = 15 (4.13), a_2 = 8, a_1 = 0.
// 3D is the source's model. 1D is V1's bar (t = omega E theta |xi| / m). 2D uses the in-plane
// split e_d = e - theta |xi|/2 with kappa_2D = K + G/3 (plane strain) or 9KG/(3K+4G) (plane
// stress): an isotropic stretch s gives W = 2 kappa_2D s^2 and a pure shear eps = diag(a, -a)
// gives W = 2 G a^2, the classical in-plane energies (tests/test_model_constants.cpp checks both).
// Pair force on i: (t_i<xi> + t_j<-xi>) V_j Y/|Y|; theta_i and the forces sum only intact bonds.
// Damage rule (Params::weighted_volume; tests/test_damage_models.cpp):
//   intact (default): m_i (and SCF_i when it was computed from positions) sums the intact bonds;
//     recompute(bonds) refreshes them after bonds break (a scene calls it, scene.hpp). The
//     damaged body is then exactly the body built without the broken bonds, and the force is the
//     gradient of the reported W (variational), as for PALS (recomputed multipliers) and
//     correspondence (K over intact bonds).
//   reference (Peridigm): m_i and SCF_i stay those of the undamaged family, recompute is a no-op.
//     Then sum_intact omega e_d |xi| V != 0 and the force is no longer the exact gradient of the
//     reported W (a few % with ~20 % of bonds broken): energy totals of damaged runs are
//     approximate beyond the energy released by the broken bonds (non-variational).
// Cost of `intact`: a node left with few bonds has a small m_i and a stiffer response, so the
// critical time step can fall after damage. Largest stiffness eigenvalue of a 7x6x5 block with
// 20 / 50 / 80 % of the pairs broken at random, over the undamaged one: 1.03 / 1.11 / 2.50
// (dt_crit -1 / -5 / -37 %); `reference`: 0.82 / 0.54 / 0.29 (tests/test_damage_models.cpp).
// Optional shear correction (spec/000b sec. 1.3, eq. 4.14): apply_shear_correction sets
// alpha_i = SCF_i a_D G / m_i with SCF_i from models/scf.hpp (Peridigm's probe); W and the force
// both use alpha_i, so the force stays the gradient of W. Without it (the default) every member
// and result is exactly as before; with SCF_i = 1 the forces are bit-identical to no correction.
// Thermal expansion (models/thermal_expansion.hpp, set_thermal_expansion; owner node i's eps_i in bond
// i -> j, as the source): e_mech = e - eps_i |xi| in (4.8)-(4.11). It enters per node only:
//   theta_i = (D/m_i) (sum_j omega |xi| e V_j - eps_i M_i),  M_i = sum_j omega |xi|^2 V_j over the
//   intact bonds with the weights of the dilatation (= m_i unless bonds broke under the reference
//   rule or scale_bonds changed the weights);
//   t_i = omega (|xi| (p_i theta_i - alpha_i theta_i / D - alpha_i eps_i) + alpha_i e),
// so the kernel and the chunks serve it unchanged (a_coef_i takes - alpha_i eps_i).
// With ThermalExpansion::bond_mean the bond's free strain is eps_ij = (eps_i + eps_j)/2 instead:
//   theta_i = (D/m_i) (sum_j omega |xi| e V_j - C_i),  C_i = sum_j omega |xi|^2 eps_ij V_j (intact bonds),
//   t_i + t_j = |xi| (a_i + a_j) + (alpha_i + alpha_j) (e - eps_ij |xi|),  a_i = (p_i - alpha_i / D) theta_i,
// C_i summed in each point pass and eps_ij gathered per bond by MeanThermalKernel (per node and chunks).
// Cost (reports/3d/model_cost.md): internal_force uses Kernel (with_kernel), which reads
// a_j = (p_j - alpha_j / D) theta_j and alpha_j precombined by point_pass instead of p_j, theta_j,
// alpha_j, with no division by D per bond; bond_scalar still
// reads theta, p_coef and alpha, for callers that edit them between the passes. Nodes with
// translated families (translated_families.hpp: same |xi| and omega V_j bond by bond) take both passes
// W nodes at a time in undamaged scenes (stretch_sums, Kernel::bond_scalar in detail::vchunk): about 1.5x PMB.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/core/field.hpp"
#include "pd/core/material.hpp"
#include "pd/models/scf.hpp"
#include "pd/models/thermal_expansion.hpp"
#include "pd/core/parallel.hpp"
#include "pd/simd/translated_families.hpp"

#include <array>
#include <functional>
#include <stdexcept>
#include <vector>

namespace pd {

struct LPS {
    static constexpr bool has_point_pass = true;
    struct Params {
        Elastic material;
        int dim = 3;
        Plane plane = Plane::strain;   // 2D reduction
        enum class WeightedVolume { intact, reference };  // m_i after damage (see header)
        WeightedVolume weighted_volume = WeightedVolume::intact;
    };
    int dim = 3;
    double kappa = 0;              // kappa_D [Pa]
    double G = 0;                  // shear modulus [Pa]
    std::vector<double> m;         // weighted volume m_i [m^5 in 3D]
    std::vector<double> p_coef;    // D kappa / m_i [Pa/m^5]
    std::vector<double> alpha;     // a_D G / m_i, times SCF_i when corrected [Pa/m^5]
    std::vector<double> theta;     // dilatation, updated by point_pass [-]
    std::vector<double> a_coef;    // (p_coef - alpha / D) theta per node, updated by point_pass [Pa/m^5]
    std::vector<double> wV;        // omega V_j per bond (influence times partner volume) [m^3]
    const Bonds* bonds = nullptr;
    std::vector<double> scf;       // shear correction factor SCF_i [-]; empty when not applied
    Params::WeightedVolume weighted_volume = Params::WeightedVolume::intact;
    // SCF from positions, re-evaluated by recompute (intact rule); empty for given factors.
    std::function<std::vector<double>(const Bonds&)> scf_source;
    TranslatedRuns runs;              // chunks of translated families (translated_families.hpp)

    LPS() = default;
    LPS(const Params& p, const Bonds& b)
        : dim(p.dim), kappa(kappa_dim(p.material, p.dim, p.plane)), G(p.material.G),
          m(b.nodes(), 0.0), p_coef(b.nodes()), alpha(b.nodes()), theta(b.nodes(), 0.0), a_coef(b.nodes(), 0.0), wV(b.size()),
          bonds(&b),
          weighted_volume(p.weighted_volume), plane_strain_2d_(p.dim == 2 && p.plane == Plane::strain)
    {
        for (std::size_t k = 0; k < b.size(); ++k) wV[k] = b.omega[k] * b.volume[k];
        weighted_volumes(b);
#ifdef PD_CHUNK_WIDTH
        runs = find_translated_runs(b, detail::chunk_width, {&b.length, &wV});
#endif
    }

    // omega V_j of bond k times factor[k] (surface correction, models/surface_correction.hpp), in
    // the dilatation, the force and the energy; m_i, p_coef and alpha are kept. factor must be
    // symmetric (factor[k] == factor[reverse[k]]) for the pair forces to balance. With m_i kept,
    // sum_j G omega e_d |xi| V != 0, so, as with WeightedVolume::reference, the force is not the
    // exact gradient of the reported W (recomputing m_i with the scaled weights would keep it
    // variational, but cancels most of the correction: bar_stiffness.md).
    void scale_bonds(const std::vector<double>& factor)
    {
        if (factor.size() != wV.size()) throw std::invalid_argument("LPS::scale_bonds: one factor per bond expected");
        for (std::size_t k = 0; k < wV.size(); ++k) wV[k] *= factor[k];
#ifdef PD_CHUNK_WIDTH
        runs = find_translated_runs(*bonds, detail::chunk_width, {&bonds->length, &wV});
#endif
        thermal_moments(*bonds);
    }

    // Thermal expansion (header): the temperatures are read at each point pass.
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        t.validate(m.size(), plane_strain_2d_);
        thermal = t;
        thermal_moments(*bonds);
    }
    const ThermalExpansion& thermal_expansion() const { return thermal; }

    // After bonds broke: with the intact rule, m_i over the intact bonds (4.8), p_coef, alpha and
    // a position-based SCF_i rebuilt; with the reference rule nothing changes (see header).
    void recompute(const Bonds& b)
    {
        bonds = &b;
        thermal_moments(b);
        if (weighted_volume == Params::WeightedVolume::reference) return;
        weighted_volumes(b);
        if (scf_source) scf = scf_source(b);
        if (!scf.empty()) apply_factors(scf);
    }

    // alpha_i = SCF_i a_D G / m_i (4.14), one factor per node [-]. Replaces any earlier correction
    // (alpha is rebuilt from m_i, not rescaled), so calling it twice does not compound.
    void apply_shear_correction(const std::vector<double>& factor)
    {
        if (factor.size() != m.size()) throw std::invalid_argument("LPS::apply_shear_correction: one factor per node expected");
        for (double s : factor)
            if (!(s > 0)) throw std::invalid_argument("LPS::apply_shear_correction: SCF must be > 0");
        apply_factors(factor);
        scf = factor;
        scf_source = nullptr;
    }
    // The same with Peridigm's SCF computed from the reference positions x [m] (models/scf.hpp),
    // with m_i of this model's rule; a copy of x is kept for recompute.
    template <int D>
    void apply_shear_correction(const Field<D>& x)
    {
        const bool intact_m = weighted_volume == Params::WeightedVolume::intact;
        auto source = [x, d = dim, intact_m](const Bonds& b) { return shear_correction_factor(b, x, d, scf_gamma, intact_m); };
        apply_shear_correction(source(*bonds));
        scf_source = source;
    }

    // theta_i = (D/m_i) sum_j omega |xi| e V_j over intact bonds (stretch_sums, bond_loop.hpp).
    template <int D>
    void point_pass(const Bonds& b, const Field<D>& y)
    {
        const double* len = b.length.data();
        const double* wv = wV.data();
        stretch_sums<1>(b, y, runs, [&](std::int64_t k, const auto& ylen) { return wv[k] * len[k] * (ylen - len[k]); }, Unweighted{},
                        [&](std::size_t i, const std::array<double, 1>& S) { set_dilatation(b, i, D * S[0]); });
    }

    // (t_i + t_j) V_j / |Y|: force on i is this times Y, with t = omega (D kappa theta |xi| / m
    // + alpha e_d) (4.11) regrouped as omega (|xi| (p theta - alpha theta / D) + alpha e).
    // Reads theta, p_coef and alpha as they are; the bond loop uses kernel() instead (same value
    // up to round-off).
    double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const
    {
        const double L = bonds->length[k];
        const double e = ylen - L;
        const double dev = (alpha[i] * theta[i] + alpha[j] * theta[j]) / dim;
        const double th = !thermal.active() ? 0.0
                          : thermal.bond_mean ? (alpha[i] + alpha[j]) * thermal.pair_strain(i, static_cast<std::size_t>(j))
                                              : alpha[i] * thermal.strain(i) + alpha[j] * thermal.strain(j);
        const double tij = L * (p_coef[i] * theta[i] + p_coef[j] * theta[j] - dev - th) + (alpha[i] + alpha[j]) * e;
        return tij * wV[k] / ylen;
    }

    // Bond kernel of the bond loop (bond_loop.hpp, with_kernel): the same t_i + t_j as
    // bond_scalar with the node terms precombined by point_pass, a = (p - alpha / D) theta:
    //   t_i + t_j = |xi| (a_i + a_j) + (alpha_i + alpha_j) e.
    // Per bond it gathers a_j and alpha_j (not p_j, theta_j, alpha_j) and has no division by D.
    struct Kernel {
        const double* length;  // |xi| per bond [m]
        const double* wV;      // omega V_j per bond [m^3]
        const double* a;       // a_coef per node [Pa/m^5]
        const double* alpha;   // alpha per node [Pa/m^5]
        const TranslatedRuns* runs;
        // T = double, or the lanes of a chunk (detail::vchunk; bond_loop.hpp).
        template <class T>
        T bond_scalar(std::size_t i, std::int64_t k, int j, const T& ylen) const
        {
            const double L = length[k];
            const T tij = L * (node_value<T>(a, i) + node_value<T>(a, j)) + (node_value<T>(alpha, i) + node_value<T>(alpha, j)) * (ylen - L);
            return tij * wV[k] / ylen;
        }
        const TranslatedRuns* chunks(const Bonds& b) const { return runs->fits(b) && !runs->chunk_start.empty() ? runs : nullptr; }
    };
    // Kernel with the bond-mean thermal strain (header): e less eps_ij |xi| (ThermalExpansion::PairStrain).
    struct MeanThermalKernel : Kernel {
        ThermalExpansion::PairStrain pair;
        template <class V>
        V bond_scalar(std::size_t i, std::int64_t k, int j, const V& ylen) const
        {
            const double L = length[k];
            const V eps = pair.at<V>(i, j);
            const V tij = L * (node_value<V>(a, i) + node_value<V>(a, j)) + (node_value<V>(alpha, i) + node_value<V>(alpha, j)) * (ylen - L * (1 + eps));
            return tij * wV[k] / ylen;
        }
    };
    // Valid after point_pass (a_coef of the current y, alpha of the current correction).
    Kernel kernel() const { return {bonds->length.data(), wV.data(), a_coef.data(), alpha.data(), &runs}; }
    template <class Pass>
    void with_kernel(Pass&& pass) const
    {
        if (thermal.active() && thermal.bond_mean) pass(MeanThermalKernel{kernel(), thermal.pair_strains()});
        else pass(kernel());
    }

    // W_i (4.10) [J/m^3]; call after point_pass at the same y.
    template <int D>
    std::vector<double> energy_density(const Bonds& b, const Field<D>& y) const
    {
        auto bond = [&](std::size_t i, std::int64_t k) {
            const double L = b.length[k];
            const double ed = norm(y[b.partner[k]] - y[i]) - L * (1 + thermal.bond_strain(i, b.partner[k])) - theta[i] * L / dim;
            return wV[k] * ed * ed;
        };
        return node_sums(b, bond, [&](std::size_t i, double dev) { return 0.5 * kappa * theta[i] * theta[i] + 0.5 * alpha[i] * dev; });
    }

private:
    bool plane_strain_2d_ = false;
    ThermalExpansion thermal;             // header; inactive by default (set_thermal_expansion)
    std::vector<double> thermal_moment;   // M_i of the header, while thermal expansion is active [m^5 in 3D]

    // m_i (4.8) over the whole family, or over the intact bonds under the intact rule; then
    // p_coef = D kappa / m_i and alpha = a_D G / m_i (no SCF).
    void weighted_volumes(const Bonds& b)
    {
        const bool skip_broken = b.has_damage() && weighted_volume == Params::WeightedVolume::intact;
        const double a_D = detail::scf_shear_constant(dim);
        for (std::size_t i = 0; i < b.nodes(); ++i) {
            m[i] = 0;
            for_family(b, i, [&](std::int64_t k, int) {
                if (!skip_broken || b.intact[k]) m[i] += b.omega[k] * b.length[k] * b.length[k] * b.volume[k];
            });
            const double inv_m = m[i] > 0 ? 1.0 / m[i] : 0.0;  // isolated node: no force
            p_coef[i] = dim * kappa * inv_m;
            alpha[i] = a_D * G * inv_m;
        }
    }
    // alpha_i = SCF_i a_D G / m_i (4.14).
    void apply_factors(const std::vector<double>& factor)
    {
        const double a_D = detail::scf_shear_constant(dim);
        for (std::size_t i = 0; i < m.size(); ++i) {
            const double inv_m = m[i] > 0 ? 1.0 / m[i] : 0.0;
            alpha[i] = a_D * G * inv_m * factor[i];  // same product as the constructor, times SCF_i
        }
    }

    // theta_i = sum / m_i, sum = D sum_j omega |xi| e V_j less D eps_i M_i (thermal; bond mean: less D C_i,
    // header), and a_coef_i.
    void set_dilatation(const Bonds& b, std::size_t i, double sum)
    {
        if (thermal.active() && thermal.bond_mean) {
            double C = 0;  // C_i (header)
            for_intact_bonds(b, i, [&](std::int64_t k, int j) {
                C += wV[k] * b.length[k] * b.length[k] * thermal.pair_strain(i, static_cast<std::size_t>(j));
            });
            theta[i] = m[i] > 0 ? (sum - dim * C) / m[i] : 0.0;
            a_coef[i] = (p_coef[i] - alpha[i] / dim) * theta[i];
            return;
        }
        const double eps = thermal.strain(i);
        const double th = m[i] > 0 ? (eps != 0 ? sum - dim * eps * thermal_moment[i] : sum) / m[i] : 0.0;
        theta[i] = th;
        a_coef[i] = (p_coef[i] - alpha[i] / dim) * th - (eps != 0 ? alpha[i] * eps : 0.0);
    }
    // M_i (header) over the intact bonds with the current weights; none while thermal expansion is off
    // or takes the bond mean.
    void thermal_moments(const Bonds& b)
    {
        if (!thermal.active() || thermal.bond_mean) return thermal_moment.clear();
        thermal_moment = node_sums(b, [&](std::size_t, std::int64_t k) { return wV[k] * b.length[k] * b.length[k]; },
                                   [](std::size_t, double sum) { return sum; });
    }
};

}  // namespace pd
