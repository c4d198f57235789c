// What each region of a cut face sees (internal header): whose backs, surface by surface, and
// which surfaces close around it (by ray parity), so that a region is judged against the rest
// of its face, whichever way the face points.
#pragma once
#include "radiosity/rays.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace rad::imprinting {

// Rays over the scene's faces, each face's surface (faces connected across welded edges: an
// object, a room's shell, a vault) and which way each face points as the orientation checks
// would turn it (`turned`).
class SurfaceViews {
  public:
    SurfaceViews(const Scene& scene, const std::vector<bool>& turned,
                 const std::vector<std::uint32_t>& welded);

    // What the rays from the point `from`, just off a face on the side `side` (u, v across
    // it), meet first.
    struct View {
        int rays = 0, hits = 0;
        // (surface, how many rays met its back first), by surface.
        std::vector<std::pair<std::uint32_t, int>> backs;
        // ... its front, by surface.
        std::vector<std::pair<std::uint32_t, int>> fronts;
        // (surface, how many of parity_rays of the rays cross it an odd number of times), by
        // surface.
        std::vector<std::pair<std::uint32_t, int>> odd;
        int parity_rays = 0;
        int backs_of(std::uint32_t surface) const { return count(backs, surface); }
        // Whether `counted` backs are most of what the rays met (sees_mostly_backs).
        bool mostly(int counted) const {
            return hits > 0 && sees_mostly_backs(double(hits) / rays, double(counted) / hits);
        }
        int fronts_of(std::uint32_t surface) const { return count(fronts, surface); }
        // The surface closes around the point: nearly every ray crosses it an odd number of
        // times (a block over a footprint, a wall around a beam's end, a vault over a floor,
        // a room). A closed object's parity is exact, but a few rays may slip through a crack
        // between its faces, or a thin gap under it.
        bool inside(std::uint32_t surface) const {
            return count(odd, surface) >= 0.9 * parity_rays;
        }
        // ... or clearly does not (by the same margin: near an open vault's mouth, neither).
        bool outside(std::uint32_t surface) const {
            return count(odd, surface) <= 0.1 * parity_rays;
        }

      private:
        static int count(const std::vector<std::pair<std::uint32_t, int>>& list,
                         std::uint32_t surface) {
            const auto it = std::lower_bound(list.begin(), list.end(),
                                             std::pair<std::uint32_t, int>{surface, 0});
            return it != list.end() && it->first == surface ? it->second : 0;
        }
    };
    View view(const Vec3& from, const Vec3& side, const Vec3& u, const Vec3& v) const;
    // The same rays followed on, for how often they cross each of `surfaces` (sorted; into
    // View::odd): costlier.
    void add_parity(View& view, const Vec3& from, const Vec3& side, const Vec3& u, const Vec3& v,
                    const std::vector<std::uint32_t>& surfaces) const;
    double epsilon() const { return rays_.epsilon(); }
    std::uint32_t surface_of(std::size_t face) const { return surfaces_.of[face]; }
    // Whether a surface is closed: each of its edges shared by an even number of its faces.
    bool closed(std::uint32_t surface) const { return surfaces_.closed[surface]; }
    // Whether a surface is a room: its box holds the rest of the scene, or most of it.
    bool room(std::uint32_t surface) const { return surfaces_.room[surface]; }
    // Whether, from `from` (on a face in the plane normal . x = offset), a ray through the
    // middle of one of the surface's openings (a chain of the edges it leaves open off the
    // plane, joined at shared corners; edges within `gap` of it close on the face) leaves
    // the scene: the scene's open side reaches in (a tunnel
    // under a vault open at its ends). The openings of a block standing on a floor lie on the
    // floor; a cabinet's open back against a wall leads to the wall.
    bool open_to_outside(std::uint32_t surface, const Vec3& from, const Vec3& normal, double offset,
                         double gap) const;

    // Each face's surface (faces connected across welded edges), and by surface id (its
    // first face's index) whether it is closed and a room, and its box.
    struct Surfaces {
        std::vector<std::uint32_t> of;
        std::vector<char> closed, room;
        std::vector<Box> box;
        // The edges each surface leaves open (used by an odd number of its faces), as pairs
        // of scene vertices, surface by surface (open_start[s] to open_start[s + 1]).
        std::vector<std::size_t> open_start;
        std::vector<std::array<std::uint32_t, 2>> open_edges;
    };

  private:
    // Which of `surfaces` (sorted) a ray from `from` along `dir` crosses an odd number of
    // times, into `odd`; false when it crosses too many faces to follow. It is followed only
    // as far as it takes to leave their boxes.
    bool odd_crossings(const Vec3& from, const Vec3& dir,
                       const std::vector<std::uint32_t>& surfaces,
                       std::vector<std::uint32_t>& odd) const;
    // How far along the ray it leaves the last of the surfaces' boxes (< 0: it meets none).
    double leaves_boxes(const Vec3& from, const Vec3& dir,
                        const std::vector<std::uint32_t>& surfaces) const;

    std::vector<std::size_t> face_of_; // per traced triangle
    Surfaces surfaces_;
    const std::vector<Vec3>& vertices_;
    const std::vector<std::uint32_t>& welded_; // the owner's (the Imprinter's)
    RayScene rays_;
};

} // namespace rad::imprinting
