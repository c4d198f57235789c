// The sun's beam made sharp in a solution under one sky: the beam's light the solve spread over
// its sky patch's view taken out, the beam traced where it is seen (rad-shade --sky, the page).
#include "radiosity/daylight.hpp"
#include "radiosity/gather.hpp"

namespace rad {

std::vector<Rgb> spread_beam(const radfmt::SkyData& view, const radfmt::MeshData& mesh,
                             std::size_t sky_patch, double radiance) {
    std::vector<Rgb> out(mesh.patches.size(), Rgb{{0, 0, 0}});
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto& rho = mesh.materials[mesh.patches[i].material].reflectance;
        const auto d = view.of(i, sky_patch);
        for (std::size_t c = 0; c < 3; ++c) out[i][c] = rho[c] * d[c] * radiance;
    }
    return out;
}

SharpBeam sharp_beam(const DaylightSolution& solution, const radfmt::SkyData& view,
                     const radfmt::MeshData& mesh, const Sky& sky,
                     const std::vector<Rgb>& under_sky) {
    SharpBeam out{under_sky, sky.sun_direction(), 0};
    const auto sun = sun_patch(solution.patches, sky);
    if (!sun) return out;
    out.normal_illuminance = sky.sun_normal_illuminance();
    const auto spread = spread_beam(view, mesh, sun->patch, sun->luminance / kRadianceEfficacy);
    for (std::size_t i = 0; i < out.radiosity.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            out.radiosity[i][c] = std::max(0.0, out.radiosity[i][c] - spread[i][c]);
    return out;
}

Rgb beam_radiosity(const SharpBeam& beam, const RayScene& scene, const SpecularSurfaces& specular,
                   int depth, const Rgb& rho, const Vec3& point, const Vec3& normal) {
    if (!(beam.normal_illuminance > 0)) return {0, 0, 0};
    const double lux =
        sensor_sun(scene, specular, depth, point, normal, beam.direction, beam.normal_illuminance);
    const double irradiance = lux / kRadianceEfficacy;
    return {rho[0] * irradiance, rho[1] * irradiance, rho[2] * irradiance};
}

} // namespace rad
