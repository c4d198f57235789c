// A z-buffer rasteriser with near-plane clipping, perspective-correct interpolation and
// supersampling, in parallel row bands.
#include "radiosity/raster.hpp"

#include "radiosity/patch_geometry.hpp"
#include "radiosity/specular_view.hpp"
#include "radiosity/twins.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace rad {

namespace {
constexpr double kDeg = std::numbers::pi / 180;
}

namespace {

struct ScreenVertex {
    double x, y;  // pixel coordinates of the supersampled frame
    double inv_z; // 1 / depth, interpolated linearly in screen space
    Rgb colour_over_z;
};

struct ScreenTriangle {
    std::array<ScreenVertex, 3> v;
    double min_y, max_y;
    bool back; // the camera sees the back of a one-sided patch
};

} // namespace

std::uint64_t estimate_render_memory(int width, int height, int supersampling, int images) {
    const std::uint64_t pixels = std::uint64_t(std::max(0, width)) * std::max(0, height);
    const std::uint64_t ss = std::max(1, supersampling);
    return pixels * ss * ss * 21 + pixels * std::max(1, images) * (17 + 16);
}

namespace {

// A camera's frame and the frame buffer's size (supersampled).
struct Camera {
    Vec3 position, dir, right, up;
    double tan_h, tan_v, near;
    int W, H;
};

struct CamPoint {
    Vec3 p; // camera space: x right, y up, z depth
    Rgb c;
};

// A convex polygon in camera space, clipped against the near plane (so geometry behind the
// eye never projects), projected and split into screen triangles.
void add_screen_triangles(const std::vector<CamPoint>& poly, const Camera& cam, bool back,
                          std::vector<ScreenTriangle>& triangles) {
    std::vector<CamPoint> clipped;
    for (std::size_t k = 0; k < poly.size(); ++k) {
        const auto& a = poly[k];
        const auto& b = poly[(k + 1) % poly.size()];
        if (a.p[2] >= cam.near) clipped.push_back(a);
        if ((a.p[2] >= cam.near) != (b.p[2] >= cam.near)) {
            const double t = (cam.near - a.p[2]) / (b.p[2] - a.p[2]);
            CamPoint m;
            m.p = a.p + (b.p - a.p) * t;
            for (int c = 0; c < 3; ++c) m.c[c] = a.c[c] + (b.c[c] - a.c[c]) * t;
            clipped.push_back(m);
        }
    }
    if (clipped.size() < 3) return;
    std::vector<ScreenVertex> screen;
    for (const auto& cp : clipped) {
        const double inv_z = 1.0 / cp.p[2];
        ScreenVertex sv;
        sv.x = (cp.p[0] * inv_z / cam.tan_h + 1) * 0.5 * cam.W;
        sv.y = (1 - cp.p[1] * inv_z / cam.tan_v) * 0.5 * cam.H;
        sv.inv_z = inv_z;
        for (int c = 0; c < 3; ++c) sv.colour_over_z[c] = cp.c[c] * inv_z;
        screen.push_back(sv);
    }
    for (std::size_t k = 1; k + 1 < screen.size(); ++k) {
        ScreenTriangle t{{screen[0], screen[k], screen[k + 1]}, 0, 0, back};
        t.min_y = std::min({t.v[0].y, t.v[1].y, t.v[2].y});
        t.max_y = std::max({t.v[0].y, t.v[1].y, t.v[2].y});
        if (t.max_y < 0 || t.min_y > cam.H) continue;
        triangles.push_back(t);
    }
}

// Every patch the camera may see as screen triangles. A polygon need not be convex: it is
// drawn as its fan's triangles, each clipped alone.
std::vector<ScreenTriangle> screen_triangles(const radfmt::MeshData& mesh,
                                             const CornerColours& corners, const Camera& cam) {
    const auto twins = find_twins(mesh);
    std::vector<ScreenTriangle> triangles;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& patch = mesh.patches[i];
        // The camera is behind the patch's plane: it sees the back. Of a two-sided pair only
        // the side facing the camera is drawn.
        const bool back = dot(patch.normal, patch.centroid - cam.position) > 0;
        if (back && twins[i] >= 0) continue;
        std::vector<CamPoint> poly;
        const auto ids = mesh.corners(i);
        for (std::size_t k = 0; k < ids.size(); ++k) {
            const Vec3 d = mesh.vertices[ids[k]] - cam.position;
            poly.push_back(
                {{dot(d, cam.right), dot(d, cam.up), dot(d, cam.dir)}, corners.at(mesh, i, k)});
        }
        if (!patch.is_polygon()) {
            add_screen_triangles(poly, cam, back, triangles);
            continue;
        }
        for (const auto& [a, b, c] : patch_triangles(mesh, i))
            add_screen_triangles({poly[a], poly[b], poly[c]}, cam, back, triangles);
    }
    return triangles;
}

// The supersampled frame: colour, 1/z (0 where empty) and whether a back shows.
struct Frame {
    std::vector<float> hi;
    std::vector<double> depth;
    std::vector<std::uint8_t> shows_back;
};

Frame rasterise(const std::vector<ScreenTriangle>& triangles, int W, int H) {
    Frame f;
    f.hi.assign(static_cast<std::size_t>(W) * H * 3, 0.0f);
    f.depth.assign(static_cast<std::size_t>(W) * H, 0.0);
    f.shows_back.assign(static_cast<std::size_t>(W) * H, 0);
    const int band = 16;
    tbb::parallel_for(0, (H + band - 1) / band, [&](int b) {
        const int y0 = b * band, y1 = std::min(H, y0 + band);
        for (const auto& t : triangles) {
            if (t.max_y < y0 || t.min_y > y1) continue;
            const auto &a = t.v[0], &bb = t.v[1], &c = t.v[2];
            const double area = (bb.x - a.x) * (c.y - a.y) - (bb.y - a.y) * (c.x - a.x);
            if (std::abs(area) < 1e-12) continue;
            const int ya = std::max(y0, static_cast<int>(std::floor(t.min_y)));
            const int yb = std::min(y1 - 1, static_cast<int>(std::ceil(t.max_y)));
            const int xa = std::max(0, static_cast<int>(std::floor(std::min({a.x, bb.x, c.x}))));
            const int xb = std::min(W - 1, static_cast<int>(std::ceil(std::max({a.x, bb.x, c.x}))));
            for (int y = ya; y <= yb; ++y)
                for (int x = xa; x <= xb; ++x) {
                    const double px = x + 0.5, py = y + 0.5;
                    const double w0 = ((bb.x - px) * (c.y - py) - (bb.y - py) * (c.x - px)) / area;
                    const double w1 = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
                    const double w2 = 1 - w0 - w1;
                    // A small tolerance: the two triangles beside a shared edge compute it in
                    // opposite orders, and rounding must not leave a crack between them.
                    if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
                    const double inv_z = w0 * a.inv_z + w1 * bb.inv_z + w2 * c.inv_z;
                    const std::size_t at = static_cast<std::size_t>(y) * W + x;
                    if (inv_z <= f.depth[at]) continue;
                    f.depth[at] = inv_z;
                    f.shows_back[at] = t.back;
                    for (int ch = 0; ch < 3; ++ch)
                        f.hi[3 * at + ch] = static_cast<float>((w0 * a.colour_over_z[ch] +
                                                                w1 * bb.colour_over_z[ch] +
                                                                w2 * c.colour_over_z[ch]) /
                                                               inv_z);
                }
        }
    });
    return f;
}

// The frame averaged down to the image, with its coverage and back-face counts.
Image resolve(const Frame& f, int width, int height, int ss) {
    const int W = width * ss;
    Image image;
    image.width = width;
    image.height = height;
    image.rgb.assign(static_cast<std::size_t>(width) * height * 3, 0.0f);
    image.back_coverage.assign(static_cast<std::size_t>(width) * height, 0.0f);
    image.covered.assign(static_cast<std::size_t>(width) * height, 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum[3] = {0, 0, 0};
            bool covered = false;
            int back_samples = 0;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    const std::size_t at =
                        static_cast<std::size_t>(y * ss + sy) * W + (x * ss + sx);
                    covered = covered || f.depth[at] > 0;
                    back_samples += f.shows_back[at];
                    for (int c = 0; c < 3; ++c) sum[c] += f.hi[3 * at + c];
                }
            image.covered_pixels += covered;
            image.covered[static_cast<std::size_t>(y) * width + x] = covered;
            const float back_share = static_cast<float>(back_samples) / float(ss * ss);
            image.back_coverage[static_cast<std::size_t>(y) * width + x] = back_share;
            image.back_face_pixels += back_share >= 0.5f;
            for (int c = 0; c < 3; ++c)
                image.rgb[3 * (static_cast<std::size_t>(y) * width + x) + c] =
                    static_cast<float>(sum[c] / (ss * ss));
        }
    return image;
}

} // namespace

Image render(const radfmt::MeshData& mesh, const CornerColours& corners, const View& view,
             int width, int height, int supersampling) {
    // Mirrors and glass show what lies beyond them: rays, not a z-buffer.
    if (mesh.has_specular()) {
        const RayScene scene(mesh);
        const SpecularSurfaces surfaces(mesh);
        return render_specular({mesh, scene, surfaces, kDefaultSpecularDepth}, view, width, height,
                               supersampling, smoothed_shader(mesh, corners), true);
    }
    const int ss = std::max(1, supersampling);
    Camera cam;
    cam.W = width * ss;
    cam.H = height * ss;
    cam.position = view.position;
    cam.dir = normalized(view.direction);
    cam.right = normalized(cross(cam.dir, view.up));
    cam.up = cross(cam.right, cam.dir);
    cam.tan_h = std::tan(0.5 * view.horizontal_deg * kDeg);
    cam.tan_v = std::tan(0.5 * view.vertical_deg * kDeg);
    double extent = 0;
    for (const auto& v : mesh.vertices) extent = std::max(extent, length(v - view.position));
    cam.near = std::max(1e-9, 1e-5 * extent);
    const auto triangles = screen_triangles(mesh, corners, cam);
    return resolve(rasterise(triangles, cam.W, cam.H), width, height, ss);
}

void mark_back_faces(Image& image, const Rgb& colour) {
    for (std::size_t p = 0; p < image.back_coverage.size(); ++p)
        if (image.back_coverage[p] >= 0.5f)
            for (int c = 0; c < 3; ++c) image.rgb[3 * p + c] = static_cast<float>(colour[c]);
}

} // namespace rad
