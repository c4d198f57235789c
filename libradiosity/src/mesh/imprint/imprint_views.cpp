#include "mesh/imprint/imprint_views.hpp"

#include "core/union_find.hpp"
#include "mesh/orientation/room_box.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace rad::imprinting {

namespace {
constexpr int kRays = 64;
// Parity is followed on every kParityStride-th of them (16): a closed object's parity is the
// same on every ray, and following a ray to the end costs several traces.
constexpr int kParityStride = 4;
// The k-th of the kRays cosine-weighted directions about `side`.
Vec3 direction(int k, const Vec3& side, const Vec3& u, const Vec3& v) {
    return cosine_direction(side, u, v, (k + 0.5) / kRays, std::fmod(k * 0.6180339887498949, 1.0));
}
// A ray crossing more surfaces than this is not followed to the end: it proves nothing.
constexpr int kMaxCrossings = 256;

// A room with a beam or a pipe sticking out through its wall does not hold the scene's box,
// but most of it: half its volume (each side counted at least a thousandth of the scene's
// size, for a flat scene).
bool holds_most_of(const Box& surface, const Box& scene) {
    const double floor = 1e-3 * scene.diagonal();
    double held = 1, whole = 1;
    for (int c = 0; c < 3; ++c) {
        held *= std::max(floor, surface.hi[c] - surface.lo[c]);
        whole *= std::max(floor, scene.hi[c] - scene.lo[c]);
    }
    return held >= 0.5 * whole;
}

struct EdgeUse {
    std::size_t first = 0; // the first face using it
    int uses = 0;
    std::array<std::uint32_t, 2> ends{}; // scene vertices, from the first face
};
using EdgeUses = std::map<std::pair<std::uint32_t, std::uint32_t>, EdgeUse>;

// The open edges (used an odd number of times), by surface, into out.open_start and
// out.open_edges.
void open_edges(const Scene& scene, const EdgeUses& edges, SurfaceViews::Surfaces& out) {
    out.open_start.assign(scene.polygons.size() + 1, 0);
    for (const auto& [edge, use] : edges)
        if (use.uses % 2) ++out.open_start[out.of[use.first] + 1];
    for (std::size_t s = 0; s < scene.polygons.size(); ++s)
        out.open_start[s + 1] += out.open_start[s];
    out.open_edges.resize(out.open_start.back());
    auto next = out.open_start;
    for (const auto& [edge, use] : edges)
        if (use.uses % 2) out.open_edges[next[out.of[use.first]]++] = use.ends;
}

// Each face's surface: closed when every edge it has is shared by an even number of its
// faces, a room when its box holds the scene's, or most of it.
SurfaceViews::Surfaces connected_surfaces(const Scene& scene,
                                          const std::vector<std::uint32_t>& welded) {
    UnionFind sets(scene.polygons.size());
    EdgeUses edges;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        const auto& vs = scene.polygons[f].vertices;
        for (std::size_t k = 0; k < vs.size(); ++k) {
            auto a = welded[vs[k]], b = welded[vs[(k + 1) % vs.size()]];
            if (a == b) continue;
            auto& use = edges[{std::min(a, b), std::max(a, b)}];
            if (use.uses++ == 0)
                use.first = f, use.ends = {vs[k], vs[(k + 1) % vs.size()]};
            else
                sets.unite(f, use.first);
        }
    }
    SurfaceViews::Surfaces out;
    out.of.resize(scene.polygons.size());
    for (std::size_t f = 0; f < out.of.size(); ++f)
        out.of[f] = static_cast<std::uint32_t>(sets.find(f));
    out.closed.assign(scene.polygons.size(), 1);
    for (const auto& [edge, use] : edges)
        if (use.uses % 2) out.closed[out.of[use.first]] = 0;
    open_edges(scene, edges, out);
    out.box.resize(scene.polygons.size());
    for (std::size_t f = 0; f < out.of.size(); ++f)
        for (auto v : scene.polygons[f].vertices) out.box[out.of[f]].add(scene.vertices[v]);
    const Box scene_box = bounds(scene.vertices);
    out.room.resize(out.box.size());
    for (std::size_t s = 0; s < out.box.size(); ++s)
        out.room[s] = encloses(out.box[s], scene_box) || holds_most_of(out.box[s], scene_box);
    return out;
}
} // namespace

SurfaceViews::SurfaceViews(const Scene& scene, const std::vector<bool>& turned,
                           const std::vector<std::uint32_t>& welded)
    : surfaces_(connected_surfaces(scene, welded)), vertices_(scene.vertices), welded_(welded),
      rays_(face_triangles(scene, &face_of_, nullptr, &turned), RayBuild::Fast) {}

bool SurfaceViews::open_to_outside(std::uint32_t surface, const Vec3& from, const Vec3& normal,
                                   double offset, double gap) const {
    const auto off_plane = [&](std::uint32_t v) {
        return !(std::abs(dot(normal, vertices_[v]) - offset) <= gap);
    };
    std::vector<std::array<std::uint32_t, 2>> edges;
    for (auto k = surfaces_.open_start[surface]; k < surfaces_.open_start[surface + 1]; ++k) {
        const auto& e = surfaces_.open_edges[k];
        if (off_plane(e[0]) || off_plane(e[1])) edges.push_back(e);
    }
    // The openings: those edges in chains joined at shared (welded) corners.
    const auto chains = groups_sharing_keys(edges.size(), [&](std::size_t k, auto add) {
        for (const auto v : edges[k]) add(welded_[v]);
    });
    for (const auto& chain : chains) {
        Vec3 sum{0, 0, 0};
        for (const auto k : chain) sum = sum + vertices_[edges[k][0]] + vertices_[edges[k][1]];
        const Vec3 towards = sum * (1.0 / double(2 * chain.size())) - from;
        if (length(towards) > 0 && rays_.trace(from, normalized(towards)).patch < 0) return true;
    }
    return false;
}

double SurfaceViews::leaves_boxes(const Vec3& from, const Vec3& dir,
                                  const std::vector<std::uint32_t>& surfaces) const {
    const double pad = 16 * rays_.epsilon();
    double farthest = -1;
    for (auto s : surfaces) {
        double enter = 0, leave = 1e300;
        for (int c = 0; c < 3; ++c) {
            const double lo = surfaces_.box[s].lo[c] - pad - from[c],
                         hi = surfaces_.box[s].hi[c] + pad - from[c];
            if (dir[c] == 0) {
                if (lo > 0 || hi < 0) leave = -1;
                continue;
            }
            const double a = lo / dir[c], b = hi / dir[c];
            enter = std::max(enter, std::min(a, b));
            leave = std::min(leave, std::max(a, b));
        }
        if (enter <= leave) farthest = std::max(farthest, leave);
    }
    return farthest;
}

bool SurfaceViews::odd_crossings(const Vec3& from, const Vec3& dir,
                                 const std::vector<std::uint32_t>& surfaces,
                                 std::vector<std::uint32_t>& odd) const {
    odd.clear();
    const double reach = leaves_boxes(from, dir, surfaces);
    Vec3 origin = from;
    double travelled = 0;
    for (int k = 0; k < kMaxCrossings; ++k) {
        const auto hit = rays_.trace(origin, dir);
        travelled += hit.distance;
        if (hit.patch < 0 || travelled > reach) return true;
        const auto s = surfaces_.of[face_of_[hit.patch]];
        origin = origin + dir * hit.distance;
        if (!std::binary_search(surfaces.begin(), surfaces.end(), s)) continue;
        const auto it = std::find(odd.begin(), odd.end(), s);
        if (it == odd.end())
            odd.push_back(s);
        else
            odd.erase(it);
    }
    return false;
}

SurfaceViews::View SurfaceViews::view(const Vec3& from, const Vec3& side, const Vec3& u,
                                      const Vec3& v) const {
    std::map<std::uint32_t, int> backs, fronts;
    View out;
    out.rays = kRays;
    for (int k = 0; k < kRays; ++k) {
        const auto hit = rays_.trace(from, direction(k, side, u, v));
        if (hit.patch < 0) continue;
        ++out.hits;
        ++(hit.front ? fronts : backs)[surfaces_.of[face_of_[hit.patch]]];
    }
    out.backs.assign(backs.begin(), backs.end());
    out.fronts.assign(fronts.begin(), fronts.end());
    return out;
}

void SurfaceViews::add_parity(View& view, const Vec3& from, const Vec3& side, const Vec3& u,
                              const Vec3& v, const std::vector<std::uint32_t>& surfaces) const {
    std::map<std::uint32_t, int> odd_rays;
    std::vector<std::uint32_t> odd;
    view.parity_rays = 0;
    for (int k = 0; k < kRays; k += kParityStride, ++view.parity_rays)
        if (odd_crossings(from, direction(k, side, u, v), surfaces, odd))
            for (auto s : odd) ++odd_rays[s];
    view.odd.assign(odd_rays.begin(), odd_rays.end());
}

} // namespace rad::imprinting
