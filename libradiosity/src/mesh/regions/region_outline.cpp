// Pass 2 of mesh_surfaces: a region's outline from the constrained triangulation of its faces.
#include "mesh/geometry/polygon2d.hpp"
#include "mesh/regions/regions.hpp"

#include "radiosity/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rad::surfaces {

namespace {

using Triangle2 = std::array<std::array<double, 2>, 3>;

// The region's faces as 2D triangles in buckets of a uniform grid: which face holds a point.
class TriangleBuckets {
  public:
    explicit TriangleBuckets(std::vector<Triangle2> triangles) : triangles_(std::move(triangles)) {
        for (const auto& t : triangles_)
            for (const auto& p : t)
                for (int c = 0; c < 2; ++c)
                    lo_[c] = std::min(lo_[c], p[c]), hi_[c] = std::max(hi_[c], p[c]);
        side_ = std::max<std::size_t>(1, std::size_t(std::sqrt(double(triangles_.size()))));
        buckets_.resize(side_ * side_);
        for (std::uint32_t k = 0; k < triangles_.size(); ++k) {
            std::array<double, 2> a{1e300, 1e300}, b{-1e300, -1e300};
            for (const auto& p : triangles_[k])
                for (int c = 0; c < 2; ++c)
                    a[c] = std::min(a[c], p[c]), b[c] = std::max(b[c], p[c]);
            const auto i0 = cell(a[0], 0), i1 = cell(b[0], 0), j0 = cell(a[1], 1),
                       j1 = cell(b[1], 1);
            for (auto j = j0; j <= j1; ++j)
                for (auto i = i0; i <= i1; ++i) buckets_[j * side_ + i].push_back(k);
        }
    }
    bool contains(double x, double y) const {
        if (x < lo_[0] || x > hi_[0] || y < lo_[1] || y > hi_[1]) return false;
        for (const auto k : buckets_[cell(y, 1) * side_ + cell(x, 0)])
            if (inside(triangles_[k], x, y)) return true;
        return false;
    }

  private:
    std::size_t cell(double x, int axis) const {
        const double span = std::max(1e-300, hi_[axis] - lo_[axis]);
        const auto i = static_cast<long long>((x - lo_[axis]) / span * double(side_));
        return static_cast<std::size_t>(
            std::clamp<long long>(i, 0, static_cast<long long>(side_) - 1));
    }
    static bool inside(const Triangle2& t, double x, double y) {
        double s[3];
        for (int k = 0; k < 3; ++k) {
            const auto& a = t[k];
            const auto& b = t[(k + 1) % 3];
            s[k] = (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
        }
        return (s[0] >= 0 && s[1] >= 0 && s[2] >= 0) || (s[0] <= 0 && s[1] <= 0 && s[2] <= 0);
    }
    std::vector<Triangle2> triangles_;
    std::array<double, 2> lo_{1e300, 1e300}, hi_{-1e300, -1e300};
    std::size_t side_ = 1;
    std::vector<std::vector<std::uint32_t>> buckets_;
};

double corner_angle(const XY& before, const XY& at, const XY& after) {
    const double ax = before[0] - at[0], ay = before[1] - at[1];
    const double bx = after[0] - at[0], by = after[1] - at[1];
    return std::atan2(std::abs(ax * by - ay * bx), ax * bx + ay * by);
}

// The region's sides when its faces tile it without overlapping, which is what nearly every
// input gives: the directed edges of its faces that no other face of it has reversed. They
// count only when each point starts and ends exactly one side (loops that neither cross nor
// touch) and the faces' corners around each inner point add up to a full turn (no face folds
// over another there). Fills `sides`; false when a triangulation must decide instead
// (overlapping faces, T-vertices, a point where two loops touch).
bool sides_of_a_tiling(const Region& region, const radfmt::MeshData& faces,
                       const std::vector<std::uint32_t>& weld, const Points& points,
                       std::vector<std::array<std::uint32_t, 2>>& sides) {
    std::vector<std::array<std::uint32_t, 2>> edges;
    std::vector<std::pair<std::uint32_t, double>> turn; // inner angle at each corner's point
    for (const auto f : region.faces) {
        const auto& p = faces.patches[f];
        const int n = p.corner_count();
        std::array<XY, 4> xy;
        std::array<std::uint32_t, 4> id;
        for (int k = 0; k < n; ++k)
            id[k] = weld[p.corners[k]], xy[k] = region.plane.to_2d(points.position[id[k]]);
        for (int k = 0; k < n; ++k) {
            if (id[k] == id[(k + 1) % n]) return false;
            edges.push_back({id[k], id[(k + 1) % n]});
            turn.emplace_back(id[k], corner_angle(xy[(k + n - 1) % n], xy[k], xy[(k + 1) % n]));
        }
    }
    std::sort(edges.begin(), edges.end());
    if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
    sides.clear();
    for (const auto& e : edges)
        if (!std::binary_search(edges.begin(), edges.end(), std::array{e[1], e[0]}))
            sides.push_back(e);
    if (sides.empty()) return false;
    std::vector<std::uint32_t> starts, ends;
    for (const auto& e : sides) starts.push_back(e[0]), ends.push_back(e[1]);
    std::sort(starts.begin(), starts.end());
    std::sort(ends.begin(), ends.end());
    if (starts != ends || std::adjacent_find(starts.begin(), starts.end()) != starts.end())
        return false;
    std::sort(turn.begin(), turn.end());
    for (std::size_t k = 0; k < turn.size();) {
        const auto id = turn[k].first;
        double sum = 0;
        for (; k < turn.size() && turn[k].first == id; ++k) sum += turn[k].second;
        const bool on_side = std::binary_search(starts.begin(), starts.end(), id);
        if (on_side ? !(sum < 2 * std::numbers::pi - 1e-9)
                    : !(std::abs(sum - 2 * std::numbers::pi) <= 1e-6))
            return false;
    }
    return true;
}

} // namespace

SideIndex::SideIndex(std::vector<std::array<XY, 2>> sides) : sides_(std::move(sides)) {
    for (const auto& s : sides_)
        for (const auto& p : s) lo_ = std::min(lo_, p[1]), hi_ = std::max(hi_, p[1]);
    const std::size_t count = std::max<std::size_t>(1, sides_.size() / 4);
    strips_.resize(count);
    step_ = std::max(1e-300, (hi_ - lo_) / double(count));
    for (std::uint32_t k = 0; k < sides_.size(); ++k) {
        const auto& s = sides_[k];
        const auto a = strip(std::min(s[0][1], s[1][1])), b = strip(std::max(s[0][1], s[1][1]));
        for (auto i = a; i <= b; ++i) strips_[i].push_back(k);
    }
}

std::size_t SideIndex::strip(double y) const {
    const auto i = static_cast<long long>((y - lo_) / step_);
    return static_cast<std::size_t>(std::clamp<long long>(i, 0, (long long)strips_.size() - 1));
}

bool SideIndex::contains(double x, double y) const {
    if (!(y >= lo_ && y <= hi_)) return false;
    bool inside = false;
    for (const auto k : strips_[strip(y)]) {
        const auto& a = sides_[k][0];
        const auto& b = sides_[k][1];
        if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0])
            inside = !inside;
    }
    return inside;
}

namespace {

// Whether p lies in one of the region's faces (their triangulation's inside).
bool in_faces(const CDT& cdt, const Point2& p) {
    const auto face = cdt.locate(p);
    return face != nullptr && !cdt.is_infinite(face) && face->info().inside;
}

// A region whose faces tile it: its sides are its outline, and they tell what is inside.
bool outline_of_a_tiling(Region& region, const radfmt::MeshData& faces,
                         const std::vector<std::uint32_t>& weld, const Points& points) {
    std::vector<std::array<std::uint32_t, 2>> sides;
    if (!sides_of_a_tiling(region, faces, weld, points, sides)) return false;
    std::vector<std::array<XY, 2>> segments;
    for (const auto& [a, b] : sides) {
        region.outline.push_back({a, b});
        segments.push_back(
            {region.plane.to_2d(points.position[a]), region.plane.to_2d(points.position[b])});
    }
    region.sides = std::make_unique<SideIndex>(std::move(segments));
    return true;
}

} // namespace

// A region whose faces' edges cross one another more than a surface's would.
[[noreturn]] void refuse_crossings(const Region& region, const radfmt::MeshData& faces,
                                   const std::string& source) {
    throw InputError(source + ": faces of one plane (group '" + faces.groups[region.group] +
                     "', material '" + faces.materials[region.material].name +
                     "') cross one another at more points than they have corners many times "
                     "over: a stack of copies or of crossing strips, not a surface (remove the "
                     "copies, or mesh with --surfaces faces)");
}

void cover(Region& region, std::vector<XY> polygon) {
    // A hair larger than itself: a point on the side it shares with the faces (a band
    // triangle's centroid can lie there) is inside one or the other.
    XY centre{0, 0};
    for (const auto& q : polygon) centre[0] += q[0], centre[1] += q[1];
    centre[0] /= double(polygon.size()), centre[1] /= double(polygon.size());
    for (auto& q : polygon)
        for (int i = 0; i < 2; ++i) q[i] = centre[i] + (q[i] - centre[i]) * (1 + 1e-6);
    Region::Covered c{{1e300, 1e300}, {-1e300, -1e300}, std::move(polygon)};
    for (const auto& q : c.polygon)
        for (int i = 0; i < 2; ++i)
            c.lo[i] = std::min(c.lo[i], q[i]), c.hi[i] = std::max(c.hi[i], q[i]);
    region.covered.push_back(std::move(c));
}

bool Region::contains(const Point2& p) const {
    if (sides ? sides->contains(p.x(), p.y()) : in_faces(*cdt, p)) return true;
    for (const auto& c : covered)
        if (p.x() >= c.lo[0] && p.x() <= c.hi[0] && p.y() >= c.lo[1] && p.y() <= c.hi[1] &&
            point_in_polygon({p.x(), p.y()}, c.polygon))
            return true;
    return false;
}

void trace_outline(Region& region, const radfmt::MeshData& faces,
                   const std::vector<std::uint32_t>& weld, Points& points,
                   const std::string& source) {
    if (outline_of_a_tiling(region, faces, weld, points)) return;
    region.cdt = std::make_unique<CDT>();
    auto& cdt = *region.cdt;
    std::vector<Triangle2> triangles;
    // Crossings of the faces' edges become points: a few where faces overlap in part, but the
    // square of the faces' count in a stack of copies (200 nudged copies of one triangle took
    // 88 s and 2.5 GB here).
    std::size_t corners = 0;
    for (const auto f : region.faces) corners += faces.patches[f].corner_count();
    const std::size_t most_points = 8 * corners + 4096;
    for (const auto f : region.faces) {
        if (cdt.number_of_vertices() > most_points) refuse_crossings(region, faces, source);
        const auto& p = faces.patches[f];
        const int n = p.corner_count();
        std::array<CDT::Vertex_handle, 4> handle;
        std::array<std::array<double, 2>, 4> xy;
        for (int k = 0; k < n; ++k) {
            const auto id = weld[p.corners[k]];
            xy[k] = region.plane.to_2d(points.position[id]);
            handle[k] = cdt.insert(Point2(xy[k][0], xy[k][1]));
            if (handle[k]->info().id == kNone) handle[k]->info().id = id;
        }
        for (int k = 0; k < n; ++k)
            if (handle[k] != handle[(k + 1) % n])
                cdt.insert_constraint(handle[k], handle[(k + 1) % n]);
        triangles.push_back({xy[0], xy[1], xy[2]});
        if (n == 4) triangles.push_back({xy[0], xy[2], xy[3]});
    }
    // The faces' areas in the plane, against the area they cover: more where faces are drawn
    // partly over each other (past rounding: a millionth of the sum).
    double sum = 0, covered = 0;
    for (const auto& t : triangles)
        sum += std::abs(CGAL::area(Point2(t[0][0], t[0][1]), Point2(t[1][0], t[1][1]),
                                   Point2(t[2][0], t[2][1])));
    const TriangleBuckets buckets(std::move(triangles));
    for (auto face = cdt.finite_faces_begin(); face != cdt.finite_faces_end(); ++face) {
        const auto &a = face->vertex(0)->point(), &b = face->vertex(1)->point(),
                   &d = face->vertex(2)->point();
        const auto c = CGAL::centroid(a, b, d);
        face->info().inside = buckets.contains(c.x(), c.y());
        if (face->info().inside) covered += std::abs(CGAL::area(a, b, d));
    }
    if (sum - covered > 1e-6 * sum) region.area_beyond_union = sum - covered;
    // Points made where overlapping faces' edges cross get ids of their own.
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
        if (v->info().id == kNone)
            v->info().id = points.add(region.plane.to_3d(v->point().x(), v->point().y()));
    // The sides of the inside faces that border the outside, in the faces' order and each
    // counter-clockwise around its face: CGAL's edge iterator reports an edge from whichever
    // of its two faces lies first in memory, which would make the outline's order and
    // direction (and so the mesh) depend on the process's memory layout.
    for (auto face = cdt.finite_faces_begin(); face != cdt.finite_faces_end(); ++face) {
        if (!face->info().inside) continue;
        for (int k = 0; k < 3; ++k) {
            const auto other = face->neighbor(k);
            if (!cdt.is_infinite(other) && other->info().inside) continue;
            region.outline.push_back(
                {face->vertex(cdt.ccw(k))->info().id, face->vertex(cdt.cw(k))->info().id});
        }
    }
}

} // namespace rad::surfaces
