// choose_view: candidate cameras around and inside the scene's box, scored by probe rays.
#include "radiosity/auto_view.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace rad {

namespace {
constexpr int kProbeColumns = 48, kProbeRows = 36;
constexpr double kOutsideFov = 50, kInsideFov = 80; // degrees, horizontal

struct Candidate {
    View view;
    std::string where;
};

struct Score {
    double value = 0;       // the patches seen from the front, less twice the rays on backs
    double front_share = 0; // the share of the rays that meet a front
};

// A grid of rays through the view: the more distinct patches they meet from the front, the
// more of the scene the view shows; rays that meet a back count against it (a camera inside
// an object, or behind a one-sided wall).
Score score_view(const RayScene& scene, const View& view) {
    std::vector<std::int64_t> seen;
    int front = 0, back = 0;
    for (int r = 0; r < kProbeRows; ++r)
        for (int c = 0; c < kProbeColumns; ++c) {
            const auto hit = scene.trace(
                view.position, view_ray(view, (c + 0.5) / kProbeColumns, (r + 0.5) / kProbeRows));
            if (hit.patch < 0) continue;
            if (!hit.front) {
                ++back;
                continue;
            }
            ++front;
            seen.push_back(hit.patch);
        }
    std::sort(seen.begin(), seen.end());
    const auto distinct = std::unique(seen.begin(), seen.end()) - seen.begin();
    return {double(distinct) - 2.0 * back, double(front) / (kProbeColumns * kProbeRows)};
}

// "+x", "-z", or for a level direction between axes "+x-z".
std::string view_text_direction(const Vec3& d) {
    const char* names[] = {"x", "y", "z"};
    std::string text;
    for (int c = 0; c < 3; ++c)
        if (std::abs(d[c]) > 0.1) text += std::string(d[c] > 0 ? "+" : "-") + names[c];
    return text;
}

double vertical_fov(double horizontal_deg, double aspect) {
    const double h = horizontal_deg * std::numbers::pi / 180;
    return 2 * std::atan(std::tan(h / 2) / aspect) * 180 / std::numbers::pi;
}

std::vector<Candidate> candidates(const Box& box, int up_axis, double aspect) {
    const Vec3 centre = (box.lo + box.hi) * 0.5, size = box.hi - box.lo;
    Vec3 up{0, 0, 0};
    up[up_axis] = 1;
    std::vector<Candidate> out;
    const char* names[] = {"x", "y", "z"};
    for (int axis = 0; axis < 3; ++axis)
        for (const int sign : {+1, -1}) {
            if (axis == up_axis && sign < 0) continue; // not from below
            Vec3 d{0, 0, 0};
            d[axis] = -sign; // looking in from the +axis side when sign is +1
            // Far enough that the box's cross-section fills the narrower angle.
            double across = 0;
            for (int k = 0; k < 3; ++k)
                if (k != axis) across = std::max(across, size[k]);
            const double half =
                std::tan(vertical_fov(kOutsideFov, aspect) * std::numbers::pi / 360);
            const double distance = 0.5 * size[axis] + 0.6 * across / half;
            View v;
            v.position = centre - d * distance;
            v.direction = d;
            v.up = up;
            if (axis == up_axis) { // looking down: the image's up is along the next axis
                v.up = Vec3{0, 0, 0};
                v.up[(up_axis + 1) % 3] = -1;
            }
            v.horizontal_deg = kOutsideFov;
            v.vertical_deg = vertical_fov(kOutsideFov, aspect);
            out.push_back(
                {v, std::string("outside, from ") + (sign > 0 ? "+" : "-") + names[axis]});
        }
    for (int axis = 0; axis < 3; ++axis)
        for (const int sign : {+1, -1}) {
            if (axis == up_axis) continue;
            // Near the wall behind (the room in front), at about eye height.
            View v;
            v.position = centre;
            v.position[axis] -= sign * 0.42 * size[axis];
            v.position[up_axis] = box.lo[up_axis] + 0.55 * size[up_axis];
            v.direction = Vec3{0, 0, 0};
            v.direction[axis] = sign;
            v.up = up;
            v.horizontal_deg = kInsideFov;
            v.vertical_deg = vertical_fov(kInsideFov, aspect);
            out.push_back(
                {v, std::string("inside, towards ") + (sign > 0 ? "+" : "-") + names[axis]});
        }
    return out;
}

// The axis that is up: +y (the OBJ and glTF convention), or +z when far more of the scene's
// level surfaces (floors, ceilings, roofs) face along z than along y (a building exported z-up
// from 3ds Max: 7 times as much). Not by the box's shape: a flat level and a tall z-up house
// both fooled that; nor by the most area alone: in a box room every axis has about as much.
int up_axis_of(const radfmt::MeshData& mesh) {
    double level[3] = {0, 0, 0};
    for (const auto& p : mesh.patches) {
        const Vec3 n = normalized(p.normal);
        for (int c = 0; c < 3; ++c)
            if (std::abs(n[c]) > 0.9) level[c] += p.area;
    }
    return level[2] > 2 * level[1] && level[2] > level[0] ? 2 : 1;
}

// Where people stand: points over the scene's up-facing patches (picked by area, so floors
// more than table tops), at 0.55 of the height to what is overhead, looking level each of
// eight ways. Points with nothing overhead, or a back there (inside a solid), are skipped.
constexpr int kStandingPoints = 64, kStandingTurns = 8;
std::vector<Candidate> standing_candidates(const radfmt::MeshData& mesh, const RayScene& scene,
                                           int up_axis, double aspect) {
    Vec3 up{0, 0, 0};
    up[up_axis] = 1;
    std::vector<std::size_t> floors;
    std::vector<double> cumulative;
    double total = 0;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& p = mesh.patches[i];
        if (!(dot(normalized(p.normal), up) > 0.9) || mesh.materials[p.material].emits()) continue;
        total += p.area;
        floors.push_back(i), cumulative.push_back(total);
    }
    std::vector<Candidate> out;
    if (floors.empty()) return out;
    const int across[2] = {(up_axis + 1) % 3, (up_axis + 2) % 3};
    for (int k = 0; k < kStandingPoints; ++k) {
        const double at = (k + 0.5) / kStandingPoints * total;
        const auto i =
            floors[std::lower_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin()];
        const Vec3 base = mesh.patches[i].centroid + up * (4 * scene.epsilon());
        const auto overhead = scene.trace(base, up);
        if (overhead.patch < 0 || overhead.front == false) continue;
        const Vec3 eye = base + up * (0.55 * overhead.distance);
        for (int t = 0; t < kStandingTurns; ++t) {
            const double angle = 2 * std::numbers::pi * t / kStandingTurns;
            View v;
            v.position = eye;
            v.direction = Vec3{0, 0, 0};
            v.direction[across[0]] = std::cos(angle);
            v.direction[across[1]] = std::sin(angle);
            v.up = up;
            v.horizontal_deg = kInsideFov;
            v.vertical_deg = vertical_fov(kInsideFov, aspect);
            out.push_back({v, "inside, towards " + view_text_direction(v.direction) +
                                  ", standing over a floor"});
        }
    }
    return out;
}

// The share of 256 rays spread evenly over the sphere from a point that meet the front of a
// surface: near 1 in a closed room or a game level, lower in an open box (rays leave by its
// open side) or outside.
double enclosure(const RayScene& scene, const Vec3& point) {
    constexpr int kRays = 256;
    int fronts = 0;
    for (int k = 0; k < kRays; ++k) {
        // A Fibonacci spiral: evenly spread, the same every time.
        const double z = 1 - (2 * k + 1.0) / kRays, r = std::sqrt(std::max(0.0, 1 - z * z));
        const double phi = k * std::numbers::pi * (3 - std::sqrt(5.0));
        const auto hit = scene.trace(point, Vec3{r * std::cos(phi), r * std::sin(phi), z});
        fronts += hit.patch >= 0 && hit.front;
    }
    return double(fronts) / kRays;
}

// An interior when the median standing point is enclosed this much (game levels 0.985 to
// 0.99, a house 0.99 or more, a furnished room with glazing 0.96; the open Cornell box 0.8);
// then a camera stands only where at least kEnclosedPoint of the rays meet fronts.
constexpr double kInteriorMedian = 0.95, kEnclosedPoint = 0.9;

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", std::abs(v) < 1e-12 ? 0.0 : v);
    return text;
}
} // namespace

std::string view_text(const View& v) {
    auto vec = [](const Vec3& a) { return number(a[0]) + " " + number(a[1]) + " " + number(a[2]); };
    return "-vp " + vec(v.position) + " -vd " + vec(v.direction) + " -vu " + vec(v.up) + " -vh " +
           number(v.horizontal_deg) + " -vv " + number(v.vertical_deg);
}

ChosenView choose_view(const radfmt::MeshData& mesh, const RayScene& scene, double aspect) {
    const Box box = bounds(mesh.vertices);
    const int up_axis = up_axis_of(mesh);
    auto all = candidates(box, up_axis, aspect);
    // In an interior (a closed room, a game level, a house under its roof) a camera stands
    // inside, where people stand: the views from outside show walls and roofs. An open box is
    // still seen from outside, by the views around it.
    const auto standing = standing_candidates(mesh, scene, up_axis, aspect);
    std::vector<double> shares; // per standing point (each has kStandingTurns views)
    std::vector<bool> allowed(all.size() + standing.size(), true);
    for (std::size_t k = 0; k < standing.size(); k += kStandingTurns)
        shares.push_back(enclosure(scene, standing[k].view.position));
    auto median = shares;
    std::sort(median.begin(), median.end());
    const bool interior = !median.empty() && median[median.size() / 2] >= kInteriorMedian;
    for (std::size_t k = 0; k < all.size(); ++k)
        allowed[k] = !interior || (all[k].where.starts_with("inside") &&
                                   enclosure(scene, all[k].view.position) >= kEnclosedPoint);
    for (std::size_t k = 0; k < standing.size(); ++k)
        allowed[all.size() + k] = interior && shares[k / kStandingTurns] >= kEnclosedPoint;
    for (const auto& c : standing) all.push_back(c);
    ChosenView best;
    double best_score = -1e300;
    for (std::size_t k = 0; k < all.size(); ++k) {
        if (!allowed[k]) continue;
        const auto score = score_view(scene, all[k].view);
        // A view that sees no front at all is the last resort.
        const double value = score.front_share > 0 ? score.value : score.value - 1e12;
        if (value > best_score) {
            best_score = value;
            best = {all[k].view, view_text(all[k].view), score.front_share, all[k].where};
        }
    }
    // The text is what the image is rendered from, so the printed view reproduces it.
    best.view = parse_view(best.text, FileLoc{"the chosen view"});
    return best;
}

} // namespace rad
