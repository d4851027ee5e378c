// pd/kernel_concepts.hpp -- the roles a model (or the kernel it hands to the bond pass) can play,
// one named concept per role. The bond pass (bond_loop.hpp) and the integrators test these
// concepts at compile time (if constexpr), so a role a model does not play costs nothing.
//
// Every model:   static constexpr bool has_point_pass;  point_pass(bonds, y) when true.
// Every kernel:  either ordinary, with   double bond_scalar(i, k, j, |Y|)   (force on i = t Y),
//                or NonOrdinaryKernel,  with   Vec<D> bond_force(i, k, j, Y)   (both ends' states).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/simd/chunk_vector.hpp"
#include "pd/core/field.hpp"
#include "pd/simd/translated_families.hpp"

#include <concepts>
#include <cstddef>
#include <cstdint>

namespace pd {

// A kernel whose bond force is not along the deformed bond (correspondence): it declares
// `static constexpr bool ordinary = false;` and supplies bond_force, the force density on i from
// bond k with both ends' states included, (T_i<xi> - T_j<-xi>) V_j [N/m^3]; finite for broken bonds.
template <class K>
concept NonOrdinaryKernel = requires { K::ordinary; } && !K::ordinary;

// A model that hands the bond pass a separate kernel object: with_kernel(pass) calls pass(kernel)
// exactly once; with_kernel(pass, bonds) when the kernel's set-up depends on the bonds of the pass.
// The model picks at run time among kernels specialised at compile time (a switched-off term costs
// no branch in the hot loop), and a kernel holding raw pointers keeps them in registers.
template <class M, class Pass>
concept KernelProvider = requires(const M& m, Pass& pass) { m.with_kernel(pass); };
template <class M, class Pass>
concept KernelProviderForBonds = requires(const M& m, Pass& pass, const Bonds& b) { m.with_kernel(pass, b); };

// A kernel that returns node i's whole force (node term included) and vectorises its own way:
// family_force<Damaged, Out>(i, bonds, y, work). It must add bond begin(i) + l + 8 m into partial
// sum l and reduce them as the bond pass does, so that the result does not depend on the threads.
template <class K, int D>
concept FamilyKernel = requires(const K& k, std::size_t i, const Bonds& b, const Field<D>& y) {
    k.template family_force<false>(i, b, y);
};

// A part of the force that factors out of the family sum, added once per node (correspondence:
// P_i K_i^-1 sum_j omega xi V_j): node_force(i) [N/m^3]; with bond work, node_share(i, k, j) gives
// bond k's part of it.
template <class K>
concept NodeTermKernel = requires(const K& k, std::size_t i) { k.node_force(i); };

// The hourglass part of bond_force, hourglass_force(i, k, j, Y) [N/m^3], which the bond work leaves
// out when asked (Peridigm's micropotential, spec/000c sec. 2.3).
template <class K, int D>
concept HourglassKernel = requires(const K& k, const Vec<D>& Y) { k.hourglass_force(std::size_t{}, std::int64_t{}, 0, Y); };

// Chunks of W nodes with translated families (translated_families.hpp), undamaged scenes only:
// chunks(bonds) (null when there are none) and run_force(p, bonds, y, f), the forces of the nodes of
// run p's chunks.
template <class K, int D>
concept ChunkRunKernel = requires(const K& k, const Bonds& b, const Field<D>& y, Field<D>& f) {
    k.chunks(b);
    k.run_force(0, b, y, f);
};

#ifdef PD_CHUNK_WIDTH
// An ordinary kernel whose bond_scalar is written once for both paths (node_value, simd/chunk_vector.hpp):
// taken in detail::vchunk, bond_scalar(i0, k, j, |Y|) is that of bond k of node i0 (partner j) for the
// W lanes i0 + l (partners j + l) of a chunk; chunks(b) names the runs.
template <class K>
concept OrdinaryChunkKernel = requires(const K& k, const Bonds& b, const detail::vchunk& v) {
    k.chunks(b);
    { k.bond_scalar(std::size_t{}, std::int64_t{}, 0, v) } -> std::same_as<detail::vchunk>;
};
#endif

// A model with per-node constants that depend on the intact bonds (LPS m_i and SCF_i, PALS
// multipliers): recompute(bonds) after bonds broke.
template <class M>
concept BondDependentModel = requires(M& m, const Bonds& b) { m.recompute(b); };

// A model with history (viscoelastic, plastic): point_pass(bonds, y, dt) evaluates the trial state at
// y over the step dt [s] from the committed history (dt = 0: the state is reached at once; it does
// not accumulate), commit() makes it the committed one.
template <class M, int D>
concept HistoryModel = requires(M& m, const Bonds& b, const Field<D>& y) {
    m.point_pass(b, y, 0.0);
    m.commit();
};

// A model that turns mechanical work into heat (plastic: beta_TQ sigma_y dlambda; viscoelastic: the
// energy its Maxwell branches dissipate): step_heat(i), the heat released at node i by the step just
// committed [J/m^3]. A scene with a heat component accumulates it (scene.hpp, spec/000a eq. 3.24).
template <class M>
concept DissipativeModel = requires(const M& m, std::size_t i) {
    { m.step_heat(i) } -> std::convertible_to<double>;
};

// The mechanical energy a DissipativeModel's last committed step dissipated at node i [J/m^3], heat
// or not (the energy books of time/verlet.hpp): step_dissipation(i) where the model tells it apart
// (plastic: all of sigma_y dlambda, of which beta_TQ becomes heat), else step_heat(i).
template <class M>
    requires DissipativeModel<M>
double step_dissipation(const M& m, std::size_t i)
{
    if constexpr (requires { m.step_dissipation(i); }) return m.step_dissipation(i);
    else return m.step_heat(i);
}

}  // namespace pd
