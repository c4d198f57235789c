// Faces in one plane that overlap: a copy inside another face with the same winding is one
// surface (dropped); with opposite windings, a sheet drawn from both sides (kept as twins) or a
// surface with a wrongly facing copy (the copy dropped, by what each side's rays meet).
#include "radiosity/coincident.hpp"

#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"

#include "polygon2d.hpp"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace rad {

namespace {

struct FacePlane {
    Vec3 normal{}, centroid{};
    double area = 0, offset = 0;
    std::array<double, 4> box{1e300, 1e300, -1e300, -1e300}; // of its corners in (u, v)
    // The plane's axes, shared by every face of that plane (up to the normal's sign): made
    // when needed, as a scene has millions of faces.
    Vec3 axis() const {
        for (int c = 0; c < 3; ++c)
            if (std::abs(normal[c]) > 1e-9) return normal[c] < 0 ? normal * -1.0 : normal;
        return normal;
    }
    Vec3 u() const { return orthogonal(axis()); }
    Vec3 v() const { return cross(axis(), u()); }
};

// A face's corners in its plane's (u, v): made when needed, as few faces are compared.
std::vector<std::array<double, 2>> outline_of(const Scene& scene, const FacePlane& plane,
                                              std::size_t f) {
    std::vector<std::array<double, 2>> outline;
    const Vec3 u = plane.u(), v = plane.v();
    for (const auto k : scene.polygons[f].vertices)
        outline.push_back({dot(scene.vertices[k], u), dot(scene.vertices[k], v)});
    return outline;
}

// The plane of each face, with axes shared by every face of that plane (up to the normal's
// sign), so that outlines of faces drawn both ways can be compared.
std::vector<FacePlane> face_planes(const Scene& scene) {
    std::vector<FacePlane> planes(scene.polygons.size());
    std::vector<Vec3> pts;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f) {
        pts.clear();
        for (const auto v : scene.polygons[f].vertices) pts.push_back(scene.vertices[v]);
        auto& p = planes[f];
        const Vec3 n2 = pts.size() >= 3 ? newell_normal(pts) : Vec3{0, 0, 0};
        p.area = 0.5 * length(n2);
        if (!(p.area > 0)) continue;
        p.normal = normalized(n2);
        p.centroid = polygon_centroid(pts);
        p.offset = dot(p.normal, p.centroid);
        const Vec3 u = p.u(), v = p.v();
        for (const auto& q : pts) {
            const std::array<double, 2> xy{dot(q, u), dot(q, v)};
            p.box = {std::min(p.box[0], xy[0]), std::min(p.box[1], xy[1]),
                     std::max(p.box[2], xy[0]), std::max(p.box[3], xy[1])};
        }
    }
    return planes;
}

// Whether p is inside the outline; a point within `tolerance` of it counts as inside when
// `boundary_inside`.
bool inside(const std::vector<Point2d>& poly, const Point2d& p, double tolerance,
            bool boundary_inside) {
    if (on_outline(p, poly, tolerance)) return boundary_inside;
    return point_in_polygon(p, poly);
}

// The share of rays from the front of these faces that meet the front of another surface.
double front_hits(const std::vector<FacePlane>& planes, const std::vector<std::size_t>& faces,
                  const RayScene& rays) {
    constexpr int kRays = 64;
    double fronts = 0, cast = 0;
    for (const auto f : faces) {
        const auto& p = planes[f];
        const Vec3 origin = p.centroid + p.normal * (4 * rays.epsilon());
        const Vec3 u = p.u(), v = p.v();
        Rng rng(0x636f696e, f);
        for (int k = 0; k < kRays; ++k) {
            const Vec3 d = cosine_direction(p.normal, u, v, rng.uniform(), rng.uniform());
            bool front = false;
            if (rays.first_hit(origin, d, front) >= 0 && front) ++fronts;
            ++cast;
        }
    }
    return cast > 0 ? fronts / cast : 0;
}

using SideKey = std::array<long long, 3>; // facing sign, group, material
using Pairs = std::map<std::array<long long, 4>, std::set<std::pair<std::size_t, std::size_t>>>;

// Per plane, the two sides of each copied surface vote by their rays: a side whose rays meet
// fronts faces the rest of the scene; one that sees backs or nothing is a wrongly facing copy.
void decide_opposite_copies(const Scene& scene, const std::vector<FacePlane>& planes,
                            const Pairs& opposite, std::vector<bool>& drop,
                            CoincidentReport& report) {
    if (opposite.empty()) return;
    const RayScene rays(face_triangles(scene), RayBuild::Fast);
    for (const auto& [plane, pairs] : opposite) {
        auto side_of = [&](std::size_t f) -> SideKey {
            const auto& p = planes[f];
            return {dot(p.normal, cross(p.u(), p.v())) > 0 ? 1 : -1, scene.polygons[f].group,
                    scene.polygons[f].material};
        };
        std::map<std::pair<SideKey, SideKey>, std::vector<std::pair<std::size_t, std::size_t>>>
            sets;
        for (auto [a, b] : pairs) {
            if (side_of(a) > side_of(b)) std::swap(a, b);
            sets[{side_of(a), side_of(b)}].push_back({a, b});
        }
        for (const auto& [sides, members] : sets) {
            std::vector<std::size_t> first, second;
            for (const auto& [a, b] : members) first.push_back(a), second.push_back(b);
            for (auto* list : {&first, &second}) {
                std::sort(list->begin(), list->end());
                list->erase(std::unique(list->begin(), list->end()), list->end());
            }
            const double f1 = front_hits(planes, first, rays);
            const double f2 = front_hits(planes, second, rays);
            CoincidentCase::Kind kind = CoincidentCase::kUndecided;
            if (f1 > 0.5 && f2 > 0.5)
                kind = CoincidentCase::kTwins;
            else if (f1 >= 2 * f2 + 0.1 || f2 >= 2 * f1 + 0.1)
                kind = CoincidentCase::kWrongCopy;
            const bool drop_second = f1 > f2;
            for (const auto& [a, b] : members) {
                const auto kept = drop_second ? a : b, gone = drop_second ? b : a;
                const double area = std::min(planes[a].area, planes[b].area);
                if (kind == CoincidentCase::kWrongCopy) {
                    if (drop[gone]) continue;
                    drop[gone] = true;
                }
                report.cases.push_back(
                    {kind, scene.polygons[kept].line, scene.polygons[gone].line, area});
            }
        }
    }
}

// The pairs of one plane's faces whose boxes overlap by more than `tolerance`, each as (the
// face first by its box's lower u, the other), in that order. CGAL's box intersection finds
// the candidates on a large plane (a sweep along u alone is quadratic on a finely
// triangulated floor).
std::vector<std::pair<std::size_t, std::size_t>>
overlapping_pairs(const std::vector<FacePlane>& planes, std::vector<std::size_t>& faces,
                  double tolerance) {
    std::sort(faces.begin(), faces.end(), [&](auto a, auto b) {
        return std::pair(planes[a].box[0], a) < std::pair(planes[b].box[0], b);
    });
    std::vector<std::pair<std::size_t, std::size_t>> ranks; // positions in `faces`
    auto consider = [&](std::size_t i, std::size_t j) {
        if (j < i) std::swap(i, j);
        const auto &a = planes[faces[i]].box, &b = planes[faces[j]].box;
        if (b[0] > a[2] - tolerance || b[1] > a[3] - tolerance || a[1] > b[3] - tolerance) return;
        ranks.emplace_back(i, j);
    };
    constexpr std::size_t kSweepAtMost = 64;
    if (faces.size() <= kSweepAtMost) {
        for (std::size_t i = 0; i < faces.size(); ++i)
            for (std::size_t j = i + 1; j < faces.size(); ++j) consider(i, j);
    } else {
        using Box2 = CGAL::Box_intersection_d::Box_with_info_d<double, 2, std::size_t>;
        std::vector<Box2> boxes;
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const auto& b = planes[faces[i]].box;
            double lo[2] = {b[0], b[1]}, hi[2] = {b[2], b[3]};
            boxes.emplace_back(lo, hi, i);
        }
        CGAL::box_self_intersection_d(
            boxes.begin(), boxes.end(),
            [&](const Box2& a, const Box2& b) { consider(a.info(), b.info()); });
        std::sort(ranks.begin(), ranks.end());
    }
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (const auto& [i, j] : ranks) pairs.emplace_back(faces[i], faces[j]);
    return pairs;
}

} // namespace

CoincidentReport resolve_coincident_faces(Scene& scene) {
    CoincidentReport report;
    auto planes = face_planes(scene);
    const double size = bounds(scene.vertices).diagonal();
    const double tolerance = 1e-6 * size;
    // Faces by plane (normal up to sign, offset), quantised to the tolerance.
    std::map<std::array<long long, 4>, std::vector<std::size_t>> by_plane;
    for (std::size_t f = 0; f < planes.size(); ++f) {
        const auto& p = planes[f];
        if (!(p.area > 0)) continue;
        const double sign = dot(p.normal, cross(p.u(), p.v())) > 0 ? 1 : -1;
        std::array<long long, 4> key;
        for (int c = 0; c < 3; ++c) key[c] = std::llround(sign * p.normal[c] * 1e6);
        key[3] = std::llround(sign * p.offset / std::max(1e-300, 1e-6 * size));
        by_plane[key].push_back(f);
    }
    std::vector<bool> drop(scene.polygons.size(), false);
    // Opposite copies, by the side sets they belong to: (plane, facing, group, material).
    std::map<std::array<long long, 4>, std::set<std::pair<std::size_t, std::size_t>>> opposite;
    for (auto& [key, faces] : by_plane) {
        if (faces.size() < 2) continue;
        for (const auto& [fa0, fb0] : overlapping_pairs(planes, faces, tolerance)) {
            auto fa = fa0, fb = fb0;
            const auto &a = planes[fa], &b = planes[fb];
            const bool same = dot(a.normal, b.normal) > 0;
            const auto ca = std::array<double, 2>{dot(a.centroid, a.u()), dot(a.centroid, a.v())};
            const auto cb = std::array<double, 2>{dot(b.centroid, b.u()), dot(b.centroid, b.v())};
            if (!inside(outline_of(scene, b, fb), ca, tolerance, false) &&
                !inside(outline_of(scene, a, fa), cb, tolerance, false))
                continue;
            if (same) { // the smaller one, when it lies wholly in the other, is a copy
                if (planes[fa].area > planes[fb].area) std::swap(fa, fb);
                const auto big = outline_of(scene, planes[fb], fb);
                const auto small = outline_of(scene, planes[fa], fa);
                if (!std::all_of(small.begin(), small.end(),
                                 [&](const auto& q) { return inside(big, q, tolerance, true); }))
                    continue;
                if (drop[fa]) continue;
                drop[fa] = true;
                report.cases.push_back({CoincidentCase::kMerged, scene.polygons[fa].line,
                                        scene.polygons[fb].line, planes[fa].area});
            } else {
                opposite[{key[0], key[1], key[2], key[3]}].insert({fa, fb});
            }
        }
    }
    decide_opposite_copies(scene, planes, opposite, drop, report);
    std::vector<FacePlane>().swap(planes);
    // Kept faces moved down in place: a second vector of every face would double the
    // polygons' memory on a large scene.
    std::size_t count = 0;
    for (std::size_t f = 0; f < scene.polygons.size(); ++f)
        if (!drop[f]) {
            if (count != f) scene.polygons[count] = std::move(scene.polygons[f]);
            ++count;
            report.kept.push_back(f);
        }
    scene.polygons.resize(count);
    return report;
}

} // namespace rad
