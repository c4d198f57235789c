// Marching squares, and round contour levels.
#include "radiosity/contours.hpp"

#include <cmath>

namespace rad {
namespace {

// Where along the edge from value a to value b the level is crossed (0..1).
double crossing(double a, double b, double level) {
    return (level - a) / (b - a);
}

} // namespace

std::vector<IsoSegment> isolines(std::span<const double> values, long columns, long rows,
                                 double level) {
    std::vector<IsoSegment> out;
    const auto at = [&](long c, long r) { return values[std::size_t(r * columns + c)]; };
    for (long r = 0; r + 1 < rows; ++r)
        for (long c = 0; c + 1 < columns; ++c) {
            // Corners counter-clockwise from (c, r): 0 (c,r), 1 (c+1,r), 2 (c+1,r+1), 3 (c,r+1).
            const double v[4] = {at(c, r), at(c + 1, r), at(c + 1, r + 1), at(c, r + 1)};
            if (std::isnan(v[0]) || std::isnan(v[1]) || std::isnan(v[2]) || std::isnan(v[3]))
                continue;
            int mask = 0;
            for (int k = 0; k < 4; ++k) mask |= (v[k] >= level ? 1 : 0) << k;
            if (mask == 0 || mask == 15) continue;
            // The crossing on edge k (from corner k to corner k+1).
            const auto point = [&](int k, double& x, double& y) {
                static constexpr int dx[4] = {0, 1, 1, 0}, dy[4] = {0, 0, 1, 1};
                const int k1 = (k + 1) % 4;
                const double t = crossing(v[k], v[k1], level);
                x = double(c) + dx[k] + t * (dx[k1] - dx[k]);
                y = double(r) + dy[k] + t * (dy[k1] - dy[k]);
            };
            const auto segment = [&](int e0, int e1) {
                IsoSegment s;
                point(e0, s.x0, s.y0);
                point(e1, s.x1, s.y1);
                out.push_back(s);
            };
            // The edges whose ends are on different sides of the level.
            int edges[4], n = 0;
            for (int k = 0; k < 4; ++k)
                if (((mask >> k) & 1) != ((mask >> ((k + 1) % 4)) & 1)) edges[n++] = k;
            if (n == 2) {
                segment(edges[0], edges[1]);
            } else { // a saddle: corners 0 and 2 on one side, 1 and 3 on the other
                const bool centre_high = (v[0] + v[1] + v[2] + v[3]) / 4 >= level;
                const bool corner0_high = mask & 1;
                if (centre_high == corner0_high) { // corners 1 and 3 are cut off
                    segment(0, 1), segment(2, 3);
                } else { // corners 0 and 2 are cut off
                    segment(3, 0), segment(1, 2);
                }
            }
        }
    return out;
}

std::vector<double> contour_levels(double low, double high, int count) {
    std::vector<double> levels;
    if (!(high > low) || !std::isfinite(low) || !std::isfinite(high) || count < 1) return levels;
    const double rough = (high - low) / count;
    const double power = std::pow(10.0, std::floor(std::log10(rough)));
    double step = power;
    for (const double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * power >= rough) {
            step = m * power;
            break;
        }
    for (double level = std::floor(low / step + 1) * step; level < high; level += step)
        if (level > low) levels.push_back(level);
    return levels;
}

} // namespace rad
