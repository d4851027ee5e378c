// Correspondence model, non-ordinary state-based (Silling et al. 2007; Warren 2009; spec/000b
// sec. 0, 1.5, 1.6 and errata 1-4; spec/000a sec. 2.7, 2.8). Per node i, over intact bonds:
//   shape tensor       K_i = sum_j omega xi (x) xi V_j                      (000b eq. 2.51, "H")
//   deformation grad.  F_i = (sum_j omega Y (x) xi V_j) K_i^-1               (2.50)
//   stress             P_i (first Piola-Kirchhoff) from a point law, below
//   force state        T_i<xi> = omega P_i K_i^-1 xi                         (erratum 1: not P^T)
//   bond force on i    (T_i<xi> - T_j<-xi>) V_j = omega (P_i K_i^-1 + P_j K_j^-1) xi V_j
// Stress laws:
//   Law::linear           small strain: eps = sym(F) - I, sigma = lambda tr(eps) I + 2 G eps, P = sigma
//                         (2D: plane strain, or plane stress with lambda* = 2 lambda G/(lambda + 2G)).
//   Law::saint_venant_kirchhoff  (3D) hyperelastic, objective: E = (F^T F - I)/2, S = lambda tr(E) I + 2 G E,
//                         P = F S = dW/dF, W = lambda tr(E)^2/2 + G E:E (a non-symmetric P: it tests erratum 1).
//   Law::flanagan_taylor  hypoelastic rate form on the unrotated Cauchy stress (3D only), advanced by
//                         update_stress(bonds, y, v, dt) (000b sec. 1.5 [CODE] steps 1-8, errata 2-3):
//                         sigma_hat += (K tr(d) I + 2 G dev(d)) dt, sigma = R sigma_hat R^T, P = J sigma F^-T.
// Littlewood hourglass control (000b sec. 1.6, stabilising sign of erratum 4; the formula once in
// models/hourglass.hpp for the per-node, AVX2 and chunk code), from both ends:
//   t_hg = C_hg c ((y_j - y_i - F xi) . M)/|xi| M,  M = Y/|Y|,  c = PMB micromodulus (18K/(pi delta^4) in 3D),
//   summed with F = F_i (bond i->j) and F = F_j (bond j->i): on i, C_hg c V_j ((2Y - (F_i + F_j) xi).M)/|xi| M.
//   No omega factor (as Peridigm). C_hg = 0 (default) switches it off; the source uses 0.02.
//   HourglassDirection::bond (Peridigm's form): along Y instead of M, i.e. times |Y| (the force then
//   carries an extra length in the input's unit).
// Thermal expansion (models/thermal_expansion.hpp, set_thermal_expansion; spec/000a sec. 2.11, V7), with
// eps_i = alpha (theta_i - theta_ref) of node i:
//   Law::linear           sigma = lambda tr(eps - eps_i I) I + 2 G (eps - eps_i I) = sigma(eps) - (D lambda + 2 G) eps_i I
//                         (3D: 3 K eps_i; 2D plane stress: E/(1 - nu) eps_i; 2D plane strain is refused);
//   Law::flanagan_taylor  the strain increment of each update_stress less alpha (theta^(n+1) - theta^n) I (eq. 2.81),
//                         theta^n the temperature of node i at the previous update (theta_ref before the first:
//                         a body that starts at theta != theta_ref and y = x is then under the same -3 K eps_i as
//                         the linear law; the rate form knows no other reference). theta^n is rate state.
//                         K, G and alpha of theta: set_temperature_dependence (correspondence_rate_form.hpp).
//   Law::saint_venant_kirchhoff refuses it.
// The free body y = (1 + eps) x carries no stress in the linear law; in the rate form sum d dt = ln(1 + eps),
// so sigma_hat is 3 K (ln(1 + eps) - eps) = O(K eps^2) there.
// A node whose K is singular (fewer than D independent intact bonds; the rule of models/shape_tensor.hpp)
// gets K^-1 = 0 and F = I: no stress force.
// Usage: internal_force(model, bonds, y, f) (bond_loop.hpp) runs point_pass (K on damage, F, P) and the
// bond pass. With Law::flanagan_taylor call update_stress(bonds, y, v, dt) once per step (Explicit does), then
// internal_force at y_np1. Pass v = v_nph = (y_np1 - y_n)/dt with the mid-step configuration y = (y_n + y_np1)/2:
// L = Fdot F^-1 is then exactly skew for a rigid rotation (Cayley), so no spurious stress. Peridigm pairs v_nph
// with y_np1: a spurious expansion N (1 - cos(theta/N)) per rotation theta in N steps (2.8e-2 K of stress for
// 90 degrees in 100 steps; tests/test_correspondence_flanagan_taylor.cpp).
// Cost (reports/3d/model_cost.md): family sums are lane sums in the bond-loop order; the
// i-end force P_i K_i^-1 sum_j omega xi V_j is summed once per node (node_force); the bond kernel
// reads P_j K_j^-1 and F_j (18 values per bond). 3D with AVX2/FMA: vectorised within the bond
// (correspondence_simd.hpp, `blocks`); undamaged, nodes with translated families (translated_families.hpp)
// take both passes W at a time (correspondence_chunks.hpp, `soa`). Damaged: K and m are formed again
// only for the families whose intact flags changed (ShapeTensorRecord, shape_tensor.hpp). The rate
// form's member definitions are in correspondence_rate_form.hpp.
#pragma once
#include "pd/bond_loop.hpp"
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/influence.hpp"
#include "pd/core/lattice.hpp"
#include "pd/laws/elastic.hpp"
#include "pd/laws/flanagan_taylor.hpp"
#include "pd/core/material.hpp"
#include "pd/models/correspondence_chunks.hpp"
#include "pd/models/correspondence_kernel.hpp"
#include "pd/models/correspondence_simd.hpp"
#include "pd/models/pmb.hpp"
#include "pd/models/shape_tensor.hpp"
#include "pd/models/thermal_expansion.hpp"
#include "pd/core/parallel.hpp"
#include "pd/core/state_archive.hpp"
#include "pd/simd/translated_families.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <mutex>
#include <new>
#include <stdexcept>
#include <vector>

namespace pd {

// Direction of the Littlewood hourglass force (header): unit = M = Y/|Y|, bond = Y (Peridigm).
enum class HourglassDirection { unit, bond };

template <int D>
struct Correspondence {
    static_assert(D == 2 || D == 3, "correspondence is written for 2D and 3D");
    static constexpr bool has_point_pass = true;
    static constexpr bool ordinary = false;
    static constexpr int DD = D * D;            // entries of a D x D matrix
    static constexpr int DK = D * (D + 1) / 2;  // upper triangle of the symmetric K
    using Mat = Eigen::Matrix<double, D, D>;
    using Col = Eigen::Matrix<double, D, 1>;
    static_assert(sizeof(Mat) == DD * sizeof(double), "the bond kernel reads std::vector<Mat> as D x D column-major blocks");
    enum class Law { linear, saint_venant_kirchhoff, flanagan_taylor };
    struct Params {
        Elastic material;
        Law law = Law::linear;
        double C_hg = 0;               // Littlewood hourglass coefficient [-]; 0 = off, source 0.02
        Plane plane = Plane::strain;   // 2D reduction of the linear law
        double measure = 1;            // 2D thickness [m] (hourglass micromodulus only)
        HourglassDirection hourglass_direction = HourglassDirection::unit;  // header
        laws::RotationIncrement rotation = laws::RotationIncrement::rodrigues;  // Law::flanagan_taylor (laws/flanagan_taylor.hpp)
        // F, sigma, P, PKinv of every node after each point pass (default). false: the chunked point
        // pass (3D, Law::linear, no damage) leaves those of chunk nodes in its own arrays until
        // sync_node_matrices() (energy_density and a bond pass that needs them call it): for runs
        // that read only forces and energies; saves their memory traffic (~6 % of a step).
        bool node_matrices = true;
    };

    Params par;
    double lambda = 0;                // Lame constant of the (reduced) linear law [Pa]
    double c_hg = 0;                  // C_hg times the PMB micromodulus [N/m^6 in 3D]
    Field<D> x;                       // reference positions [m]
    std::vector<double> wV;           // omega V_j per bond [m^3]
    std::vector<double> hg;           // c_hg V_j / |xi| per bond [N/m^4 in 3D]; empty when C_hg = 0
    Field<D> m_xi;                    // sum_j omega xi V_j over intact bonds [m^4 in 3D] (0 for a full family)
    Field<D> f_own;                   // P_i K_i^-1 m_xi: the i-end force summed over the family [N/m^3]
    std::vector<Mat> Kinv;            // K_i^-1 [m^-5 in 3D]
    // Per node (mutable: sync_node_matrices fills them in on demand, Params::node_matrices):
    mutable std::vector<Mat> F;       // deformation gradient [-]
    mutable std::vector<Mat> sigma;   // Cauchy stress [Pa] (Law::linear: the small-strain stress)
    mutable std::vector<Mat> P;       // first Piola-Kirchhoff stress [Pa]
    mutable std::vector<Mat> PKinv;   // P_i K_i^-1 [Pa/m^5 in 3D]
    mutable bool matrices_partial = false;  // chunk nodes' F, sigma, P, PKinv not written (node_matrices = false)
    std::vector<Mat> sigma_hat, R, V; // Flanagan-Taylor: unrotated stress [Pa], rotation, left stretch [-]
    // Flanagan-Taylor: the stored energy as the integrated stress power [J/m^3 of the reference]: each
    // update adds J (w(sigma_hat after) - w(sigma_hat before)), w = 1/2 sigma_hat : C^-1 : sigma_hat =
    // tr^2/(18 K) + s_hat : s_hat/(4 G) with the moduli of the node's temperature, J = det F at the
    // update's configuration (the discrete P : Fdot = J sigma : d).
    std::vector<double> stress_work;
    std::vector<double> theta_n;      // Flanagan-Taylor with thermal expansion: theta^n of each node (header) [K]
    // P K^-1 [Pa/m^5] and F [-] per node for the bond kernel (3D, correspondence_simd.hpp: 24 doubles
    // per node, 64-byte aligned). The chunk path writes them only where the per-node kernels of that
    // pass read them (block_read); a bond pass that reads all completes them first (with_kernel).
    using Aligned64 = detail::Aligned64;
    mutable std::vector<double, Aligned64> blocks;
    mutable bool blocks_partial = false;
    std::vector<std::uint8_t> block_read;  // per node: read by the per-node kernels of an undamaged pass
    std::vector<double, Aligned64> xpad, ypad;  // x [m] (set-up) and y [m] (point_pass), 4-padded per node (3D)
    static constexpr int BS = detail::correspondence_block;  // doubles per node block (24)
    // The families whose K and m a damaged pass (point pass or Flanagan-Taylor update) formed, and from
    // which intact flags: an unchanged family keeps its K^-1 and m, the pass sums N only (shape_tensor.hpp).
    ShapeTensorRecord k_formed_;
    // Chunks of translated families (translated_families.hpp; 3D with AVX2 or AVX-512, undamaged scenes):
    // the bond pass and the deformation sums take W nodes at once (correspondence_chunks.hpp), reading
    // A = P K^-1 and F from `soa` (18 arrays of soa_n doubles, written by point_pass).
    TranslatedRuns runs;
    std::vector<double> soa;
    std::size_t soa_n = 0;  // stride of soa and kinv_soa [doubles] (detail::soa_stride)
#ifdef PD_CHUNK_WIDTH
    detail::ChunkTemplates templates;
    std::vector<double> kinv_soa;          // K^-1 as 9 arrays (chunks, Law::linear)
    std::vector<std::uint8_t> regular;     // per chunk: every lane has K^-1 != 0
#endif

    Correspondence() = default;
    Correspondence(const Params& p, const Body<D>& body, const Bonds& b)
        : par(p), x(body.x), wV(b.size()), m_xi(b.nodes()), f_own(b.nodes()), Kinv(b.nodes(), Mat::Zero()), F(b.nodes(), Mat::Identity()),
          sigma(b.nodes(), Mat::Zero()), P(b.nodes(), Mat::Zero()), PKinv(b.nodes(), Mat::Zero())
    {
        if (D != 3 && p.law != Law::linear) throw std::invalid_argument("Correspondence: only Law::linear is written for 2D");
        const double K = p.material.K, G = p.material.G;
        lambda = K - 2 * G / 3;
        if (D == 2 && p.plane == Plane::stress) lambda = 2 * lambda * G / (lambda + 2 * G);
        c_hg = p.C_hg * pmb_micromodulus(kappa_dim(p.material, D, p.plane), D,
                                         horizon_moment(Influence{}, 1, b.delta, D, p.measure));
        for (std::size_t k = 0; k < b.size(); ++k) wV[k] = b.omega[k] * b.volume[k];
        if (c_hg != 0) {
            hg.resize(b.size());
            for (std::size_t k = 0; k < b.size(); ++k) hg[k] = c_hg * b.volume[k] / b.length[k];
        }
        if (p.law == Law::flanagan_taylor) {
            sigma_hat.assign(b.nodes(), Mat::Zero());
            stress_work.assign(b.nodes(), 0.0);
            R.assign(b.nodes(), Mat::Identity());
            V.assign(b.nodes(), Mat::Identity());
        }
        if constexpr (D == 3) {
            blocks.assign(BS * b.nodes(), 0.0);
            xpad.assign(4 * b.nodes(), 0.0);
            ypad.assign(4 * b.nodes(), 0.0);
            for (std::size_t i = 0; i < b.nodes(); ++i)
                for (int d = 0; d < D; ++d) xpad[4 * i + d] = x.c[d][i];
#ifdef PD_CHUNK_WIDTH
            const std::initializer_list<const std::vector<double>*> xc{&x.c[0], &x.c[1], &x.c[2]};
            runs = c_hg != 0 ? find_translated_runs(b, detail::chunk_width, {&wV, &hg}, xc) : find_translated_runs(b, detail::chunk_width, {&wV}, xc);
            if (!runs.chunk_start.empty()) {
                soa_n = detail::soa_stride(b.nodes());
                soa.assign(18 * soa_n, 0.0);
                templates = detail::chunk_templates(runs, b, x, wV, hg);
            }
#endif
        }
        shape_tensors(b);
#ifdef PD_CHUNK_WIDTH
        if (!soa.empty()) detail::chunk_node_data(runs, b, Kinv, kinv_soa, regular, block_read);
#endif
    }

    // Thermal expansion (header); ThermalExpansion{} switches it off. Throws std::invalid_argument for
    // Law::saint_venant_kirchhoff, 2D plane strain, or a temperature vector of another length.
    void set_thermal_expansion(const ThermalExpansion& t)
    {
        t.validate(F.size(), D == 2 && par.plane == Plane::strain);
        if (t.active() && t.bond_mean)
            throw std::invalid_argument("Correspondence: its thermal strain is a node's (bond_mean is for the ordinary models)");
        if (t.active() && par.law == Law::saint_venant_kirchhoff)
            throw std::invalid_argument("Correspondence: thermal expansion is not written for Law::saint_venant_kirchhoff");
        thermal = t;
        theta_n.clear();
        if (t.active() && par.law == Law::flanagan_taylor) theta_n.assign(F.size(), t.theta_ref);
    }
    const ThermalExpansion& thermal_expansion() const { return thermal; }
    // Temperature-dependent Flanagan-Taylor elasticity (correspondence_rate_form.hpp); needs the thermal
    // expansion (its temperatures and theta^n). Empty functions: back to par.material and thermal.alpha.
    struct TemperatureDependence {
        std::function<Elastic(double theta)> material;  // K(theta), G(theta)
        std::function<double(double theta)> alpha;      // linear expansion coefficient [1/K]
    };
    void set_temperature_dependence(TemperatureDependence t);
    // (D lambda + 2 G) eps_i: the stress of the linear law held at the free thermal strain of node i [Pa]
    // (the chunk kernels' operations, detail::ChunkThermal).
    double thermal_pressure(std::size_t i) const { return (D * lambda + 2 * par.material.G) * (thermal.alpha * ((*thermal.theta)[i] - thermal.theta_ref)); }

    Col xi(std::size_t i, int j) const
    {
        Col r;
        for (int d = 0; d < D; ++d) r(d) = x.c[d][j] - x.c[d][i];
        return r;
    }

    // Family sums of node i over its intact bonds (N of NZ fields, and K, m when WithK), in the lane
    // order of bond_loop.hpp; damaged_sums forms K^-1 and m again only where the family's intact flags
    // changed (k_formed_). Defined in correspondence_point_pass.hpp.
    template <int NZ>
    [[gnu::always_inline]] inline void damaged_sums(const Bonds& b, std::size_t i, const std::array<const Field<D>*, NZ>& z, Mat* N);
    template <bool Damaged, bool WithK, int NZ>
    void family_sums(const Bonds& b, std::size_t i, const std::array<const Field<D>*, NZ>& z, Mat* N, Mat* K, Col* m) const;

    // K^-1, or 0 when K is singular: pd::inverse_or_zero's rule (models/shape_tensor.hpp, which says
    // why this copy is kept).
    static Mat inverse_or_zero(const Mat& K)
    {
        const double scale = K.trace() / D;
        const double det = K.determinant();
        return scale > 0 && std::abs(det) > singular_K_tolerance * std::pow(scale, D) ? Mat(K.inverse()) : Mat::Zero();
    }

    // K_i^-1 over intact bonds (000b eq. 2.51).
    void shape_tensors(const Bonds& b)
    {
        parallel_for(b.nodes(), [&](std::size_t i) {
            Mat K;
            Col m;
            if (b.has_damage()) family_sums<true, true, 0>(b, i, {}, nullptr, &K, &m);
            else family_sums<false, true, 0>(b, i, {}, nullptr, &K, &m);
            Kinv[i] = inverse_or_zero(K);
            for (int d = 0; d < D; ++d) m_xi.c[d][i] = m(d);
        });
    }

    // sum_j omega z (x) xi V_j K_i^-1 over intact bonds, z = field difference z_j - z_i (F from y, Fdot from v).
    Mat gradient(const Bonds& b, std::size_t i, const Field<D>& z) const
    {
        Mat N;
        if (b.has_damage()) family_sums<true, false, 1>(b, i, {&z}, &N, nullptr, nullptr);
        else family_sums<false, false, 1>(b, i, {&z}, &N, nullptr, nullptr);
        return N * Kinv[i];
    }

    // The point laws (laws/elastic.hpp): Saint Venant-Kirchhoff S(E), E = (F^T F - I)/2, and the
    // small-strain sigma(eps), eps = sym(F) - I, both lambda tr(e) I + 2 G e.
    Mat svk_stress(const Mat& Fi) const { return laws::lame_stress(laws::green_lagrange(Fi), lambda, par.material.G); }
    Mat linear_stress(const Mat& Fi) const { return laws::lame_stress(laws::small_strain(Fi), lambda, par.material.G); }

    // K^-1 (after damage, in the same pass over the bonds as F, for the families whose intact flags changed
    // since it was last formed), F, then P and P K^-1.
    // Law::linear: P = sigma(F). Law::saint_venant_kirchhoff: P = F S, sigma = P F^T / J.
    // Law::flanagan_taylor: P = J sigma F^-T with the sigma of the last update_stress.
    template <int Dy>
    void point_pass(const Bonds& b, const Field<Dy>& y)
    {
        static_assert(Dy == D);
        if (b.has_damage()) stress_pass<true>(b, y);
        else stress_pass<false>(b, y);
    }

    // After a point pass: P = J sigma F^-T, P K^-1 and the i-end forces again from sigma as a caller
    // has set it since, F as the pass left it (Law::flanagan_taylor; the plasticity wrapper sets sigma
    // from F by its return, and this spares it a second family traversal). Bit for bit what a second
    // point_pass at the same y gives.
    void stress_from_sigma()
    {
        if (par.law != Law::flanagan_taylor) throw std::logic_error("Correspondence::stress_from_sigma: the given-stress law only");
        parallel_for(F.size(), [&](std::size_t i) {
            if (!Kinv[i].isZero(0)) node_stress_at_F(i);
        });
    }

    // The bond kernel (models/correspondence_kernel.hpp), with the hourglass term compiled in or out.
    template <bool Hourglass, bool AlongBond = false>
    using Kernel = CorrespondenceKernel<D, Hourglass, AlongBond>;
    template <bool Hourglass, bool AlongBond = false>
    Kernel<Hourglass, AlongBond> kernel() const
    {
        Kernel<Hourglass, AlongBond> kn{};
        for (int d = 0; d < D; ++d) { kn.x[d] = x.c[d].data(); kn.f_own[d] = f_own.c[d].data(); }
        kn.wV = wV.data();
        kn.hg = Hourglass ? hg.data() : nullptr;
        kn.A = PKinv.empty() ? nullptr : PKinv.front().data();
        kn.F = F.empty() ? nullptr : F.front().data();
        kn.blk = blocks.empty() ? nullptr : blocks.data();
        kn.runs = soa.empty() ? nullptr : &runs;
        kn.soa = soa.empty() ? nullptr : soa.data();
        kn.soa_n = soa_n;
#ifdef PD_CHUNK_WIDTH
        kn.templates = &templates;
#endif
        return kn;
    }
    // Calls pass(kernel) with the hourglass term compiled in or out (bond_loop.hpp), after
    // completing the blocks when this pass's per-node kernels read every node.
    template <class Pass>
    void with_kernel(Pass&& pass, const Bonds& b) const
    {
        if (blocks_partial && (b.has_damage() || !runs.fits(b))) {
            sync_node_matrices();
            parallel_for(F.size(), [&](std::size_t i) { write_node_block(i); });
            blocks_partial = false;
        }
        if (c_hg == 0) pass(kernel<false>());
        else if (par.hourglass_direction == HourglassDirection::unit) pass(kernel<true>());
        else pass(kernel<true, true>());
    }

    // F, sigma, P and PKinv of the chunk nodes a point pass with node_matrices = false left in its
    // own arrays (no-op otherwise): F and P K^-1 from soa, sigma by the chunk's formula
    // (laws::small_strain_stress), P = sigma. Safe from parallel code: the first caller
    // fills them in, the others wait for it.
    void sync_node_matrices() const
    {
#ifdef PD_CHUNK_WIDTH
        std::atomic_ref<bool> partial(matrices_partial);
        if (!partial.load(std::memory_order_acquire)) return;
        static std::mutex m;
        const std::lock_guard<std::mutex> lock(m);
        if (!partial.load(std::memory_order_relaxed)) return;
        if constexpr (D == 3)
            detail::sync_chunk_matrices(runs, regular, block_read, soa.data(), soa_n, lambda, par.material.G, chunk_thermal(), F, PKinv, sigma, P);
        partial.store(false, std::memory_order_release);
#endif
    }

    // Force density on i from bond k (i -> j), both ends' states included [N/m^3]: the kernel's
    // plus the i-end term omega V_j P_i K_i^-1 xi of this bond.
    Vec<D> bond_force(std::size_t i, std::int64_t k, int j, const Vec<D>& Y) const
    {
        sync_node_matrices();  // the kernel reads F and P K^-1 of both nodes
        Vec<D> f = c_hg == 0 ? kernel<false>().bond_force(i, k, j, Y)
                   : par.hourglass_direction == HourglassDirection::unit ? kernel<true>().bond_force(i, k, j, Y)
                                                                         : kernel<true, true>().bond_force(i, k, j, Y);
        const Col own = wV[k] * (PKinv[i] * xi(i, j));
        for (int d = 0; d < D; ++d) f[d] += own(d);
        return f;
    }

    // Energy density W_i [J/m^3]; call after point_pass. Law::saint_venant_kirchhoff: the exact
    // W = lambda tr(E)^2/2 + G E:E. Law::linear: 1/2 sigma : eps, eps = sym(F) - I less the free
    // thermal strain eps_i I (exact). Law::flanagan_taylor: stress_work, the stress power J sigma : d
    // that the force's work supplies, integrated over the updates (a hypo-elastic law has no W(F);
    // 1/2 sigma : eps(F) does not follow the integrated stress). Hourglass energy not included (its
    // work is integrated, time/verlet.hpp).
    template <int Dy>
    std::vector<double> energy_density(const Bonds& b, const Field<Dy>&) const
    {
        sync_node_matrices();
        std::vector<double> W(b.nodes(), 0.0);
        for (std::size_t i = 0; i < b.nodes(); ++i) {
            if (par.law == Law::flanagan_taylor) {
                W[i] = stress_work[i];
                continue;
            }
            Mat eps = par.law == Law::saint_venant_kirchhoff ? laws::green_lagrange(F[i]) : laws::small_strain(F[i]);
            eps.diagonal().array() -= thermal.strain(i);  // the mechanical strain (0 without thermal expansion)
            const Mat stress = par.law == Law::saint_venant_kirchhoff ? svk_stress(F[i]) : sigma[i];
            W[i] = 0.5 * (stress.array() * eps.array()).sum();
        }
        return W;
    }

    // RateFormModel (models/rate_form.hpp): the stress of this instance needs update_stress each step.
    bool rate_form() const { return par.law == Law::flanagan_taylor; }
    // w of stress_work: the elastic energy of an unrotated stress with the moduli m [J/m^3].
    static double elastic_energy(const Mat& sh, const Elastic& m)
    {
        const double p3 = sh.trace();  // 3 x the mean stress [Pa]
        Mat s = sh;
        s.diagonal().array() -= p3 / 3;
        return p3 * p3 / (18 * m.K) + (s.array() * s.array()).sum() / (4 * m.G);
    }
    // Back to the reference state of the rate form (sigma_hat = sigma = 0, R = V = I): after Peridigm's
    // first evaluation (scene.hpp, RateFormPairing::initial_velocity_step).
    void reset_rate_state();
    // The rate form's history for a checkpoint (core/state_archive.hpp): sigma_hat, R, V and the
    // sigma of the last update (and theta^n with thermal expansion); a point pass at the restored
    // positions then rebuilds F and P.
    void rate_state(StateArchive& ar);
    // Flanagan-Taylor update (3D): from F at y and Fdot at v, advance R, V, sigma_hat by dt [s]
    // and set sigma = R sigma_hat R^T (laws/flanagan_taylor.hpp; 000b sec. 1.5 [CODE] steps 1-8), with
    // the thermal strain increment alpha (theta - theta^n) of the temperatures now (header).
    template <int Dy>
    void update_stress(const Bonds& b, const Field<Dy>& y, const Field<Dy>& v, double dt);

private:
    ThermalExpansion thermal;  // header; inactive by default (set_thermal_expansion)
    TemperatureDependence tdep_;  // set_temperature_dependence

#ifdef PD_CHUNK_WIDTH
    detail::ChunkThermal chunk_thermal() const
    {
        if (!thermal.active()) return {};
        return {thermal.theta->data(), D * lambda + 2 * par.material.G, thermal.alpha, thermal.theta_ref};
    }
#endif

    // The point pass (correspondence_point_pass.hpp): the deformation sums of every node by the
    // chunk, AVX2 or lane path, then node_stress (F = N K^-1, the stress law, P K^-1, the i-end force,
    // the blocks the bond kernels read).
    template <bool Damaged, int Dy>
    void stress_pass(const Bonds& b, const Field<Dy>& y);
#ifdef PD_CHUNK_WIDTH
    void chunk_linear_stress(int i0, const double (*N)[detail::chunk_width]);
#endif
    void node_stress(std::size_t i, const Mat& N);
    void node_stress_at_F(std::size_t i);
#ifdef PD_CORRESPONDENCE_AVX2
    Mat deformation_sum(const Bonds& b, std::size_t i) const;
#endif
    void write_block(std::size_t i);
    void write_node_block(std::size_t i) const;
};

}  // namespace pd

#include "pd/models/correspondence_point_pass.hpp"  // the point pass's member definitions
#include "pd/models/correspondence_rate_form.hpp"  // the rate form's member definitions
