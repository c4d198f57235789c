// A small RGB8 canvas for the false-colour pictures' legends (internal header): filled
// rectangles and text from stb_easy_font (its quads, filled here).
#pragma once
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace rad::image_canvas {

struct Canvas {
    int width, height;
    std::vector<std::uint8_t> pixels;
    Canvas(int w, int h) : width(w), height(h), pixels(std::size_t(w) * h * 3, 255) {}
    void fill(int x0, int y0, int x1, int y1, std::array<std::uint8_t, 3> c) {
        for (int y = std::max(0, y0); y < std::min(height, y1); ++y)
            for (int x = std::max(0, x0); x < std::min(width, x1); ++x)
                std::copy(c.begin(), c.end(), pixels.begin() + (std::size_t(y) * width + x) * 3);
    }
    // Text at (x, y) (top left), `scale` pixels per font unit, in black.
    void text(int x, int y, const std::string& s, int scale = 2) {
        std::vector<char> buffer(s.size() * 300 + 1000);
        std::vector<char> copy(s.begin(), s.end());
        copy.push_back('\0');
        const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(),
                                              static_cast<int>(buffer.size()));
        // Each quad: 4 vertices of (x, y, z floats, 4 colour bytes) = 16 bytes.
        for (int q = 0; q < quads; ++q) {
            float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
            for (int v = 0; v < 4; ++v) {
                float xy[2];
                std::memcpy(xy, buffer.data() + (q * 4 + v) * 16, sizeof xy);
                for (int k = 0; k < 2; ++k)
                    lo[k] = std::min(lo[k], xy[k]), hi[k] = std::max(hi[k], xy[k]);
            }
            fill(x + int(lo[0] * scale), y + int(lo[1] * scale), x + int(hi[0] * scale),
                 y + int(hi[1] * scale), {0, 0, 0});
        }
    }
};

} // namespace rad::image_canvas
