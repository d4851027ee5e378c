// reference/lps_shear.hpp -- LPS kinematics of one node under a homogeneous pure shear, written out
// by hand and independent of the peridynamics library (the reference of the viscoelastic drivers
// problems/3d/viscoelastic_relaxation.cpp and numerical_viscosity.cpp).
// Family of node i: every other point with |xi| <= delta (1 + 1e-10) (the horizon rule of
// pd::build_bonds), influence omega = 1, full volumes V_j. Under y = (I + (gamma/2)(e_x e_y + e_y e_x)) x:
//   m = sum |xi|^2 V_j,  e = |Y| - |xi|,  theta = (3/m) sum |xi| e V_j,  e_d = e - theta |xi|/3   (LPS 4.8-4.9)
//   alpha = 15 G / m                                                                       (4.13)
#pragma once
#include <array>
#include <cmath>
#include <vector>

namespace pd::ref {

struct LpsShearFamily {
    double alpha = 0;          // 15 G / m [Pa/m^5]
    double theta = 0;          // dilatation [-]
    std::vector<int> partner;  // j of each family bond
    std::vector<double> ed;    // deviatoric extension e_d of each bond [m]
};

// x: reference positions [m]; V: volumes [m^3]; i: the node; delta: horizon [m]; G [Pa]; gamma: shear [-].
inline LpsShearFamily lps_shear_family(const std::vector<std::array<double, 3>>& x, const std::vector<double>& V, int i,
                                       double delta, double G, double gamma)
{
    LpsShearFamily f;
    std::vector<double> L, e;
    double m = 0, s = 0;
    for (int j = 0; j < static_cast<int>(x.size()); ++j) {
        if (j == i) continue;
        const double X = x[j][0] - x[i][0], Y = x[j][1] - x[i][1], Z = x[j][2] - x[i][2];
        const double len = std::sqrt(X * X + Y * Y + Z * Z);
        if (len > delta * (1 + 1e-10)) continue;
        const double y_len = std::sqrt(std::pow(X + 0.5 * gamma * Y, 2) + std::pow(Y + 0.5 * gamma * X, 2) + Z * Z);
        f.partner.push_back(j), L.push_back(len), e.push_back(y_len - len);
        m += len * len * V[j];
        s += len * (y_len - len) * V[j];
    }
    f.alpha = 15 * G / m;
    f.theta = 3 * s / m;
    for (std::size_t k = 0; k < L.size(); ++k) f.ed.push_back(e[k] - f.theta * L[k] / 3);
    return f;
}

}  // namespace pd::ref
