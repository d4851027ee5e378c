// THE bond loop: internal force density f_i = sum_j t_ij(Y) Y_ij over the intact bonds of i
// [N/m^3], for every ordinary model (force along the deformed bond Y = y_j - y_i).
// A model supplies
//   static constexpr bool has_point_pass;      // per-point pass before the bond pass (LPS theta)
//   void point_pass(const Bonds&, const Field<D>& y);
//   double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const;
//        // |force density of bond k| / |Y| [N/m^6 / m... i.e. N/m^7]; force on i is bond_scalar * Y
// Owner computes (gather only, no atomics): bit-identical results for any number of threads.
// Broken bonds are skipped by multiplying with intact[k]; the undamaged scene compiles a loop
// without that array (if constexpr).
#pragma once
#include "pd/bonds.hpp"
#include "pd/field.hpp"
#include "pd/parallel.hpp"

namespace pd {

namespace detail {
template <bool Damaged, int D, class Model>
void bond_pass(const Model& model, const Bonds& bonds, const Field<D>& y, Field<D>& f)
{
    const int* partner = bonds.partner.data();
    const std::uint8_t* intact = bonds.intact.data();
    const double* y0 = y.c[0].data();
    const double* y1 = D > 1 ? y.c[1].data() : nullptr;
    const double* y2 = D > 2 ? y.c[2].data() : nullptr;
    parallel_for(bonds.nodes(), [&](std::size_t i) {
        double f0 = 0, f1 = 0, f2 = 0;
        const double yi0 = y0[i], yi1 = D > 1 ? y1[i] : 0, yi2 = D > 2 ? y2[i] : 0;
        const std::int64_t kb = bonds.begin(i), ke = bonds.end(i);
#pragma omp simd reduction(+ : f0, f1, f2)
        for (std::int64_t k = kb; k < ke; ++k) {
            const int j = partner[k];
            const double Y0 = y0[j] - yi0;
            const double Y1 = D > 1 ? y1[j] - yi1 : 0;
            const double Y2 = D > 2 ? y2[j] - yi2 : 0;
            double t = model.bond_scalar(i, k, j, std::sqrt(Y0 * Y0 + Y1 * Y1 + Y2 * Y2));
            if constexpr (Damaged) t *= intact[k];
            f0 += t * Y0;
            f1 += t * Y1;
            f2 += t * Y2;
        }
        f.c[0][i] = f0;
        if constexpr (D > 1) f.c[1][i] = f1;
        if constexpr (D > 2) f.c[2][i] = f2;
    });
}
}  // namespace detail

// f: internal force density at current positions y [N/m^3].
template <int D, class Model>
void internal_force(Model& model, const Bonds& bonds, const Field<D>& y, Field<D>& f)
{
    if (f.size() != y.size()) f.resize(y.size());
    if constexpr (Model::has_point_pass) model.point_pass(bonds, y);
    if (bonds.has_damage())
        detail::bond_pass<true>(model, bonds, y, f);
    else
        detail::bond_pass<false>(model, bonds, y, f);
}

}  // namespace pd
