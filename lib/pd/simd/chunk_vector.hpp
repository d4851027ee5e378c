// The vector type of the chunk kernels (translated_families.hpp): W doubles, one per node of a chunk.
// W = 8 with AVX-512, 4 with AVX2 and FMA; without either the chunk kernels are not compiled
// (PD_CHUNK_WIDTH undefined) and every node takes the per-node code. Written with GCC vector
// extensions, so the compiler picks the instructions; loads and stores are unaligned.
#pragma once
#include <cstddef>
#include <cstring>
#include <type_traits>

#if defined(__AVX512F__)
#define PD_CHUNK_WIDTH 8
#elif defined(__AVX2__) && defined(__FMA__)
#define PD_CHUNK_WIDTH 4
#endif

#ifdef PD_CHUNK_WIDTH
#include <immintrin.h>

namespace pd::detail {

inline constexpr int chunk_width = PD_CHUNK_WIDTH;
using vchunk = double __attribute__((vector_size(8 * PD_CHUNK_WIDTH)));

inline vchunk load_chunk(const double* p)
{
    vchunk v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline void store_chunk(double* p, const vchunk& v) { std::memcpy(p, &v, sizeof v); }
inline vchunk splat(double s) { return vchunk{} + s; }
inline vchunk sqrt_chunk(const vchunk& v)
{
#if PD_CHUNK_WIDTH == 8
    return reinterpret_cast<vchunk>(_mm512_sqrt_pd(reinterpret_cast<__m512d>(v)));
#else
    return reinterpret_cast<vchunk>(_mm256_sqrt_pd(reinterpret_cast<__m256d>(v)));
#endif
}

}  // namespace pd::detail
#endif

namespace pd {
// A per-node array's value in a bond formula written once for both paths of the bond loop
// (bond_loop.hpp; bond_scalar of models/pmb.hpp, lps.hpp, pals.hpp): a[i] when the formula is taken in
// double (one node), the W contiguous values a[i .. i + W - 1] in detail::vchunk (the lanes of a chunk).
template <class T>
inline T node_value(const double* a, std::size_t i)
{
#ifdef PD_CHUNK_WIDTH
    if constexpr (std::is_same_v<T, detail::vchunk>) return detail::load_chunk(a + i);
    else
#endif
        return a[i];
}
}  // namespace pd
