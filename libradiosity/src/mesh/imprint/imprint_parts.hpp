// The steps of contact imprinting (internal header): where other faces touch or cross each
// face (its cut lines), then each cut face's regions, hidden ones dropped.
#pragma once
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace rad::imprinting {

using XY = std::array<double, 2>;

// A face's plane and its own 2D coordinates (u, v, with u x v = the normal).
struct Frame {
    Vec3 origin{}, normal{}, u{}, v{};
    double offset = 0; // normal . x on the plane
    XY to2d(const Vec3& p) const {
        const Vec3 d = p - origin;
        return {dot(d, u), dot(d, v)};
    }
    Vec3 to3d(double x, double y) const { return origin + u * x + v * y; }
};

struct Face {
    std::vector<Vec3> points;
    Frame frame;
    Box box;
    std::vector<std::uint32_t> welded; // sorted welded ids of its corners
    bool planar = false;
    double area = 0;
};

struct Segment {
    XY a, b;
};

bool convex(const std::vector<XY>& poly);

// The faces that other objects' faces touch or cross, with their planes (planar within
// `tol`), and the lines where they do, in each face's plane coordinates: contacts that reach
// into it, and (for a convex face) lines parallel to a side run on to its outline and across
// the coplanar faces of its surface, so cut rectangles stay rectangles. Faces without cuts are
// in neither map. An edge of another object within `gap` in front of a face may touch it
// (gap_for in imprint_cuts.cpp).
struct CutLines {
    std::map<std::size_t, Face> faces;
    std::map<std::size_t, std::vector<Segment>> cuts; // by face
    // Each contact (not run on) in 3D, those along a face's outline too: where each side
    // may see another room (Scene::contact_lines).
    std::vector<std::array<Vec3, 2>> contacts;
};
CutLines find_cut_lines(const Scene& scene, const std::vector<std::uint32_t>& welded, double tol,
                        double gap, double size);

} // namespace rad::imprinting
