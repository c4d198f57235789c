// Images of a daylight solution with the sun's beam sharp: the smoothed radiosity (the spread
// beam taken out) plus the beam traced at every point a camera ray meets.
#include "radiosity/daylight.hpp"
#include "radiosity/specular_view.hpp"

namespace rad {

Image render_with_beam(const radfmt::MeshData& mesh, const CornerColours& corners,
                       const SharpBeam& beam, const View& view, int width, int height,
                       int supersampling, bool quiet, RowBand rows) {
    const RayScene scene(mesh);
    const SpecularSurfaces surfaces(mesh);
    const auto smoothed = smoothed_shader(mesh, corners);
    const HitShader shade = [&](const PathHit& h, std::uint64_t sample, Rgb* error) {
        auto colour = smoothed(h, sample, error);
        const auto& patch = mesh.patches[std::size_t(h.hit.patch)];
        // Off the surface a little, so that the ray to the sun does not meet it again.
        const Vec3 point =
            h.origin + h.direction * h.hit.distance + patch.normal * (4 * scene.epsilon());
        const auto sun =
            beam_radiosity(beam, scene, surfaces, kDefaultSpecularDepth,
                           mesh.materials[patch.material].reflectance, point, patch.normal);
        for (std::size_t c = 0; c < 3; ++c) colour[c] += sun[c];
        return colour;
    };
    return render_specular({mesh, scene, surfaces, kDefaultSpecularDepth}, view, width, height,
                           supersampling, shade, quiet, rows);
}

} // namespace rad
