// pd/laws/flanagan_taylor.hpp -- the hypoelastic large-rotation update of Flanagan and Taylor for
// one material point (knows nothing of bonds; spec/000b sec. 1.5 [CODE] steps 2-8 with errata 2-3,
// spec/000a sec. 2.7). From F and Fdot at the point:
//   L = Fdot F^-1, D = sym L, W = skew L;  omega = w + (tr(V) I - V)^-1 z,  z_i = eps_ijk (V D)_jk
//   R <- exp(dt Omega) R (Rodrigues),  V <- V + dt (L V - V Omega)
//   d = R^T D R,  sigma_hat <- sigma_hat + dt (K tr(d) I + 2 G dev(d)) - 3 K d_eps_th I,  sigma = R sigma_hat R^T.
// d_eps_th = alpha (theta^(n+1) - theta^n) is the free thermal strain increment of the step (spec/000a
// eq. 2.81: D : (d dt - alpha dtheta I), isotropic alpha; 0 without thermal expansion).
// R, V and the unrotated stress sigma_hat are the point's state; returns sigma [Pa].
// RotationIncrement::peridigm: Q = I + sin(dt |om|)/|om| Om - (1 - cos(dt |om|))/|om|^2 Om^2, the sign
// of Peridigm's code (reference/peridigm_cloud/README.md); Q is then not exactly orthogonal
// (|Q^T Q - I| ~ (dt |om|)^2). The default is the exact exponential (Rodrigues, plus sign).
#pragma once
#include "pd/laws/elastic.hpp"

#include <cmath>

namespace pd::laws {

enum class RotationIncrement { rodrigues, peridigm };

inline Mat3 flanagan_taylor_step(const Mat3& F, const Mat3& Fdot, Mat3& R, Mat3& V, Mat3& sigma_hat, double K, double G, double dt,
                                 RotationIncrement rotation = RotationIncrement::rodrigues, double d_eps_th = 0)
{
    using Col = Eigen::Vector3d;
    const Mat3 L = Fdot * F.inverse();                    // step 2
    const Mat3 Dr = 0.5 * (L + L.transpose()), Wr = 0.5 * (L - L.transpose());
    const Mat3 VD = V * Dr;                               // step 3: z_i = eps_ijk (V D)_jk
    const Col z(VD(1, 2) - VD(2, 1), VD(2, 0) - VD(0, 2), VD(0, 1) - VD(1, 0));
    const Col w(Wr(2, 1), Wr(0, 2), Wr(1, 0));            // axial vector, W a = w x a
    const Col om = w + (V.trace() * Mat3::Identity() - V).inverse() * z;  // step 4
    Mat3 Om;                                              // Om a = om x a
    Om << 0, -om(2), om(1), om(2), 0, -om(0), -om(1), om(0), 0;
    const double o2 = om.squaredNorm();
    Mat3 Q = Mat3::Identity();                            // step 5: Q = exp(dt Om), Rodrigues
    if (o2 > 1e-30) {
        const double o = std::sqrt(o2);
        const double sign = rotation == RotationIncrement::rodrigues ? 1.0 : -1.0;
        Q += std::sin(dt * o) / o * Om + sign * (1 - std::cos(dt * o)) / o2 * Om * Om;
    }
    R = Q * R;                                            // step 6
    V += dt * (L * V - V * Om);                           // step 7
    const Mat3 d = R.transpose() * Dr * R;                // step 8
    const double tr = d.trace();                          // erratum 2: K tr(d)
    sigma_hat += dt * (K * tr * Mat3::Identity() + 2 * G * (d - tr / 3 * Mat3::Identity()));
    if (d_eps_th != 0) sigma_hat.diagonal().array() -= 3 * K * d_eps_th;  // eq. 2.81
    return R * sigma_hat * R.transpose();                 // erratum 3
}

}  // namespace pd::laws
