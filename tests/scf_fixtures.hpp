// Shared reference of the SCF tests (test_scf.cpp, test_lps_scf.cpp): the lattice SCF of a node
// whose family is the integer offsets kept by its position in a box, written out by hand.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace pd_test::scf_fixtures {

// Lattice SCF of a node whose family is the integer offsets n (0 < |n| <= 3, full volumes,
// omega = 1, lengths in dx) that pass `keep` (the node's position in a box), written out from
// the linearised probe: per shear (a, c), e = 2 n_a n_c / |n| (per gamma), theta = (D/m)
// sum |n| e, N = sum (e - theta |n| / D)^2; SCF = 4 m / (a_D max N).
template <int D>
double lattice_scf(const std::function<bool(const std::array<int, 3>&)>& keep = {})
{
    std::vector<std::array<int, 3>> fam;
    for (int p = -3; p <= 3; ++p)
        for (int q = -3; q <= 3; ++q)
            for (int r = (D == 3 ? -3 : 0); r <= (D == 3 ? 3 : 0); ++r) {
                const int n2 = p * p + q * q + r * r;
                if (n2 > 0 && n2 <= 9 && (!keep || keep({p, q, r}))) fam.push_back({p, q, r});
            }
    double m = 0;
    for (const auto& n : fam) m += n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const int planes[3][2] = {{0, 1}, {2, 0}, {1, 2}};
    double N_max = 0;
    for (int md = 0; md < (D == 3 ? 3 : 1); ++md) {
        const int a = planes[md][0], c = planes[md][1];
        double sth = 0, N = 0;
        for (const auto& n : fam) sth += 2.0 * n[a] * n[c];  // |n| e
        for (const auto& n : fam) {
            const double L = std::sqrt(double(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]));
            N += std::pow(2.0 * n[a] * n[c] / L - sth / m * L, 2);  // theta |n| / D = (sth/m) |n|
        }
        N_max = std::max(N_max, N);
    }
    return 4 * m / ((D == 3 ? 15.0 : 8.0) * N_max);
}

}  // namespace pd_test::scf_fixtures
