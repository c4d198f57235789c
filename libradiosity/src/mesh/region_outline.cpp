// Pass 2 of mesh_surfaces: a region's outline from the constrained triangulation of its faces.
#include "regions.hpp"

#include <algorithm>
#include <cmath>

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

} // namespace

bool Region::contains(const Point2& p) const {
    const auto face = cdt->locate(p);
    return face != nullptr && !cdt->is_infinite(face) && face->info().inside;
}

void trace_outline(Region& region, const radfmt::MeshData& faces,
                   const std::vector<std::uint32_t>& weld, Points& points) {
    region.cdt = std::make_unique<CDT>();
    auto& cdt = *region.cdt;
    std::vector<Triangle2> triangles;
    for (const auto f : region.faces) {
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
    const TriangleBuckets buckets(std::move(triangles));
    for (auto face = cdt.finite_faces_begin(); face != cdt.finite_faces_end(); ++face) {
        const auto c = CGAL::centroid(face->vertex(0)->point(), face->vertex(1)->point(),
                                      face->vertex(2)->point());
        face->info().inside = buckets.contains(c.x(), c.y());
    }
    // Points made where overlapping faces' edges cross get ids of their own.
    for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v)
        if (v->info().id == kNone)
            v->info().id = points.add(region.plane.to_3d(v->point().x(), v->point().y()));
    for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
        const auto face = e->first;
        const int k = e->second;
        const auto other = face->neighbor(k);
        const bool in = !cdt.is_infinite(face) && face->info().inside;
        const bool out_in = !cdt.is_infinite(other) && other->info().inside;
        if (in == out_in) continue;
        region.outline.push_back(
            {face->vertex(cdt.cw(k))->info().id, face->vertex(cdt.ccw(k))->info().id});
    }
}

} // namespace rad::surfaces
