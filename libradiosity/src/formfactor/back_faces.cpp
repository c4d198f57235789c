// The back-face check of rad-ff: probe rays for methods that cast no cosine-weighted rays,
// and the per-group report of patches that look at, or are reached at, their back.
#include "radiosity/formfactor.hpp"
#include "sampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

namespace rad {

namespace ff {

void probe_back_faces(const FormFactorContext& context, std::size_t i, std::uint64_t seed, int rays,
                      RayLog& log) {
    // A stream of its own (the seed's complement), so probing leaves the form factors alone.
    Rng rng(~seed, context.stream_key[i]);
    const auto& pi = context.mesh.patches[i];
    const auto poly = context.polygons[i].points();
    const auto cdf = fan_cdf(poly);
    const Vec3 tu = orthogonal(pi.normal), tv = cross(pi.normal, tu);
    for (int r = 0; r < rays; ++r) {
        const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
        const double u3 = rng.uniform(), u4 = rng.uniform();
        const Vec3 origin = uniform_point(poly, cdf, u0, u1, u2);
        const Vec3 dir = cosine_direction(pi.normal, tu, tv, u3, u4);
        const auto hit = context.scene.trace(origin, dir);
        log.record(hit.patch == static_cast<std::int64_t>(i) ? -1 : hit.patch, hit.front,
                   hit.distance);
    }
}

} // namespace ff

std::vector<std::string> back_face_warnings(const radfmt::MeshData& mesh,
                                            std::span<const float> back_fraction,
                                            const FormFactorStats& stats) {
    struct GroupTally {
        std::size_t patches = 0, looking_at_backs = 0;
        std::uint64_t reached_front = 0, reached_back = 0;
        Vec3 weighted_centre{0, 0, 0};
        double area = 0;
    };
    // By group; the patches of the unnamed group (an OBJ with no g/o lines) by material and
    // plane, the only names the file gives them.
    const double size = bounds(mesh.vertices).diagonal();
    char text[160];
    std::map<std::array<long long, 4>, long long> plane_index;
    auto plane_of = [&](const radfmt::Patch& patch) {
        const double d = dot(patch.normal, patch.centroid);
        const std::array<long long, 4> key{
            std::llround(patch.normal[0] * 1e3), std::llround(patch.normal[1] * 1e3),
            std::llround(patch.normal[2] * 1e3), std::llround(d / std::max(size, 1e-300) * 1e4)};
        return plane_index.emplace(key, (long long)plane_index.size()).first->second;
    };
    std::map<std::array<long long, 3>, GroupTally> groups;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& patch = mesh.patches[i];
        const bool unnamed = mesh.groups[patch.group] == "default";
        auto& g = groups[{patch.group, unnamed ? (long long)patch.material : -1,
                          unnamed ? plane_of(patch) : -1}];
        ++g.patches;
        g.weighted_centre = g.weighted_centre + patch.centroid * patch.area;
        g.area += patch.area;
        if (i < back_fraction.size() && back_fraction[i] > 0.5f) ++g.looking_at_backs;
        if (i < stats.reached_front.size()) {
            g.reached_front += stats.reached_front[i];
            g.reached_back += stats.reached_back[i];
        }
    }
    // Each line with its weight (the area concerned), so the worst come first.
    std::vector<std::pair<double, std::string>> weighted;
    for (const auto& [key, g] : groups) {
        std::string name = "group " + mesh.groups[key[0]];
        std::string fix = "rad-mesh --orient fix, or --flip " + mesh.groups[key[0]];
        if (key[1] >= 0) {
            const Vec3 c = g.weighted_centre * (1 / std::max(g.area, 1e-300));
            std::snprintf(text, sizeof text, ", the surface around (%.4g, %.4g, %.4g)", c[0], c[1],
                          c[2]);
            name = "material " + mesh.materials[key[1]].name + text;
            fix = "rad-mesh --orient fix";
        }
        // Patches of a correct scene may look at a back now and then (the top of a lamp
        // under the ceiling): only a group where most patches do is reported.
        if (2 * g.looking_at_backs > g.patches) {
            std::snprintf(text, sizeof text,
                          "%zu of %zu patches look at the back of other surfaces (most of their "
                          "rays arrive at back faces): ",
                          g.looking_at_backs, g.patches);
            std::string line = name + ": " + text;
            line += "they probably face the wrong way, or what they look at does (a sheet seen "
                    "from both sides needs rad-mesh --two-sided)";
            weighted.emplace_back(g.area * double(g.looking_at_backs) / double(g.patches),
                                  std::move(line));
        }
        // Enough rays to tell (a few per patch), nearly all of them at the back: a right
        // lamp just under a ceiling is reached at its back by the ceiling above it about as
        // often as at its front by the room, but a wall facing out of its room only ever
        // from behind.
        const auto reached = g.reached_front + g.reached_back;
        if (reached >= 32 && 5 * g.reached_back > 4 * reached) {
            std::snprintf(text, sizeof text,
                          "%.0f%% of the %llu rays that reach it arrive at its back: ",
                          100.0 * double(g.reached_back) / double(reached),
                          static_cast<unsigned long long>(reached));
            std::string line = name + ": " + text;
            line += "it probably faces the wrong way (" + fix + ")";
            weighted.emplace_back(g.area * double(g.reached_back) / double(reached),
                                  std::move(line));
        }
    }
    std::stable_sort(weighted.begin(), weighted.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::string> out;
    for (auto& [weight, line] : weighted) out.push_back(std::move(line));
    return out;
}

} // namespace rad
