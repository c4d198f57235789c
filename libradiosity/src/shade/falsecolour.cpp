// False-colour PNG of a grid of values with a legend.
#include "radiosity/falsecolour.hpp"

#include "radiosity/error.hpp"
#include "radiosity/image_io.hpp"

#include "shade/canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace rad {

std::array<std::uint8_t, 3> false_colour(double t) {
    struct Stop {
        double at, r, g, b;
    };
    static constexpr Stop stops[] = {{0.0, 0.05, 0.05, 0.35}, {0.2, 0.10, 0.30, 0.90},
                                     {0.4, 0.10, 0.75, 0.75}, {0.6, 0.40, 0.85, 0.20},
                                     {0.8, 0.95, 0.80, 0.10}, {1.0, 0.85, 0.10, 0.10}};
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    std::size_t k = 1;
    while (k + 1 < std::size(stops) && t > stops[k].at) ++k;
    const auto &a = stops[k - 1], &b = stops[k];
    const double w = (t - a.at) / (b.at - a.at);
    auto mix = [w](double x, double y) {
        return static_cast<std::uint8_t>(std::lround(255 * (x + (y - x) * w)));
    };
    return {mix(a.r, b.r), mix(a.g, b.g), mix(a.b, b.b)};
}

double false_colour_top(double value) {
    if (!(value > 0)) return 1;
    const double decade = std::pow(10.0, std::floor(std::log10(value)));
    for (double step : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (step * decade >= value * (1 - 1e-12)) return step * decade;
    return 10 * decade;
}

namespace {

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

} // namespace

void write_false_colour_png(const std::string& path, std::span<const double> values, int columns,
                            int rows, const std::string& unit, const std::string& title,
                            double top_value) {
    if (columns <= 0 || rows <= 0 || values.size() != std::size_t(columns) * rows)
        throw InternalError("false-colour map: " + std::to_string(values.size()) +
                            " values for a " + std::to_string(columns) + "x" +
                            std::to_string(rows) + " grid");
    double lo = 1e300, hi = -1e300, sum = 0;
    std::size_t finite = 0;
    for (double v : values)
        if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v), sum += v, ++finite;
    const double top = top_value > 0 ? top_value : false_colour_top(finite ? hi : 1);
    // Cells at least 2 px, the map about 480 px on its longer side.
    const int cell = std::max(2, 480 / std::max(columns, rows));
    const int map_w = columns * cell, map_h = rows * cell;
    const int margin = 12, header = 56, legend_w = 150;
    image_canvas::Canvas canvas(margin + map_w + margin + legend_w,
                                header + std::max(map_h, 310) + margin);
    canvas.text(margin, 8, title);
    canvas.text(margin, 30,
                finite ? "min " + number(lo) + "  mean " + number(sum / finite) + "  max " +
                             number(hi) + " " + unit
                       : "no values");
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < columns; ++c) {
            const double v = values[std::size_t(r) * columns + c];
            const auto colour = std::isfinite(v) ? false_colour(v / top)
                                                 : std::array<std::uint8_t, 3>{128, 128, 128};
            canvas.fill(margin + c * cell, header + r * cell, margin + (c + 1) * cell,
                        header + (r + 1) * cell, colour);
        }
    // Legend: a bar from 0 (bottom) to `top`, ticks every fifth.
    const int bar_x = margin + map_w + margin + 8, bar_y = header + 8, bar_h = 240;
    for (int y = 0; y < bar_h; ++y)
        canvas.fill(bar_x, bar_y + y, bar_x + 24, bar_y + y + 1,
                    false_colour(1 - (y + 0.5) / bar_h));
    for (int t = 0; t <= 5; ++t) {
        const int y = bar_y + bar_h - t * bar_h / 5;
        canvas.fill(bar_x + 24, y - 1, bar_x + 32, y + 1, {0, 0, 0});
        canvas.text(bar_x + 36, y - 6, number(top * t / 5));
    }
    canvas.text(bar_x, bar_y + bar_h + 8, unit);
    if (finite < values.size()) {
        canvas.fill(bar_x, bar_y + bar_h + 34, bar_x + 24, bar_y + bar_h + 46, {128, 128, 128});
        canvas.text(bar_x + 30, bar_y + bar_h + 34, "no value");
    }
    write_png_rgb8(path, canvas.width, canvas.height, canvas.pixels);
}

} // namespace rad
