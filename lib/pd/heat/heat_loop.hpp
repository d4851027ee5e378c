// The heat loop: nodal heat-flow density Q_i = sum_j h_ij V_j over the intact bonds of i [W/m^3],
// on the family traversal of the force loop (bond_loop.hpp, lane_sums: owner computes, the fixed
// 8-lane summation order, so results are bit-identical for any number of threads).
// A heat model supplies
//   static constexpr bool has_point_pass;                   // e.g. temperature gradients first
//   void point_pass(const Bonds&, const std::vector<double>& theta);   // only if has_point_pass
//   double bond_heat(std::size_t i, std::int64_t k, int j, double dtheta) const;
//        // heat-flow density into i through bond k (both ends' states included) [W/m^3],
//        // dtheta = theta_j - theta_i [K]
// A broken bond conducts nothing (multiplied by intact[k]).
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/parallel.hpp"

#include <vector>

namespace pd {

namespace detail {
template <bool Damaged, class Model>
void heat_pass(const Model& model, const Bonds& bonds, const std::vector<double>& theta, std::vector<double>& Q)
{
    const double* th = theta.data();
    parallel_for(bonds.nodes(), [&](std::size_t i) {
        Q[i] = lane_sums<1, Damaged>(bonds, i, [&](std::int64_t k, int j, double keep, auto&& add) {
            double h = model.bond_heat(i, k, j, th[j] - th[i]);
            if constexpr (Damaged) h *= keep;
            add(0, h);
        })[0];
    });
}
}  // namespace detail

// Q: heat-flow density into every node at temperatures theta [W/m^3].
template <class Model>
void heat_flow(Model& model, const Bonds& bonds, const std::vector<double>& theta, std::vector<double>& Q)
{
    Q.resize(theta.size());
    if constexpr (Model::has_point_pass) model.point_pass(bonds, theta);
    if (bonds.has_damage())
        detail::heat_pass<true>(model, bonds, theta, Q);
    else
        detail::heat_pass<false>(model, bonds, theta, Q);
}

}  // namespace pd
