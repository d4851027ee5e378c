// PALS multipliers: the two 6x6 least-squares systems per node (spec/000b sec. 1.4 [CODE],
// Peridigm pals.cxx), written in units of the horizon (xi/delta, V/delta^3, multipliers times
// delta^5) so that they do not depend on the length unit. See pals.hpp for the formulas.
#include "pd/models/pals.hpp"

#include <Eigen/Dense>

#include <cmath>

namespace pd {

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Right-hand sides: tr H_j and dev H_j : dev H_j of the six matching deformations.
const Vec6 trace_H = (Vec6() << 1, 1, 1, 0, 0, 0).finished();
const Vec6 devH_devH = (Vec6() << 2.0 / 3, 2.0 / 3, 2.0 / 3, 2, 2, 2).finished();

// Peridigm's degenerate-row threshold, relative to the trace (scale-free).
constexpr double degenerate_row = 1e-15;

// x e_j = xi.H_j xi for xi = (a, b, c): [a^2, b^2, c^2, 2ab, 2ac, 2bc].
Vec6 dilatation_basis(double a, double b, double c)
{
    return (Vec6() << a * a, b * b, c * c, 2 * a * b, 2 * a * c, 2 * b * c).finished();
}

// eps_j = xi.dev(H_j) xi / |xi|: [a^2/r - r/3, b^2/r - r/3, c^2/r - r/3, 2ab/r, 2ac/r, 2bc/r].
Vec6 deviatoric_basis(double a, double b, double c)
{
    const double r = std::sqrt(a * a + b * b + c * c);
    const double r3 = r / 3;
    return (Vec6() << a * a / r - r3, b * b / r - r3, c * c / r - r3, 2 * a * b / r, 2 * a * c / r, 2 * b * c / r).finished();
}

// Solves A x = rhs after Peridigm's degenerate-row rule; returns false (x = 0) when singular.
bool solve6(Mat6 A, Vec6 rhs, PALS::Multipliers& out)
{
    const double tr = A.trace();
    for (int d = 0; d < 6; ++d)
        if (A(d, d) < degenerate_row * tr) {
            A.row(d).setZero();
            A.col(d).setZero();
            A(d, d) = 1;
            rhs(d) = 0;
        }
    Eigen::FullPivLU<Mat6> lu(A);
    out.fill(0.0);
    if (!(tr > 0) || !lu.isInvertible()) return false;
    const Vec6 sol = lu.solve(rhs);
    if (!sol.allFinite()) return false;
    for (int d = 0; d < 6; ++d) out[d] = sol(d);
    return true;
}

}  // namespace

PALS::PALS(const Params& prm, const Body<3>& body, const Bonds& b)
    : K(prm.material.K), G(prm.material.G), delta(b.delta),
      lambda(b.nodes()), tau(b.nodes()), m_sigma(b.nodes(), 0.0), m_omega(b.nodes(), 0.0), theta(b.nodes(), 0.0), p(b.nodes(), 0.0),
      w_i(b.size()), w_j(b.size()), s_i(b.size()), s_j(b.size()), bonds(&b), x(&body.x),
      omega0_base(prm.omega0), sigma0_base(prm.sigma0), length(b.length.data())
{
    // Full-sphere normalisation: (omega0 x)•x = 3 and (sigma0 eps)•eps = dev H : dev H,
    // using <(n_x^2 - 1/3)^2> = 4/45 over the sphere: sigma0 M2 4/45 = 2/3 -> sigma0 = 15/(2 M2).
    omega0_scale = prm.base == Base::unit ? 1.0 : 3.0 / horizon_moment(prm.omega0, 2, delta, 3, 1.0);
    sigma0_scale = prm.base == Base::unit ? 1.0 : 7.5 / horizon_moment(prm.sigma0, 2, delta, 3, 1.0);
    recompute(b);
}

double PALS::omega(std::size_t i, const Vec<3>& xi) const
{
    const double d5 = std::pow(delta, 5);
    const Vec6 q = dilatation_basis(xi[0] / delta, xi[1] / delta, xi[2] / delta);
    double w = omega0_base(norm(xi), delta) * omega0_scale * d5;
    for (int n = 0; n < 6; ++n) w += lambda[i][n] * q(n);
    return w / d5;
}

double PALS::sigma(std::size_t i, const Vec<3>& xi) const
{
    const double d5 = std::pow(delta, 5);
    const Vec6 g = deviatoric_basis(xi[0] / delta, xi[1] / delta, xi[2] / delta).array().square();
    double s = sigma0_base(norm(xi), delta) * sigma0_scale * d5;
    for (int n = 0; n < 6; ++n) s += tau[i][n] * g(n);
    return s / d5;
}

void PALS::recompute(const Bonds& b)
{
    bonds = &b;
    length = b.length.data();
    const std::size_t nn = b.nodes(), nb = b.size();
    lambda.resize(nn); tau.resize(nn); m_sigma.resize(nn); m_omega.resize(nn); theta.resize(nn); p.resize(nn);
    w_i.resize(nb); w_j.resize(nb); s_i.resize(nb); s_j.resize(nb);
    const Field<3>& X = *x;
    const double d3 = delta * delta * delta, d5 = d3 * delta * delta;
    const double w0 = omega0_scale * d5, s0 = sigma0_scale * d5;  // dimensionless scales
    std::vector<std::uint8_t> singular(b.nodes(), 0);
    auto xi_hat = [&](std::size_t i, int j) {
        return Vec<3>{{(X.c[0][j] - X.c[0][i]) / delta, (X.c[1][j] - X.c[1][i]) / delta, (X.c[2][j] - X.c[2][i]) / delta}};
    };
    // 1. Per node: the two systems (4.20) over the intact bonds, in units of delta.
    parallel_for(b.nodes(), [&](std::size_t i) {
        Mat6 A = Mat6::Zero(), Ad = Mat6::Zero();
        Vec6 rhs = trace_H, rhs_d = devH_devH;
        for_intact_bonds(b, i, [&](std::int64_t k, int j) {
            const Vec<3> h = xi_hat(i, j);
            const double V = b.volume[k] / d3;
            const double r = b.length[k];
            const Vec6 q = dilatation_basis(h[0], h[1], h[2]);
            const Vec6 g = deviatoric_basis(h[0], h[1], h[2]).array().square();
            A.noalias() += V * q * q.transpose();        // sum (x e_n)(x e_j) V
            Ad.noalias() += V * g * g.transpose();       // sum eps_n^2 eps_j^2 V
            rhs -= (omega0_base(r, delta) * w0 * V) * q;  // - (omega0 x)•e_j
            rhs_d -= (sigma0_base(r, delta) * s0 * V) * g;  // - (sigma0 eps_j)•eps_j
        });
        const bool ok_w = solve6(A, rhs, lambda[i]);
        const bool ok_s = solve6(Ad, rhs_d, tau[i]);
        singular[i] = !(ok_w && ok_s);
    });
    singular_nodes = 0;
    for (auto s : singular) singular_nodes += s;
    // 2. Per bond: omega and sigma of both ends, and m_sigma = (sigma_i x)•x, m_omega = (omega_i x)•x per node.
    auto omega_hat = [&](std::size_t n, const Vec<3>& h, double r) {
        const Vec6 q = dilatation_basis(h[0], h[1], h[2]);
        double w = omega0_base(r, delta) * w0;
        for (int d = 0; d < 6; ++d) w += lambda[n][d] * q(d);
        return w;
    };
    auto sigma_hat = [&](std::size_t n, const Vec<3>& h, double r) {
        const Vec6 g = deviatoric_basis(h[0], h[1], h[2]).array().square();
        double s = sigma0_base(r, delta) * s0;
        for (int d = 0; d < 6; ++d) s += tau[n][d] * g(d);
        return s;
    };
    parallel_for(b.nodes(), [&](std::size_t i) {
        double ms = 0, mw = 0;
        for_family(b, i, [&](std::int64_t k, int j) {
            const Vec<3> h = xi_hat(i, j);
            const double r = b.length[k];
            const double V = b.volume[k] / d3;  // omega V = omega_hat V_hat / delta^2
            w_i[k] = omega_hat(i, h, r) * V / (delta * delta);
            w_j[k] = omega_hat(j, h, r) * V / (delta * delta);
            const double si = sigma_hat(i, h, r);
            s_i[k] = 2 * G * si * V / (delta * delta);
            s_j[k] = 2 * G * sigma_hat(j, h, r) * V / (delta * delta);
            if (!b.has_damage() || b.intact[k]) ms += si * dot(h, h) * V, mw += omega_hat(i, h, r) * dot(h, h) * V;
        });
        m_sigma[i] = ms;
        m_omega[i] = mw;
    });
#ifdef PD_CHUNK_WIDTH
    runs = b.has_damage() ? TranslatedRuns{} : find_translated_runs(b, detail::chunk_width, {&b.length, &w_i, &w_j, &s_i, &s_j});
#endif
}

}  // namespace pd
