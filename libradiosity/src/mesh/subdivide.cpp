#include "../union_find.hpp"
#include "radiosity/error.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/two_sided.hpp"
#include "radiosity/vec.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Utils/vector_cast.hh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <unordered_map>

namespace rad {

namespace {

using Edge = std::uint64_t; // two vertex indices, smaller first

Edge edge_key(std::uint32_t a, std::uint32_t b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(a) << 32) | b;
}

struct Element { // a triangle or convex quad over scene vertices, ready to subdivide
    std::array<std::uint32_t, 4> v{};
    int corners = 3;
    std::uint32_t group = 0, material = 0;
    Vec3 normal{};
    double area = 0;
    // A long or thin triangle: subdivided in bands along its longest edge, each edge with
    // its own segment count, instead of the regular n x n pattern (whose n^2 patches follow
    // the longest edge: a 466 x 0.13 sliver at max-edge 10 would become 2209 patches).
    bool banded = false;
};

// Longest edge squared over twice the area: 1.15 for an equilateral triangle, 2 for a
// right isosceles one, thousands for a sliver.
double elongation(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double longest = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
    const double twice_area = length(cross(b - a, c - a));
    return twice_area > 0 ? longest / twice_area : 1e300;
}
constexpr double kBandedElongation = 4;

// Ear clipping in the polygon's plane; polygons here are planar and simple.
std::vector<std::array<std::uint32_t, 3>> triangulate(const std::vector<Vec3>& pts,
                                                      const std::vector<std::uint32_t>& ids,
                                                      const Vec3& normal) {
    std::vector<std::size_t> remaining(pts.size());
    std::iota(remaining.begin(), remaining.end(), 0);
    std::vector<std::array<std::uint32_t, 3>> out;
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
    for (std::size_t i = 1; i + 1 < remaining.size(); ++i)
        out.push_back({ids[remaining[0]], ids[remaining[i]], ids[remaining[i + 1]]});
    return out;
}

} // namespace

radfmt::MeshData subdivide(const Scene& scene, const SubdivisionOptions& options,
                           SubdivisionReport* report) {
    SubdivisionReport local;
    SubdivisionReport& rep = report ? *report : local;

    // Scene size sets what "degenerate" means.
    double extent = 0;
    {
        Vec3 lo = scene.vertices.empty() ? Vec3{0, 0, 0} : scene.vertices[0], hi = lo;
        for (const auto& v : scene.vertices)
            for (int k = 0; k < 3; ++k) {
                lo[k] = std::min(lo[k], v[k]);
                hi[k] = std::max(hi[k], v[k]);
            }
        extent = length(hi - lo);
    }
    const double min_area = 1e-14 * extent * extent;

    std::vector<Element> elements;
    for (const auto& poly : scene.polygons) {
        // Drop repeated consecutive vertices, which contribute nothing.
        std::vector<std::uint32_t> ids;
        for (auto id : poly.vertices)
            if (ids.empty() || scene.vertices[ids.back()] != scene.vertices[id]) ids.push_back(id);
        while (ids.size() > 1 && scene.vertices[ids.front()] == scene.vertices[ids.back()])
            ids.pop_back();
        std::vector<Vec3> pts;
        for (auto id : ids) pts.push_back(scene.vertices[id]);
        const Vec3 n2 = pts.size() >= 3 ? newell_normal(pts) : Vec3{0, 0, 0};
        const double area = 0.5 * length(n2);
        if (pts.size() < 3 || !(area > min_area)) {
            ++rep.degenerate_dropped;
            continue;
        }
        const Vec3 normal = n2 * (0.5 / area);
        // Planarity: every vertex within a tolerance (relative to the face size) of the plane.
        const Vec3 centre = polygon_centroid(pts);
        double size = 0, worst = 0;
        std::size_t worst_vertex = 0;
        for (const auto& p : pts) size = std::max(size, length(p - centre));
        for (std::size_t k = 0; k < pts.size(); ++k) {
            const double off = std::abs(dot(pts[k] - centre, normal));
            if (off > worst) worst = off, worst_vertex = k;
        }
        const bool planar = worst <= options.planarity_tolerance * size;
        if (!planar && options.strict)
            throw InputError(face_location(scene, poly.line) + ": face is not planar: vertex " +
                             std::to_string(worst_vertex + 1) + " lies " + std::to_string(worst) +
                             " off the face's plane (tolerance " +
                             std::to_string(options.planarity_tolerance * size) +
                             "; without --strict it is split into triangles, or raise "
                             "--planarity-tolerance)");
        bool convex_quad = pts.size() == 4;
        for (std::size_t k = 0; k < 4 && convex_quad; ++k)
            convex_quad = dot(cross(pts[(k + 1) % 4] - pts[k], pts[(k + 2) % 4] - pts[(k + 1) % 4]),
                              normal) > 0;
        // Each element takes its own plane: the face's, or for the triangles of a face that
        // is not planar, each triangle's.
        auto add = [&](std::initializer_list<std::uint32_t> corners) {
            Element e;
            std::copy(corners.begin(), corners.end(), e.v.begin());
            e.corners = static_cast<int>(corners.size());
            e.group = poly.group;
            e.material = poly.material;
            std::vector<Vec3> c;
            for (int k = 0; k < e.corners; ++k) c.push_back(scene.vertices[e.v[k]]);
            const Vec3 own = newell_normal(c);
            e.area = 0.5 * length(own);
            e.normal = planar ? normal : normalized(own);
            e.banded = e.corners == 3 && elongation(c[0], c[1], c[2]) > kBandedElongation;
            if (e.area > min_area)
                elements.push_back(e);
            else
                ++rep.degenerate_dropped;
        };
        if (!planar) {
            ++rep.nonplanar_split;
            if (worst / size > rep.worst_nonplanar_relative) {
                rep.worst_nonplanar_relative = worst / size;
                rep.worst_nonplanar_offset = worst;
                rep.worst_nonplanar_line = poly.line;
            }
        }
        if (pts.size() == 3) {
            add({ids[0], ids[1], ids[2]});
        } else if (!planar && pts.size() == 4) {
            // The diagonal whose two triangles fold least (their normals agree best).
            auto fold = [&](int d) {
                const Vec3 a = newell_normal(std::vector<Vec3>{pts[d], pts[d + 1], pts[d + 2]});
                const Vec3 b =
                    newell_normal(std::vector<Vec3>{pts[d], pts[d + 2], pts[(d + 3) % 4]});
                return dot(normalized(a), normalized(b));
            };
            const int d = fold(1) > fold(0) ? 1 : 0;
            add({ids[d], ids[d + 1], ids[d + 2]});
            add({ids[d], ids[d + 2], ids[(d + 3) % 4]});
        } else if (planar && convex_quad) {
            add({ids[0], ids[1], ids[2], ids[3]});
        } else {
            if (planar) ++rep.polygons_triangulated;
            for (const auto& t : triangulate(pts, ids, normal)) add({t[0], t[1], t[2]});
        }
    }
    if (elements.empty())
        throw InputError(scene.path + ": scene is empty (every face is degenerate)");

    // Number the edges, tie the ones that must share a segment count, and agree on counts.
    std::unordered_map<Edge, std::size_t> edge_index;
    std::vector<Edge> edges;
    auto edge_of = [&](std::uint32_t a, std::uint32_t b) {
        auto [it, inserted] = edge_index.try_emplace(edge_key(a, b), edges.size());
        if (inserted) edges.push_back(edge_key(a, b));
        return it->second;
    };
    std::vector<std::array<std::size_t, 4>> element_edges(elements.size());
    for (std::size_t f = 0; f < elements.size(); ++f) {
        const auto& e = elements[f];
        for (int k = 0; k < e.corners; ++k)
            element_edges[f][k] = edge_of(e.v[k], e.v[(k + 1) % e.corners]);
    }
    std::vector<double> edge_limit(edges.size(), 0);
    std::vector<double> element_limit(elements.size(), 0); // banded triangles' patch size
    UnionFind classes(edges.size());
    for (std::size_t f = 0; f < elements.size(); ++f) {
        const auto& e = elements[f];
        const auto& ee = element_edges[f];
        const auto& group = scene.groups[e.group];
        double limit = limit_for(options.max_edge_by_group, group, options.max_edge);
        if (e.banded) {
            // A banded triangle meets an area limit through its edge length: its patches
            // are about as high as they are long, so about half a square.
            const double area_limit = limit_for(options.max_area_by_group, group, options.max_area);
            if (area_limit > 0) {
                const double side = std::sqrt(2 * area_limit);
                limit = limit > 0 ? std::min(limit, side) : side;
            }
            element_limit[f] = limit;
        }
        for (int k = 0; k < e.corners; ++k)
            if (limit > 0 && (edge_limit[ee[k]] == 0 || limit < edge_limit[ee[k]]))
                edge_limit[ee[k]] = limit;
        if (e.banded) {
            // Each edge keeps its own count: none is tied to the others.
        } else if (e.corners == 4) {
            classes.unite(ee[0], ee[2]);
            classes.unite(ee[1], ee[3]);
        } else {
            classes.unite(ee[0], ee[1]);
            classes.unite(ee[1], ee[2]);
        }
    }
    // What the limits will cost, estimated before anything is made: about one patch per
    // half square of the edge limit (or per area limit) plus one per edge segment of the
    // outline. Counts are computed in double, so absurd limits cannot overflow.
    double estimate = 0;
    for (const auto& e : elements) {
        const auto& group = scene.groups[e.group];
        const double edge = limit_for(options.max_edge_by_group, group, options.max_edge);
        const double area = limit_for(options.max_area_by_group, group, options.max_area);
        double perimeter = 0;
        for (int k = 0; k < e.corners; ++k)
            perimeter += length(scene.vertices[e.v[(k + 1) % e.corners]] - scene.vertices[e.v[k]]);
        double pieces = 1;
        if (edge > 0) pieces = std::max(pieces, e.area / (0.5 * edge * edge) + perimeter / edge);
        if (area > 0) pieces = std::max(pieces, e.area / area);
        estimate += pieces;
    }
    if (!(estimate <= options.max_patches)) {
        char text[160];
        std::snprintf(text, sizeof text, "about %.3g patches, more than --max-patches %.3g",
                      estimate, options.max_patches);
        throw InputError(scene.path + ": these limits (--max-edge, --max-area) would make " + text +
                         " (use larger limits, or raise --max-patches)");
    }
    std::vector<std::size_t> segments(edges.size(), 1);
    for (std::size_t i = 0; i < edges.size(); ++i) {
        if (edge_limit[i] <= 0) continue;
        const auto a = static_cast<std::uint32_t>(edges[i] >> 32),
                   b = static_cast<std::uint32_t>(edges[i]);
        const double len = length(scene.vertices[a] - scene.vertices[b]);
        auto& s = segments[classes.find(i)];
        s = std::max(s, static_cast<std::size_t>(std::ceil(len / edge_limit[i] - 1e-9)));
    }
    // Area limits raise counts until every element's patches are small enough; counts only
    // grow, so this settles.
    for (bool changed = true; changed;) {
        changed = false;
        for (std::size_t f = 0; f < elements.size(); ++f) {
            const auto& e = elements[f];
            const double limit =
                limit_for(options.max_area_by_group, scene.groups[e.group], options.max_area);
            if (limit <= 0 || e.banded) continue;
            auto& a = segments[classes.find(element_edges[f][0])];
            auto& b = segments[classes.find(element_edges[f][1])];
            const double pieces = e.corners == 4 ? double(a) * double(b) : double(a) * double(a);
            if (e.area / pieces <= limit * (1 + 1e-9)) continue;
            const double needed = e.area / limit;
            if (e.corners == 3 || &a == &b) {
                a = static_cast<std::size_t>(std::ceil(std::sqrt(needed) - 1e-9));
            } else {
                // Jump to just under square patches of the limit's area, then add one piece
                // at a time along the direction whose patches are longest: the fewest patches
                // that meet the limit, in passes that do not grow with how many are needed.
                const auto& p = scene.vertices;
                const double u =
                    0.5 * (length(p[e.v[1]] - p[e.v[0]]) + length(p[e.v[2]] - p[e.v[3]]));
                const double v =
                    0.5 * (length(p[e.v[3]] - p[e.v[0]]) + length(p[e.v[2]] - p[e.v[1]]));
                const double side = std::sqrt(limit);
                const auto a0 = a, b0 = b;
                a = std::max(a, static_cast<std::size_t>(std::floor(u / side)));
                b = std::max(b, static_cast<std::size_t>(std::floor(v / side)));
                if (a == a0 && b == b0) (u / double(a) >= v / double(b) ? a : b) += 1;
            }
            changed = true;
        }
    }
    auto count_of = [&](std::size_t edge) { return segments[classes.find(edge)]; };

    radfmt::MeshData mesh;
    mesh.groups = scene.groups;
    mesh.materials = scene.materials;
    std::vector<std::uint32_t> remap(scene.vertices.size(), radfmt::kNoVertex);
    auto corner_vertex = [&](std::uint32_t id) {
        if (remap[id] == radfmt::kNoVertex) {
            remap[id] = static_cast<std::uint32_t>(mesh.vertices.size());
            mesh.vertices.push_back(scene.vertices[id]);
        }
        return remap[id];
    };
    std::unordered_map<Edge, std::uint32_t> edge_points; // first interior point of an edge
    // The vertex at step k of n from a to b; interior points are created once per edge, from
    // its smaller endpoint, so both faces sharing the edge use the same vertices.
    auto edge_vertex = [&](std::uint32_t a, std::uint32_t b, std::size_t k, std::size_t n) {
        if (k == 0) return corner_vertex(a);
        if (k == n) return corner_vertex(b);
        const auto lo = std::min(a, b), hi = std::max(a, b);
        const std::size_t step = a < b ? k : n - k;
        auto [it, inserted] = edge_points.try_emplace(edge_key(a, b), 0);
        if (inserted) {
            it->second = static_cast<std::uint32_t>(mesh.vertices.size());
            for (std::size_t i = 1; i < n; ++i) {
                const double t = double(i) / double(n);
                mesh.vertices.push_back(scene.vertices[lo] * (1 - t) + scene.vertices[hi] * t);
            }
        }
        return static_cast<std::uint32_t>(it->second + step - 1);
    };
    auto emit = [&](const Element& e, std::initializer_list<std::uint32_t> corners) {
        radfmt::Patch p;
        std::copy(corners.begin(), corners.end(), p.corners.begin());
        std::vector<Vec3> pts;
        for (auto c : corners) pts.push_back(mesh.vertices[c]);
        p.group = e.group;
        p.material = e.material;
        p.normal = e.normal;
        p.area = 0.5 * length(newell_normal(pts));
        p.centroid = polygon_centroid(pts);
        mesh.patches.push_back(p);
    };

    // The points of edge (a, b) from a to b, its agreed count of segments.
    auto edge_chain = [&](std::uint32_t a, std::uint32_t b, std::size_t edge) {
        const std::size_t n = count_of(edge);
        std::vector<std::uint32_t> chain;
        for (std::size_t k = 0; k <= n; ++k) chain.push_back(edge_vertex(a, b, k, n));
        return chain;
    };
    // A triangle as a patch, turned to face the element's way.
    auto emit_triangle = [&](const Element& e, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const Vec3 n =
            cross(mesh.vertices[b] - mesh.vertices[a], mesh.vertices[c] - mesh.vertices[a]);
        if (dot(n, e.normal) < 0) std::swap(b, c);
        emit(e, {a, b, c});
    };
    // Twice the area of a triangle of mesh vertices, and whether it is too thin to keep.
    auto flat = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        const Vec3 pa = mesh.vertices[a], pb = mesh.vertices[b], pc = mesh.vertices[c];
        const double longest =
            std::max({dot(pb - pa, pb - pa), dot(pc - pb, pc - pb), dot(pa - pc, pa - pc)});
        return length(cross(pb - pa, pc - pa)) <= 1e-9 * longest;
    };
    // Triangulates a convex region bounded by two chains of points that start at the same
    // point and end at the same point (the lower one straight, the upper one bending at
    // corners; points may be collinear), without new points: a zipper that advances
    // whichever chain lags along the lower one, never making a triangle of three collinear
    // points, so every patch has area and the outline's points all stay (conforming).
    auto zip = [&](const Element& e, const std::vector<std::uint32_t>& lower,
                   const std::vector<std::uint32_t>& upper) {
        const std::size_t n = lower.size(), m = upper.size();
        if (n < 2 || m < 2 || n + m < 5) return;
        if (n == 2) {
            // No point between the lower chain's ends A and B: fan from B over the upper
            // chain while its points are not in line with B, then from the last of them.
            std::size_t j = 0;
            while (j + 2 < m && !flat(upper[j + 1], upper[j + 2], lower[1])) {
                emit_triangle(e, upper[j], upper[j + 1], lower[1]);
                ++j;
            }
            for (std::size_t k = j + 1; k + 1 < m; ++k)
                emit_triangle(e, upper[j], upper[k], upper[k + 1]);
            return;
        }
        // Each point's position along the lower chain (a straight row): both chains run
        // monotonically along it, so pairing by it joins points across the band.
        const Vec3 origin = mesh.vertices[lower.front()];
        const Vec3 along = normalized(mesh.vertices[lower.back()] - origin);
        auto positions = [&](const std::vector<std::uint32_t>& chain) {
            std::vector<double> t;
            for (auto v : chain) t.push_back(dot(mesh.vertices[v] - origin, along));
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
    };
    // A long or thin triangle: bands parallel to its longest edge, about `size` apart, each
    // zipped between its two rows. The edges keep the counts agreed with their neighbours,
    // so the result conforms, and the patch count grows with area and perimeter.
    auto emit_banded = [&](const Element& e, const std::array<std::size_t, 4>& ee, double size) {
        // Rotate so that corner 0 -> 1 is the longest edge: base A B, apex C.
        int base = 0;
        double longest = -1;
        for (int k = 0; k < 3; ++k) {
            const double len = length(scene.vertices[e.v[(k + 1) % 3]] - scene.vertices[e.v[k]]);
            if (len > longest) longest = len, base = k;
        }
        const auto A = e.v[base], B = e.v[(base + 1) % 3], C = e.v[(base + 2) % 3];
        const auto bottom = edge_chain(A, B, ee[base]);
        const auto right = edge_chain(B, C, ee[(base + 1) % 3]); // B ... C
        const auto left = edge_chain(A, C, ee[(base + 2) % 3]);  // A ... C
        const double height = 2 * e.area / std::max(1e-300, longest);
        // Bands: as many as the height needs, at most what the sides' points allow.
        std::size_t bands =
            size > 0 ? static_cast<std::size_t>(std::ceil(height / size - 1e-9)) : 1;
        bands = std::clamp<std::size_t>(bands, 1, std::min(left.size(), right.size()) - 1);
        std::vector<std::uint32_t> previous = bottom;
        std::size_t il_prev = 0, ir_prev = 0;
        for (std::size_t k = 1; k <= bands; ++k) {
            // Row k runs from left[il] to right[ir] (the apex C for the last).
            const std::size_t il = k * (left.size() - 1) / bands;
            const std::size_t ir = k * (right.size() - 1) / bands;
            std::vector<std::uint32_t> row;
            if (k == bands) {
                row = {left.back()}; // the apex C, as a mesh vertex
            } else {
                const Vec3 from = mesh.vertices[left[il]], to = mesh.vertices[right[ir]];
                const std::size_t pieces =
                    size > 0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(
                                                            length(to - from) / size - 1e-9)))
                             : 1;
                row.push_back(left[il]);
                for (std::size_t q = 1; q < pieces; ++q) {
                    row.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
                    mesh.vertices.push_back(from + (to - from) * (double(q) / double(pieces)));
                }
                row.push_back(right[ir]);
            }
            // The band's outline as two chains from its lower left to its lower right
            // corner: along the lower row; or up the left side, along the upper row and
            // down the right side.
            std::vector<std::uint32_t> upper(left.begin() + il_prev, left.begin() + il);
            upper.insert(upper.end(), row.begin(), row.end());
            for (std::size_t q = ir; q-- > ir_prev + 1;) upper.push_back(right[q]);
            upper.push_back(right[ir_prev]);
            zip(e, previous, upper);
            previous = std::move(row);
            il_prev = il;
            ir_prev = ir;
        }
    };

    for (std::size_t f = 0; f < elements.size(); ++f) {
        const auto& e = elements[f];
        const auto& v = e.v;
        if (e.corners == 4) {
            const std::size_t nu = count_of(element_edges[f][0]),
                              nv = count_of(element_edges[f][1]);
            std::vector<std::uint32_t> grid((nu + 1) * (nv + 1));
            auto at = [&](std::size_t i, std::size_t j) -> std::uint32_t& {
                return grid[j * (nu + 1) + i];
            };
            const Vec3 p0 = scene.vertices[v[0]], p1 = scene.vertices[v[1]],
                       p2 = scene.vertices[v[2]], p3 = scene.vertices[v[3]];
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
                        at(i, j) = static_cast<std::uint32_t>(mesh.vertices.size());
                        mesh.vertices.push_back(p0 * ((1 - s) * (1 - t)) + p1 * (s * (1 - t)) +
                                                p2 * (s * t) + p3 * ((1 - s) * t));
                    }
                }
            for (std::size_t j = 0; j < nv; ++j)
                for (std::size_t i = 0; i < nu; ++i)
                    emit(e, {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        } else if (e.banded) {
            emit_banded(e, element_edges[f], element_limit[f]);
        } else {
            const std::size_t n = count_of(element_edges[f][0]);
            std::vector<std::uint32_t> grid((n + 1) * (n + 1), radfmt::kNoVertex);
            auto at = [&](std::size_t i, std::size_t j) -> std::uint32_t& {
                return grid[j * (n + 1) + i];
            };
            const Vec3 p0 = scene.vertices[v[0]], p1 = scene.vertices[v[1]],
                       p2 = scene.vertices[v[2]];
            for (std::size_t j = 0; j <= n; ++j)
                for (std::size_t i = 0; i + j <= n; ++i) {
                    if (j == 0)
                        at(i, j) = edge_vertex(v[0], v[1], i, n);
                    else if (i == 0)
                        at(i, j) = edge_vertex(v[0], v[2], j, n);
                    else if (i + j == n)
                        at(i, j) = edge_vertex(v[1], v[2], j, n);
                    else {
                        at(i, j) = static_cast<std::uint32_t>(mesh.vertices.size());
                        mesh.vertices.push_back(p0 + (p1 - p0) * (double(i) / n) +
                                                (p2 - p0) * (double(j) / n));
                    }
                }
            for (std::size_t j = 0; j < n; ++j)
                for (std::size_t i = 0; i + j < n; ++i) {
                    emit(e, {at(i, j), at(i + 1, j), at(i, j + 1)});
                    if (i + j + 1 < n) emit(e, {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
                }
        }
    }
    if (mesh.patches.size() >= radfmt::kNoVertex)
        throw InputError(scene.path + ": too many patches for 32-bit indices");
    return mesh;
}

Topology analyze_topology(const radfmt::MeshData& mesh) {
    using OMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
    OMesh om;
    std::vector<OMesh::VertexHandle> handles;
    handles.reserve(mesh.vertices.size());
    for (const auto& v : mesh.vertices)
        handles.push_back(om.add_vertex(OMesh::Point(v[0], v[1], v[2])));
    Topology topo;
    omerr().disable(); // OpenMesh reports each non-manifold face; we count them instead
    // The back of a two-sided surface repeats its front's corners: one side is the surface.
    const auto twins = find_twins(mesh);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        if (twins[i] >= 0 && static_cast<std::size_t>(twins[i]) < i) continue;
        const auto& p = mesh.patches[i];
        std::vector<OMesh::VertexHandle> face;
        for (int k = 0; k < p.corner_count(); ++k) face.push_back(handles[p.corners[k]]);
        if (!om.add_face(face).is_valid()) ++topo.rejected_patches;
    }
    omerr().enable();
    for (auto e : om.edges()) {
        ++topo.edges;
        if (om.is_boundary(e)) ++topo.boundary_edges;
    }
    return topo;
}

} // namespace rad
