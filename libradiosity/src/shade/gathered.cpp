// Images by final gather: each pixel's visible point lit by rays cast from that point.
#include "radiosity/gathered.hpp"

#include "radiosity/irradiance_cache.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/rays.hpp"
#include "radiosity/sensors.hpp"
#include "radiosity/specular_view.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <optional>

#include <cmath>
#include <numbers>

namespace rad {

namespace {
// E + rho x (what is gathered at the point, and the luminaires' direct light there); with
// `error`, rho x the gather's standard error there.
Rgb gathered_colour(const Gatherer& gatherer, const LuminaireSet* luminaires,
                    const RayScene::Hit& hit, const Vec3& point, std::uint64_t index,
                    Rgb* error = nullptr) {
    const auto& mesh = gatherer.mesh();
    const auto& patch = mesh.patches[static_cast<std::size_t>(hit.patch)];
    const auto& material = mesh.materials[patch.material];
    const auto normal = gatherer.shading_normal(hit);
    const Rgb known = luminaire_light(gatherer, luminaires, point, normal); // exactly
    const auto gathered = gatherer.gather(point, normal, patch.normal, index, known);
    const auto h = gathered.total();
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = material.emission[c] + material.reflectance[c] * (h[c] + known[c]);
    if (error)
        for (int c = 0; c < 3; ++c) (*error)[c] = material.reflectance[c] * gathered.error[c];
    return out;
}

// A mesh with mirrors and glass: the camera's rays go on through them, and each surface they
// reach is gathered (each with its error: the error layer).
Image render_gathered_specular(const Gatherer& gatherer, const View& view, int width, int height,
                               int supersampling, bool quiet, const LuminaireSet* luminaires,
                               RowBand rows) {
    const SpecularView scene{gatherer.mesh(), gatherer.scene(), gatherer.specular(),
                             gatherer.specular_depth()};
    const HitShader shade = [&](const PathHit& h, std::uint64_t index, Rgb* error) {
        return gathered_colour(gatherer, luminaires, h.hit, h.origin + h.direction * h.hit.distance,
                               index, error);
    };
    return render_specular(scene, view, width, height, supersampling, shade, quiet, rows, true);
}
// The cache's records at every `spacing`-th pixel of the whole image (a band builds the same
// ones, so its pixels are those of a whole run), each from its own stream. A record's radius
// is the harmonic mean distance its rays met, at least what reaches min_reach_pixels (their
// footprint over the accuracy), at most what reaches max_reach_pixels and a tenth of the scene.
IrradianceCache build_cache(const Gatherer& gatherer, const View& view, int width, int height,
                            const IrradianceCacheOptions& o, bool quiet) {
    const int spacing = std::max(1, o.spacing);
    const int nx = (width + spacing - 1) / spacing, ny = (height + spacing - 1) / spacing;
    const auto& mesh = gatherer.mesh();
    const Box box = bounds(mesh.vertices);
    const double largest = 0.1 * length(box.hi - box.lo);
    std::vector<IrradianceCache::Record> slots(std::size_t(nx) * ny);
    std::vector<std::uint8_t> used(slots.size(), 0);
    Progress progress("rad-shade cache", std::uint64_t(ny), quiet);
    tbb::parallel_for(0, ny, [&](int j) {
        for (int i = 0; i < nx; ++i) {
            const double px = std::min(i * spacing + spacing / 2, width - 1) + 0.5;
            const double py = std::min(j * spacing + spacing / 2, height - 1) + 0.5;
            const Vec3 ray = view_ray(view, px / width, py / height);
            const auto hit = gatherer.scene().trace(view.position, ray);
            if (hit.patch < 0 || !hit.front) continue;
            const auto& patch = mesh.patches[static_cast<std::size_t>(hit.patch)];
            const Vec3 point = view.position + ray * hit.distance;
            const Vec3 normal = gatherer.shading_normal(hit);
            const std::size_t at = std::size_t(j) * nx + i;
            const auto sample = gatherer.indirect_sample(point, normal, patch.normal, o.rays, at);
            const double footprint =
                length(view_ray(view, (px + 1) / width, py / height) - ray) * hit.distance;
            const double smallest = o.min_reach_pixels * footprint / o.accuracy;
            const double widest = std::min(largest, o.max_reach_pixels * footprint / o.accuracy);
            auto& r = slots[at];
            r.position = point;
            r.normal = normal;
            r.indirect = sample.indirect;
            r.radius = std::clamp(sample.harmonic_distance > 0 ? sample.harmonic_distance : widest,
                                  smallest, std::max(smallest, widest));
            used[at] = 1;
        }
        progress.advance(1);
    });
    progress.finish();
    std::vector<IrradianceCache::Record> records;
    for (std::size_t k = 0; k < slots.size(); ++k)
        if (used[k]) records.push_back(slots[k]);
    return IrradianceCache(std::move(records), o.accuracy);
}

// E + rho x (the direct light, the cache's indirect light or, where no record is valid, the
// point's own, and the luminaires'); `own` counts the points that gathered their own.
Rgb cached_colour(const Gatherer& gatherer, const IrradianceCache& cache,
                  const LuminaireSet* luminaires, const RayScene::Hit& hit, const Vec3& point,
                  std::uint64_t index, std::atomic<long>& own) {
    const auto& mesh = gatherer.mesh();
    const auto& patch = mesh.patches[static_cast<std::size_t>(hit.patch)];
    const auto& material = mesh.materials[patch.material];
    const auto normal = gatherer.shading_normal(hit);
    Rgb h = gatherer.direct_light(point, normal, index);
    Rgb indirect;
    if (!cache.lookup(point, normal, indirect)) {
        ++own;
        indirect = gatherer
                       .indirect_sample(point, normal, patch.normal,
                                        std::max(1, gatherer.options().rays), index)
                       .indirect;
    }
    const Rgb lum = luminaire_light(gatherer, luminaires, point, normal);
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = material.emission[c] + material.reflectance[c] * (h[c] + indirect[c] + lum[c]);
    return out;
}
} // namespace

Image render_gathered(const Gatherer& gatherer, const View& view, int width, int height,
                      int supersampling, bool quiet, const LuminaireSet* luminaires, RowBand rows,
                      const IrradianceCacheOptions* cache_options) {
    if (gatherer.specular().any())
        return render_gathered_specular(gatherer, view, width, height, supersampling, quiet,
                                        luminaires, rows);
    const int first_row = std::clamp(rows.begin, 0, height);
    const int end_row = rows.end < 0 ? height : std::clamp(rows.end, first_row, height);
    const int ss = std::max(1, supersampling);
    const int W = width * ss, H = height * ss;

    Image image;
    image.width = width;
    image.height = height;
    image.rgb.assign(std::size_t(width) * height * 3, 0.0f);
    image.back_coverage.assign(std::size_t(width) * height, 0.0f);
    auto& covered = image.covered;
    covered.assign(std::size_t(width) * height, 0);
    std::optional<IrradianceCache> cache;
    std::atomic<long> own{0};
    if (cache_options) {
        cache.emplace(build_cache(gatherer, view, width, height, *cache_options, quiet));
    } else {
        image.error.assign(std::size_t(width) * height * 3, 0.0f);
    }
    Progress progress("rad-shade gather", std::uint64_t(end_row - first_row), quiet);
    tbb::parallel_for(first_row, end_row, [&](int y) {
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0}, squared_error[3] = {0, 0, 0};
            int backs = 0;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    // The sample's centre, in the rasteriser's screen convention.
                    const double px = x * ss + sx + 0.5, py = y * ss + sy + 0.5;
                    const Vec3 ray = view_ray(view, px / W, py / H);
                    const auto hit = gatherer.scene().trace(view.position, ray);
                    if (hit.patch < 0) continue;
                    covered[std::size_t(y) * width + x] = 1;
                    if (!hit.front) {
                        ++backs;
                        continue;
                    }
                    const std::uint64_t index = std::uint64_t(y * ss + sy) * W + (x * ss + sx);
                    Rgb error{0, 0, 0};
                    const Vec3 point = view.position + ray * hit.distance;
                    const auto colour =
                        cache ? cached_colour(gatherer, *cache, luminaires, hit, point, index, own)
                              : gathered_colour(gatherer, luminaires, hit, point, index, &error);
                    for (int c = 0; c < 3; ++c) {
                        sum[c] += colour[c];
                        squared_error[c] += error[c] * error[c];
                    }
                }
            // The pixel is the mean of its samples, each gathered from its own streams: its
            // error, theirs added in quadrature over the count.
            const std::size_t at = std::size_t(y) * width + x;
            for (int c = 0; c < 3; ++c) {
                image.rgb[3 * at + c] = static_cast<float>(sum[c] / (ss * ss));
                if (!cache)
                    image.error[3 * at + c] =
                        static_cast<float>(std::sqrt(squared_error[c]) / (ss * ss));
            }
            image.back_coverage[at] = float(backs) / float(ss * ss);
        }
        progress.advance(1);
    });
    progress.finish();
    image.cache_records = cache ? cache->size() : 0;
    image.uncached_samples = own.load();
    for (std::size_t p = 0; p < covered.size(); ++p) {
        image.covered_pixels += covered[p];
        image.back_face_pixels += image.back_coverage[p] >= 0.5f;
    }
    return image;
}

} // namespace rad
