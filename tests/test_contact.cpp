// Contact (lib/pd/bc/contact.hpp): node-node penalty against hand values and a brute-force pair sum;
// impactor geometry against hand values; a sphere bouncing off a free PMB cube, and two free PMB
// blocks colliding by node-node contact, integrated with Explicit's extra-force hook: total
// momentum and total energy (bodies + impactor + contact potential), rebound.
#include "pd/bc/contact.hpp"
#include "pd/models/pmb.hpp"
#include "pd/time/critical_step.hpp"
#include "pd/time/verlet.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace pd;

namespace {
Body<3> two_points(double r)
{
    Body<3> b;
    b.push({0, 0, 0}, 1e-9);
    b.push({r, 0, 0}, 2e-9);
    return b;
}
}  // namespace

TEST(Contact, PairInsideContactDistanceGetsEqualAndOppositeForces)
{
    // r = 0.8 mm < r_c = 1 mm, C = 1e20 N/m^6, V0 = 1e-9, V1 = 2e-9 m^3:
    // |force| = C (r_c - r) V0 V1 = 1e20 * 2e-4 * 2e-18 = 4e-2 N, pushing the points apart.
    const Body<3> body = two_points(0.8e-3);
    ShortRangeContact<3> contact(body, nullptr, 1e-3, 0.2e-3, 1e20);
    Field<3> b(2);
    contact.add(body.x, b);
    EXPECT_NEAR(b.c[0][0] * body.volume[0], -4e-2, 1e-15);  // round-off of a few products
    EXPECT_NEAR(b.c[0][1] * body.volume[1], 4e-2, 1e-15);
    EXPECT_EQ(b.c[1][0], 0.0);
    EXPECT_EQ(b.c[2][1], 0.0);
    // U = 1/2 C V0 V1 (r_c - r)^2 = 0.5 * 1e20 * 2e-18 * 4e-8 = 4e-6 J.
    EXPECT_NEAR(contact.energy(body.x), 4e-6, 1e-18);
}

TEST(Contact, NoForceBeyondContactDistanceOrAcrossAnIntactBond)
{
    const Body<3> far = two_points(1.05e-3);
    ShortRangeContact<3> c1(far, nullptr, 1e-3, 0.2e-3, 1e20);
    Field<3> b(2);
    c1.add(far.x, b);
    EXPECT_EQ(b.c[0][0], 0.0);
    EXPECT_EQ(b.c[0][1], 0.0);
    // Bonded pair at 0.8 mm: no contact while the bond is intact, contact once it is broken.
    const Body<3> near = two_points(0.8e-3);
    Bonds bonds = build_bonds(near, 1e-3);
    ASSERT_EQ(bonds.size(), 2u);
    bonds.enable_damage();
    ShortRangeContact<3> c2(near, &bonds, 1e-3, 0.2e-3, 1e20);
    Field<3> b2(2);
    c2.add(near.x, b2);
    EXPECT_EQ(b2.c[0][0], 0.0);
    bonds.intact.assign(2, 0);
    c2.add(near.x, b2);
    EXPECT_LT(b2.c[0][0], 0.0);
}

TEST(Contact, CellListMatchesBruteForceAndRebuildsAfterMotion)
{
    // A jittered cloud, compared with the O(n^2) sum of the header formula; then every point moves
    // by more than skin/2 and the lists must be rebuilt to stay exact.
    Body<3> body = box<3>({0, 0, 0}, {6e-3, 6e-3, 6e-3}, 1e-3);
    Field<3> y = body.x;
    for (std::size_t i = 0; i < body.size(); ++i)
        for (int d = 0; d < 3; ++d) y.c[d][i] += 0.3e-3 * std::sin(1.7 * i + 2.3 * d);
    const double rc = 0.9e-3, C = 3e19;
    ShortRangeContact<3> contact(body, nullptr, rc, 0.3e-3, C);
    auto brute = [&](const Field<3>& pos) {
        Field<3> r(body.size());
        for (std::size_t i = 0; i < body.size(); ++i)
            for (std::size_t j = 0; j < body.size(); ++j) {
                if (i == j) continue;
                const double dx = pos.c[0][j] - pos.c[0][i], dy = pos.c[1][j] - pos.c[1][i], dz = pos.c[2][j] - pos.c[2][i];
                const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
                if (d >= rc) continue;
                const double s = -C * (rc - d) * body.volume[j] / d;
                r.c[0][i] += s * dx, r.c[1][i] += s * dy, r.c[2][i] += s * dz;
            }
        return r;
    };
    for (int pass = 0; pass < 2; ++pass) {
        Field<3> b(body.size());
        contact.add(y, b);
        const Field<3> ref = brute(y);
        double scale = 0;
        for (int d = 0; d < 3; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) scale = std::max(scale, std::abs(ref.c[d][i]));
        ASSERT_GT(scale, 0.0);  // some pairs are in contact
        for (int d = 0; d < 3; ++d)
            for (std::size_t i = 0; i < body.size(); ++i) ASSERT_NEAR(b.c[d][i], ref.c[d][i], 1e-12 * scale) << i;  // summation order
        for (std::size_t i = 0; i < body.size(); ++i) y.c[0][i] += 0.2e-3 * std::cos(0.9 * i);  // up to 0.2 mm > skin/2
    }
    EXPECT_EQ(contact.rebuilds, 2);
}

TEST(Contact, ImpactorPenetrationHandValues)
{
    Impactor<3> s{.shape = Impactor<3>::Shape::sphere, .mass = 1, .radius = 2e-3, .c = {0, 0, 0}, .k = 1};
    Vec<3> n;
    EXPECT_NEAR(s.penetration({0, 1.5e-3, 0}, n), 0.5e-3, 1e-18);  // 2 - 1.5 mm
    EXPECT_DOUBLE_EQ(n[1], 1.0);
    Impactor<3> cyl{.shape = Impactor<3>::Shape::cylinder, .mass = 1, .radius = 2e-3, .length = 4e-3, .axis = {0, 0, 1}, .k = 1};
    EXPECT_NEAR(cyl.penetration({1.2e-3, 1.6e-3, 1e-3}, n), 0.0, 1e-18);   // rho = 2 mm: touching
    EXPECT_LT(cyl.penetration({0, 1e-3, 2.5e-3}, n), 1e-30);               // beyond L/2
    Impactor<3> punch{.shape = Impactor<3>::Shape::flat_punch, .mass = 1, .radius = 2e-3, .axis = {0, 0, -1}, .c = {0, 0, 1e-3}, .k = 1};
    EXPECT_NEAR(punch.penetration({1e-3, 0, 1.3e-3}, n), 0.3e-3, 1e-18);  // face at z = 1 mm moving down, punch above it
    EXPECT_DOUBLE_EQ(n[2], -1.0);
    EXPECT_LT(punch.penetration({1e-3, 0, 0.7e-3}, n), 1e-30);              // in front of the face
    EXPECT_LT(punch.penetration({3e-3, 0, 1.3e-3}, n), 1e-30);              // outside the face radius
    Impactor<3> bad = s;
    bad.mass = 0;
    EXPECT_THROW(bad.validate(), std::invalid_argument);
}

namespace {
struct Rebound { double p0, p1, e0, e_dev_max, v_imp_end, p_scale; int contact_steps; };

// Steel-like PMB cube 6 x 6 x 6 mm (free), a sphere of 1/10 the cube's mass flying at it along -z
// (lighter than the cube, so it bounces back).
Rebound rebound(double dt_factor)
{
    const double dx = 1e-3, delta = 3.015e-3, rho = 7800, E = 200e9;
    const Body<3> body = box<3>({0, 0, 0}, {6e-3, 6e-3, 6e-3}, dx);
    Bonds bonds = build_bonds(body, delta);
    const Elastic mat = Elastic::from_E_nu(E, 0.25);
    PMB model({.material = mat, .dim = 3}, bonds);
    Explicit<3, PMB> sim(body, bonds, model, rho);
    double mass = 0;
    for (double V : body.volume) mass += rho * V;
    Impactor<3> imp{.mass = 0.1 * mass, .radius = 2e-3, .c = {3e-3, 3e-3, 6e-3 + 2.05e-3}, .V = {0, 0, -5}};
    imp.k = Impactor<3>::default_penalty(E, dx);
    imp.validate();
    sim.scene.extra_force = [&](double t, const Field<3>& y, const Field<3>&, Field<3>& b) { imp(t, y, b, body.volume); };
    sim.start();
    const double c = PMB::micromodulus({.material = mat, .dim = 3}, Influence{}, delta);
    const double dt = dt_factor * critical_step_silling_askari(bonds, sim.rho, c).dt;
    auto momentum = [&] {
        double p = imp.mass * imp.V[2];
        for (std::size_t i = 0; i < body.size(); ++i) p += rho * body.volume[i] * sim.v.c[2][i];
        return p;
    };
    auto energy = [&] {
        const Energies e = detail::body_energies(model, bonds, body, sim.positions(), sim.v, sim.rho, 0);
        return e.kinetic + e.strain + imp.kinetic_energy() + imp.contact_energy(sim.positions(), body.volume);
    };
    Rebound r{momentum(), 0, energy(), 0, 0, imp.mass * 5, 0};
    for (long n = 0; n < 20000; ++n) {
        sim.step(dt);
        r.contact_steps += imp.in_contact > 0;
        r.e_dev_max = std::max(r.e_dev_max, std::abs(energy() / r.e0 - 1));
        if (r.contact_steps > 0 && imp.in_contact == 0 && imp.V[2] > 0) break;  // separated, moving away
    }
    r.p1 = momentum();
    r.v_imp_end = imp.V[2];
    return r;
}
}  // namespace

TEST(Contact, ImpactorReboundConservesMomentumAndEnergy)
{
    const Rebound r = rebound(0.5);
    ASSERT_GT(r.contact_steps, 10);   // a real contact phase happened
    EXPECT_GT(r.v_imp_end, 0.0);      // the sphere bounced back (+z)
    // Body and impactor forces are equal and opposite, both kicked with dt: round-off only
    // (1e-12 of the impactor momentum: ~1e4 steps of sums over ~300 points).
    EXPECT_NEAR(r.p1, r.p0, 1e-12 * r.p_scale);
    // Verlet conserves energy to O(dt^2) without damage: the deviation must drop by about 4x when
    // dt halves (order 2; > 2.5 allows for the phase of the oscillation at the sampled steps), and
    // stay below 1 % at half the critical step (measured 6.3e-3: the largest transient error
    // comes from the stiff penalty on the few nodes in contact; the order check is the real test).
    const Rebound h = rebound(0.25);
    EXPECT_LT(r.e_dev_max, 1e-2);
    EXPECT_GT(r.e_dev_max / h.e_dev_max, 2.5);
    std::printf("rebound: momentum drift %.3g, energy deviation %.3g (dt) %.3g (dt/2), v_end %.3g m/s\n",
                (r.p1 - r.p0) / r.p_scale, r.e_dev_max, h.e_dev_max, r.v_imp_end);
}

namespace {
struct Collision { double p_scale, p_drift, e0, e_dev_max, v_a_end, v_b_end, gap_end; int contact_steps; long rebuilds; };

// Two free steel-like PMB blocks 5 x 5 x 5 mm, no bond between them (keep filter), the facing
// node layers 1.1 dx apart, flying at each other at -+v along x; node-node contact with
// r_c = 0.9 dx (no pair of the reference lattice is in contact: bonded pairs are skipped, and the
// blocks start 1.1 dx apart), default penalty. Runs until 100 steps after the last contact.
Collision collide(double dt_factor)
{
    const double dx = 1e-3, delta = 3.015e-3, rho = 7800, E = 200e9, v0 = 5, shift = 5 * dx + 0.1 * dx;
    Body<3> body = box<3>({0, 0, 0}, {5e-3, 5e-3, 5e-3}, dx);
    const std::size_t half = body.size();
    for (std::size_t i = 0; i < half; ++i) body.push(body.x[i] + Vec<3>{shift, 0, 0}, body.volume[i]);
    auto in_b = [half](int i) { return static_cast<std::size_t>(i) >= half; };
    Bonds bonds = build_bonds(body, delta, BondOptions{.keep = [&](int i, int j) { return in_b(i) == in_b(j); }});
    const Elastic mat = Elastic::from_E_nu(E, 0.25);
    PMB model({.material = mat, .dim = 3}, bonds);
    ShortRangeContact<3> contact(body, &bonds, 0.9 * dx, 0.2 * dx, ShortRangeContact<3>::default_constant(mat.K, delta));
    Explicit<3, PMB> sim(body, bonds, model, rho);
    for (std::size_t i = 0; i < body.size(); ++i) sim.v.c[0][i] = in_b(static_cast<int>(i)) ? -v0 : v0;
    sim.scene.extra_force = [&](double, const Field<3>& y, const Field<3>&, Field<3>& b) { contact.add(y, b); };
    sim.start();
    const double c = PMB::micromodulus({.material = mat, .dim = 3}, Influence{}, delta);
    const double dt = dt_factor * critical_step_silling_askari(bonds, sim.rho, c).dt;
    auto block_velocity = [&](bool b_side) {  // mean x velocity of a block [m/s]
        double s = 0;
        for (std::size_t i = 0; i < body.size(); ++i) if (in_b(static_cast<int>(i)) == b_side) s += sim.v.c[0][i];
        return s / half;
    };
    auto momentum = [&] {
        Vec<3> p{};
        for (std::size_t i = 0; i < body.size(); ++i) p += (rho * body.volume[i]) * sim.v[i];
        return p;
    };
    auto energy = [&] {
        const Energies e = detail::body_energies(model, bonds, body, sim.positions(), sim.v, sim.rho, 0);
        return e.kinetic + e.strain + contact.energy(sim.positions());
    };
    double mass = 0;
    for (double V : body.volume) mass += rho * V;
    Collision r{0.5 * mass * v0, 0, energy(), 0, 0, 0, 0, 0, 0};
    const Vec<3> p0 = momentum();
    int quiet = 0;
    for (long n = 0; n < 20000 && quiet < 100; ++n) {
        sim.step(dt);
        const bool touching = contact.energy(sim.positions()) > 0;
        r.contact_steps += touching;
        quiet = r.contact_steps > 0 && !touching ? quiet + 1 : 0;
        r.e_dev_max = std::max(r.e_dev_max, std::abs(energy() / r.e0 - 1));
    }
    const Vec<3> p1 = momentum();
    r.p_drift = norm(p1 - p0);
    r.v_a_end = block_velocity(false);
    r.v_b_end = block_velocity(true);
    double a_max = -1e300, b_min = 1e300;  // facing layers: right face of A, left face of B
    for (std::size_t i = 0; i < body.size(); ++i) {
        const double y = sim.positions().c[0][i];
        if (in_b(static_cast<int>(i))) b_min = std::min(b_min, y); else a_max = std::max(a_max, y);
    }
    r.gap_end = b_min - a_max;
    r.rebuilds = contact.rebuilds;
    return r;
}
}  // namespace

// Node-node contact in a real run: the two blocks collide through Explicit's extra-force hook and
// separate. Total momentum: the pair forces V_i b_i = -V_j b_j are equal and opposite and every
// node is kicked with the same dt, so it stays 0 up to round-off (1e-12 of one block's momentum).
// Total energy KE + SE + contact potential (1/2 C V_i V_j (r_c - r)^2, the potential of the
// forces): velocity Verlet conserves it to O(dt^2) (no damage, no constraint), so halving dt
// must shrink the largest deviation by about 4 (> 2.5: the sampled phase of the oscillation).
TEST(Contact, TwoBlocksCollideAndReboundThroughTheExtraForceHook)
{
    const Collision r = collide(0.5), h = collide(0.25);
    ASSERT_GT(r.contact_steps, 5);  // a contact phase of several steps happened
    EXPECT_LT(r.p_drift, 1e-12 * r.p_scale);
    EXPECT_LT(h.p_drift, 1e-12 * h.p_scale);
    EXPECT_LT(r.v_a_end, 0.0);  // block A (was +v) moves back in -x
    EXPECT_GT(r.v_b_end, 0.0);  // block B (was -v) moves back in +x
    EXPECT_GT(r.gap_end, 0.9e-3);  // separated beyond the contact distance
    EXPECT_GT(r.e_dev_max / h.e_dev_max, 2.5);
    // Size at half the critical step: below 1e-3 (measured 1.7e-4; 5.3e-5 at dt/2, ratio 3.2; the
    // order check above is the real test).
    EXPECT_LT(r.e_dev_max, 1e-3);
    std::printf("collision: momentum drift %.3g, energy deviation %.3g (dt) %.3g (dt/2), v_end %.3g / %.3g m/s, "
                "%d contact steps, %ld list builds\n",
                r.p_drift / r.p_scale, r.e_dev_max, h.e_dev_max, r.v_a_end, r.v_b_end, r.contact_steps, r.rebuilds);
}
