// PALS, position-aware linear solid (Mitchell et al. 2015; spec/000b sec. 1.4), 3D, ordinary.
//   energy        W_i = K theta_i^2 / 2 + G (sigma_i e_d)•e_d                        (4.15)
//   dilatation    theta_i = (omega_i x)•e,  e = |Y| - |xi|,  e_d = e - theta_i |xi| / 3
//   force state   t_i = (K theta_i - (2G/3)(sigma_i x)•e_d) omega_i x + 2G sigma_i e_d  (4.21)
// Each node has its own dilatational influence state omega_i and deviatoric sigma_i, closest
// (least squares) to normalised base functions omega0, sigma0 such that the six matching
// deformations H_j (e1e1, e2e2, e3e3, and the xy, xz, yz unit shears) are reproduced exactly:
//   omega_i<xi> = omega0 + l1 a^2 + l2 b^2 + l3 c^2 + 2 (l4 ab + l5 ac + l6 bc),  xi = (a, b, c)
//     with (omega_i x)•(xi.H_j xi / |xi|) = tr H_j                                    (4.18)-(4.20)
//   sigma_i<xi> = sigma0 + sum_j tau_j eps_j^2,  eps_j = xi.dev(H_j) xi / |xi|
//     with (sigma_i eps_j)•eps_j = dev H_j : dev H_j = [2/3, 2/3, 2/3, 2, 2, 2]
// (two 6x6 systems per node, the Peridigm `pals.cxx` construction of spec/000b sec. 1.4 [CODE],
// including its degenerate-row rule, here applied to both systems: a diagonal entry < 1e-15
// trace gets its row and column zeroed, diagonal 1, rhs 0; a system still singular gets zero
// multipliers, i.e. omega = omega0 or sigma = sigma0 at that node).
// Consequences: (omega_i x)•x = 3 and theta = 3s under isotropic expansion at EVERY node.
// Dimensional consistency (spec/000b sec. 1.4 [RECON], the cause of the unit-system dependence
// of thesis Tables 4.2-4.3): Peridigm uses omega0 = sigma0 = 1 in whatever length unit the
// input has. Here the base functions are normalised on the full sphere,
//   omega0 = 3 w0 / M2(w0),  sigma0 = (15/2) s0 / M2(s0),  M2(w) = int_sphere w |xi|^2 dV,
// so (omega0 x)•x = 3 and (sigma0 eps)•eps = dev H : dev H on a full sphere (constant w:
// omega0 = 15 / (4 pi delta^5), sigma0 = 75 / (8 pi delta^5), i.e. LPS's 3/m and 15/(2m)),
// (PALS::Base::unit instead: omega0 = sigma0 = 1 in the unit system of the input, Peridigm's
// default with its normalisation off; the result then depends on the length unit),
// and the systems are solved in units of delta (xi/delta, V/delta^3, multipliers times
// delta^5): the same specimen in SI, mm or cm gives the same multipliers and modulus.
// Pair force on i: (t_i<xi> + t_j<-xi>) V_j Y/|Y| (omega and sigma are even in xi), through
// bond_scalar with t regrouped as in Peridigm: t = p_i omega_i |xi| + 2G sigma_i (e - theta_i
// |xi|/3), p_i = (K + 2G m_sigma/9) theta_i - (2G/3)(sigma_i x)•e, m_sigma = (sigma_i x)•x.
// Thermal expansion (models/thermal_expansion.hpp, set_thermal_expansion): e_mech = e - eps_i |xi| with
// the owner node's eps_i = alpha (theta_i - theta_ref), per node only: the mechanical dilatation is
// theta_i - eps_i m_omega_i, (sigma_i x)•e_mech = (sigma_i x)•e - eps_i m_sigma_i, and the deviatoric
// extension e_mech - theta_mech |xi|/3 = e - theta_i |xi|/3 with theta_i the total dilatation (kept in
// `theta`, which the bond kernel reads), since m_omega = 3 wherever the systems are regular; so p_i
// alone carries it and the bond kernel and chunks are unchanged.
// With ThermalExpansion::bond_mean (eps_ij = (eps_i + eps_j)/2 per bond) `theta` holds the mechanical
// dilatation theta_i - C^w_i, p_i takes (sigma_i x)•e - C^s_i, C^w_i = sum_j w_ik |xi|^2 eps_ij and
// C^s_i = sum_j s_ik |xi|^2 eps_ij over the intact bonds, and MeanThermalKernel uses e - eps_ij |xi| in
// the bond force: e_d = e - eps_ij |xi| - theta_i |xi| / 3 from both ends.
// Multipliers use the intact bonds; after damage call recompute(bonds) (a scene, scene.hpp, does it whenever
// bonds break): the damaged body is then the body built without the broken bonds
// (tests/test_damage_models.cpp). Before recompute the multipliers are those of the old families.
// Cost: nodes with translated families (translated_families.hpp: same |xi|, w_i, w_j, s_i, s_j bond by
// bond, found by recompute) take both passes W nodes at a time in undamaged scenes.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/core/field.hpp"
#include "pd/core/influence.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/material.hpp"
#include "pd/core/parallel.hpp"
#include "pd/models/thermal_expansion.hpp"
#include "pd/simd/translated_families.hpp"

#include <array>
#include <vector>

namespace pd {

struct PALS {
    static constexpr bool has_point_pass = true;
    enum class Base { normalised, unit };  // scale of the base functions (header)
    struct Params {
        Elastic material;
        Influence omega0{};  // dilatational base function (shape only; normalised, see header)
        Influence sigma0{};  // deviatoric base function (shape only; normalised, see header)
        Base base = Base::normalised;
    };
    using Multipliers = std::array<double, 6>;  // dimensionless (times delta^5)

    double K = 0;                       // bulk modulus [Pa]
    double G = 0;                       // shear modulus [Pa]
    double delta = 0;                   // horizon [m]
    double omega0_scale = 0;            // 3 / M2(w0) [1/m^5] (Base::unit: 1)
    double sigma0_scale = 0;            // (15/2) / M2(s0) [1/m^5] (Base::unit: 1)
    std::vector<Multipliers> lambda;    // omega multipliers per node, lambda * delta^5 [-]
    std::vector<Multipliers> tau;       // sigma multipliers per node, tau * delta^5 [-]
    std::vector<double> m_sigma;        // (sigma_i x)•x per node [-]
    std::vector<double> m_omega;        // (omega_i x)•x per node [-] (3 where the system is regular)
    std::vector<double> theta;          // dilatation (thermal strain included; bond_mean: mechanical, header), by point_pass [-]
    std::vector<double> p;              // PALS pressure p_i, updated by point_pass [Pa]
    std::vector<double> w_i, w_j;       // omega_i<xi> V_j and omega_j<xi> V_j per bond i->j [1/m^2]
    std::vector<double> s_i, s_j;       // 2G sigma_i<xi> V_j and 2G sigma_j<xi> V_j per bond [Pa/m^2]
    TranslatedRuns runs;                   // chunks of translated families (set by recompute)
    int singular_nodes = 0;             // nodes with a singular system (see header), after recompute
    const Bonds* bonds = nullptr;
    const Field<3>* x = nullptr;        // reference positions of the body [m] (kept for recompute)
    Influence omega0_base{}, sigma0_base{};  // shapes of omega0, sigma0 (Params)

    PALS() = default;
    // body and bonds must outlive the model (recompute reads both).
    PALS(const Params& prm, const Body<3>& body, const Bonds& b);

    // Solve the two 6x6 systems of every node over the intact bonds of `b` and refresh the
    // per-bond influence values (after damage, or after a change of partial volumes).
    void recompute(const Bonds& b);

    // Thermal expansion (header); ThermalExpansion{} switches it off. Throws std::invalid_argument for a
    // temperature vector of another length.
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        t.validate(theta.size());
        thermal = t;
    }
    const ThermalExpansion& thermal_expansion() const { return thermal; }

    // Influence states of node i at bond vector xi [1/m^5] (from the stored multipliers).
    double omega(std::size_t i, const Vec<3>& xi) const;
    double sigma(std::size_t i, const Vec<3>& xi) const;

    // theta_i = (omega_i x)•e and p_i over intact bonds (stretch_sums, bond_loop.hpp), x e = |xi| (|Y| - |xi|).
    template <int D>
    void point_pass(const Bonds& b, const Field<D>& y)
    {
        static_assert(D == 3, "PALS is a 3D model");
        const double* len = length;
        const double* wi = w_i.data();
        const double* si = s_i.data();
        stretch_sums<2>(b, y, runs, [&](std::int64_t k, const auto& ylen) { return len[k] * (ylen - len[k]); },
                        [&](std::int64_t k) { return std::array<double, 2>{wi[k], si[k]}; },
                        [&](std::size_t i, const std::array<double, 2>& S) { set_dilatation(b, i, S[0], S[1]); });
    }

    // (t_i<xi> + t_j<-xi>) V_j / |Y|: force on i is this times Y, with
    // t_i + t_j = |xi| (p_i w_i + p_j w_j - (theta_i s_i + theta_j s_j)/3) + e (s_i + s_j).
    // Without the bond-mean thermal term (header), which MeanThermalKernel adds: the bond pass
    // (with_kernel) is the caller that gets it right in both cases.
    // T = double, or the lanes of a chunk (detail::vchunk; bond_loop.hpp).
    template <class T>
    T bond_scalar(std::size_t i, std::int64_t k, int j, const T& ylen) const
    {
        const double L = length[k];
        const T e = ylen - L;
        const T tij = L * (node_value<T>(p.data(), i) * w_i[k] + node_value<T>(p.data(), j) * w_j[k]
                           - third * (node_value<T>(theta.data(), i) * s_i[k] + node_value<T>(theta.data(), j) * s_j[k]))
                      + e * (s_i[k] + s_j[k]);
        return tij / ylen;
    }
    // Chunk hook of the bond loop (bond_loop.hpp): the runs whose W nodes take bond_scalar at once.
    const TranslatedRuns* chunks(const Bonds& b) const { return runs.fits(b) && !runs.chunk_start.empty() ? &runs : nullptr; }
    // Kernel with the bond-mean thermal strain (header): bond_scalar with e less eps_ij |xi|
    // (ThermalExpansion::PairStrain).
    struct MeanThermalKernel {
        const PALS* m;
        ThermalExpansion::PairStrain pair;
        template <class V>
        V bond_scalar(std::size_t i, std::int64_t k, int j, const V& ylen) const
        {
            const double L = m->length[k];
            const V eps = pair.at<V>(i, j);
            return m->bond_scalar(i, k, j, ylen) - eps * L * (m->s_i[k] + m->s_j[k]) / ylen;
        }
        const TranslatedRuns* chunks(const Bonds& b) const { return m->chunks(b); }
    };
    // The bond pass's kernel: this model, or MeanThermalKernel with a bond-mean thermal expansion.
    template <class Pass>
    void with_kernel(Pass&& pass) const
    {
        if (thermal.active() && thermal.bond_mean) pass(MeanThermalKernel{this, thermal.pair_strains()});
        else pass(*this);
    }

    // W_i = K theta_i^2 / 2 + G (sigma_i e_d)•e_d (4.15) [J/m^3]; call after point_pass at y.
    template <int D>
    std::vector<double> energy_density(const Bonds& b, const Field<D>& y) const
    {
        static_assert(D == 3, "PALS is a 3D model");
        auto bond = [&](std::size_t i, std::int64_t k) {  // summed: 2G (sigma e_d)•e_d
            const double L = b.length[k];
            const double eps = thermal.bond_mean ? thermal.pair_strain(i, static_cast<std::size_t>(b.partner[k])) : 0.0;  // header
            const double ed = norm(y[b.partner[k]] - y[i]) - L * (1 + eps) - theta[i] * L * third;
            return s_i[k] * ed * ed;
        };
        return node_sums(b, bond, [&](std::size_t i, double dev) {
            const double th = thermal.bond_mean ? theta[i] : theta[i] - thermal.strain(i) * m_omega[i];  // the mechanical dilatation
            return 0.5 * K * th * th + 0.5 * dev;
        });
    }

private:
    static constexpr double third = 1.0 / 3.0;
    const double* length = nullptr;  // |xi| of the bonds [m]
    ThermalExpansion thermal;        // header; inactive by default

    // theta_i = (omega_i x)•e and p_i = (K + 2G m_sigma/9) theta - (2G/3)(sigma x)•e from the
    // two family sums (s_i already holds 2G sigma V), e the mechanical extension (header).
    void set_dilatation(const Bonds& b, std::size_t i, double omega_xe, double sigma_xe)
    {
        if (thermal.active() && thermal.bond_mean) {
            double Cw = 0, Cs = 0;  // C^w_i, C^s_i (header)
            for_intact_bonds(b, i, [&](std::int64_t k, int j) {
                const double e = length[k] * length[k] * thermal.pair_strain(i, static_cast<std::size_t>(j));
                Cw += w_i[k] * e, Cs += s_i[k] * e;
            });
            theta[i] = omega_xe - Cw;
            p[i] = (K + 2 * G * m_sigma[i] / 9) * theta[i] - third * (sigma_xe - Cs);
            return;
        }
        theta[i] = omega_xe;
        const double eps = thermal.strain(i);
        if (eps == 0) {
            p[i] = (K + 2 * G * m_sigma[i] / 9) * omega_xe - third * sigma_xe;
            return;
        }
        p[i] = (K + 2 * G * m_sigma[i] / 9) * (omega_xe - eps * m_omega[i]) - third * (sigma_xe - 2 * G * eps * m_sigma[i]);
    }
};

}  // namespace pd
