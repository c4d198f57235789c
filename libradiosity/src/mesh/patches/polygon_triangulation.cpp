#include "mesh/patches/polygon_triangulation.hpp"

#include "mesh/regions/regions.hpp"

#include <numeric>
#include <set>

namespace rad {

namespace {

using Triangles = std::vector<std::array<std::uint32_t, 3>>;

// The rest of the corners `remaining` as a fan from the first.
void add_fan(const std::vector<std::size_t>& remaining, const std::vector<std::uint32_t>& ids,
             Triangles& out) {
    for (std::size_t i = 1; i + 1 < remaining.size(); ++i)
        out.push_back({ids[remaining[0]], ids[remaining[i]], ids[remaining[i + 1]]});
}

// Ear clipping in the polygon's plane.
Triangles clip_ears(const std::vector<Vec3>& pts, const std::vector<std::uint32_t>& ids,
                    const Vec3& normal) {
    std::vector<std::size_t> remaining(pts.size());
    std::iota(remaining.begin(), remaining.end(), 0);
    Triangles out;
    auto convex = [&](std::size_t a, std::size_t b, std::size_t c) {
        return dot(cross(pts[b] - pts[a], pts[c] - pts[b]), normal) > 0;
    };
    auto inside = [&](const Vec3& p, std::size_t a, std::size_t b, std::size_t c) {
        const double d1 = dot(cross(pts[b] - pts[a], p - pts[a]), normal);
        const double d2 = dot(cross(pts[c] - pts[b], p - pts[b]), normal);
        const double d3 = dot(cross(pts[a] - pts[c], p - pts[c]), normal);
        return d1 >= 0 && d2 >= 0 && d3 >= 0;
    };
    std::size_t guard = 0;
    while (remaining.size() > 3 && guard++ < 10 * pts.size() * pts.size()) {
        const std::size_t m = remaining.size();
        bool clipped = false;
        for (std::size_t i = 0; i < m && !clipped; ++i) {
            const auto a = remaining[(i + m - 1) % m], b = remaining[i], c = remaining[(i + 1) % m];
            if (!convex(a, b, c)) continue;
            bool ear = true;
            for (auto o : remaining)
                if (o != a && o != b && o != c && inside(pts[o], a, b, c)) {
                    ear = false;
                    break;
                }
            if (!ear) continue;
            out.push_back({ids[a], ids[b], ids[c]});
            remaining.erase(remaining.begin() + static_cast<long>(i));
            clipped = true;
        }
        if (!clipped) break; // numerically stuck: fall back to a fan for the rest
    }
    add_fan(remaining, ids, out);
    return out;
}

// The constrained Delaunay triangulation of the polygon's sides in its plane, its faces
// inside the polygon (an odd number of sides crossed from outside); empty when the sides
// cross each other (a point no corner is).
Triangles constrained_triangles(const std::vector<Vec3>& pts, const std::vector<std::uint32_t>& ids,
                                const Vec3& normal) {
    using surfaces::CDT;
    const Vec3 u = orthogonal(normal), v = cross(normal, u);
    CDT cdt;
    std::vector<CDT::Vertex_handle> corner(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
        corner[k] = cdt.insert(surfaces::Point2(dot(pts[k], u), dot(pts[k], v)));
        corner[k]->info().id = static_cast<std::uint32_t>(k);
    }
    for (std::size_t k = 0; k < pts.size(); ++k)
        if (corner[k] != corner[(k + 1) % pts.size()])
            cdt.insert_constraint(corner[k], corner[(k + 1) % pts.size()]);
    for (auto vertex = cdt.finite_vertices_begin(); vertex != cdt.finite_vertices_end(); ++vertex)
        if (vertex->info().id == surfaces::kNone) return {};
    // Faces by how many sides lie between them and the outside: flood from the infinite face,
    // a side crossed only once the faces before it are all reached.
    std::vector<CDT::Face_handle> level{cdt.infinite_face()}, beyond;
    std::set<CDT::Face_handle> done;
    for (bool inside = false; !level.empty(); inside = !inside, level.swap(beyond), beyond.clear())
        while (!level.empty()) {
            const auto f = level.back();
            level.pop_back();
            if (!done.insert(f).second) continue;
            f->info().inside = inside;
            for (int k = 0; k < 3; ++k)
                if (!done.count(f->neighbor(k)))
                    (f->is_constrained(k) ? beyond : level).push_back(f->neighbor(k));
        }
    Triangles out;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        if (f->info().inside) // counter-clockwise in (u, v): wound as the polygon
            out.push_back({ids[f->vertex(0)->info().id], ids[f->vertex(1)->info().id],
                           ids[f->vertex(2)->info().id]});
    return out;
}

} // namespace

Triangles triangulate_polygon(const std::vector<Vec3>& pts, const std::vector<std::uint32_t>& ids,
                              const Vec3& normal) {
    constexpr std::size_t kEarClippingAtMost = 64;
    if (pts.size() <= kEarClippingAtMost) return clip_ears(pts, ids, normal);
    auto out = constrained_triangles(pts, ids, normal);
    if (out.empty()) {
        std::vector<std::size_t> all(pts.size());
        std::iota(all.begin(), all.end(), 0);
        add_fan(all, ids, out);
    }
    return out;
}

} // namespace rad
