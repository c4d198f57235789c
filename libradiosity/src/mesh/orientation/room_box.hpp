// Whether a surface is a room by its size (internal header): the orientation checks and
// imprinting tell a room from an object so.
#pragma once
#include "radiosity/vec.hpp"

namespace rad {

// A surface encloses the rest of the scene (a room) when its box holds the scene's box, give
// or take 1% of the scene's size: exporters let water or furniture poke a few millimetres
// through a wall.
inline bool encloses(const Box& surface, const Box& scene) {
    const double tol = 0.01 * length(scene.hi - scene.lo);
    for (int c = 0; c < 3; ++c)
        if (scene.lo[c] < surface.lo[c] - tol || scene.hi[c] > surface.hi[c] + tol) return false;
    return true;
}

} // namespace rad
