// Step 3 of subdivide: each element's patches over the agreed edge counts.
#include "mesh/patches/subdivide_parts.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace rad::subdivision {

namespace {

class PatchWriter {
  public:
    // No counts: every edge is one segment (no limits), and each element one patch.
    PatchWriter(const Scene& scene, EdgeCounts* counts)
        : scene_(scene), counts_(counts), remap_(scene.vertices.size(), radfmt::kNoVertex) {
        mesh_.groups = scene.groups;
        mesh_.materials = scene.materials;
    }
    void write(const Element& e, std::size_t f) {
        static constexpr std::array<std::size_t, 4> kUncounted{};
        const auto& ee = counts_ ? counts_->element_edges[f] : kUncounted;
        if (e.corners == 4)
            quad_grid(e, ee);
        else if (e.banded)
            banded(e, ee, counts_ ? counts_->element_limit[f] : 0);
        else
            triangle_grid(e, ee);
    }
    void reserve(std::size_t patches, std::size_t vertices) {
        mesh_.patches.reserve(patches);
        mesh_.vertices.reserve(vertices);
    }
    radfmt::MeshData take() { return std::move(mesh_); }

  private:
    std::size_t count(std::size_t edge) const { return counts_ ? counts_->count(edge) : 1; }
    std::uint32_t add_vertex(const Vec3& p) {
        mesh_.vertices.push_back(p);
        return static_cast<std::uint32_t>(mesh_.vertices.size() - 1);
    }
    std::uint32_t corner_vertex(std::uint32_t id) {
        if (remap_[id] == radfmt::kNoVertex) remap_[id] = add_vertex(scene_.vertices[id]);
        return remap_[id];
    }
    // The vertex at step k of n from a to b; interior points are created once per edge, from
    // its smaller endpoint, so both faces sharing the edge use the same vertices.
    std::uint32_t edge_vertex(std::uint32_t a, std::uint32_t b, std::size_t k, std::size_t n) {
        if (k == 0) return corner_vertex(a);
        if (k == n) return corner_vertex(b);
        const auto lo = std::min(a, b), hi = std::max(a, b);
        const std::size_t step = a < b ? k : n - k;
        auto [it, inserted] = edge_points_.try_emplace(edge_key(a, b), 0);
        if (inserted) {
            it->second = static_cast<std::uint32_t>(mesh_.vertices.size());
            for (std::size_t i = 1; i < n; ++i) {
                const double t = double(i) / double(n);
                mesh_.vertices.push_back(scene_.vertices[lo] * (1 - t) + scene_.vertices[hi] * t);
            }
        }
        return static_cast<std::uint32_t>(it->second + step - 1);
    }
    // The points of edge (a, b) from a to b, its agreed count of segments.
    std::vector<std::uint32_t> edge_chain(std::uint32_t a, std::uint32_t b, std::size_t edge) {
        const std::size_t n = count(edge);
        std::vector<std::uint32_t> chain;
        for (std::size_t k = 0; k <= n; ++k) chain.push_back(edge_vertex(a, b, k, n));
        return chain;
    }
    void emit(const Element& e, std::initializer_list<std::uint32_t> corners) {
        radfmt::Patch p;
        std::copy(corners.begin(), corners.end(), p.corners.begin());
        std::vector<Vec3> pts;
        for (auto c : corners) pts.push_back(mesh_.vertices[c]);
        p.group = e.group;
        p.material = e.material;
        p.normal = e.normal;
        p.area = 0.5 * length(newell_normal(pts));
        p.centroid = polygon_centroid(pts);
        mesh_.patches.push_back(p);
    }
    // A triangle as a patch, turned to face the element's way.
    void emit_triangle(const Element& e, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const auto& m = mesh_.vertices;
        if (dot(cross(m[b] - m[a], m[c] - m[a]), e.normal) < 0) std::swap(b, c);
        emit(e, {a, b, c});
    }
    // Whether a triangle of mesh vertices is too thin to keep.
    bool flat(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
        const Vec3 pa = mesh_.vertices[a], pb = mesh_.vertices[b], pc = mesh_.vertices[c];
        const double longest =
            std::max({dot(pb - pa, pb - pa), dot(pc - pb, pc - pb), dot(pa - pc, pa - pc)});
        return length(cross(pb - pa, pc - pa)) <= 1e-9 * longest;
    }
    void quad_grid(const Element& e, const std::array<std::size_t, 4>& ee);
    void triangle_grid(const Element& e, const std::array<std::size_t, 4>& ee);
    void banded(const Element& e, const std::array<std::size_t, 4>& ee, double size);
    std::vector<std::uint32_t> band_row(std::uint32_t from, std::uint32_t to, double size);
    void zip(const Element& e, const std::vector<std::uint32_t>& lower,
             const std::vector<std::uint32_t>& upper);
    void zip_to_point(const Element& e, std::uint32_t end, const std::vector<std::uint32_t>& upper);

    const Scene& scene_;
    EdgeCounts* counts_; // null: one segment an edge
    radfmt::MeshData mesh_;
    std::vector<std::uint32_t> remap_;                    // scene vertex -> mesh vertex
    std::unordered_map<Edge, std::uint32_t> edge_points_; // first interior point of an edge
};

void PatchWriter::quad_grid(const Element& e, const std::array<std::size_t, 4>& ee) {
    const auto& v = e.v;
    const std::size_t nu = count(ee[0]), nv = count(ee[1]);
    std::vector<std::uint32_t> grid((nu + 1) * (nv + 1));
    auto at = [&](std::size_t i, std::size_t j) -> std::uint32_t& {
        return grid[j * (nu + 1) + i];
    };
    const Vec3 p0 = scene_.vertices[v[0]], p1 = scene_.vertices[v[1]], p2 = scene_.vertices[v[2]],
               p3 = scene_.vertices[v[3]];
    for (std::size_t j = 0; j <= nv; ++j)
        for (std::size_t i = 0; i <= nu; ++i) {
            if (j == 0)
                at(i, j) = edge_vertex(v[0], v[1], i, nu);
            else if (j == nv)
                at(i, j) = edge_vertex(v[3], v[2], i, nu);
            else if (i == 0)
                at(i, j) = edge_vertex(v[0], v[3], j, nv);
            else if (i == nu)
                at(i, j) = edge_vertex(v[1], v[2], j, nv);
            else {
                const double s = double(i) / nu, t = double(j) / nv;
                at(i, j) = add_vertex(p0 * ((1 - s) * (1 - t)) + p1 * (s * (1 - t)) + p2 * (s * t) +
                                      p3 * ((1 - s) * t));
            }
        }
    for (std::size_t j = 0; j < nv; ++j)
        for (std::size_t i = 0; i < nu; ++i)
            emit(e, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
}

void PatchWriter::triangle_grid(const Element& e, const std::array<std::size_t, 4>& ee) {
    const auto& v = e.v;
    const std::size_t n = count(ee[0]);
    std::vector<std::uint32_t> grid((n + 1) * (n + 1), radfmt::kNoVertex);
    auto at = [&](std::size_t i, std::size_t j) -> std::uint32_t& { return grid[j * (n + 1) + i]; };
    const Vec3 p0 = scene_.vertices[v[0]], p1 = scene_.vertices[v[1]], p2 = scene_.vertices[v[2]];
    for (std::size_t j = 0; j <= n; ++j)
        for (std::size_t i = 0; i + j <= n; ++i) {
            if (j == 0)
                at(i, j) = edge_vertex(v[0], v[1], i, n);
            else if (i == 0)
                at(i, j) = edge_vertex(v[0], v[2], j, n);
            else if (i + j == n)
                at(i, j) = edge_vertex(v[1], v[2], j, n);
            else
                at(i, j) =
                    add_vertex(p0 + (p1 - p0) * (double(i) / n) + (p2 - p0) * (double(j) / n));
        }
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i + j < n; ++i) {
            emit(e, {at(i, j), at(i + 1, j), at(i, j + 1)});
            if (i + j + 1 < n) emit(e, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
}

// A row across a band, from one side's point to the other's, in pieces about `size` long.
std::vector<std::uint32_t> PatchWriter::band_row(std::uint32_t from, std::uint32_t to,
                                                 double size) {
    const Vec3 a = mesh_.vertices[from], b = mesh_.vertices[to];
    const std::size_t pieces =
        size > 0 ? std::max<std::size_t>(
                       1, static_cast<std::size_t>(std::ceil(length(b - a) / size - 1e-9)))
                 : 1;
    std::vector<std::uint32_t> row{from};
    for (std::size_t q = 1; q < pieces; ++q)
        row.push_back(add_vertex(a + (b - a) * (double(q) / double(pieces))));
    row.push_back(to);
    return row;
}

// A long or thin triangle: bands parallel to its longest edge, about `size` apart, each
// zipped between its two rows. The edges keep the counts agreed with their neighbours, so the
// result conforms, and the patch count grows with area and perimeter.
void PatchWriter::banded(const Element& e, const std::array<std::size_t, 4>& ee, double size) {
    // Rotate so that corner 0 -> 1 is the longest edge: base A B, apex C.
    int base = 0;
    double longest = -1;
    for (int k = 0; k < 3; ++k) {
        const double len = length(scene_.vertices[e.v[(k + 1) % 3]] - scene_.vertices[e.v[k]]);
        if (len > longest) longest = len, base = k;
    }
    const auto A = e.v[base], B = e.v[(base + 1) % 3], C = e.v[(base + 2) % 3];
    const auto bottom = edge_chain(A, B, ee[base]);
    const auto right = edge_chain(B, C, ee[(base + 1) % 3]); // B ... C
    const auto left = edge_chain(A, C, ee[(base + 2) % 3]);  // A ... C
    const double height = 2 * e.area / std::max(1e-300, longest);
    // Bands: as many as the height needs, at most what the sides' points allow.
    std::size_t bands = size > 0 ? static_cast<std::size_t>(std::ceil(height / size - 1e-9)) : 1;
    bands = std::clamp<std::size_t>(bands, 1, std::min(left.size(), right.size()) - 1);
    std::vector<std::uint32_t> previous = bottom;
    std::size_t il_prev = 0, ir_prev = 0;
    for (std::size_t k = 1; k <= bands; ++k) {
        // Row k runs from left[il] to right[ir] (the apex C for the last).
        const std::size_t il = k * (left.size() - 1) / bands;
        const std::size_t ir = k * (right.size() - 1) / bands;
        auto row = k == bands ? std::vector<std::uint32_t>{left.back()}
                              : band_row(left[il], right[ir], size);
        // The band's outline as two chains from its lower left to its lower right corner:
        // along the lower row; or up the left side, along the upper row and down the right.
        std::vector<std::uint32_t> upper(left.begin() + il_prev, left.begin() + il);
        upper.insert(upper.end(), row.begin(), row.end());
        for (std::size_t q = ir; q-- > ir_prev + 1;) upper.push_back(right[q]);
        upper.push_back(right[ir_prev]);
        zip(e, previous, upper);
        previous = std::move(row);
        il_prev = il;
        ir_prev = ir;
    }
}

// No point between the lower chain's ends A and B (`end` is B): fan from B over the upper
// chain while its points are not in line with B, then from the last of them.
void PatchWriter::zip_to_point(const Element& e, std::uint32_t end,
                               const std::vector<std::uint32_t>& upper) {
    const std::size_t m = upper.size();
    std::size_t j = 0;
    while (j + 2 < m && !flat(upper[j + 1], upper[j + 2], end)) {
        emit_triangle(e, upper[j], upper[j + 1], end);
        ++j;
    }
    for (std::size_t k = j + 1; k + 1 < m; ++k) emit_triangle(e, upper[j], upper[k], upper[k + 1]);
}

// Triangulates a convex region bounded by two chains of points that start at the same point
// and end at the same point (the lower one straight, the upper one bending at corners; points
// may be collinear), without new points: a zipper that advances whichever chain lags along
// the lower one, never making a triangle of three collinear points, so every patch has area
// and the outline's points all stay (conforming).
void PatchWriter::zip(const Element& e, const std::vector<std::uint32_t>& lower,
                      const std::vector<std::uint32_t>& upper) {
    const std::size_t n = lower.size(), m = upper.size();
    if (n < 2 || m < 2 || n + m < 5) return;
    if (n == 2) return zip_to_point(e, lower[1], upper);
    // Each point's position along the lower chain (a straight row): both chains run
    // monotonically along it, so pairing by it joins points across the band.
    const Vec3 origin = mesh_.vertices[lower.front()];
    const Vec3 along = normalized(mesh_.vertices[lower.back()] - origin);
    auto positions = [&](const std::vector<std::uint32_t>& chain) {
        std::vector<double> t;
        for (auto v : chain) t.push_back(dot(mesh_.vertices[v] - origin, along));
        return t;
    };
    const auto tl = positions(lower), tu = positions(upper);
    // The first triangle steps along both chains; the last closes on the shared end.
    emit_triangle(e, lower[0], lower[1], upper[1]);
    std::size_t i = 1, j = 1;
    while (i + 2 < n || j + 2 < m) {
        const bool can_lower = i + 2 < n && !flat(lower[i], lower[i + 1], upper[j]);
        const bool can_upper = j + 2 < m && !flat(lower[i], upper[j + 1], upper[j]);
        const bool lower_lags = tl[i + 1] <= tu[j + 1];
        if (can_lower && (lower_lags || !can_upper)) {
            emit_triangle(e, lower[i], lower[i + 1], upper[j]);
            ++i;
        } else if (can_upper) {
            emit_triangle(e, lower[i], upper[j + 1], upper[j]);
            ++j;
        } else {
            break; // cannot happen for a convex region; never loop forever
        }
    }
    if (i + 2 == n && j + 2 == m) emit_triangle(e, lower[i], lower[i + 1], upper[j]);
}

} // namespace

radfmt::MeshData make_patches(const std::vector<Element>& elements, EdgeCounts& counts,
                              const Scene& scene) {
    PatchWriter writer(scene, &counts);
    for (std::size_t f = 0; f < elements.size(); ++f) writer.write(elements[f], f);
    return writer.take();
}

radfmt::MeshData make_whole_patches(const std::vector<Element>& elements, const Scene& scene) {
    PatchWriter writer(scene, nullptr);
    writer.reserve(elements.size(), scene.vertices.size());
    for (std::size_t f = 0; f < elements.size(); ++f) writer.write(elements[f], f);
    return writer.take();
}

} // namespace rad::subdivision
