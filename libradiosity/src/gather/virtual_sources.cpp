// Emitters seen in planar mirrors, as virtual light sources (see virtual_sources.hpp).
#include "gather/virtual_sources.hpp"

#include "formfactor/sampling.hpp"
#include "gather/light_tree.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/patch_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace rad::gather {

namespace {
bool emits(const Rgb& e) {
    return e[0] > 0 || e[1] > 0 || e[2] > 0;
}
} // namespace

VirtualSources::VirtualSources(const radfmt::MeshData& mesh, const SpecularSurfaces& specular,
                               std::span<const Rgb> emission)
    : mesh_(mesh), specular_(specular), mirrors_(planar_mirrors(mesh, specular)) {
    if (mirrors_.empty()) return;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        if (emits(emission[i])) {
            emitters_.push_back(static_cast<std::uint32_t>(i));
            emission_.push_back(emission[i]);
        }
}

Rgb VirtualSources::irradiance(const Vec3& point, const Vec3& normal, const RayScene& scene,
                               int rays, Rng& rng) const {
    Rgb sum{0, 0, 0};
    if (empty()) return sum;
    thread_local std::vector<Image> images;
    thread_local std::vector<Vec3> mirrored;
    for (std::size_t k = 0; k < mirrors_.planes.size(); ++k) {
        const auto& plane = mirrors_.planes[k];
        if (dot(point - plane.point, plane.normal) <= scene.epsilon()) continue; // behind it
        std::size_t count = 0;
        double total = 0;
        for (std::size_t e = 0; e < emitters_.size(); ++e) {
            const auto patch = emitters_[e];
            const auto& p = mesh_.patches[patch];
            if (dot(p.centroid - plane.point, plane.normal) <= 0) continue; // behind the mirror
            const Vec3 image_normal = mirrors_.mirrored_direction(k, p.normal);
            const Vec3 image_centre = mirrors_.mirrored(k, p.centroid);
            if (dot(point - image_centre, image_normal) <= 0) continue; // its image faces away
            // Mirrored, the corners run the other way: reversed, they face as the image shines.
            mirrored.clear();
            for (const auto& v : patch_points(mesh_, patch))
                mirrored.push_back(mirrors_.mirrored(k, v));
            std::reverse(mirrored.begin(), mirrored.end());
            if (count == images.size()) images.emplace_back();
            Image& image = images[count];
            ff::clip_to_front(mirrored, point, normal, image.clipped);
            if (image.clipped.size() < 3) continue;
            const double f = point_to_polygon_form_factor(point, normal, image.clipped);
            if (!(f > 0)) continue;
            image.cdf = ff::fan_cdf(image.clipped);
            image.normal = image_normal;
            for (int c = 0; c < 3; ++c) image.irradiance[c] = emission_[e][c] * f;
            image.weight = brightness(image.irradiance);
            total += image.weight;
            ++count;
        }
        if (!(total > 0)) continue;
        const auto through =
            through_mirror(point, normal, k, std::span<const Image>(images.data(), count), total,
                           scene, rays, rng);
        for (int c = 0; c < 3; ++c) sum[c] += through[c];
    }
    return sum;
}

// The images' light that comes through mirror `plane`: shadow rays to points on the images,
// each chosen by what it gives, weighted by the form-factor kernel; a ray counts when it meets
// the mirror's front before the image and the reflected segment reaches the emitter, with the
// mirror's reflectance at its angle.
Rgb VirtualSources::through_mirror(const Vec3& point, const Vec3& normal, std::size_t plane,
                                   std::span<const Image> images, double total,
                                   const RayScene& scene, int rays, Rng& rng) const {
    rays = std::max(rays, 1);
    const double offset = rng.uniform();
    double weight_sum = 0, plain = 0;
    Rgb seen_sum{0, 0, 0}, plain_seen{0, 0, 0};
    std::size_t at = 0;
    double below = 0;
    for (int s = 0; s < rays; ++s) {
        const double target = ff::wrap((s + 0.5) / rays + offset) * total;
        if (target < below) at = 0, below = 0;
        while (at + 1 < images.size() && below + images[at].weight <= target)
            below += images[at++].weight;
        const Image& image = images[at];
        const Vec3 q = ff::uniform_point(image.clipped, image.cdf, rng.uniform(), rng.uniform(),
                                         rng.uniform());
        const Vec3 d = q - point;
        const double r2 = dot(d, d);
        if (!(r2 > 0)) continue;
        const double w =
            std::max(0.0, dot(d, normal)) * std::max(0.0, -dot(d, image.normal)) / (r2 * r2);
        const Rgb seen =
            via_mirror(scene, specular_, mirrors_, plane, point, mirrors_.mirrored(plane, q));
        weight_sum += w;
        plain += 1;
        for (int c = 0; c < 3; ++c) {
            seen_sum[c] += w * seen[c];
            plain_seen[c] += seen[c];
        }
    }
    Rgb out{0, 0, 0};
    for (int c = 0; c < 3; ++c) {
        const double fraction =
            weight_sum > 0 ? seen_sum[c] / weight_sum : (plain > 0 ? plain_seen[c] / plain : 0);
        double light = 0;
        for (const auto& image : images) light += image.irradiance[c];
        out[c] = light * fraction;
    }
    return out;
}

} // namespace rad::gather
