// Irradiance gradients (Ward and Heckbert 1992) from a record's rays on a theta x phi grid:
// how the gathered light changes as the point moves (translational) and as its normal turns
// (rotational), so that an irradiance cache extrapolates each record to where it is used
// instead of taking its value as flat. Ring j of m holds sin^2(theta) in [j/m, (j+1)/m) (equal
// projected solid angle), sector k of n holds phi in [2 pi k/n, 2 pi (k+1)/n), phi measured from
// the tangent `tu` towards `tv`. The translational gradient comes from how the cells' borders
// move with the point: across each border, the difference of the light on either side over the
// nearer of the two distances.
#pragma once
#include "radiosity/vec.hpp"

#include <array>
#include <span>

namespace rad {

struct HemisphereCell {
    Rgb radiance{0, 0, 0};
    double distance = 0; // to what the cell's ray met; 0: nothing (no border term across it)
};

struct IrradianceGradients {
    Rgb mean{0, 0, 0}; // the cells' mean radiance: the irradiance over pi
    // Per colour channel, in the mean's units: per unit of distance, and per radian of the
    // normal's turn (the change for a normal n' is dot(cross(n, n'), rotational[c])).
    std::array<Vec3, 3> translational{}, rotational{};
};

// `cells` holds ring j, sector k at j * n + k; `tu`, `tv` the tangents of the cells' frame.
IrradianceGradients irradiance_gradients(std::span<const HemisphereCell> cells, int m, int n,
                                         const Vec3& tu, const Vec3& tv);

// The grid for about `rays` rays: m rings of n sectors, n about pi m (cells about as wide as
// tall; 512 rays: 13 x 39).
struct HemisphereGridSize {
    int m = 1, n = 1;
    int cells() const { return m * n; }
};
HemisphereGridSize hemisphere_grid(int rays);

// The direction through ring j, sector k at (u, v) in [0, 1)^2 within the cell.
Vec3 hemisphere_cell_direction(int j, int k, int m, int n, double u, double v, const Vec3& normal,
                               const Vec3& tu, const Vec3& tv);

} // namespace rad
