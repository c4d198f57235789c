// bench-image-diff A.exr B.exr: how far image B is from image A (the reference), over the
// pixels both cover: the ratio of their means, the rms of the per-pixel relative difference,
// and the worst 8 x 8 block's mean relative difference (a splotch or a seam shows there, where
// per-pixel noise averages out).
#include "radiosity/image_io.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: bench-image-diff REFERENCE.exr OTHER.exr\n");
        return 1;
    }
    try {
        const auto a = rad::read_exr(argv[1]), b = rad::read_exr(argv[2]);
        if (a.width != b.width || a.height != b.height) {
            std::fprintf(stderr, "bench-image-diff: the images differ in size\n");
            return 1;
        }
        const auto value = [](const rad::Image& im, std::size_t p) {
            return rad::luminous({im.rgb[3 * p], im.rgb[3 * p + 1], im.rgb[3 * p + 2]});
        };
        double sum_a = 0, sum_b = 0, squares = 0;
        long count = 0;
        const std::size_t pixels = std::size_t(a.width) * a.height;
        for (std::size_t p = 0; p < pixels; ++p) {
            const double x = value(a, p), y = value(b, p);
            if (!(x > 1e-6)) continue;
            sum_a += x, sum_b += y, ++count;
            squares += (y - x) * (y - x) / (x * x);
        }
        double worst = 0;
        int worst_x = 0, worst_y = 0;
        for (int by = 0; by + 8 <= a.height; by += 8)
            for (int bx = 0; bx + 8 <= a.width; bx += 8) {
                double sa = 0, sb = 0;
                for (int y = by; y < by + 8; ++y)
                    for (int x = bx; x < bx + 8; ++x) {
                        const auto p = std::size_t(y) * a.width + x;
                        sa += value(a, p), sb += value(b, p);
                    }
                // Blocks of the lit scene (a quarter of the mean at least): a block of the
                // near-black frame measures only its edge pixels' noise.
                if (sa > 64 * 0.25 * (sum_a / std::max(count, 1L)) &&
                    std::abs(sb - sa) / sa > worst)
                    worst = std::abs(sb - sa) / sa, worst_x = bx, worst_y = by;
            }
        std::printf("mean ratio %.4f, rms pixel difference %.2f%%, worst 8x8 block %.2f%% (at "
                    "x %d, y %d)\n",
                    sum_b / sum_a, 100 * std::sqrt(squares / std::max(count, 1L)), 100 * worst,
                    worst_x, worst_y);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench-image-diff: %s\n", e.what());
        return 2;
    }
}
