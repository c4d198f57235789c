// Daylight at sensors: the sky seen directly (traced from the sensor through openings and
// glass) and the light the room reflects (rays taking each patch's radiosity per sky patch
// from the solve of the .sky's light groups).
#include "radiosity/daylight.hpp"

#include "radiosity/batch_error.hpp"
#include "radiosity/error.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/random.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdlib>
#include <numbers>

namespace rad {
namespace {
// Where an opening's edge crosses a sky patch it is sampled at 3 times the side (576
// directions at the default 8 x 8; 4 times read 0.16% off under a roof opening for 3 times
// the time, 2 times 2.4% for 1.5 times), at most 32.
constexpr int kRefineFactor = 3, kFinestSkySide = 32;
// The stream of the sky's jittered cells at a sensor (batch_stream's batches are >= 0).
constexpr int kSkyJitterStream = -1;
} // namespace

SkyRefinement sky_refinement(const SkyPatches& patches, const SkyFrame& frame,
                             const SkyPatches::Cells& cells, int side) {
    SkyRefinement out;
    if (side >= kFinestSkySide) return out;
    out.fine_side = std::min(kRefineFactor * side, kFinestSkySide);
    out.fine = patches.cells(frame, out.fine_side);
    out.frame = frame;
    // Each patch's centre and angular radius from its cells; neighbours overlap when grown by
    // half.
    const std::size_t count = cells.size();
    std::vector<Vec3> centre(count);
    std::vector<double> radius(count, 0);
    for (std::size_t p = 0; p < count; ++p) {
        Vec3 sum{0, 0, 0};
        for (const auto& d : cells[p]) sum = sum + d;
        centre[p] = length(sum) > 0 ? normalized(sum) : Vec3{0, 1, 0};
        for (const auto& d : cells[p])
            radius[p] = std::max(radius[p], std::acos(std::clamp(dot(d, centre[p]), -1.0, 1.0)));
    }
    out.neighbours.resize(count);
    for (std::size_t p = 0; p < count; ++p)
        for (std::size_t q = 0; q < count; ++q) {
            if (q == p) continue;
            const double apart = std::acos(std::clamp(dot(centre[p], centre[q]), -1.0, 1.0));
            if (apart < 1.5 * (radius[p] + radius[q]))
                out.neighbours[p].push_back(static_cast<std::uint32_t>(q));
        }
    return out;
}

bool is_daylight_solution(const radfmt::Header& header) {
    return header.find("sky_subdivision") != nullptr;
}

SkyFrame daylight_frame(const radfmt::Header& header, const std::string& path) {
    const auto& north = header.get("north", path);
    char* end = nullptr;
    SkyFrame frame{std::strtod(north.c_str(), &end)};
    if (end == north.c_str() || *end || !(frame.north_deg >= -360 && frame.north_deg <= 360))
        throw InputError(path + ": north '" + north +
                         "' is no angle from -360 to 360 degrees, which rad-ff writes");
    return frame;
}

DaylightSolution daylight_solution(const radfmt::RadiosityData& solution,
                                   const radfmt::Header& header, const std::string& path) {
    const auto* subdivision = header.find("sky_subdivision");
    if (!subdivision)
        throw InputError(path + " was not solved with a sky: run rad-ff MESH --sky reinhart:1 -o "
                                "SKY, then rad-solve MESH FF --direct SKY -o SOLUTION");
    DaylightSolution out{SkyPatches::parse(*subdivision), daylight_frame(header, path), {}};
    const std::size_t count = out.patches.count(), groups = solution.group_count();
    std::vector<std::size_t> group(count);
    for (std::size_t s = 0; s < count; ++s) {
        const auto name = out.patches.name(s);
        std::size_t g = 0;
        while (g < groups && solution.group_names[g] != name) ++g;
        if (g == groups)
            throw InputError(path + ": light group '" + name +
                             "' of the sky is missing: solve "
                             "with rad-solve --direct SKY again");
        group[s] = g;
    }
    const std::size_t n = solution.radiosity.size();
    out.radiosity.resize(n * count * 3);
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t s = 0; s < count; ++s)
            for (std::size_t c = 0; c < 3; ++c)
                out.radiosity[(j * count + s) * 3 + c] = float(solution.of_group(j, group[s])[c]);
    return out;
}

DaylightSensors::DaylightSensors(const radfmt::MeshData& mesh, DaylightSolution solution,
                                 DaylightOptions options)
    : mesh_(mesh), solution_(std::move(solution)), options_(options),
      cells_(solution_.patches.cells(solution_.frame, options.sky_side)),
      refine_(sky_refinement(solution_.patches, solution_.frame, cells_, options.sky_side)),
      scene_(std::make_unique<RayScene>(mesh)), specular_(std::make_unique<SpecularSurfaces>(mesh)),
      mirrors_(planar_mirrors(mesh, *specular_)) {}

DaylightSensors::~DaylightSensors() = default;

std::vector<std::uint8_t> DaylightSensors::inside(std::span<const Vec3> points,
                                                  std::span<const Vec3> normals) const {
    constexpr int kRays = 64;
    std::vector<std::uint8_t> out(points.size(), 0);
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        const Vec3 n = normals[k], tu = orthogonal(n), tv = cross(n, tu);
        Rng rng(0x1A51DE, k);
        int hits = 0, backs = 0;
        for (int r = 0; r < kRays; ++r) {
            const double u = (r + rng.uniform()) / kRays, v = rng.uniform();
            const auto hit = scene_->trace(points[k], cosine_direction(n, tu, tv, u, v));
            if (hit.patch < 0) continue;
            ++hits;
            // Glass is met from behind as often as from the front.
            if (!hit.front && !specular_->transmits(static_cast<std::size_t>(hit.patch))) ++backs;
        }
        out[k] = sees_mostly_backs(double(hits) / kRays, hits ? double(backs) / hits : 0);
    });
    return out;
}

DaylightSensors::Coefficients DaylightSensors::coefficients(const Vec3& point, const Vec3& normal,
                                                            std::uint64_t index) const {
    Coefficients out{std::vector<double>(patches().count(), 0.0), reflected(point, normal, index)};
    sensor_sky_paths(
        *scene_, *specular_, patches(), cells_, options_.specular_depth, point, normal,
        [&](const Vec3& d, const Rgb& w, std::int64_t) {
            out.direct[patches().patch_of(frame(), d)] += weighted(w);
        },
        &refine_);
    return out;
}

namespace {
// The reflected light's rays as batches: `batches` of side x side jittered strata (16 of a
// quarter of the side where each then has at least 9 rays; else 4 of half; else 1).
struct ReflectedBatches {
    int batches = 1, side = 1;
};
ReflectedBatches reflected_plan(int rays) {
    const int side = std::max(1, int(std::lround(std::sqrt(double(rays)))));
    if (side / 4 >= 3) return {16, side / 4};
    if (side / 2 >= 2) return {4, side / 2};
    return {1, side};
}
} // namespace

// The room's reflected light per sky patch: E = (1 / M) sum of B where M cosine-weighted
// rays (jittered strata) land, through mirrors and glass; batch by batch.
template <class Each>
void DaylightSensors::reflected_batches(const Vec3& point, const Vec3& normal, std::uint64_t index,
                                        Each&& each, int first, int end) const {
    const std::size_t count = patches().count();
    const auto plan = reflected_plan(options_.rays);
    const int side = plan.side;
    const double share = 1.0 / (side * side);
    const Vec3 tu = orthogonal(normal), tv = cross(normal, tu);
    const auto& b = solution_.radiosity;
    thread_local std::vector<double> out;
    for (int batch = first; batch < (end < 0 ? plan.batches : end); ++batch) {
        out.assign(count, 0.0);
        Rng rng = batch_stream(options_.seed, index, batch);
        for (int k = 0; k < side * side; ++k) {
            const double u = ((k / side) + rng.uniform()) / side;
            const double v = ((k % side) + rng.uniform()) / side;
            follow_specular(*scene_, *specular_, point, cosine_direction(normal, tu, tv, u, v),
                            Rgb{{1, 1, 1}}, options_.specular_depth, [&](const PathHit& h) {
                                if (!h.hit.front) return;
                                const float* row = &b[std::size_t(h.hit.patch) * count * 3];
                                const auto& c = options_.channel_weights;
                                const double w0 = c[0] * h.weight[0] * share,
                                             w1 = c[1] * h.weight[1] * share,
                                             w2 = c[2] * h.weight[2] * share;
                                for (std::size_t s = 0; s < count; ++s)
                                    out[s] +=
                                        w0 * row[3 * s] + w1 * row[3 * s + 1] + w2 * row[3 * s + 2];
                            });
        }
        each(static_cast<const std::vector<double>&>(out));
    }
}

int DaylightSensors::reflected_batch_count() const {
    return options_.rays > 0 ? reflected_plan(options_.rays).batches : 0;
}

std::vector<double> DaylightSensors::reflected_batch_coefficients(const Vec3& point,
                                                                  const Vec3& normal,
                                                                  std::uint64_t index,
                                                                  int& batches) const {
    std::vector<double> out;
    batches = 0;
    if (options_.rays <= 0) return out;
    reflected_batches(point, normal, index, [&](const std::vector<double>& c) {
        out.insert(out.end(), c.begin(), c.end());
        ++batches;
    });
    return out;
}

std::vector<double> DaylightSensors::reflected(const Vec3& point, const Vec3& normal,
                                               std::uint64_t index) const {
    std::vector<double> sum(patches().count(), 0.0);
    if (options_.rays <= 0) return sum;
    int batches = 0;
    reflected_batches(point, normal, index, [&](const std::vector<double>& c) {
        for (std::size_t s = 0; s < c.size(); ++s) sum[s] += c[s];
        ++batches;
    });
    for (auto& v : sum) v /= batches;
    return sum;
}

std::optional<SunPatch> sun_patch(const SkyPatches& patches, const Sky& sky) {
    if (!sky.sun_up() || !(sky.sun_normal_illuminance() > 0)) return std::nullopt;
    const auto p = patches.patch_of(sky.frame(), sky.sun_direction());
    return SunPatch{p, sky.sun_normal_illuminance() / patches.solid_angle(p)};
}

std::vector<double> patch_luminance_with_sun(const SkyPatches& patches, const Sky& sky, int side) {
    auto out = patches.mean_luminance(sky, side);
    if (const auto sun = sun_patch(patches, sky)) out[sun->patch] += sun->luminance;
    return out;
}

std::vector<Rgb> mix_sky_groups(const DaylightSolution& solution,
                                const std::vector<double>& weights) {
    const std::size_t count = weights.size(), n = solution.radiosity.size() / (count * 3);
    std::vector<Rgb> out(n, Rgb{});
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t s = 0; s < count; ++s)
            if (weights[s] != 0)
                for (std::size_t c = 0; c < 3; ++c)
                    out[j][c] += weights[s] * solution.radiosity[(j * count + s) * 3 + c];
    return out;
}

std::vector<Rgb> sky_radiosity(const DaylightSolution& solution, const Sky& sky) {
    auto radiance = patch_luminance_with_sun(solution.patches, sky);
    for (auto& l : radiance) l /= kRadianceEfficacy;
    return mix_sky_groups(solution, radiance);
}

DaylightSensors::Illuminance DaylightSensors::illuminance(const Sky& sky, const Vec3& point,
                                                          const Vec3& normal,
                                                          std::uint64_t index) const {
    Illuminance out;
    // Under one sky, the cells where an opening's edge crosses are jittered (their own
    // stream), so the sky's direct part carries its error too.
    Rng jitter = batch_stream(options_.seed, index, kSkyJitterStream);
    SkyQuadratureVariance variance;
    sensor_sky_paths(
        *scene_, *specular_, patches(), cells_, options_.specular_depth, point, normal,
        [&](const Vec3& d, const Rgb& w, std::int64_t slot) {
            const double lux = weighted(w) * sky.luminance(d);
            out.sky += lux;
            variance.add(slot, lux);
        },
        &refine_, &jitter);
    out.sky_error = std::sqrt(variance.variance());
    if (sky.sun_up())
        out.sun = options_.beam_weight *
                  sun(point, normal, sky.sun_direction(), sky.sun_normal_illuminance());
    if (options_.rays > 0) {
        const auto luminance = patch_luminance_with_sun(patches(), sky);
        BatchError batches;
        const auto add = [&](const std::vector<double>& c) {
            double lux = 0;
            for (std::size_t s = 0; s < luminance.size(); ++s) lux += c[s] * luminance[s];
            batches.add({lux, lux, lux});
        };
        reflected_batches(point, normal, index, add);
        const auto plan = reflected_plan(options_.rays);
        const int per_batch = plan.side * plan.side;
        int cast = plan.batches * per_batch;
        // Rounds to the accuracy asked for: a batch at a time, each from its own stream.
        // The sky's quadrature error is fixed by its cells: rays lower only the reflected
        // light's, to what the target leaves beside it (none left: rays cannot help).
        const auto short_of_accuracy = [&] {
            const double total = out.sky + out.sun + batches.mean()[0];
            const double error = batches.standard_error()[0];
            const double target = options_.accuracy * total;
            const double left = target * target - out.sky_error * out.sky_error;
            return options_.accuracy > 0 && std::isfinite(error) && left > 0 &&
                   error * error > left;
        };
        for (int batch = plan.batches; short_of_accuracy(); ++batch) {
            if (cast + per_batch > std::max(options_.max_rays, options_.rays)) {
                out.at_budget = true;
                break;
            }
            reflected_batches(point, normal, index, add, batch, batch + 1);
            cast += per_batch;
        }
        out.reflected = batches.mean()[0];
        out.reflected_error = batches.standard_error()[0];
        out.rays = cast;
    }
    return out;
}

std::vector<DaylightSensors::Illuminance>
DaylightSensors::illuminance(const Sky& sky, std::span<const Vec3> points,
                             std::span<const Vec3> normals, bool quiet) const {
    std::vector<Illuminance> out(points.size());
    Progress progress("sensors", points.size(), quiet);
    tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t k) {
        out[k] = illuminance(sky, points[k], normals[k], k);
        progress.advance(1);
    });
    progress.finish();
    return out;
}

double DaylightSensors::sun(const Vec3& point, const Vec3& normal, const Vec3& direction,
                            double lux) const {
    return sensor_sun(*scene_, *specular_, options_.specular_depth, point, normal, direction, lux,
                      &mirrors_);
}

} // namespace rad
