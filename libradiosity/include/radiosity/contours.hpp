// Isolines of values on a regular grid (a calculation surface's illuminance): marching
// squares with linear interpolation along each cell's edges, so every endpoint lies where the
// values between two neighbouring sensors, taken linearly, equal the level.
#pragma once
#include <span>
#include <vector>

namespace rad {

// A piece of an isoline, in sensor coordinates: sensor (column c, row r) is at (c, r).
struct IsoSegment {
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// The isoline at `level` of `values` (row-major, `columns` x `rows`). A square with a NaN
// corner has none; a saddle is resolved by the square's mean.
std::vector<IsoSegment> isolines(std::span<const double> values, long columns, long rows,
                                 double level);

// Round levels (1, 2, 2.5 or 5 times a power of ten apart) strictly between `low` and `high`,
// about `count` of them (none when the range is empty).
std::vector<double> contour_levels(double low, double high, int count = 6);

} // namespace rad
