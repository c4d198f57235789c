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
// E + rho x (the direct, indirect and luminaires' light at a sample on `patch`).
Rgb lit_colour(const radfmt::MeshData& mesh, std::int64_t patch, const Rgb& direct,
               const Rgb& indirect, const Rgb& luminaires) {
    const auto& material = mesh.materials[mesh.patches[static_cast<std::size_t>(patch)].material];
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = material.emission[c] +
                 material.reflectance[c] * (direct[c] + indirect[c] + luminaires[c]);
    return out;
}

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
    const Rgb out = lit_colour(mesh, hit.patch, gathered.direct, gathered.indirect, known);
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

// The streams of gathers made where no record reaches: apart from the records' (numbered by
// their slots, fewer than the image's samples).
constexpr std::uint64_t kUncoveredStreams = std::uint64_t(1) << 48;

// A pixel's front-facing samples on one patch: what changes little across a pixel is found
// once at the samples' mean (`centre`, `facing`): the lights they see and what each gives
// unshadowed, and the indirect light: the cache's, or where no record covers the mean, one
// gather there (a gather's rays, --gather N) for these samples only. Each sample is shadowed
// from its own point.
struct PatchGroup {
    std::int64_t patch = -1;
    Vec3 centre{0, 0, 0}, facing{0, 0, 0};
    std::vector<Gatherer::DirectSample> samples;
    Gatherer::SeenLights seen;
};

// A sample that met the front of a surface: where, and its random streams' index.
struct PixelSample {
    RayScene::Hit hit;
    Vec3 point;
    std::uint64_t index;
};

// A pixel's samples by the cache, grouped by patch; `kept`: its cut of the light tree when
// it lies wholly on one patch (the even pixel two columns on, on that patch too, may take it).
struct CachedPixel {
    std::vector<PixelSample> samples;
    std::vector<PatchGroup> groups;
    std::size_t group_count = 0;
    int backs = 0;
    bool covered = false;
    Gatherer::KeptCut kept;
    bool one_patch() const { return group_count == 1; }
    const PatchGroup* group_on(std::int64_t patch) const {
        for (std::size_t g = 0; g < group_count; ++g)
            if (groups[g].patch == patch) return &groups[g];
        return nullptr;
    }
};

// Pixel x's ss x ss samples of row y (of a W x H grid of samples) traced: those that met the
// front of a surface into `front`, in order; `backs` counts those that met a back, `covered`
// says whether any met a surface.
void trace_samples(const Gatherer& gatherer, const View& view, int x, int y, int ss, int W, int H,
                   std::vector<PixelSample>& front, int& backs, bool& covered) {
    front.clear();
    backs = 0;
    covered = false;
    for (int sy = 0; sy < ss; ++sy)
        for (int sx = 0; sx < ss; ++sx) {
            // The sample's centre, in the rasteriser's screen convention.
            const double sample_x = x * ss + sx + 0.5, sample_y = y * ss + sy + 0.5;
            const Vec3 ray = view_ray(view, sample_x / W, sample_y / H);
            const auto hit = gatherer.scene().trace(view.position, ray);
            if (hit.patch < 0) continue;
            covered = true;
            if (!hit.front) {
                ++backs;
                continue;
            }
            const std::uint64_t index = std::uint64_t(y * ss + sy) * W + (x * ss + sx);
            front.push_back({hit, view.position + ray * hit.distance, index});
        }
}

// Pixel x's samples of row y traced and grouped by the patch they lie on.
void trace_pixel(const Gatherer& gatherer, const View& view, int x, int y, int ss, int W, int H,
                 CachedPixel& px) {
    trace_samples(gatherer, view, x, y, ss, W, H, px.samples, px.backs, px.covered);
    px.group_count = 0;
    for (std::size_t k = 0; k < px.samples.size(); ++k) {
        const auto patch = px.samples[k].hit.patch;
        if (px.group_on(patch)) continue;
        if (px.group_count == px.groups.size()) px.groups.emplace_back();
        PatchGroup& g = px.groups[px.group_count++];
        g.patch = patch;
        g.samples.clear();
        Vec3 centre{0, 0, 0}, facing{0, 0, 0};
        for (std::size_t m = k; m < px.samples.size(); ++m) {
            if (px.samples[m].hit.patch != patch) continue;
            const auto& s = px.samples[m];
            g.samples.push_back({s.point, gatherer.shading_normal(s.hit), s.index});
            centre = centre + s.point;
            facing = facing + g.samples.back().normal;
        }
        g.centre = centre * (1.0 / double(g.samples.size()));
        const double n = length(facing);
        g.facing = n > 0 ? facing * (1 / n) : g.samples[0].normal;
    }
}

// The lights a pixel at an even column sees, group by group at each group's centre. Wholly
// on one patch, it keeps its cut of the light tree, or takes `previous`'s (the even pixel
// before it, two columns away), when that one lies wholly on the same patch: their cuts would
// differ by nothing or a group opened one level more or less, and the pixel between them then
// finds all its lights in both (find_odd).
void find_even(const Gatherer& gatherer, CachedPixel& px, CachedPixel* previous) {
    px.kept.held = false;
    Gatherer::KeptCut* kept = nullptr;
    if (px.one_patch()) {
        const bool take = previous && previous->one_patch() && previous->kept.held &&
                          previous->groups[0].patch == px.groups[0].patch;
        kept = take ? &previous->kept : &px.kept;
    }
    for (std::size_t g = 0; g < px.group_count; ++g)
        gatherer.seen_lights(px.groups[g].centre, px.groups[g].facing, px.groups[g].seen, kept);
}

// How far off the line between its neighbours a group's centre may lie and still blend their
// lights, as a share of their distance apart.
constexpr double kMostOffLine = 0.05;

// The lights a pixel at an odd column sees. What a light gives unshadowed is smooth along a
// surface: where its left neighbour has samples on the group's patch, the group takes that
// neighbour's cut, each light and group of it blended linearly between the two neighbours'
// values to the group's centre where the right one found it too, and found there where not
// (Gatherer::seen_between): the exact form factors, most of a pixel's cost beside its shadow
// rays, for about half the pixels. Elsewhere it finds its own.
void find_odd(const Gatherer& gatherer, CachedPixel& px, const CachedPixel& left,
              const CachedPixel* right) {
    static const Gatherer::SeenLights none;
    for (std::size_t g = 0; g < px.group_count; ++g) {
        PatchGroup& group = px.groups[g];
        const PatchGroup* a = left.group_on(group.patch);
        if (!a) {
            gatherer.seen_lights(group.centre, group.facing, group.seen);
            continue;
        }
        const PatchGroup* b = right ? right->group_on(group.patch) : nullptr;
        const Vec3 span = b ? b->centre - a->centre : Vec3{0, 0, 0};
        const double span2 = dot(span, span);
        const double share =
            span2 > 0 ? std::clamp(dot(group.centre - a->centre, span) / span2, 0.0, 1.0) : 0.0;
        // Off the line between them (a pixel partly on the patch has its samples' centre
        // off its own), the light changes across the line too: none is blended.
        const Vec3 off = group.centre - a->centre - span * share;
        if (dot(off, off) > kMostOffLine * kMostOffLine * span2) b = nullptr;
        gatherer.seen_between(a->seen, b ? b->seen : none, share, group.centre, group.facing,
                              group.seen);
    }
}

// The pixel's colour: its groups' samples shadowed, their indirect light from the cache (or
// one gather where no record covers the centre), their sum over the pixel's samples;
// `own` counts the samples no record covered.
Rgb shade_pixel(const Gatherer& gatherer, const IrradianceCache& cache,
                const LuminaireSet* luminaires, CachedPixel& px, std::atomic<long>& own) {
    const auto& mesh = gatherer.mesh();
    thread_local std::vector<Rgb> direct;
    Rgb sum{0, 0, 0};
    for (std::size_t g = 0; g < px.group_count; ++g) {
        PatchGroup& group = px.groups[g];
        direct.resize(group.samples.size());
        gatherer.direct_light(group.seen, group.samples, direct);
        Rgb indirect;
        if (!cache.lookup(group.centre, group.facing, indirect)) {
            own += long(group.samples.size());
            const Vec3 surface = mesh.patches[static_cast<std::size_t>(group.patch)].normal;
            indirect = gatherer
                           .indirect_sample(group.centre, group.facing, surface,
                                            std::max(1, gatherer.options().rays),
                                            kUncoveredStreams + group.samples[0].index)
                           .indirect;
        }
        for (std::size_t k = 0; k < group.samples.size(); ++k) {
            const auto& s = group.samples[k];
            const Rgb lum = luminaire_light(gatherer, luminaires, s.point, s.normal);
            const Rgb colour = lit_colour(mesh, group.patch, direct[k], indirect, lum);
            for (int c = 0; c < 3; ++c) sum[c] += colour[c];
        }
    }
    return sum;
}

// A row by the cache. Pixels at even columns find their lights first, so that each pixel
// between two may blend theirs (find_odd); per row, in column order: the same at any thread
// count and in any --rows band.
void render_cached_row(const Gatherer& gatherer, const IrradianceCache& cache,
                       const LuminaireSet* luminaires, const View& view, int y, int ss,
                       Image& image, std::atomic<long>& own) {
    const int width = image.width, W = width * ss, H = image.height * ss;
    if (width <= 0) return;
    thread_local CachedPixel left, middle, right;
    const auto finish = [&](CachedPixel& px, int x) {
        const Rgb sum = shade_pixel(gatherer, cache, luminaires, px, own);
        const std::size_t at = std::size_t(y) * width + x;
        for (int c = 0; c < 3; ++c) image.rgb[3 * at + c] = static_cast<float>(sum[c] / (ss * ss));
        image.covered[at] = px.covered;
        image.back_coverage[at] = float(px.backs) / float(ss * ss);
    };
    trace_pixel(gatherer, view, 0, y, ss, W, H, left);
    find_even(gatherer, left, nullptr);
    for (int x = 1; x < width; x += 2) {
        trace_pixel(gatherer, view, x, y, ss, W, H, middle);
        const bool has_right = x + 1 < width;
        if (has_right) {
            trace_pixel(gatherer, view, x + 1, y, ss, W, H, right);
            // Even pixels pair up: 0 keeps its cut and 2 takes it, 4 keeps and 6 takes...
            find_even(gatherer, right, (x + 1) % 4 == 2 ? &left : nullptr);
        }
        find_odd(gatherer, middle, left, has_right ? &right : nullptr);
        finish(left, x - 1);
        finish(middle, x);
        if (has_right)
            std::swap(left, right);
        else
            return;
    }
    finish(left, width - 1); // an odd width's last pixel
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
        if (cache) {
            render_cached_row(gatherer, *cache, luminaires, view, y, ss, image, own);
            progress.advance(1);
            return;
        }
        thread_local std::vector<PixelSample> front;
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0}, squared_error[3] = {0, 0, 0};
            int backs = 0;
            bool any = false;
            trace_samples(gatherer, view, x, y, ss, W, H, front, backs, any);
            if (any) covered[std::size_t(y) * width + x] = 1;
            for (const auto& s : front) {
                Rgb error{0, 0, 0};
                const auto colour =
                    gathered_colour(gatherer, luminaires, s.hit, s.point, s.index, &error);
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
