// pd/models/correspondence_rate_form.hpp -- the rate form of the correspondence model (Law::flanagan_taylor,
// models/rate_form.hpp): the definitions of Correspondence<D>::reset_rate_state, rate_state and
// update_stress, declared and described in models/correspondence.hpp (which includes this file at its
// end). The hypo-elastic update itself is laws/flanagan_taylor.hpp.
#pragma once
#include "pd/models/correspondence.hpp"

namespace pd {

template <int D>
void Correspondence<D>::reset_rate_state()
{
    std::fill(sigma_hat.begin(), sigma_hat.end(), Mat::Zero());
    std::fill(sigma.begin(), sigma.end(), Mat::Zero());
    std::fill(R.begin(), R.end(), Mat::Identity());
    std::fill(V.begin(), V.end(), Mat::Identity());
    std::fill(theta_n.begin(), theta_n.end(), thermal.theta_ref);
    std::fill(stress_work.begin(), stress_work.end(), 0.0);
}

template <int D>
void Correspondence<D>::rate_state(StateArchive& ar)
{
    ar.blocks("correspondence.sigma_hat", sigma_hat), ar.blocks("correspondence.R", R), ar.blocks("correspondence.V", V);
    ar.blocks("correspondence.sigma", sigma);
    ar("correspondence.stress_work", stress_work);
    if (!theta_n.empty()) ar("correspondence.theta_n", theta_n);
}

// Temperature-dependent elasticity (spec/000b sec. 1.7, eqs. 4.38-4.44, V12; the source's
// jc_correspondence): at each update of node i from theta^n to theta^(n+1),
//   s_hat   <- (G^(n+1)/G^n) s_hat,   sigma_H <- (K^(n+1)/K^n) sigma_H     (4.44: sigma_hat = D(theta):eps_hat
//                                                                         kept at fixed strain)
//   then the increment with K^(n+1), G^(n+1) and the thermal strain increment
//   (alpha(theta^n) + alpha(theta^(n+1)))/2 (theta^(n+1) - theta^n)         (exact for a linear alpha(theta)).
// The hourglass force and the stable-step bounds keep par.material.
template <int D>
void Correspondence<D>::set_temperature_dependence(TemperatureDependence t)
{
    if (par.law != Law::flanagan_taylor) throw std::invalid_argument("Correspondence: temperature-dependent elasticity is written for Law::flanagan_taylor");
    if ((t.material || t.alpha) && theta_n.empty())
        throw std::invalid_argument("Correspondence: temperature-dependent elasticity needs the thermal expansion (its temperatures) set first");
    tdep_ = std::move(t);
}

template <int D>
template <int Dy>
void Correspondence<D>::update_stress(const Bonds& b, const Field<Dy>& y, const Field<Dy>& v, double dt)
{
    static_assert(Dy == 3 && D == 3, "Flanagan-Taylor is written for 3D");
    const double K = par.material.K, G = par.material.G;
    const bool damaged = b.has_damage();
    if (damaged) k_formed_.track(b);
    parallel_for(b.nodes(), [&](std::size_t i) {
        Mat N[2];  // F K, Fdot K over intact bonds
        if (damaged) damaged_sums<2>(b, i, {&y, &v}, N);
        else family_sums<false, false, 2>(b, i, {&y, &v}, N, nullptr, nullptr);
        double d_eps_th = 0, th0 = 0, th1 = 0;
        if (!theta_n.empty()) {  // thermal expansion: theta^n -> theta^(n+1), also where K is singular
            th0 = theta_n[i], th1 = (*thermal.theta)[i];
            d_eps_th = (tdep_.alpha ? 0.5 * (tdep_.alpha(th0) + tdep_.alpha(th1)) : thermal.alpha) * (th1 - th0);
            theta_n[i] = th1;
        }
        if (Kinv[i].isZero(0)) return;
        double Ki = K, Gi = G;
        double w0 = elastic_energy(sigma_hat[i], par.material);  // [J/m^3] (stress_work)
        if (tdep_.material) {  // (4.44)
            const Elastic m0 = tdep_.material(th0), m1 = tdep_.material(th1);
            w0 = elastic_energy(sigma_hat[i], m0);
            Ki = m1.K, Gi = m1.G;
            const double pH = sigma_hat[i].trace() / 3;
            sigma_hat[i] *= m1.G / m0.G;
            sigma_hat[i].diagonal().array() += pH * (m1.K / m0.K - m1.G / m0.G);
        }
        F[i] = N[0] * Kinv[i];
        sigma[i] = laws::flanagan_taylor_step(F[i], N[1] * Kinv[i], R[i], V[i], sigma_hat[i], Ki, Gi, dt,  // step 1: Fdot = N[1] K^-1
                                              par.rotation, d_eps_th);
        stress_work[i] += F[i].determinant() * (elastic_energy(sigma_hat[i], {.K = Ki, .G = Gi}) - w0);
    });
}

}  // namespace pd
