// Images through mirrors and glass: a ray per sample, followed through specular events.
#include "radiosity/specular_view.hpp"

#include "radiosity/progress.hpp"
#include "radiosity/twins.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace rad {

namespace {
// One sample: the colour its path brings, whether it met anything, whether its first
// surface showed its back.
struct SampleColour {
    Rgb colour{0, 0, 0};
    Rgb squared_error{0, 0, 0};
    bool covered = false, back = false;
};

SampleColour trace_sample(const SpecularView& s, const std::vector<std::int64_t>& twins,
                          const Vec3& origin, const Vec3& ray, const HitShader& shade,
                          std::uint64_t index, bool errors) {
    SampleColour out;
    std::uint64_t reached = 0;
    follow_specular(
        s.scene, s.surfaces, origin, ray, Rgb{{1, 1, 1}}, s.depth, [&](const PathHit& h) {
            auto hit = h;
            const auto j = static_cast<std::size_t>(h.hit.patch);
            if (h.events == 0) out.covered = true;
            if (!h.hit.front) {
                if (s.surfaces.transmits(j)) return;
                // Of a two-sided pair, the side facing the ray.
                if (twins[j] < 0) {
                    if (h.events == 0) out.back = true;
                    return;
                }
                hit.hit.patch = twins[j];
                hit.hit.front = true;
            }
            Rgb error{0, 0, 0};
            const auto c = shade(hit, index * 64 + std::min<std::uint64_t>(reached++, 63),
                                 errors ? &error : nullptr);
            for (int k = 0; k < 3; ++k) {
                out.colour[k] += h.weight[k] * c[k];
                out.squared_error[k] += h.weight[k] * h.weight[k] * error[k] * error[k];
            }
        });
    return out;
}
} // namespace

Image render_specular(const SpecularView& s, const View& view, int width, int height,
                      int supersampling, const HitShader& shade, bool quiet, RowBand rows,
                      bool errors) {
    const int first_row = std::clamp(rows.begin, 0, height);
    const int end_row = rows.end < 0 ? height : std::clamp(rows.end, first_row, height);
    const int ss = std::max(1, supersampling);
    const int W = width * ss, H = height * ss;
    const auto twins = find_twins(s.mesh);
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.assign(std::size_t(width) * height * 3, 0.0f);
    image.back_coverage.assign(std::size_t(width) * height, 0.0f);
    image.covered.assign(std::size_t(width) * height, 0);
    if (errors) image.error.assign(std::size_t(width) * height * 3, 0.0f);
    Progress progress("rad-shade specular", std::uint64_t(end_row - first_row), quiet);
    tbb::parallel_for(first_row, end_row, [&](int y) {
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0}, squared_error[3] = {0, 0, 0};
            int backs = 0;
            bool covered = false;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    const double px = x * ss + sx + 0.5, py = y * ss + sy + 0.5;
                    const std::uint64_t index = std::uint64_t(y * ss + sy) * W + (x * ss + sx);
                    const auto sample =
                        trace_sample(s, twins, view.position, view_ray(view, px / W, py / H), shade,
                                     index, errors);
                    covered = covered || sample.covered;
                    backs += sample.back;
                    for (int k = 0; k < 3; ++k) {
                        sum[k] += sample.colour[k];
                        squared_error[k] += sample.squared_error[k];
                    }
                }
            const std::size_t at = std::size_t(y) * width + x;
            image.covered[at] = covered;
            for (int k = 0; k < 3; ++k) {
                image.rgb[3 * at + k] = static_cast<float>(sum[k] / (ss * ss));
                if (errors)
                    image.error[3 * at + k] =
                        static_cast<float>(std::sqrt(squared_error[k]) / (ss * ss));
            }
            image.back_coverage[at] = float(backs) / float(ss * ss);
        }
        progress.advance(1);
    });
    progress.finish();
    for (std::size_t p = 0; p < image.covered.size(); ++p) {
        image.covered_pixels += image.covered[p];
        image.back_face_pixels += image.back_coverage[p] >= 0.5f;
    }
    return image;
}

HitShader smoothed_shader(const radfmt::MeshData& mesh, const CornerColours& corners) {
    return [&mesh, &corners](const PathHit& h, std::uint64_t, Rgb* error) {
        if (error) *error = Rgb{0, 0, 0}; // smoothed corners: nothing sampled here
        return interpolate_corners(mesh, corners, h.hit.patch, h.hit.u, h.hit.v, h.hit.piece);
    };
}

} // namespace rad
