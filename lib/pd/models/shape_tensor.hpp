// pd/models/shape_tensor.hpp -- the shape tensor of the correspondence models (mechanics, heat,
// stable-step bounds) and its inverse, in one place:
//   K_i = sum_j omega xi (x) xi V_j over the intact bonds of i            (000b eq. 2.51, "H")
// Singularity rule: K_i counts as singular, and K_i^-1 is taken as 0 (the node then gets no
// correspondence force or flux of its own), when
//   tr K_i <= 0   or   |det K_i| <= singular_K_tolerance (tr K_i / D)^D,
// i.e. when the product of the eigenvalues falls below 1e-12 times that of an isotropic tensor of
// the same trace, so that the rule depends neither on units nor on delta. A family flattened onto a
// plane or a line (too few partners, or bonds broken on one side) has an exactly singular K whose
// computed determinant is round-off, about 1e-16 relative; 1e-12 sits four decades above that.
// The mechanics model sums K together with F in its lane order (correspondence.hpp, family_sums)
// and inverts it with its own copy of inverse_or_zero's three lines: compiled inside the model,
// its K^-1 keeps the bits the model's results were verified with (the compiler contracts the
// cofactor products into FMAs differently in the two places: 1 ulp). shape_tensor() is the plain
// family-order sum of the heat model and the stiffness bounds.
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace pd {

inline constexpr double singular_K_tolerance = 1e-12;  // [-] relative to (tr K / D)^D, see header

// True when K is regular by the rule of the header.
template <class Mat>
bool shape_tensor_regular(const Mat& K)
{
    constexpr int D = Mat::RowsAtCompileTime;
    const double scale = K.trace() / D;
    return scale > 0 && std::abs(K.determinant()) > singular_K_tolerance * std::pow(scale, D);
}

// K^-1, or 0 when K is singular (header).
template <class Mat>
Mat inverse_or_zero(const Mat& K)
{
    constexpr int D = Mat::RowsAtCompileTime;
    const double scale = K.trace() / D;
    const double det = K.determinant();
    return scale > 0 && std::abs(det) > singular_K_tolerance * std::pow(scale, D) ? Mat(K.inverse()) : Mat::Zero();
}

// Which families' K a pass formed, and from which intact flags (the shape-tensor reuse of the damaged
// correspondence passes): track(b) sizes the record for these bonds (2 per bond: never formed; reset
// when the Bonds change), unchanged(b, i) says whether node i's K was formed from its present intact
// flags, formed(b, i) records them (each node writes only its own family's range: thread-safe). A kept
// K^-1 is the one its forming pass summed; another pass may round in the last bit (contractions).
struct ShapeTensorRecord {
    std::vector<std::uint8_t> flags;
    const int* partners = nullptr;

    void track(const Bonds& b)
    {
        if (flags.size() == b.size() && partners == b.partner.data()) return;
        flags.assign(b.size(), 2);  // matches no intact flag: every K is formed once
        partners = b.partner.data();
    }
    bool unchanged(const Bonds& b, std::size_t i) const
    {
        return std::equal(b.intact.begin() + b.begin(i), b.intact.begin() + b.end(i), flags.begin() + b.begin(i));
    }
    void formed(const Bonds& b, std::size_t i)
    {
        std::copy(b.intact.begin() + b.begin(i), b.intact.begin() + b.end(i), flags.begin() + b.begin(i));
    }
};

// K_i over the intact bonds of i, summed in family order, from the reference positions x [m^(D+2)].
template <int D>
Eigen::Matrix<double, D, D> shape_tensor(const Bonds& b, const Field<D>& x, std::size_t i)
{
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    auto xi = [&](int j) {
        Col e;
        for (int d = 0; d < D; ++d) e(d) = x.c[d][j] - x.c[d][i];
        return e;
    };
    Mat K = Mat::Zero();
    for_intact_bonds(b, i, [&](std::int64_t k, int j) { K += b.omega[k] * b.volume[k] * xi(j) * xi(j).transpose(); });
    return K;
}

}  // namespace pd
