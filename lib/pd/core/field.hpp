// Point fields in structure-of-arrays layout: one std::vector<double> per component.
// Vec<D> is a small fixed vector for per-point arithmetic in the loops.
#pragma once
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace pd {

template <int D>
struct Vec {
    std::array<double, D> c{};
    double& operator[](int d) { return c[d]; }
    double operator[](int d) const { return c[d]; }
    Vec& operator+=(const Vec& o) { for (int d = 0; d < D; ++d) c[d] += o.c[d]; return *this; }
    Vec& operator-=(const Vec& o) { for (int d = 0; d < D; ++d) c[d] -= o.c[d]; return *this; }
    Vec& operator*=(double s) { for (int d = 0; d < D; ++d) c[d] *= s; return *this; }
    friend Vec operator+(Vec a, const Vec& b) { return a += b; }
    friend Vec operator-(Vec a, const Vec& b) { return a -= b; }
    friend Vec operator*(double s, Vec a) { return a *= s; }
    friend Vec operator*(Vec a, double s) { return a *= s; }
    friend double dot(const Vec& a, const Vec& b) { double r = 0; for (int d = 0; d < D; ++d) r += a.c[d] * b.c[d]; return r; }
    friend double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
};

// A vector field over n points, component-major (SoA) so the bond loop streams each component.
template <int D>
struct Field {
    std::array<std::vector<double>, D> c;
    Field() = default;
    explicit Field(std::size_t n) { resize(n); }
    void resize(std::size_t n) { for (auto& v : c) v.assign(n, 0.0); }
    std::size_t size() const { return c[0].size(); }
    Vec<D> operator[](std::size_t i) const { Vec<D> r; for (int d = 0; d < D; ++d) r[d] = c[d][i]; return r; }
    void set(std::size_t i, const Vec<D>& v) { for (int d = 0; d < D; ++d) c[d][i] = v[d]; }
    void add(std::size_t i, const Vec<D>& v) { for (int d = 0; d < D; ++d) c[d][i] += v[d]; }
    void fill(double value) { for (auto& v : c) std::fill(v.begin(), v.end(), value); }
};

// y = x + u (current positions).
template <int D>
inline void add_fields(const Field<D>& x, const Field<D>& u, Field<D>& y)
{
    y.resize(x.size());
    for (int d = 0; d < D; ++d)
        for (std::size_t i = 0; i < x.size(); ++i) y.c[d][i] = x.c[d][i] + u.c[d][i];
}

}  // namespace pd
