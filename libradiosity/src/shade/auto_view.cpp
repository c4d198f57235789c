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
    const Vec3 size = box.hi - box.lo;
    // +y up, unless the scene lies flat in x-y (a z-up export): then +z.
    const int up_axis = size[1] < 0.2 * size[2] && size[1] < 0.2 * size[0] ? 2 : 1;
    ChosenView best;
    double best_score = -1e300;
    for (const auto& c : candidates(box, up_axis, aspect)) {
        const auto score = score_view(scene, c.view);
        if (score.value > best_score) {
            best_score = score.value;
            best = {c.view, view_text(c.view), score.front_share, c.where};
        }
    }
    // The text is what the image is rendered from, so the printed view reproduces it.
    best.view = parse_view(best.text, FileLoc{"the chosen view"});
    return best;
}

} // namespace rad
