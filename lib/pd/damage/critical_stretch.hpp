// Critical-stretch damage (spec/000c sec. 2.2, spec/002 sec. 2.3): a bond breaks for good when its
// stretch s = (|Y| - |xi|)/|xi| exceeds s0; bonds touching a no-fail node never break. With the
// model's thermal expansion given (member thermal, models/thermal_expansion.hpp) s is the mechanical
// stretch s - (eps_i + eps_j)/2, the mean of the two ends so that a pair breaks as one (Peridigm tests
// each directed bond with its owner's eps).
// Point damage phi_i = 1 - sum_j intact V_j / sum_j V_j (spec/002 eq. 2.17).
// Critical stretch from the fracture energy Gc [J/m^2]:
//   PMB 3D        s0 = sqrt(5 Gc / (9 K delta))                      (Silling 2005; 000c eq. 8.9)
//   PMB 3D, E     s0 = sqrt(5 Gc / (6 E delta))   (nu = 1/4)          (spec/002 eq. 2.15a)
//   PMB 2D stress s0 = sqrt(4 pi Gc / (9 E delta))                   (spec/002 eq. 2.15b)
//   PMB 2D strain s0 = sqrt(5 pi Gc / (12 E delta))                  (spec/002 eq. 2.15c)
//   MO 2D  s0 = sqrt(Gc / ((6/pi) G + 16/(9 pi^2) (kappa - 2G)) / delta)  (Madenci-Oterkus; 000c eq. 8.10)
//          with kappa the in-plane bulk modulus of the plane condition (material.hpp). The thesis
//          prints the 3D K; only kappa_2D makes MO 2D reduce to PMB 2D where PMB holds
//          (nu = 1/3 plane stress, nu = 1/4 plane strain), as MO 3D reduces to PMB 3D at nu = 1/4.
//          For spec/000c V7 (Si3N4) this gives 8.062e-4 (stress) / 7.853e-4 (strain), not 7.975e-4.
//   MO 3D  s0 = sqrt(Gc / (3G + (3/4)^4 (K - 5G/3)) / delta)          (Madenci-Oterkus; 000c eq. 8.11)
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/core/material.hpp"
#include "pd/damage/singular_nodes.hpp"
#include "pd/models/thermal_expansion.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

struct BondWork;  // bond_loop.hpp

inline double s0_pmb_3d(double Gc, double K, double delta) { return std::sqrt(5 * Gc / (9 * K * delta)); }
inline double s0_pmb(double Gc, double E, double delta, int dim, Plane plane)
{
    const double pi = std::numbers::pi;
    if (dim == 3) return std::sqrt(5 * Gc / (6 * E * delta));
    if (plane == Plane::stress) return std::sqrt(4 * pi * Gc / (9 * E * delta));
    return std::sqrt(5 * pi * Gc / (12 * E * delta));
}
inline double s0_madenci_oterkus_2d(double Gc, const Elastic& m, double delta, Plane plane)
{
    const double pi = std::numbers::pi;
    const double kappa = kappa_dim(m, 2, plane);
    return std::sqrt(Gc / ((6 / pi) * m.G + 16 / (9 * pi * pi) * (kappa - 2 * m.G)) / delta);
}
inline double s0_madenci_oterkus_3d(double Gc, const Elastic& m, double delta)
{
    return std::sqrt(Gc / (3 * m.G + std::pow(0.75, 4) * (m.K - 5 * m.G / 3)) / delta);
}

struct CriticalStretch {
    double s0 = 0;                      // critical stretch [-]
    std::vector<double> s0_bond;        // per-bond critical stretch [-] (random_field.hpp), symmetric
                                        // (s0_bond[k] == s0_bond[reverse[k]]); empty = s0 everywhere
    std::vector<std::uint8_t> no_fail;  // per node, 1 = bonds never break; empty = none
    bool detach_singular = true;        // in a scene: the singular-node rule for correspondence (singular_nodes.hpp)
    std::vector<std::uint8_t> detached; // per node, 1 = all bonds break at the next break_bonds
    long detached_nodes = 0;            // nodes detached so far by the singular-node rule
    ThermalExpansion thermal;           // the model's (header); inactive: the total stretch

    // A uniform critical stretch s0 [-], every other member at its default.
    static CriticalStretch uniform(double s0)
    {
        CriticalStretch c;
        c.s0 = s0;
        return c;
    }

    void protect(const NodeSet& set, std::size_t nodes)
    {
        if (no_fail.empty()) no_fail.assign(nodes, 0);
        for (int i : set) no_fail[i] = 1;
    }

    // Breaks the bonds stretched beyond s0 (or s0_bond[k]) at positions y (enabling the bonds' damage
    // flags if needed); returns how many ordered bonds broke. s and s0_bond are symmetric in i, j, so
    // bond i->j and its reverse break in the same pass. The scalar case is its own instantiation of the
    // loop (no per-bond load or branch).
    template <int D>
    long apply(Bonds& b, const Field<D>& y) const
    {
        if (!s0_bond.empty()) {
            if (s0_bond.size() != b.size()) throw std::invalid_argument("CriticalStretch: s0_bond size differs from the bond count");
            return apply_with(b, y, [this](std::int64_t k) { return s0_bond[k]; });
        }
        return apply_with(b, y, [this](std::int64_t) { return s0; });
    }

    // The damage rule of a scene (scene.hpp): before a force evaluation the stretched bonds break,
    // then those of the nodes the singular-node rule detached; after it, that rule marks its nodes.
    template <int D>
    long break_bonds(Bonds& b, const Field<D>& y)
    {
        const long broke = apply(b, y);
        return detach_singular ? broke + break_detached_bonds(b, detached, no_fail) : broke;
    }
    template <class Model>
    const BondWork* bond_work(const Bonds&) const { return nullptr; }
    template <class Model, int D>
    void record(const Model& model, const Bonds& b, const Field<D>&)
    {
        if (detach_singular) detached_nodes += mark_singular_nodes(model, b.nodes(), detached);
    }
    // Its part of a checkpoint (core/state_archive.hpp): the singular-node marks.
    void state(StateArchive& ar)
    {
        ar("critical_stretch.detached", detached);
        ar("critical_stretch.detached_nodes", detached_nodes);
    }

private:
    template <int D, class S0>
    long apply_with(Bonds& b, const Field<D>& y, S0 s0_of) const
    {
        // Each pair once, by its smaller node, which writes both halves: the test is symmetric in i, j
        // (the same |Y|, pair strain and s0 from either end), so this is the ordered-bond rule exactly,
        // at half the cost. Race-free: a node reads only the halves of pairs with larger partners, and
        // those only its own thread writes.
        if (!b.has_damage()) b.enable_damage();  // the intact flags it reads and writes
        long broken = 0;
        std::uint8_t* intact = b.intact.data();
#pragma omp parallel for schedule(static) reduction(+ : broken)
        for (long i = 0; i < static_cast<long>(b.nodes()); ++i) {
            if (!no_fail.empty() && no_fail[i]) continue;
            for_family(b, i, [&](std::int64_t k, int j) {
                if (j < i) return;
                const std::int64_t r = b.reverse[k];
                const int halves = intact[k] + intact[r];
                if (halves == 0 || (!no_fail.empty() && no_fail[j])) return;
                const double L = b.length[k];
                const double rest = thermal.active() ? L * (1 + thermal.pair_strain(i, j)) : L;
                if ((norm(y[j] - y[i]) - rest) / L > s0_of(k)) intact[k] = intact[r] = 0, broken += halves;
            });
        }
        return broken;
    }
};

// phi_i [-]; zero everywhere when the scene has no damage.
inline std::vector<double> point_damage(const Bonds& b)
{
    std::vector<double> phi(b.nodes(), 0.0);
    if (!b.has_damage()) return phi;
    for (std::size_t i = 0; i < b.nodes(); ++i) {
        double all = 0, kept = 0;
        for_family(b, i, [&](std::int64_t k, int) {
            all += b.volume[k];
            kept += b.intact[k] * b.volume[k];
        });
        phi[i] = all > 0 ? 1 - kept / all : 0;
    }
    return phi;
}

}  // namespace pd
