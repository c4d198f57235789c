// Faces in one plane that overlap: a copy inside another face with the same winding is one
// surface (dropped); with opposite windings, a sheet drawn from both sides (kept as twins) or a
// surface with a wrongly facing copy (the copy dropped, by what each side's rays meet).
#include "radiosity/coincident.hpp"

#include "radiosity/error.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"

#include "core/union_find.hpp"
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/geometry/slab_points.hpp"
#include "mesh/load/weld.hpp"

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
using FacePairs = std::vector<std::pair<std::size_t, std::size_t>>;

// What the rays of the two sides of these copied faces say, with `first` the faces of one
// side and `second` the other's.
CoincidentCase::Kind judge_sides(double first_fronts, double second_fronts) {
    if (first_fronts > 0.5 && second_fronts > 0.5) return CoincidentCase::kTwins;
    if (first_fronts >= 2 * second_fronts + 0.1 || second_fronts >= 2 * first_fronts + 0.1)
        return CoincidentCase::kWrongCopy;
    return CoincidentCase::kUndecided;
}

// The pairs split into pieces that touch (a face of one pair shares a corner with a face of
// another, welded by position): the copies of one wall vote together, a copied wall of
// another room in the same plane, whose scene is on its other side, on its own.
std::vector<FacePairs> touching_pieces(const Scene& scene, const std::vector<std::uint32_t>& weld,
                                       const FacePairs& pairs) {
    std::vector<FacePairs> split;
    for (const auto& group : groups_sharing_keys(pairs.size(), [&](std::size_t k, auto add) {
             for (const auto f : {pairs[k].first, pairs[k].second})
                 for (const auto v : scene.polygons[f].vertices) add(weld[v]);
         })) {
        auto& piece = split.emplace_back();
        for (const auto k : group) piece.push_back(pairs[k]);
    }
    return split;
}

// The two sides' shares of rays meeting fronts: (a) of every pair's first face, (b) second.
std::pair<double, double> side_fronts(const std::vector<FacePlane>& planes, const FacePairs& pairs,
                                      const RayScene& rays) {
    std::vector<std::size_t> first, second;
    for (const auto& [a, b] : pairs) first.push_back(a), second.push_back(b);
    for (auto* list : {&first, &second}) {
        std::sort(list->begin(), list->end());
        list->erase(std::unique(list->begin(), list->end()), list->end());
    }
    return {front_hits(planes, first, rays), front_hits(planes, second, rays)};
}

// Records the verdict on these pairs (dropping the copies facing away from the scene).
void apply_verdict(const Scene& scene, const std::vector<FacePlane>& planes, const FacePairs& pairs,
                   CoincidentCase::Kind kind, bool drop_second, std::vector<bool>& drop,
                   CoincidentReport& report) {
    for (const auto& [a, b] : pairs) {
        const auto kept = drop_second ? a : b, gone = drop_second ? b : a;
        const double area = std::min(planes[a].area, planes[b].area);
        if (kind == CoincidentCase::kWrongCopy) {
            if (drop[gone]) continue;
            drop[gone] = true;
        }
        report.cases.push_back({kind, scene.polygons[kept].line, scene.polygons[gone].line, area});
    }
}

// Per plane, the two sides of each copied surface vote by their rays: a side whose rays meet
// fronts faces the rest of the scene; one that sees backs or nothing is a wrongly facing copy.
// The copies vote by the pieces they touch in; a piece whose votes do not tell (two rooms'
// walls touching in one plane, their scenes on opposite sides) then votes pair by pair.
void decide_opposite_copies(const Scene& scene, const std::vector<FacePlane>& planes,
                            const Pairs& opposite, std::vector<bool>& drop,
                            CoincidentReport& report) {
    if (opposite.empty()) return;
    const RayScene rays(face_triangles(scene), RayBuild::Fast);
    const auto weld = weld_by_position(scene.vertices);
    for (const auto& [plane, pairs] : opposite) {
        auto side_of = [&](std::size_t f) -> SideKey {
            const auto& p = planes[f];
            return {dot(p.normal, cross(p.u(), p.v())) > 0 ? 1 : -1, scene.polygons[f].group,
                    scene.polygons[f].material};
        };
        std::map<std::pair<SideKey, SideKey>, FacePairs> sets;
        for (auto [a, b] : pairs) {
            if (side_of(a) > side_of(b)) std::swap(a, b);
            sets[{side_of(a), side_of(b)}].push_back({a, b});
        }
        for (const auto& [sides, members] : sets)
            for (const auto& piece : touching_pieces(scene, weld, members)) {
                const auto [f1, f2] = side_fronts(planes, piece, rays);
                const auto kind = judge_sides(f1, f2);
                if (kind != CoincidentCase::kUndecided || piece.size() == 1) {
                    apply_verdict(scene, planes, piece, kind, f1 > f2, drop, report);
                    continue;
                }
                for (const auto& pair : piece) {
                    const FacePairs one{pair};
                    const auto [g1, g2] = side_fronts(planes, one, rays);
                    apply_verdict(scene, planes, one, judge_sides(g1, g2), g1 > g2, drop, report);
                }
            }
    }
}

// A uniform grid over one plane's faces, about one square per face, holding each face's
// centroid (in its own (u, v)).
class CentroidGrid {
  public:
    CentroidGrid(const std::vector<FacePlane>& planes, const std::vector<std::size_t>& faces) {
        for (const auto f : faces)
            for (int c = 0; c < 2; ++c)
                lo_[c] = std::min(lo_[c], planes[f].box[c]),
                hi_[c] = std::max(hi_[c], planes[f].box[c + 2]);
        const double w = std::max(hi_[0] - lo_[0], 1e-300), h = std::max(hi_[1] - lo_[1], 1e-300);
        side_ = std::max(std::sqrt(w * h / double(faces.size())), std::max(w, h) / 4096);
        count_[0] = std::min<std::size_t>(4096, std::size_t(w / side_) + 1);
        count_[1] = std::min<std::size_t>(4096, std::size_t(h / side_) + 1);
        start_.assign(count_[0] * count_[1] + 1, 0);
        std::vector<std::size_t> square(faces.size());
        for (std::size_t i = 0; i < faces.size(); ++i) {
            const auto c = centroid_of(planes[faces[i]]);
            square[i] = row(c[1]) * count_[0] + column(c[0]);
            ++start_[square[i] + 1];
        }
        for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
        ranks_.resize(faces.size());
        auto next = start_;
        for (std::size_t i = 0; i < faces.size(); ++i) ranks_[next[square[i]]++] = i;
    }
    static std::array<double, 2> centroid_of(const FacePlane& p) {
        return {dot(p.centroid, p.u()), dot(p.centroid, p.v())};
    }
    // Calls visit(rank) for the centroids in the squares that the outline covers (within
    // `margin`): the squares of each row between the outline's leftmost and rightmost
    // points in that row.
    template <class Visit>
    void for_each_centroid_over(const std::vector<std::array<double, 2>>& outline, double margin,
                                Visit&& visit) const {
        double ylo = 1e300, yhi = -1e300;
        for (const auto& p : outline) ylo = std::min(ylo, p[1]), yhi = std::max(yhi, p[1]);
        for (auto r = row(ylo - margin); r <= row(yhi + margin); ++r) {
            const double y0 = lo_[1] + double(r) * side_ - margin;
            const double y1 = lo_[1] + double(r + 1) * side_ + margin;
            const auto [xlo, xhi] =
                x_extent(outline, r == 0 ? -1e300 : y0, r + 1 == count_[1] ? 1e300 : y1);
            if (xlo > xhi) continue;
            for (auto c = column(xlo - margin); c <= column(xhi + margin); ++c) {
                const auto s = r * count_[0] + c;
                for (auto k = start_[s]; k < start_[s + 1]; ++k) visit(ranks_[k]);
            }
        }
    }

  private:
    std::size_t index(double x, int axis) const {
        const auto i = static_cast<long long>(std::floor((x - lo_[axis]) / side_));
        return static_cast<std::size_t>(std::clamp<long long>(i, 0, (long long)count_[axis] - 1));
    }
    std::size_t column(double x) const { return index(x, 0); }
    std::size_t row(double y) const { return index(y, 1); }
    // The outline's x extent within the band y0 <= y <= y1 (empty: lo > hi).
    static std::pair<double, double> x_extent(const std::vector<std::array<double, 2>>& outline,
                                              double y0, double y1) {
        double xlo = 1e300, xhi = -1e300;
        for_each_slab_point(outline, 1, y0, y1, [&](const std::array<double, 2>& p) {
            xlo = std::min(xlo, p[0]), xhi = std::max(xhi, p[0]);
        });
        return {xlo, xhi};
    }
    std::array<double, 2> lo_{1e300, 1e300}, hi_{-1e300, -1e300};
    std::array<std::size_t, 2> count_{1, 1};
    double side_ = 1;
    std::vector<std::size_t> start_, ranks_; // the squares' centroids, by rank
};

// A face's centroid under more faces than this is in a stack of copies, not a surface: the
// pairs of a stack grow as its square (20,000 nudged copies of one triangle ran out of time
// and memory here), and their outlines' crossings too, later.
constexpr std::uint32_t kMostFacesOver = 256;

[[noreturn]] void refuse_stack(const Scene& scene, std::size_t face) {
    throw InputError(face_location(scene, scene.polygons[face].line) +
                     ": this face lies under more than " + std::to_string(kMostFacesOver) +
                     " other faces of its plane: a stack of copies, not a surface (remove the "
                     "copies, e.g. merge vertices by distance and delete duplicate faces)");
}

// The pairs of one plane's faces where one's centroid lies inside the other (beyond
// `tolerance` from its outline), each as (the face first by its box's lower u, the other), in
// that order. The centroids are looked up in a grid by the squares each outline covers, not
// by boxes: the boxes of a fan's slivers all hold its hub, so every pair of them overlaps (a
// disc of 20,000 slivers took 17 s and 1.8 GB that way, 200,000 ran out of memory).
std::vector<std::pair<std::size_t, std::size_t>>
overlapping_pairs(const Scene& scene, const std::vector<FacePlane>& planes,
                  std::vector<std::size_t>& faces, double tolerance) {
    std::sort(faces.begin(), faces.end(), [&](auto a, auto b) {
        return std::pair(planes[a].box[0], a) < std::pair(planes[b].box[0], b);
    });
    const CentroidGrid grid(planes, faces);
    std::vector<std::pair<std::size_t, std::size_t>> ranks; // positions in `faces`
    std::vector<std::uint32_t> covering(faces.size(), 0);   // the faces over each centroid
    for (std::size_t j = 0; j < faces.size(); ++j) {
        const auto outline = outline_of(scene, planes[faces[j]], faces[j]);
        grid.for_each_centroid_over(outline, tolerance, [&](std::size_t i) {
            if (i == j ||
                !inside(outline, CentroidGrid::centroid_of(planes[faces[i]]), tolerance, false))
                return;
            ranks.emplace_back(std::min(i, j), std::max(i, j));
            if (++covering[i] > kMostFacesOver) refuse_stack(scene, faces[i]);
        });
    }
    std::sort(ranks.begin(), ranks.end());
    ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
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
        for (const auto& [fa0, fb0] : overlapping_pairs(scene, planes, faces, tolerance)) {
            auto fa = fa0, fb = fb0;
            const bool same = dot(planes[fa].normal, planes[fb].normal) > 0;
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
