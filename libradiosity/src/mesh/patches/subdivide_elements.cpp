// Step 1 of subdivide: the scene's faces cleaned into triangles and convex quads.
#include "mesh/patches/polygon_triangulation.hpp"
#include "mesh/patches/subdivide_parts.hpp"
#include "radiosity/error.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rad::subdivision {

namespace {

// Longest edge squared over twice the area: 1.15 for an equilateral triangle, 2 for a
// right isosceles one, thousands for a sliver.
double elongation(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double longest = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
    const double twice_area = length(cross(b - a, c - a));
    return twice_area > 0 ? longest / twice_area : 1e300;
}
constexpr double kBandedElongation = 4;

// A face's corners with repeats dropped, and its plane: how far its corners leave it.
struct FaceShape {
    std::vector<std::uint32_t> ids;
    std::vector<Vec3> pts;
    Vec3 normal{};
    double area = 0;
    double size = 0, worst = 0; // the largest distance from the centre; from the plane
    std::size_t worst_vertex = 0;
};

FaceShape face_shape(const Scene& scene, const Polygon& poly) {
    FaceShape f;
    // Drop repeated consecutive vertices, which contribute nothing.
    for (auto id : poly.vertices)
        if (f.ids.empty() || scene.vertices[f.ids.back()] != scene.vertices[id])
            f.ids.push_back(id);
    while (f.ids.size() > 1 && scene.vertices[f.ids.front()] == scene.vertices[f.ids.back()])
        f.ids.pop_back();
    for (auto id : f.ids) f.pts.push_back(scene.vertices[id]);
    const Vec3 n2 = f.pts.size() >= 3 ? newell_normal(f.pts) : Vec3{0, 0, 0};
    f.area = 0.5 * length(n2);
    if (f.pts.size() < 3 || !(f.area > 0)) return f;
    f.normal = n2 * (0.5 / f.area);
    // Planarity: every vertex within a tolerance (relative to the face size) of the plane.
    const Vec3 centre = polygon_centroid(f.pts);
    for (const auto& p : f.pts) f.size = std::max(f.size, length(p - centre));
    for (std::size_t k = 0; k < f.pts.size(); ++k) {
        const double off = std::abs(dot(f.pts[k] - centre, f.normal));
        if (off > f.worst) f.worst = off, f.worst_vertex = k;
    }
    return f;
}

class ElementMaker {
  public:
    ElementMaker(const Scene& scene, const SubdivisionOptions& options, SubdivisionReport& report)
        : scene_(scene), options_(options), report_(report) {
        // Scene size sets what "degenerate" means.
        const double extent = bounds(scene.vertices).diagonal();
        min_area_ = 1e-14 * extent * extent;
    }
    void add_face(const Polygon& poly) {
        const auto f = face_shape(scene_, poly);
        if (f.pts.size() < 3 || !(f.area > min_area_)) {
            ++report_.degenerate_dropped;
            return;
        }
        const bool planar = f.worst <= options_.planarity_tolerance * f.size;
        if (!planar) note_nonplanar(poly, f);
        bool convex_quad = f.pts.size() == 4;
        for (std::size_t k = 0; k < 4 && convex_quad; ++k)
            convex_quad =
                dot(cross(f.pts[(k + 1) % 4] - f.pts[k], f.pts[(k + 2) % 4] - f.pts[(k + 1) % 4]),
                    f.normal) > 0;
        const auto& ids = f.ids;
        if (f.pts.size() == 3) {
            add(poly, planar, f.normal, {ids[0], ids[1], ids[2]});
        } else if (!planar && f.pts.size() == 4) {
            const int d = least_folding_diagonal(f.pts);
            add(poly, planar, f.normal, {ids[d], ids[d + 1], ids[d + 2]});
            add(poly, planar, f.normal, {ids[d], ids[d + 2], ids[(d + 3) % 4]});
        } else if (planar && convex_quad) {
            add(poly, planar, f.normal, {ids[0], ids[1], ids[2], ids[3]});
        } else {
            if (planar) ++report_.polygons_triangulated;
            for (const auto& t : triangulate_polygon(f.pts, ids, f.normal))
                add(poly, planar, f.normal, {t[0], t[1], t[2]});
        }
    }
    std::vector<Element> take() { return std::move(elements_); }

  private:
    void note_nonplanar(const Polygon& poly, const FaceShape& f) {
        if (options_.strict)
            throw InputError(face_location(scene_, poly.line) + ": face is not planar: vertex " +
                             std::to_string(f.worst_vertex + 1) + " lies " +
                             std::to_string(f.worst) + " off the face's plane (tolerance " +
                             std::to_string(options_.planarity_tolerance * f.size) +
                             "; without --strict it is split into triangles, or raise "
                             "--planarity-tolerance)");
        ++report_.nonplanar_split;
        if (f.worst / f.size > report_.worst_nonplanar_relative) {
            report_.worst_nonplanar_relative = f.worst / f.size;
            report_.worst_nonplanar_offset = f.worst;
            report_.worst_nonplanar_line = poly.line;
        }
    }
    // Of a non-planar quad's two diagonals, the one whose triangles fold least (their normals
    // agree best): 0 for 0-2, 1 for 1-3.
    static int least_folding_diagonal(const std::vector<Vec3>& pts) {
        auto fold = [&](int d) {
            const Vec3 a = newell_normal(std::vector<Vec3>{pts[d], pts[d + 1], pts[d + 2]});
            const Vec3 b = newell_normal(std::vector<Vec3>{pts[d], pts[d + 2], pts[(d + 3) % 4]});
            return dot(normalized(a), normalized(b));
        };
        return fold(1) > fold(0) ? 1 : 0;
    }
    // Each element takes its own plane: the face's, or for the triangles of a face that is
    // not planar, each triangle's.
    void add(const Polygon& poly, bool planar, const Vec3& normal,
             std::initializer_list<std::uint32_t> corners) {
        Element e;
        std::copy(corners.begin(), corners.end(), e.v.begin());
        e.corners = static_cast<int>(corners.size());
        e.group = poly.group;
        e.material = poly.material;
        std::vector<Vec3> c;
        for (int k = 0; k < e.corners; ++k) c.push_back(scene_.vertices[e.v[k]]);
        const Vec3 own = newell_normal(c);
        e.area = 0.5 * length(own);
        e.normal = planar ? normal : normalized(own);
        e.banded = e.corners == 3 && elongation(c[0], c[1], c[2]) > kBandedElongation;
        if (e.area > min_area_)
            elements_.push_back(e);
        else
            ++report_.degenerate_dropped;
    }

    const Scene& scene_;
    const SubdivisionOptions& options_;
    SubdivisionReport& report_;
    double min_area_ = 0;
    std::vector<Element> elements_;
};

} // namespace

std::vector<Element> make_elements(const Scene& scene, const SubdivisionOptions& options,
                                   SubdivisionReport& report) {
    ElementMaker maker(scene, options, report);
    for (const auto& poly : scene.polygons) maker.add_face(poly);
    auto elements = maker.take();
    if (elements.empty())
        throw InputError(scene.path + ": scene is empty (every face is degenerate)");
    return elements;
}

} // namespace rad::subdivision
