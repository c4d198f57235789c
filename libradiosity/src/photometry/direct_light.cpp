// The luminaires' direct light: at a point (exact, for rad-gather and rad-shade --gather) and
// averaged over every patch (rad-ff --luminaires: the .lum file rad-solve takes as the first
// bounce).
#include "formfactor/sampling.hpp"
#include "radiosity/gather.hpp"
#include "radiosity/luminaires.hpp"
#include "radiosity/patch_geometry.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/specular.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

namespace rad {
namespace {
constexpr int kOpeningSamples = 64; // points over a near luminaire's opening
constexpr double kNearFactor = 5;   // near: closer than this many openings
constexpr double kPointPatch = 0.2; // a patch under this fraction of its distance: one ray

// Where rays to the luminaire end: a hair in front of its centre along the nadir, so that
// the ceiling a downlight is recessed into never shadows it.
Vec3 ray_target(const Vec3& at, const Luminaire& l, const RayScene* scene) {
    return scene ? at + l.nadir * (10 * scene->epsilon()) : at;
}

// The luminaire's opening as kOpeningSamples points in its plane (centre, c0, c90): a grid
// over a rectangle, a sunflower over a disc.
std::vector<Vec3> opening_points(const LuminaireSet& set, const Luminaire& l) {
    const auto& p = set.photometries[l.photometry];
    const double s = 1 / set.metres_per_unit;
    std::vector<Vec3> out;
    if (p.round) {
        const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
        for (int k = 0; k < kOpeningSamples; ++k) {
            const double r = 0.5 * p.length * s * std::sqrt((k + 0.5) / kOpeningSamples);
            out.push_back(l.position + l.c0 * (r * std::cos(k * golden)) +
                          l.c90 * (r * std::sin(k * golden)));
        }
        return out;
    }
    const int side = 8;
    for (int a = 0; a < side; ++a)
        for (int b = 0; b < side; ++b)
            out.push_back(l.position + l.c0 * (p.length * s * ((a + 0.5) / side - 0.5)) +
                          l.c90 * (p.width * s * ((b + 0.5) / side - 0.5)));
    return out;
}

// The share of a luminaire's light that goes from `point` to `target` (its centre a hair in
// front): 1 or 0, or through thin panes their luminous transmission.
double passes(const RayScene& scene, const LuminaireOptics& optics, const Vec3& point,
              const Vec3& target) {
    if (!optics.specular) return scene.visible(point, target) ? 1 : 0;
    return luminous(
        straight_transmission(scene, *optics.specular, point, target, kDefaultSpecularDepth));
}

// Lux at `point` from the luminaire's images in the planar mirrors (point sources).
double image_lux(const LuminaireSet& set, const Luminaire& l, const Vec3& point, const Vec3& normal,
                 const RayScene& scene, const LuminaireOptics& optics) {
    if (!optics.specular || !optics.mirrors) return 0;
    const auto& mirrors = *optics.mirrors;
    double lux = 0;
    const Vec3 source = ray_target(l.position, l, &scene);
    for (std::size_t k = 0; k < mirrors.planes.size(); ++k) {
        const auto& plane = mirrors.planes[k];
        if (dot(source - plane.point, plane.normal) <= 0) continue; // behind the mirror
        const Vec3 d = point - mirrors.mirrored(k, l.position);     // from the image
        const double r = length(d);
        if (!(r > 0)) continue;
        const double cosine = -dot(d, normal) / r;
        if (cosine <= 0) continue;
        const double intensity = set.intensity(l, mirrors.mirrored_direction(k, d * (1 / r)));
        if (intensity <= 0) continue;
        const double reflected =
            luminous(via_mirror(scene, *optics.specular, mirrors, k, point, source));
        if (!(reflected > 0)) continue;
        const double metres = r * set.metres_per_unit;
        lux += intensity * cosine / (metres * metres) * reflected;
    }
    return lux;
}

// Lux at `point` from a point source at `from` with the luminaire's distribution, shadowed
// by `scene`; `share` of its intensity.
double point_source_lux(const LuminaireSet& set, const Luminaire& l, const Vec3& from,
                        const Vec3& point, const Vec3& normal, const RayScene* scene, double share,
                        const LuminaireOptics& optics) {
    const Vec3 d = point - from;
    const double r = length(d);
    if (!(r > 0)) return 0;
    const double cosine = -dot(d, normal) / r;
    if (cosine <= 0) return 0;
    const double intensity = set.intensity(l, d * (1 / r)) * share;
    if (intensity <= 0) return 0;
    const double through = scene ? passes(*scene, optics, point, ray_target(from, l, scene)) : 1;
    if (!(through > 0)) return 0;
    const double metres = r * set.metres_per_unit;
    return intensity * cosine / (metres * metres) * through;
}

// The solid angle of a planar polygon seen from `eye` (Van Oosterom and Strackee, over its
// fan), 0 when the eye is behind it.
double solid_angle(std::span<const Vec3> polygon, const Vec3& normal, const Vec3& eye) {
    if (dot(eye - polygon[0], normal) <= 0) return 0;
    double total = 0;
    const Vec3 a = polygon[0] - eye;
    const double la = length(a);
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
        const Vec3 b = polygon[k] - eye, c = polygon[k + 1] - eye;
        const double lb = length(b), lc = length(c);
        const double num = dot(a, cross(b, c));
        const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
        total += 2 * std::atan2(num, den);
    }
    return std::abs(total);
}

PatchPolygon polygon_of(std::span<const Vec3> points) {
    PatchPolygon g{};
    g.count = int(points.size());
    if (points.size() <= 4)
        std::copy(points.begin(), points.end(), g.corners.begin());
    else
        g.more = points.data();
    return g;
}

// Mean lux over a patch from one luminaire (see patch_direct_light); adds rays cast.
double patch_lux(const LuminaireSet& set, const Luminaire& l, const radfmt::Patch& patch,
                 std::span<const Vec3> corners, const std::vector<ff::Sample>& samples,
                 double diameter, const RayScene& scene, std::uint64_t& rays,
                 const LuminaireOptics& optics) {
    const Vec3 to_light = l.position - patch.centroid;
    double imaged = 0; // the luminaire's images in planar mirrors, over the Gauss points
    if (optics.mirrors && !optics.mirrors->empty())
        for (const auto& s : samples) {
            imaged += s.weight * image_lux(set, l, s.point, patch.normal, scene, optics);
            rays += optics.mirrors->planes.size();
        }
    if (dot(to_light, patch.normal) <= 0) return imaged;
    const double distance = length(to_light);
    const double opening = set.opening_size(l);
    if (opening > 0 && distance < kNearFactor * opening) {
        double lux = 0;
        for (const auto& s : samples) {
            // The images are `imaged`'s.
            lux += s.weight * luminaire_illuminance(set, l, s.point, patch.normal, &scene,
                                                    {optics.specular, nullptr});
            rays += kOpeningSamples;
        }
        return lux + imaged;
    }
    const double omega = solid_angle(corners, patch.normal, l.position);
    if (omega <= 0) return imaged;
    // Far: the solid angle exact, the intensity and visibility averaged over the patch's
    // points weighted by what each receives (cos / r^2).
    const auto one = std::vector<ff::Sample>{{patch.centroid, 1.0}};
    const auto& points = diameter < kPointPatch * distance ? one : samples;
    double weighted = 0, weights = 0;
    for (const auto& s : points) {
        const Vec3 d = s.point - l.position;
        const double r2 = dot(d, d);
        const double w = s.weight * std::max(0.0, -dot(d, patch.normal)) / (r2 * std::sqrt(r2));
        if (!(w > 0)) continue;
        weights += w;
        const double intensity = set.intensity(l, d * (1 / std::sqrt(r2)));
        if (intensity <= 0) continue;
        ++rays;
        weighted +=
            w * intensity * passes(scene, optics, s.point, ray_target(l.position, l, &scene));
    }
    if (!(weights > 0)) return imaged;
    const double s = set.metres_per_unit;
    return weighted / weights * omega / (patch.area * s * s) + imaged;
}
} // namespace

double luminaire_illuminance(const LuminaireSet& set, const Luminaire& l, const Vec3& point,
                             const Vec3& normal, const RayScene* scene,
                             const LuminaireOptics& optics) {
    const double opening = set.opening_size(l);
    const double imaged = scene ? image_lux(set, l, point, normal, *scene, optics) : 0;
    if (opening <= 0 || length(point - l.position) >= kNearFactor * opening)
        return point_source_lux(set, l, l.position, point, normal, scene, 1, optics) + imaged;
    double lux = 0;
    for (const auto& q : opening_points(set, l))
        lux += point_source_lux(set, l, q, point, normal, scene, 1.0 / kOpeningSamples, optics);
    return lux + imaged;
}

std::vector<Rgb> luminaire_irradiance(const LuminaireSet& set, const Vec3& point,
                                      const Vec3& normal, const RayScene* scene,
                                      const LuminaireOptics& optics) {
    std::vector<Rgb> out(set.groups.size(), Rgb{});
    for (const auto& l : set.luminaires) {
        const double lux = luminaire_illuminance(set, l, point, normal, scene, optics);
        auto& g = out[set.group_of(l)];
        for (int c = 0; c < 3; ++c)
            g[std::size_t(c)] += lux / kRadianceEfficacy * l.tint[std::size_t(c)];
    }
    return out;
}

std::vector<Rgb> patch_direct_light(const radfmt::MeshData& mesh, const LuminaireSet& set,
                                    const RayScene& scene, std::uint64_t begin, std::uint64_t end,
                                    DirectLightStats* stats, bool quiet,
                                    const LuminaireOptics& optics) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t groups = set.groups.size();
    end = std::min<std::uint64_t>(end, mesh.patches.size());
    std::vector<Rgb> out(mesh.patches.size() * groups, Rgb{});
    std::vector<double> nodes, weights;
    ff::gauss_legendre(4, nodes, weights);
    std::atomic<std::uint64_t> rays{0};
    Progress progress("rad-ff luminaires", end > begin ? end - begin : 0, quiet);
    tbb::parallel_for(std::uint64_t(begin), std::max(begin, end), [&](std::uint64_t i) {
        const auto& patch = mesh.patches[i];
        const auto corners = patch_points(mesh, i);
        const auto samples = ff::gauss_samples(polygon_of(corners), patch.area, nodes, weights);
        double diameter = 0;
        for (const auto& a : corners)
            for (const auto& b : corners) diameter = std::max(diameter, length(a - b));
        std::uint64_t cast = 0;
        for (const auto& l : set.luminaires) {
            const double lux =
                patch_lux(set, l, patch, corners, samples, diameter, scene, cast, optics);
            if (lux <= 0) continue;
            auto& g = out[i * groups + set.group_of(l)];
            for (int c = 0; c < 3; ++c)
                g[std::size_t(c)] += lux / kRadianceEfficacy * l.tint[std::size_t(c)];
        }
        rays += cast;
        progress.advance(1);
    });
    progress.finish();
    if (stats) {
        stats->rays = rays;
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return out;
}

std::vector<std::string> enclosed_luminaire_warnings(const LuminaireSet& set, const RayScene& scene,
                                                     const std::string& layout_name) {
    std::vector<std::string> out;
    constexpr int kRays = 256;
    const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
    for (const auto& l : set.luminaires) {
        double total = 0, hit = 0, back = 0;
        for (int k = 0; k < kRays; ++k) {
            const double z = 1 - 2 * (k + 0.5) / kRays, r = std::sqrt(1 - z * z);
            const Vec3 d{r * std::cos(k * golden), z, r * std::sin(k * golden)};
            const double w = set.intensity(l, d);
            if (w <= 0) continue;
            total += w;
            const auto first = scene.trace(ray_target(l.position, l, &scene), d);
            if (first.patch < 0) continue;
            hit += w;
            if (!first.front) back += w;
        }
        if (total > 0 && hit > 0 && sees_mostly_backs(hit / total, back / hit))
            out.push_back(layout_name + ":" + std::to_string(l.line) + ": luminaire '" + l.name +
                          "': " + std::to_string(int(std::lround(100 * back / hit))) +
                          "% of the light it sends onto surfaces meets their backs: its centre is "
                          "inside a closed object or behind a wall (check its x, y, z and aim)");
    }
    return out;
}

} // namespace rad
