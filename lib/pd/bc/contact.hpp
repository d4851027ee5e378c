// Contact: short-range repulsion between material points that are not bonded, and rigid
// impactors (sphere, cylinder, flat punch) pressed on a body by penalty (spec/001_004
// B.5: the falling-weight impact on a PMMA disc). Both add a body-force density b [N/m^3] through
// the extra-force hook of Explicit (time/verlet.hpp), so they enter its external-work bookkeeping.
//
// Node-node contact (ShortRangeContact). Two points i, j without an intact bond between them,
// closer than the contact distance r_c (a fraction of dx, so no pair is in contact in the
// reference lattice), push each other apart along e_ij = (y_j - y_i)/r:
//   b_i += -C (r_c - r) V_j e_ij,      b_j += +C (r_c - r) V_i e_ij            (r < r_c)
// C [N/m^6] is the penalty constant; the pair potential is U_ij = 1/2 C V_i V_j (r_c - r)^2, so
// the pair forces V_i b_i = -V_j b_j are equal and opposite. Default C = 18 K/(pi delta^5) x
// factor: the PMB micromodulus c = 18K/(pi delta^4) per unit length of overlap (r_c - r)/delta.
// Search: Verlet list of the pairs closer than r_c + skin from the cell lists of neighbors.hpp
// (cell size r_c + skin), rebuilt when some point has moved more than skin/2 since the last build (then no
// pair can have entered r_c unseen). Owner computes: every point visits its own list (the list
// holds both i->j and j->i), so the result does not depend on the thread count.
//
// Rigid impactor (Impactor). A rigid body of mass M [kg] in translation (no rotation) with
// position c and velocity V. Every body point inside it at penetration p > 0 along the outward
// normal n of the nearest surface gets b_i = k p n, with the penalty k [N/m^4]; the impactor gets
// the opposite total force F = -sum_i k p n V_i. Potential U = sum_i 1/2 k p^2 V_i.
//   sphere     (centre c, radius R):       p = R - |y - c|,            n = (y - c)/|y - c|
//   cylinder   (axis a, radius R, length L): p = R - |(y - c)_perp|, n radial, for |(y - c).a| <= L/2
//   flat punch (face centre c, unit normal a into the body, radius R): p = -(y - c).a, n = a,
//              for points behind the face with lateral distance <= R
// Default k = factor x E / dx^2: a point pressed p into the impactor feels the stress E p/dx over
// its cell face, the stiffness of one lattice spring, so the penalty is as stiff as the material
// and costs no smaller time step than the bonds.
// Integration: the impactor is advanced by velocity Verlet in the same step as the body: when the
// hook is called at t_{n+1} (after the body's drift), c_{n+1} = c_n + dt (V_n + dt/2 A_n),
// A_{n+1} = F(y_{n+1}, c_{n+1})/M, V_{n+1} = V_n + dt/2 (A_n + A_{n+1}). Body and impactor forces
// are equal and opposite and both are kicked with the same dt: the total momentum is conserved to
// round-off when no point is constrained.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/errors.hpp"
#include "pd/core/field.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/core/lattice.hpp"
#include "pd/core/neighbors.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace pd {

template <int D>
class ShortRangeContact {
public:
    double rc = 0;     // contact distance [m]
    double skin = 0;   // Verlet-list skin [m]
    double C = 0;      // penalty constant [N/m^6]
    long rebuilds = 0;

    // bonds may be null (no point is bonded to any other).
    ShortRangeContact(const Body<D>& body, const Bonds* bonds, double rc, double skin, double C)
        : rc(rc), skin(skin), C(C), body_(body), bonds_(bonds)
    {
        if (!(rc > 0) || !(skin >= 0) || !(C > 0)) throw std::invalid_argument("contact: rc, C must be > 0 and skin >= 0");
    }
    static double default_constant(double K, double delta, double factor = 1)  // [N/m^6]
    {
        return factor * 18 * K / (std::numbers::pi * std::pow(delta, 5));
    }

    // Adds the contact force density to b at positions y.
    void add(const Field<D>& y, Field<D>& b)
    {
        if (needs_rebuild(y)) rebuild(y);
        const long n = static_cast<long>(body_.size());
#pragma omp parallel for schedule(static) if (n >= 2048)
        for (long i = 0; i < n; ++i) {
            Vec<D> bi{};
            for (std::int64_t q = off_[i]; q < off_[i + 1]; ++q) {
                const int j = nbr_[q];
                const Vec<D> e = y[j] - y[i];
                const double r = norm(e);
                if (r >= rc || r == 0 || bonded(i, j)) continue;
                bi += (-C * (rc - r) * body_.volume[j] / r) * e;  // -C (r_c - r) V_j e_ij
            }
            b.add(i, bi);
        }
    }

    // Contact energy sum over pairs 1/2 C V_i V_j (r_c - r)^2 [J] (lists as of the last add()).
    double energy(const Field<D>& y) const
    {
        double U = 0;
        if (off_.size() != body_.size() + 1) return 0;  // no list yet: add() was never called
        for (std::size_t i = 0; i < body_.size(); ++i)
            for (std::int64_t q = off_[i]; q < off_[i + 1]; ++q) {
                const int j = nbr_[q];
                const double r = norm(y[j] - y[i]);
                if (j > static_cast<int>(i) && r < rc && !bonded(i, j))
                    U += 0.5 * C * body_.volume[i] * body_.volume[j] * (rc - r) * (rc - r);
            }
        return U;
    }

private:
    const Body<D>& body_;
    const Bonds* bonds_;
    std::vector<std::int64_t> off_{0};
    std::vector<int> nbr_;
    Field<D> y_build_;

    bool bonded(std::size_t i, int j) const
    {
        if (!bonds_) return false;
        const auto first = bonds_->partner.begin() + bonds_->begin(i), last = bonds_->partner.begin() + bonds_->end(i);
        const auto it = std::lower_bound(first, last, j);  // families are sorted by partner (core/bonds.hpp)
        return it != last && *it == j && (!bonds_->has_damage() || bonds_->intact[it - bonds_->partner.begin()]);
    }

    bool needs_rebuild(const Field<D>& y) const
    {
        if (y_build_.size() != y.size()) return true;
        for (std::size_t i = 0; i < y.size(); ++i)
            if (norm(y[i] - y_build_[i]) > 0.5 * skin) return true;
        return false;
    }

    // Candidate pairs closer than h = rc + skin, both orders, sorted per point (neighbors.hpp).
    void rebuild(const Field<D>& y)
    {
        ++rebuilds;
        for (int d = 0; d < D; ++d)  // a blown-up run reaches the search before the integrator's finite check
            for (std::size_t i = 0; i < y.size(); ++i)
                if (!std::isfinite(y.c[d][i]))
                    throw Unstable("unstable: non-finite position of node " + std::to_string(i) + " in the contact search", 0, int(i));
        y_build_ = y;
        const double h = rc + skin;
        NeighborLists near = neighbor_lists(y, h, [&](int i, int j) { return norm(y[j] - y[i]) < h; });
        off_ = std::move(near.offset);
        nbr_ = std::move(near.partner);
    }
};

template <int D>
struct Impactor {
    enum class Shape { sphere, cylinder, flat_punch } shape = Shape::sphere;
    double mass = 0;      // [kg]
    double radius = 0;    // [m]
    double length = 0;    // cylinder length [m]
    Vec<D> axis{};        // cylinder axis / punch face normal pointing into the body (unit)
    Vec<D> c{};           // centre (punch: face centre) [m]
    Vec<D> V{};           // velocity [m/s]
    Vec<D> A{};           // acceleration [m/s^2]
    Vec<D> F{};           // contact force on the impactor [N]
    double k = 0;         // penalty [N/m^4]
    double t = 0;         // time of c, V, A [s]
    int in_contact = 0;   // body points in contact at the last call

    static double default_penalty(double E, double dx, double factor = 1) { return factor * E / (dx * dx); }

    void validate() const
    {
        if (!(mass > 0) || !(radius > 0) || !(k > 0)) throw std::invalid_argument("impactor: mass, radius, penalty must be > 0");
        if (shape == Shape::cylinder && !(length > 0)) throw std::invalid_argument("impactor: cylinder length must be > 0");
        if (shape != Shape::sphere && std::abs(norm(axis) - 1) > 1e-12) throw std::invalid_argument("impactor: axis must be a unit vector");
    }

    // Penetration p and outward normal n of point y (p <= 0: no contact).
    double penetration(const Vec<D>& y, Vec<D>& n) const
    {
        const Vec<D> r = y - c;
        if (shape == Shape::sphere) {
            const double d = norm(r);
            if (d == 0) return 0;
            n = (1 / d) * r;
            return radius - d;
        }
        const double s = dot(r, axis);
        const Vec<D> perp = r - s * axis;
        const double rho = norm(perp);
        if (shape == Shape::cylinder) {
            if (std::abs(s) > 0.5 * length || rho == 0) return 0;
            n = (1 / rho) * perp;
            return radius - rho;
        }
        if (rho > radius) return 0;  // flat punch
        n = axis;
        return -s;
    }

    // The Explicit hook at time tn: advances the impactor to tn (velocity Verlet, header) and adds
    // the contact force density to b.
    void operator()(double tn, const Field<D>& y, Field<D>& b, const std::vector<double>& volume)
    {
        const double dt = tn - t;
        if (dt > 0) c += dt * (V + (0.5 * dt) * A);
        Vec<D> Fsum{};
        int count = 0;
        for (std::size_t i = 0; i < y.size(); ++i) {
            Vec<D> n{};
            const double p = penetration(y[i], n);
            if (p <= 0) continue;
            b.add(i, (k * p) * n);              // b_i = k p n
            Fsum -= (k * p * volume[i]) * n;    // reaction on the impactor
            ++count;
        }
        const Vec<D> A_new = (1 / mass) * Fsum;
        if (dt > 0) V += (0.5 * dt) * (A + A_new);
        A = A_new, F = Fsum, t = tn, in_contact = count;
    }

    // A checkpoint of the impactor's motion (core/state_archive.hpp).
    void state(StateArchive& ar)
    {
        ar("impactor.c", c), ar("impactor.V", V), ar("impactor.A", A), ar("impactor.F", F), ar("impactor.t", t);
        ar("impactor.in_contact", in_contact);
    }

    double kinetic_energy() const { return 0.5 * mass * dot(V, V); }  // [J]
    double contact_energy(const Field<D>& y, const std::vector<double>& volume) const  // [J]
    {
        double U = 0;
        for (std::size_t i = 0; i < y.size(); ++i) {
            Vec<D> n{};
            const double p = penetration(y[i], n);
            if (p > 0) U += 0.5 * k * p * p * volume[i];
        }
        return U;
    }
};

}  // namespace pd
