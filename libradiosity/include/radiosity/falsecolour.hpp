// False-colour maps of values on a regular grid (a work plane's illuminance), the picture
// lighting designers read: one colour per cell, a legend bar with labelled ticks.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>

namespace rad {

// The colour for t in [0, 1] (dark blue - blue - cyan - green - yellow - red), sRGB bytes.
std::array<std::uint8_t, 3> false_colour(double t);

// The scale's top for values up to `value`: the smallest of 1, 2, 2.5, 5 x 10^k at or above
// it (1 when it is not positive).
double false_colour_top(double value);

// Writes a PNG of `values` (row-major, `columns` x `rows`, row 0 at the top; NaN cells
// grey), scaled from 0 to `top` (0: a round number at or above the largest value; values
// above it get the top colour), with a legend labelled in `unit` and a `title` line (min,
// mean, max are added below it).
void write_false_colour_png(const std::string& path, std::span<const double> values, int columns,
                            int rows, const std::string& unit, const std::string& title,
                            double top = 0);

} // namespace rad
