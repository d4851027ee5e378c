// problems/3d/hourglass_modes.cpp -- zero-energy (hourglass) modes of the correspondence model:
// eigenvalues of the stiffness matrix of a small free cube, with and without Littlewood control,
// beside PMB, LPS and PALS (issue 3).
// Case: n^3 cubic lattice (default 6^3), dx = 1 mm, delta = 3.05 dx, E = 200 GPa, nu = 0.3, free
// boundary, reference configuration; 2D: n2^2 square, plane strain, correspondence and LPS.
// Stiffness K = -d(f_i V_i)/du_j [N/m] by central differences of the nodal internal forces (step
// --h times dx); eigenvalues of (K + K^T)/2 (Eigen, dense), asymmetry ||K - K^T||_F / ||K||_F.
// Source: spec/000a sec. 2.7-2.8 (hourglass modes), spec/000b sec. 1.5-1.6 (Littlewood control,
// C_hg = 0.02 in the source).
// References (never the model under test): 6 rigid-body modes in 3D, 3 in 2D (theory), and K r = 0
// for the analytic rigid modes r; the PMB pair-spring matrix K_ij = -c V_i V_j n n^T / |xi|,
// c = 18K/(pi delta^4) (reference/pmb_pair_stiffness.hpp), for the finite-difference assembly.
// Test fields: problems/common/analysis/staggered_modes.hpp.
// Compared: zero modes beyond the rigid ones (|lambda| < --zero-tol lambda_max); soft modes (below
// 1/10 of the softest non-rigid eigenvalue of the reference pair-spring matrix of the same body:
// PMB springs of the same bulk modulus, c = 18 K/(pi delta^4) in 3D and 12 kappa/(pi h delta^3) in
// plane strain, kappa = K + G/3, h the thickness; written out pair by pair in
// reference/pmb_pair_stiffness.hpp, no library model); the smallest non-rigid eigenvalues; Rayleigh
// quotients of the checkerboard u = (-1)^(a+b+c) e_x, plain and under a bubble envelope, and of
// the bubble alone; the checkerboard energy density at full-family nodes (n >= 7); the share of
// the enveloped staggered patterns (-1)^(k.a), k in {0,1}^D, inside the soft subspace.
// Run: hourglass_modes_3d [--n 6] [--n2 12] [--chg 0,0.002,0.02,0.2] [--model all|pmb|lps|pals|
//      correspondence] [--zero-tol 1e-8] [--h 1e-5] [--quick] [--check] [--out DIR]
// Writes: modes.csv (one row per model), eigenvalues.csv (lowest --spectrum per model), summary.csv,
// params.csv.
#include "problems/common/analysis/staggered_modes.hpp"
#include "problems/common/analysis/stiffness_matrix.hpp"
#include "pd/io/case.hpp"
#include "pd/io/guarded_main.hpp"
#include "pd/io/list_option.hpp"
#include "pd/core/timer.hpp"
#include "pd/models/registry.hpp"
#include "reference/pmb_pair_stiffness.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace {

using Mat = Eigen::MatrixXd;
constexpr double soft_factor = 0.1;  // soft mode: below this times the softest mode of the reference springs

struct Modes : pd::StiffnessSpectrum {  // lambda, vectors, lambda_max, asymmetry, rigid_residual, rigid, negative
    std::string model;
    int dim = 3, dofs = 0, zero_extra = 0, soft = -1;
    double C_hg = NAN, wall_s = 0;
    double rq[3] = {};          // Rayleigh quotients u^T K u / u^T u of the three test fields [N/m]
    double interior_W = NAN;    // max W over full-family nodes under the checkerboard / (E (a/dx)^2 / 2)
    double in_soft = NAN;       // mean fraction of the enveloped {0, pi}^D patterns inside the soft subspace
    double rel(int k) const { return lambda(k) / lambda_max; }
};

// Spectrum of the symmetric part, zero-mode count, rigid-mode residual (pd::stiffness_spectrum),
// Rayleigh quotients of the test fields.
template <int D>
Modes analyse(const Mat& K, const pd::Body<D>& body, double zero_tol)
{
    Modes m;
    static_cast<pd::StiffnessSpectrum&>(m) = pd::stiffness_spectrum(K, body, zero_tol);
    m.dim = D;
    m.dofs = static_cast<int>(K.rows());
    m.zero_extra = m.zero - m.rigid;
    const Mat S = 0.5 * (K + K.transpose());
    double L = 0;  // edge of the cube / square [m]
    for (std::size_t i = 0; i < body.size(); ++i) L = std::max(L, body.x.c[0][i] + body.dx / 2);
    for (int kind = 0; kind < 3; ++kind) {
        const Eigen::VectorXd u = pd::staggered_pattern(body, L, kind);
        m.rq[kind] = u.dot(S * u) / u.squaredNorm();
    }
    return m;
}

}  // namespace

static int run_case(int argc, char** argv)
{
    // 1. Options (SI), echoed and saved.
    pd::io::Case run("hourglass_modes_3d", "Zero-energy modes: stiffness eigenvalues of a free cube, correspondence vs PMB/LPS/PALS.",
                     "reports/3d/hourglass_modes");
    pd::io::Options& opt = run.opt;
    double& E = opt.add("E", 200e9, "Young's modulus", "Pa");
    double& nu = opt.add("nu", 0.3, "Poisson's ratio");
    double& dx = opt.add("dx", 1e-3, "lattice spacing", "m");
    double& m = opt.add("m", 3.05, "horizon ratio delta/dx");
    int& n = opt.add_int("n", 6, "nodes per edge of the cube (quick: 5)");
    int& n2 = opt.add_int("n2", 12, "nodes per edge of the 2D square, 0 = no 2D (quick: 8)");
    opt.add_string("chg", "0,0.002,0.02,0.2", "correspondence hourglass coefficients C_hg (comma list)");
    std::string& which = opt.add_string("model", "all", "models", {"all", "pmb", "lps", "pals", "correspondence"});
    double& zero_tol = opt.add("zero-tol", 1e-8, "near-zero eigenvalue threshold, relative to lambda_max");
    double& h_rel = opt.add("h", 1e-5, "finite-difference step, relative to dx");
    int& spectrum = opt.add_int("spectrum", 100, "lowest eigenvalues per model written to eigenvalues.csv (0: all)");
    for (const char* o : {"E", "dx", "zero-tol", "h"}) opt.require_positive(o);
    opt.require_at_least("m", 1);
    opt.require_at_least("n", 2);
    opt.require_at_least("n2", 0);
    opt.require_at_least("spectrum", 0);
    run.parse(argc, argv);
    if (const std::string msg = pd::validate_elastic(E, nu, 3, pd::Plane::strain); !msg.empty()) opt.fail(msg);
    const std::vector<double> C_hg = pd::io::list_option(opt, "chg", pd::io::ListValues::non_negative);
    run.quick_default("n", 5);
    run.quick_default("n2", 8);
    if (n2 == 1) opt.fail("option --n2: 0 (no 2D) or at least 2");
    run.start();
    auto wants = [&](const char* name) { return which == "all" || which == name; };

    // 2. Discretisation: the free cube (and square), families with the full volumes.
    const pd::Elastic mat = pd::Elastic::from_E_nu(E, nu);
    const double delta = m * dx, h = h_rel * dx;
    const pd::Body<3> body = pd::box<3>({{0, 0, 0}}, {{n * dx, n * dx, n * dx}}, dx);
    const pd::Bonds bonds = pd::build_bonds(body, delta);
    std::vector<Modes> modes;
    // One model (C_hg c: correspondence; 2D plane strain, thickness dx): FD stiffness, spectrum,
    // interior checkerboard energy; the time includes the set-up.
    auto run_model = [&](const std::string& name, double c, const auto& bd, const pd::Bonds& bb) {
        pd::io::Timer t;
        return pd::with_model(pd::ModelChoice{.name = name, .material = mat, .measure = dx, .C_hg = c}, bd, bb, [&](auto& model) {
            Mat K = pd::fd_stiffness(model, bd, bb, h);
            Modes md = analyse(K, bd, zero_tol);
            md.model = name;
            md.C_hg = c;
            md.interior_W = pd::interior_checker_energy(model, bd, bb, E);
            md.wall_s = t.seconds();
            modes.push_back(std::move(md));
            return K;
        });
    };

    // 3. The reference pair-spring matrices (header) of the cube and the square; their softest
    // non-rigid eigenvalue [N/m] is the physical scale of "soft" (6 rigid modes in 3D, 3 in 2D).
    const pd::Body<2> square = pd::box<2>({{0, 0}}, {{std::max(n2, 1) * dx, std::max(n2, 1) * dx}}, dx, dx);
    const Mat Ka = pd::ref::pmb_pair_stiffness(body.x.c, body.volume, delta, 18 * mat.K / (std::numbers::pi * std::pow(delta, 4)));
    double soft_scale[4] = {NAN, NAN, NAN, NAN};  // by dimension
    soft_scale[3] = Eigen::SelfAdjointEigenSolver<Mat>(Ka, Eigen::EigenvaluesOnly).eigenvalues()(6);
    if (n2 > 0) {
        const std::array<std::vector<double>, 3> xs{square.x.c[0], square.x.c[1], std::vector<double>(square.size(), 0.0)};
        const double kappa = mat.K + mat.G / 3;  // plane-strain 2D bulk modulus [Pa]
        const Mat K3 = pd::ref::pmb_pair_stiffness(xs, square.volume, delta, 12 * kappa / (std::numbers::pi * dx * std::pow(delta, 3)));
        Mat K2(2 * square.size(), 2 * square.size());  // the in-plane dofs
        for (std::size_t i = 0; i < 2 * square.size(); ++i)
            for (std::size_t j = 0; j < 2 * square.size(); ++j) K2(i, j) = K3(3 * (i / 2) + i % 2, 3 * (j / 2) + j % 2);
        soft_scale[2] = Eigen::SelfAdjointEigenSolver<Mat>(K2, Eigen::EigenvaluesOnly).eigenvalues()(3);
    }

    // 4.-5. Models, FD stiffness, spectra. PMB also against the pair-spring matrix (its own model).
    double fd_error = NAN;
    if (wants("pmb")) {
        const Mat K = run_model("pmb", NAN, body, bonds);
        fd_error = (K - Ka).norm() / Ka.norm();
    }
    if (wants("lps")) run_model("lps", NAN, body, bonds);
    if (wants("pals")) run_model("pals", NAN, body, bonds);
    for (double c : C_hg)
        if (wants("correspondence")) run_model("correspondence", c, body, bonds);
    const pd::Bonds b2 = pd::build_bonds(square, delta);
    if (n2 > 0 && wants("lps")) run_model("lps", NAN, square, b2);
    for (double c : C_hg)
        if (n2 > 0 && wants("correspondence")) run_model("correspondence", c, square, b2);

    // 6. Tables, CSVs, checks. Soft modes: non-rigid eigenvalues below 1/10 of the reference's
    // softest non-rigid eigenvalue of the same dimension (step 3).
    for (Modes& md : modes) {
        md.soft = 0;
        for (int k = md.rigid; k < md.lambda.size(); ++k) md.soft += md.lambda(k) < soft_factor * soft_scale[md.dim];
        if (md.soft == 0) continue;
        // The 2^D - 1 staggerings times D polarisations (3D: 21, 2D: 6), enveloped, projected on the soft modes.
        const Mat Vs = md.vectors.middleCols(md.rigid, md.soft);
        const double L = (md.dim == 3 ? n : n2) * dx;
        double sum = 0;
        int count = 0;
        for (int k = 1; k < (1 << md.dim); ++k)
            for (int pol = 0; pol < md.dim; ++pol, ++count) {
                const Eigen::VectorXd u = md.dim == 3 ? pd::staggered_pattern(body, L, 1, k, pol) : pd::staggered_pattern(square, L, 1, k, pol);
                sum += (Vs.transpose() * u).squaredNorm() / u.squaredNorm();
            }
        md.in_soft = sum / count;
    }
    pd::io::CsvWriter csv(run.file("modes.csv"), {"dim", "model", "C_hg", "nodes", "dofs", "lambda_max_N_per_m", "zero_modes_extra",
                                              "negative_modes", "soft_modes", "lambda_r1_rel", "lambda_r2_rel", "lambda_r3_rel",
                                              "checker_rel", "checker_env_rel", "bubble_rel", "checker_interior_W_rel", "patterns_in_soft",
                                              "asymmetry", "rigid_residual", "wall_s"});
    pd::io::CsvWriter spectra(run.file("eigenvalues.csv"), {"dim", "model", "C_hg", "index", "lambda_N_per_m", "lambda_rel"});
    std::printf("\nzero: |lambda| < %.1e lambda_max beyond the rigid modes (3D 6, 2D 3); soft: below %.1f x the first non-rigid\n"
                "eigenvalue of the reference pair springs (3D %.4e N/m, 2D %.4e N/m); r1..r3 = first non-rigid eigenvalues / lambda_max; checker, checker*env, bubble = Rayleigh\n"
                "quotients / lambda_max; W_int = checkerboard W at full-family nodes / (E (a/dx)^2 / 2)\n",
                zero_tol, soft_factor, soft_scale[3], soft_scale[2]);
    std::printf("%3s %-14s %5s %5s %10s %4s %3s %4s %9s %9s %9s %9s %9s %9s %9s %6s %8s %8s %6s\n", "dim", "model", "C_hg", "dofs",
                "lam_max", "zero", "neg", "soft", "r1", "r2", "r3", "checker", "chk*env", "bubble", "W_int", "in_sft", "asym", "rigid", "wall_s");
    for (const Modes& md : modes) {
        const int r = md.rigid;
        const double lm = md.lambda_max;
        csv.row({md.dim, md.model, md.C_hg, md.dofs / md.dim, md.dofs, lm, md.zero_extra, md.negative, md.soft, md.rel(r),
                 md.rel(r + 1), md.rel(r + 2), md.rq[0] / lm, md.rq[1] / lm, md.rq[2] / lm, md.interior_W, md.in_soft, md.asymmetry,
                 md.rigid_residual, md.wall_s});
        const int written = spectrum > 0 ? std::min<int>(spectrum, md.lambda.size()) : md.lambda.size();
        for (int k = 0; k < written; ++k) spectra.row({md.dim, md.model, md.C_hg, k, md.lambda(k), md.rel(k)});
        std::printf("%3d %-14s %5.3g %5d %10.4e %4d %3d %4d %9.3e %9.3e %9.3e %9.3e %9.3e %9.3e %9.2e %6.3f %8.1e %8.1e %6.2f\n", md.dim,
                    md.model.c_str(), md.C_hg, md.dofs, lm, md.zero_extra, md.negative, md.soft, md.rel(r), md.rel(r + 1), md.rel(r + 2),
                    md.rq[0] / lm, md.rq[1] / lm, md.rq[2] / lm, md.interior_W, md.in_soft, md.asymmetry, md.rigid_residual, md.wall_s);
    }
    if (!std::isnan(fd_error)) std::printf("PMB: finite-difference K vs analytic pair-spring K: %.3e (Frobenius, relative)\n", fd_error);

    // --check (reasons in reports/3d/hourglass_modes.md): the FD assembly reproduces the analytic PMB
    // matrix to 1e-8; every model annihilates the rigid modes to 1e-8 of lambda_max; PMB, LPS and
    // PALS have exactly the rigid zero modes, no negative and no soft eigenvalue; correspondence
    // without control has soft modes, C_hg = 0.02 (where run) leaves none; where full-family nodes
    // exist (n >= 7) the checkerboard costs no correspondence energy there (W < 1e-12, round-off)
    // and at least 0.1 of E (a/dx)^2 / 2 in the other models.
    run.summary({"soft_scale_3d", soft_scale[3], NAN, NAN, "N/m"});
    if (n2 > 0) run.summary({"soft_scale_2d", soft_scale[2], NAN, NAN, "N/m"});
    if (!std::isnan(fd_error)) {
        run.summary({"pmb_fd_vs_analytic_rel", fd_error, 0, NAN, "-"});
        run.check(fd_error < 1e-8, "FD stiffness = analytic PMB matrix within 1e-8 (relative Frobenius)");
    }
    for (const Modes& md : modes) {
        std::string tag = std::to_string(md.dim) + "d_" + md.model;
        if (!std::isnan(md.C_hg)) tag += "_chg" + pd::io::format_shortest(md.C_hg);
        run.summary({{tag + "_zero_modes", double(md.zero_extra + md.rigid), double(md.rigid),
                      pd::io::relative_error(md.zero_extra + md.rigid, md.rigid), "-"},
                     {tag + "_soft_modes", double(md.soft), NAN, NAN, "-"},
                     {tag + "_lambda_r1_rel", md.rel(md.rigid), NAN, NAN, "-"},
                     {tag + "_checker_env_over_bubble", md.rq[1] / md.rq[2], NAN, NAN, "-"}});
        const bool corr = md.model == "correspondence";
        run.property(md.rigid_residual < 1e-8, tag + ": rigid modes annihilated to 1e-8 of lambda_max");
        if (!corr) run.property(md.zero_extra == 0 && md.negative == 0 && md.soft <= 0, tag + ": no zero, negative or soft mode beyond the rigid ones");
        if (corr && md.C_hg == 0) run.property(md.soft != 0, tag + ": spurious soft modes without control");
        if (corr && md.C_hg == 0.02) run.property(md.soft == 0, tag + ": no soft mode at the source's C_hg");
        if (!std::isnan(md.interior_W))
            run.property(corr ? md.interior_W < 1e-12 : md.interior_W > 0.1,
                      tag + (corr ? ": interior checkerboard energy < 1e-12 (round-off)" : ": interior checkerboard energy > 0.1"));
    }
    return run.finish("%zu spectra; FD assembly, rigid modes, zero/soft-mode counts and hourglass lift %s", modes.size(),
                      run.passed() ? "as expected" : "NOT all as expected");
}

int main(int argc, char** argv) { return pd::io::guarded_main("hourglass_modes_3d", [&] { return run_case(argc, argv); }); }
