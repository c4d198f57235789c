// Luminous openings drawn into an image by rays from the camera, in front of the scene.
#include "radiosity/luminaire_image.hpp"

#include "radiosity/gather.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad {
namespace {
// Where the camera ray meets the luminaire's opening (its plane through the centre, normal to
// the nadir), or a negative distance when it misses it or sees its back.
double opening_hit(const LuminaireSet& set, const Luminaire& l, const Vec3& eye, const Vec3& ray) {
    const auto& p = set.photometries[l.photometry];
    const double facing = dot(ray, l.nadir);
    if (facing >= 0) return -1; // the light leaves towards the nadir's side
    const double t = dot(l.position - eye, l.nadir) / facing;
    if (!(t > 0)) return -1;
    const Vec3 q = eye + ray * t - l.position;
    const double s = set.metres_per_unit;
    const double a = dot(q, l.c0) * s, b = dot(q, l.c90) * s;
    const bool inside = p.round ? a * a + b * b <= 0.25 * p.length * p.length
                                : std::abs(a) <= 0.5 * p.length && std::abs(b) <= 0.5 * p.width;
    return inside ? t : -1;
}

// pi x the opening's luminance towards -ray, as W/m^2 of white.
double opening_value(const LuminaireSet& set, const Luminaire& l, const Vec3& ray) {
    const auto& p = set.photometries[l.photometry];
    const double area =
        p.round ? std::numbers::pi * 0.25 * p.length * p.length : p.length * p.width;
    const double projected = area * std::abs(dot(ray, l.nadir));
    if (!(projected > 0)) return 0;
    return std::numbers::pi * set.intensity(l, ray * -1) / projected / kRadianceEfficacy;
}
} // namespace

std::size_t draw_luminaires(Image& image, const LuminaireSet& set, const RayScene& scene,
                            const View& view, int supersampling,
                            const std::vector<Rgb>& group_weights) {
    const int ss = std::max(1, supersampling);
    const int W = image.width * ss, H = image.height * ss;
    std::vector<std::uint8_t> changed(std::size_t(image.width) * image.height, 0);
    // The tolerance that lets an opening on a ceiling's plane win over the ceiling.
    const double tolerance = 100 * scene.epsilon();
    tbb::parallel_for(0, image.height, [&](int y) {
        for (int x = 0; x < image.width; ++x) {
            double sum[3] = {0, 0, 0};
            int hits = 0;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    const Vec3 ray =
                        view_ray(view, (x * ss + sx + 0.5) / W, (y * ss + sy + 0.5) / H);
                    const auto surface = scene.trace(view.position, ray);
                    double nearest = surface.patch >= 0 ? surface.distance + tolerance : 1e300;
                    const Luminaire* seen = nullptr;
                    for (const auto& l : set.luminaires) {
                        const double t = opening_hit(set, l, view.position, ray);
                        if (t > 0 && t < nearest) {
                            nearest = t;
                            seen = &l;
                        }
                    }
                    if (!seen) continue;
                    ++hits;
                    const double value = opening_value(set, *seen, ray);
                    const auto g = set.group_of(*seen);
                    for (std::size_t c = 0; c < 3; ++c)
                        sum[c] += value * seen->tint[c] *
                                  (group_weights.empty() ? 1.0 : group_weights[g][c]);
                }
            if (!hits) continue;
            // The samples that saw an opening replace theirs in the pixel's mean.
            const std::size_t at = std::size_t(y) * image.width + x;
            const double keep = 1 - double(hits) / (ss * ss);
            for (int c = 0; c < 3; ++c)
                image.rgb[3 * at + c] = float(image.rgb[3 * at + c] * keep + sum[c] / (ss * ss));
            changed[at] = 1;
        }
    });
    return std::size_t(std::count(changed.begin(), changed.end(), 1));
}

} // namespace rad
