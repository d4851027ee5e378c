// Periodic lateral faces for a plane-wave slab (x free, y and z periodic) by image layers: a block
// of Nx x n x n interior cells plus g ghost layers on each lateral side; ghost node i copies the
// x-motion of its image (iy mod n, iz mod n) before each step, and the model wrapper copies the
// image's point state (LPS-family m, p_coef, alpha at set-up, theta after each point pass), so
// the block is a slab cut from an infinite body (problems/3d/wave_block.cpp).
#pragma once
#include "pd/core/bonds.hpp"
#include "pd/core/field.hpp"
#include "pd/core/lattice.hpp"

#include <stdexcept>
#include <vector>

namespace pd {

struct ImageBlock {                     // lattice nodes; ghosts = lateral image layers
    Body<3> body;
    std::vector<int> image;        // interior node whose motion node i copies (i itself if interior)
    std::vector<int> interior, ghosts;
};

// Nx x n x n interior cells plus g ghost layers on each lateral side, image (iy mod n, iz mod n).
inline ImageBlock make_image_block(long Nx, long n, long g, double dx)
{
    ImageBlock b;
    const long S = n + 2 * g;
    for (long ix = 0; ix < Nx; ++ix)
        for (long iz = -g; iz < n + g; ++iz)
            for (long iy = -g; iy < n + g; ++iy) {
                const int i = static_cast<int>(b.body.size());
                b.body.push({(ix + 0.5) * dx, (iy + 0.5) * dx, (iz + 0.5) * dx}, dx * dx * dx);
                const long jy = (iy % n + n) % n, jz = (iz % n + n) % n;
                b.image.push_back(static_cast<int>(ix * S * S + (jz + g) * S + (jy + g)));
                (b.image.back() == i ? b.interior : b.ghosts).push_back(i);
            }
    b.body.dx = dx;
    return b;
}

// The model with periodic lateral faces: ghosts take their image's point state (LPS m, theta).
template <class Model>
struct LateralImages {
    static constexpr bool has_point_pass = Model::has_point_pass;
    Model& model;
    const ImageBlock& block;
    LateralImages(Model& m, const ImageBlock& b) : model(m), block(b)
    {
        if constexpr (requires { m.thermal_expansion(); })
            if (m.thermal_expansion().active()) throw std::invalid_argument("LateralImages: thermal expansion is not supported");
        if constexpr (has_point_pass)
            for (int g : b.ghosts) {
                model.m[g] = model.m[b.image[g]];
                model.p_coef[g] = model.p_coef[b.image[g]];
                model.alpha[g] = model.alpha[b.image[g]];
            }
    }
    void point_pass(const Bonds& bonds, const Field<3>& y)
    {
        model.point_pass(bonds, y);
        for (int g : block.ghosts) model.theta[g] = model.theta[block.image[g]];
    }
    double bond_scalar(std::size_t i, std::int64_t k, int j, double ylen) const { return model.bond_scalar(i, k, j, ylen); }
    std::vector<double> energy_density(const Bonds& b, const Field<3>& y) const { return model.energy_density(b, y); }
};

// Ghosts take the x component of their image (call before each step on u, v, a).
inline void copy_images(const ImageBlock& b, Field<3>& f)
{
    for (int g : b.ghosts) f.c[0][g] = f.c[0][b.image[g]];
}

}  // namespace pd
