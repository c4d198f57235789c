// Pass 3 of mesh_surfaces: the regions' outlines made to agree, then split into pieces.
#include "mesh/geometry/point_buckets.hpp"
#include "mesh/regions/regions.hpp"

#include "core/union_find.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace rad::surfaces {

namespace {

// Each region's outline edges, split at the other regions' outline points lying on them.
std::vector<std::vector<std::array<std::uint32_t, 2>>>
split_at_foreign_points(const std::vector<Region>& regions, const Points& points,
                        double tolerance) {
    std::vector<std::uint32_t> ids;
    for (const auto& r : regions)
        for (const auto& e : r.outline) ids.insert(ids.end(), e.begin(), e.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    const PointBuckets buckets(ids, points);
    std::vector<std::vector<std::array<std::uint32_t, 2>>> split(regions.size());
    for (std::size_t r = 0; r < regions.size(); ++r)
        for (const auto& [a, b] : regions[r].outline) {
            auto previous = a;
            for (const auto c : buckets.on_segment(a, b, tolerance)) {
                split[r].push_back({previous, c});
                previous = c;
            }
            split[r].push_back({previous, b});
        }
    return split;
}

// The outline edges (each once, by key) with the regions on them, and the edges at each
// point: sorted arrays, found by binary search.
struct Runs {
    std::vector<EdgeKey> edges;            // sorted
    std::vector<std::size_t> region_start; // edges.size() + 1: regions of edge i in
    std::vector<std::uint32_t> regions;    // regions[region_start[i] .. region_start[i + 1])
    std::vector<std::size_t> edge_start;   // points + 1: edges at point v in
    std::vector<std::size_t> edges_at;     // edges_at[edge_start[v] .. edge_start[v + 1])

    std::size_t index(EdgeKey e) const {
        return std::size_t(std::lower_bound(edges.begin(), edges.end(), e) - edges.begin());
    }
    std::span<const std::uint32_t> regions_of(std::size_t edge) const {
        return {regions.data() + region_start[edge], regions.data() + region_start[edge + 1]};
    }
    std::span<const std::size_t> edges_of(std::uint32_t v) const {
        return {edges_at.data() + edge_start[v], edges_at.data() + edge_start[v + 1]};
    }
    // A point no region needs: two outline edges meet there in a straight line, with the same
    // regions on both.
    bool droppable(std::uint32_t v, const Points& points, double tolerance) const {
        const auto at = edges_of(v);
        if (at.size() != 2 || !std::ranges::equal(regions_of(at[0]), regions_of(at[1])))
            return false;
        const auto p = other_end(edges[at[0]], v), q = other_end(edges[at[1]], v);
        const Vec3 pv = points.position[v], pp = points.position[p], pq = points.position[q];
        const Vec3 d = normalized(pq - pp);
        const Vec3 off = (pv - pp) - d * dot(pv - pp, d);
        return length(off) < tolerance && dot(pp - pv, pq - pv) < 0;
    }
    static std::uint32_t other_end(EdgeKey e, std::uint32_t v) {
        const auto a = static_cast<std::uint32_t>(e >> 32), b = static_cast<std::uint32_t>(e);
        return a == v ? b : a;
    }
};

Runs incidence_of(const std::vector<std::vector<std::array<std::uint32_t, 2>>>& split,
                  std::size_t point_count) {
    std::vector<std::pair<EdgeKey, std::uint32_t>> on; // (edge, region)
    for (std::uint32_t r = 0; r < split.size(); ++r)
        for (const auto& [a, b] : split[r])
            if (a != b) on.emplace_back(edge_key(a, b), r);
    std::sort(on.begin(), on.end());
    on.erase(std::unique(on.begin(), on.end()), on.end());
    Runs runs;
    for (std::size_t k = 0; k < on.size(); ++k) {
        if (k == 0 || on[k].first != on[k - 1].first) {
            runs.edges.push_back(on[k].first);
            runs.region_start.push_back(runs.regions.size());
        }
        runs.regions.push_back(on[k].second);
    }
    runs.region_start.push_back(runs.regions.size());
    runs.edge_start.assign(point_count + 1, 0);
    for (const auto e : runs.edges) {
        ++runs.edge_start[(e >> 32) + 1];
        ++runs.edge_start[std::uint32_t(e) + 1];
    }
    for (std::size_t v = 0; v < point_count; ++v) runs.edge_start[v + 1] += runs.edge_start[v];
    runs.edges_at.resize(2 * runs.edges.size());
    auto fill = runs.edge_start;
    for (std::size_t i = 0; i < runs.edges.size(); ++i) {
        runs.edges_at[fill[runs.edges[i] >> 32]++] = i;
        runs.edges_at[fill[std::uint32_t(runs.edges[i])]++] = i;
    }
    return runs;
}

// The straight run through edge e: points from one kept end to the other; the edges it
// takes are marked in `seen`.
std::vector<std::uint32_t> walk_run(std::size_t e, const Runs& runs, const Points& points,
                                    double tolerance, std::vector<char>& seen) {
    const auto a = static_cast<std::uint32_t>(runs.edges[e] >> 32),
               b = static_cast<std::uint32_t>(runs.edges[e]);
    seen[e] = 1;
    auto extend = [&](std::uint32_t from, std::uint32_t at) {
        std::vector<std::uint32_t> chain{at};
        while (runs.droppable(at, points, tolerance)) {
            const auto two = runs.edges_of(at);
            const auto next_edge =
                Runs::other_end(runs.edges[two[0]], at) == from ? two[1] : two[0];
            if (seen[next_edge]) break;
            seen[next_edge] = 1;
            from = at;
            at = Runs::other_end(runs.edges[next_edge], at);
            chain.push_back(at);
        }
        return chain;
    };
    auto back = extend(b, a), front = extend(a, b);
    std::reverse(back.begin(), back.end());
    back.insert(back.end(), front.begin(), front.end());
    return back;
}

// A walked chain cut where it bends past the tolerance as a whole (Douglas-Peucker): each of
// its points lies within the tolerance of its neighbours' line, but such points can still turn
// a full circle (a disc drawn as 10,000 slivers: each rim point 2e-6 off its neighbours' chord).
// A closed chain is first cut at its point farthest from its start.
std::vector<std::vector<std::uint32_t>> straight_parts(const std::vector<std::uint32_t>& chain,
                                                       const Points& points, double tolerance) {
    const auto at = [&](std::size_t k) { return points.position[chain[k]]; };
    const auto off_line = [&](std::size_t k, std::size_t i, std::size_t j) {
        const Vec3 d = at(j) - at(i);
        const double len2 = dot(d, d);
        if (!(len2 > 0)) return length(at(k) - at(i));
        const double t = std::clamp(dot(at(k) - at(i), d) / len2, 0.0, 1.0);
        return length(at(i) + d * t - at(k));
    };
    const std::size_t last = chain.size() - 1;
    std::vector<char> keep(chain.size(), 0);
    keep[0] = keep[last] = 1;
    std::vector<std::pair<std::size_t, std::size_t>> todo{{0, last}};
    if (chain.front() == chain.back() && last > 1) {
        std::size_t far = 1;
        for (std::size_t k = 2; k < last; ++k)
            if (length(at(k) - at(0)) > length(at(far) - at(0))) far = k;
        keep[far] = 1;
        todo = {{0, far}, {far, last}};
    }
    while (!todo.empty()) {
        const auto [i, j] = todo.back();
        todo.pop_back();
        std::size_t worst = i;
        double worst_off = tolerance;
        for (std::size_t k = i + 1; k < j; ++k)
            if (const double off = off_line(k, i, j); off > worst_off) worst_off = off, worst = k;
        if (worst == i) continue;
        keep[worst] = 1;
        todo.emplace_back(i, worst);
        todo.emplace_back(worst, j);
    }
    std::vector<std::vector<std::uint32_t>> parts;
    std::size_t start = 0;
    for (std::size_t k = 1; k <= last; ++k)
        if (keep[k]) {
            parts.emplace_back(chain.begin() + start, chain.begin() + k + 1);
            start = k;
        }
    return parts;
}

struct Run {
    std::vector<std::uint32_t> chain;   // the points from one kept end to the other
    std::vector<std::uint32_t> regions; // on either side
    double cell = 0;                    // the shortest piece of those regions
    std::vector<std::uint32_t> points;  // after splitting, from chain.front() to chain.back()
};

// The four runs of a region around a convex quadrilateral, counter-clockwise in its plane,
// each with whether it is walked from its front; empty when the outline is anything else.
std::vector<std::pair<std::size_t, bool>> quad_loop(const Region& region,
                                                    const std::vector<std::size_t>& mine,
                                                    const std::vector<Run>& runs,
                                                    const Points& points) {
    if (mine.size() != 4) return {};
    std::vector<std::pair<std::size_t, bool>> loop{{mine[0], true}};
    std::vector<bool> used(4, false);
    used[0] = true;
    auto end_of = [&](const std::pair<std::size_t, bool>& r) {
        return r.second ? runs[r.first].chain.back() : runs[r.first].chain.front();
    };
    for (int step = 1; step < 4; ++step) {
        const auto at = end_of(loop.back());
        bool found = false;
        for (std::size_t k = 0; k < 4 && !found; ++k) {
            if (used[k]) continue;
            const auto& chain = runs[mine[k]].chain;
            if (chain.front() == at || chain.back() == at) {
                loop.emplace_back(mine[k], chain.front() == at);
                used[k] = found = true;
            }
        }
        if (!found) return {};
    }
    if (end_of(loop.back()) != runs[loop.front().first].chain.front()) return {};
    std::array<std::array<double, 2>, 4> c;
    for (int k = 0; k < 4; ++k) {
        const auto& r = loop[k];
        c[k] = region.plane.to_2d(
            points.position[r.second ? runs[r.first].chain.front() : runs[r.first].chain.back()]);
    }
    double turns[4];
    for (int k = 0; k < 4; ++k) {
        const auto &a = c[k], &b = c[(k + 1) % 4], &d = c[(k + 2) % 4];
        turns[k] = (b[0] - a[0]) * (d[1] - b[1]) - (b[1] - a[1]) * (d[0] - b[0]);
    }
    const bool ccw = turns[0] > 0 && turns[1] > 0 && turns[2] > 0 && turns[3] > 0;
    const bool cw = turns[0] < 0 && turns[1] < 0 && turns[2] < 0 && turns[3] < 0;
    if (!ccw && !cw) return {};
    if (cw) {
        std::reverse(loop.begin(), loop.end());
        for (auto& r : loop) r.second = !r.second;
    }
    return loop;
}

// Every straight run of outline once, and for each region the runs on its outline.
std::vector<Run> find_runs(const std::vector<std::vector<std::array<std::uint32_t, 2>>>& split,
                           const std::vector<Region>& regions, const Points& points,
                           double tolerance, std::vector<std::vector<std::size_t>>& runs_of_region,
                           std::size_t& dropped) {
    const auto incidence = incidence_of(split, points.position.size());
    std::vector<char> seen(incidence.edges.size(), 0);
    std::vector<std::size_t> run_of(incidence.edges.size());
    std::vector<Run> runs;
    for (std::uint32_t r = 0; r < split.size(); ++r)
        for (const auto& [a, b] : split[r]) {
            if (a == b) continue;
            const auto e = incidence.index(edge_key(a, b));
            if (seen[e]) continue;
            // The regions on either side, and their shortest piece: the same for every part.
            Run along;
            const auto on = incidence.regions_of(e);
            along.regions.assign(on.begin(), on.end());
            for (const auto region : along.regions)
                if (regions[region].piece > 0)
                    along.cell = along.cell > 0 ? std::min(along.cell, regions[region].piece)
                                                : regions[region].piece;
            const auto walked = walk_run(e, incidence, points, tolerance, seen);
            for (auto& chain : straight_parts(walked, points, tolerance)) {
                Run run = along;
                run.chain = std::move(chain);
                for (std::size_t k = 0; k + 1 < run.chain.size(); ++k)
                    run_of[incidence.index(edge_key(run.chain[k], run.chain[k + 1]))] = runs.size();
                dropped += run.chain.size() - 2;
                runs.push_back(std::move(run));
            }
        }
    runs_of_region.assign(split.size(), {});
    for (std::uint32_t r = 0; r < split.size(); ++r) {
        auto& mine = runs_of_region[r];
        for (const auto& [a, b] : split[r])
            if (a != b) mine.push_back(run_of[incidence.index(edge_key(a, b))]);
        std::sort(mine.begin(), mine.end());
        mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    }
    return runs;
}

} // namespace

std::size_t split_outline_runs(std::vector<Region>& regions, Points& points, double tolerance) {
    const auto split = split_at_foreign_points(regions, points, tolerance);
    std::vector<std::vector<std::size_t>> runs_of_region;
    std::size_t dropped = 0;
    auto runs = find_runs(split, regions, points, tolerance, runs_of_region, dropped);
    // Opposite sides of a quadrilateral region get one piece count, so its grid is regular.
    UnionFind same_count(runs.size());
    std::vector<std::vector<std::pair<std::size_t, bool>>> loops(regions.size());
    for (std::size_t r = 0; r < regions.size(); ++r) {
        loops[r] = quad_loop(regions[r], runs_of_region[r], runs, points);
        if (loops[r].empty()) continue;
        same_count.unite(loops[r][0].first, loops[r][2].first);
        same_count.unite(loops[r][1].first, loops[r][3].first);
    }
    std::vector<std::size_t> count(runs.size(), 1);
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const auto& run = runs[k];
        const double len =
            length(points.position[run.chain.back()] - points.position[run.chain.front()]);
        const auto n = run.cell > 0
                           ? std::max<std::size_t>(1, std::size_t(std::ceil(len / run.cell - 1e-9)))
                           : 1;
        auto& c = count[same_count.find(k)];
        c = std::max(c, n);
    }
    for (std::size_t k = 0; k < runs.size(); ++k) {
        auto& run = runs[k];
        const auto n = count[same_count.find(k)];
        const Vec3 p0 = points.position[run.chain.front()], p1 = points.position[run.chain.back()];
        run.points = {run.chain.front()};
        for (std::size_t q = 1; q < n; ++q)
            run.points.push_back(points.add(p0 + (p1 - p0) * (double(q) / double(n))));
        run.points.push_back(run.chain.back());
    }
    for (std::size_t r = 0; r < regions.size(); ++r) {
        for (const auto k : runs_of_region[r])
            for (std::size_t q = 0; q + 1 < runs[k].points.size(); ++q)
                regions[r].pieces.push_back({runs[k].points[q], runs[k].points[q + 1]});
        for (const auto& [k, forward] : loops[r]) {
            auto side = runs[k].points;
            if (!forward) std::reverse(side.begin(), side.end());
            regions[r].quad_sides.push_back(std::move(side));
        }
    }
    return dropped;
}

} // namespace rad::surfaces
