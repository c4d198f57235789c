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
// How much a record's light may change by its translational gradient where its reach ends
// (its accuracy a x its radius): a record whose light changes fast reaches less. At 0.4 this
// costs about 1% more samples gathering their own on the game maps, where Krivanek et al.'s
// bound (the light over the gradient's length, a change of a) costs 14-20%, and the images are
// the same.
constexpr double kMostExtrapolated = 0.4;

// A record from its sample: its radius the harmonic mean distance, at most what keeps its
// extrapolation within kMostExtrapolated, clamped to [smallest, widest]. Where what its rays
// met is nearer than the smallest radius, the gradient holds over less than the record
// reaches: scaled down (Krivanek et al. 2006).
IrradianceCache::Record make_record(const Vec3& point, const Vec3& normal,
                                    const Gatherer::IndirectSample& sample, double accuracy,
                                    double smallest, double widest) {
    IrradianceCache::Record r;
    r.position = point;
    r.normal = normal;
    r.indirect = sample.indirect;
    r.rotational = sample.rotational;
    double radius = sample.harmonic_distance > 0 ? sample.harmonic_distance : widest;
    for (int c = 0; c < 3; ++c) {
        const double slope = length(sample.translational[c]) * accuracy;
        if (slope > 0 && sample.indirect[c] > 0)
            radius = std::min(radius, kMostExtrapolated * sample.indirect[c] / slope);
    }
    r.radius = std::clamp(radius, smallest, std::max(smallest, widest));
    const double trust = sample.nearest > 0 ? std::min(1.0, sample.nearest / smallest) : 1.0;
    for (int c = 0; c < 3; ++c) r.translational[c] = sample.translational[c] * trust;
    return r;
}

// The cache's records at every `spacing`-th pixel of the whole image (a band builds the same
// ones, so its pixels are those of a whole run), each from its own stream (make_record): at
// least what reaches min_reach_pixels (their footprint over the accuracy), at most what
// reaches max_reach_pixels and a tenth of the scene.
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
            slots[at] = make_record(point, normal, sample, o.accuracy, smallest, widest);
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

// E + rho x (the direct, indirect and luminaires' light at a sample on `hit`'s patch).
Rgb lit_colour(const radfmt::MeshData& mesh, const RayScene::Hit& hit, const Rgb& direct,
               const Rgb& indirect, const Rgb& luminaires) {
    const auto& patch = mesh.patches[static_cast<std::size_t>(hit.patch)];
    const auto& material = mesh.materials[patch.material];
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = material.emission[c] +
                 material.reflectance[c] * (direct[c] + indirect[c] + luminaires[c]);
    return out;
}

// The streams of gathers made where no record reaches: apart from the records' (numbered by
// their slots, fewer than the image's samples).
constexpr std::uint64_t kUncoveredStreams = std::uint64_t(1) << 48;

// A pixel's front-facing samples on one patch, by the cache. What changes little across a
// pixel is found once at the samples' mean: the lights they see and what each gives
// unshadowed (Gatherer::direct_light over several points), and the indirect light: the
// cache's, or where no record covers the mean, one gather there (a gather's rays, --gather N)
// for these samples only. Each sample is shadowed from its own point. Their
// colours' sum goes to `sum`; `own` counts the samples no record covered.
void add_cached_patch(const Gatherer& gatherer, const IrradianceCache& cache,
                      const LuminaireSet* luminaires,
                      std::span<const Gatherer::DirectSample> samples,
                      std::span<const RayScene::Hit* const> hits, Gatherer::KeptCut* kept,
                      std::atomic<long>& own, double sum[3]) {
    Vec3 centre{0, 0, 0}, facing{0, 0, 0};
    for (const auto& s : samples) {
        centre = centre + s.point;
        facing = facing + s.normal;
    }
    centre = centre * (1.0 / double(samples.size()));
    const double n = length(facing);
    facing = n > 0 ? facing * (1 / n) : samples[0].normal;
    thread_local std::vector<Rgb> direct;
    direct.resize(samples.size());
    gatherer.direct_light(centre, facing, samples, direct, kept);
    const auto& mesh = gatherer.mesh();
    Rgb indirect;
    if (!cache.lookup(centre, facing, indirect)) {
        own += long(samples.size());
        const Vec3 surface = mesh.patches[static_cast<std::size_t>(hits[0]->patch)].normal;
        indirect =
            gatherer
                .indirect_sample(centre, facing, surface, std::max(1, gatherer.options().rays),
                                 kUncoveredStreams + samples[0].index)
                .indirect;
    }
    for (std::size_t k = 0; k < samples.size(); ++k) {
        const auto& s = samples[k];
        const Rgb lum = luminaire_light(gatherer, luminaires, s.point, s.normal);
        const Rgb colour = lit_colour(mesh, *hits[k], direct[k], indirect, lum);
        for (int c = 0; c < 3; ++c) sum[c] += colour[c];
    }
}

// Neighbouring pixels share which lights they see (the light tree's cut; each light's value
// is still found per pixel): a pixel at an even column wholly on one patch keeps its cut, and
// the next pixel, wholly on that patch, takes it. Per row, in column order: the same at any
// thread count and in any --rows band.
struct CutShare {
    Gatherer::KeptCut kept;
    std::int64_t patch = -1;
};

// The cut a pixel's samples keep or take (nullptr: neither, they span patches).
Gatherer::KeptCut* shared_cut(std::int64_t patch, bool one_patch, bool second, CutShare& share) {
    Gatherer::KeptCut* kept = nullptr;
    if (second) {
        if (one_patch && share.patch == patch) kept = &share.kept;
    } else if (one_patch) {
        share.kept.held = false;
        kept = &share.kept;
    }
    share.patch = !second && one_patch ? patch : -1;
    return kept;
}

// A pixel's front-facing samples by the cache, patch by patch (add_cached_patch); `second`:
// the pixel is at an odd column (it may take its left neighbour's cut).
struct PixelSample {
    RayScene::Hit hit;
    Vec3 point;
    std::uint64_t index;
};
void add_cached_samples(const Gatherer& gatherer, const IrradianceCache& cache,
                        const LuminaireSet* luminaires, std::span<const PixelSample> samples,
                        bool second, CutShare& share, std::atomic<long>& own, double sum[3]) {
    thread_local std::vector<Gatherer::DirectSample> on_patch;
    thread_local std::vector<const RayScene::Hit*> hits;
    thread_local std::vector<char> done;
    done.assign(samples.size(), 0);
    const bool one_patch =
        !samples.empty() && std::all_of(samples.begin(), samples.end(), [&](const auto& s) {
            return s.hit.patch == samples[0].hit.patch;
        });
    Gatherer::KeptCut* kept =
        shared_cut(samples.empty() ? -1 : samples[0].hit.patch, one_patch, second, share);
    for (std::size_t first = 0; first < samples.size(); ++first) {
        if (done[first]) continue;
        on_patch.clear();
        hits.clear();
        for (std::size_t k = first; k < samples.size(); ++k) {
            if (done[k] || samples[k].hit.patch != samples[first].hit.patch) continue;
            done[k] = 1;
            hits.push_back(&samples[k].hit);
            on_patch.push_back(
                {samples[k].point, gatherer.shading_normal(samples[k].hit), samples[k].index});
        }
        add_cached_patch(gatherer, cache, luminaires, on_patch, hits, kept, own, sum);
    }
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
        thread_local std::vector<PixelSample> samples;
        CutShare share;
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0}, squared_error[3] = {0, 0, 0};
            int backs = 0;
            samples.clear();
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
                    const Vec3 point = view.position + ray * hit.distance;
                    if (cache) {
                        samples.push_back({hit, point, index});
                        continue;
                    }
                    Rgb error{0, 0, 0};
                    const auto colour =
                        gathered_colour(gatherer, luminaires, hit, point, index, &error);
                    for (int c = 0; c < 3; ++c) {
                        sum[c] += colour[c];
                        squared_error[c] += error[c] * error[c];
                    }
                }
            if (cache)
                add_cached_samples(gatherer, *cache, luminaires, samples, x % 2 == 1, share, own,
                                   sum);
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
