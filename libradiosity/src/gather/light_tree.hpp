// The lights of a final gather in a bounding volume hierarchy (internal header), so that the
// direct light at a point costs about the number of lights near it, not their number: a node
// behind the point's plane, or whose lights all face away from it, is skipped whole; a node
// small for its distance, entirely in front and facing the point, is taken as one (its lights'
// summed exitance vectors: error about (size / distance)^2); the rest are opened down to
// single lights, whose form factors the caller computes exactly. The tree also picks a light
// of a node in proportion to power, for shadow rays into a node taken as one.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rad::gather {

// r + g + b: what the tree and the shadow rays weigh lights by.
inline double brightness(const Rgb& c) {
    return c[0] + c[1] + c[2];
}

struct Light {
    std::uint32_t patch;
    Rgb radiosity; // what it sends: its exitance E (plus its reflected B - E when bright)
};

class LightTree {
  public:
    // A node of the tree taken as one at a point, and the irradiance it gives there.
    struct Cluster {
        std::uint32_t node;
        Rgb irradiance;
    };
    // What a point sees of the lights: single lights (indices into lights()) and clusters.
    struct Cut {
        std::vector<std::uint32_t> lights;
        std::vector<Cluster> clusters;
    };

    LightTree(const radfmt::MeshData& mesh, std::vector<Light> lights);

    // The cut at `point` facing `normal` (unit): nodes whose bounding-sphere radius is under
    // `max_ratio` times their distance are clusters when wholly in front and facing the point;
    // so is a node up to kLooseRatio across whose irradiance x (radius / distance)^2 is at most
    // `tolerance` (brightness, absolute; 0: none).
    void cut(const Vec3& point, const Vec3& normal, double max_ratio, Cut& out,
             double tolerance = 0) const;
    // A cluster's irradiance at another point (a cut kept for points close by).
    Rgb cluster_irradiance(std::uint32_t node, const Vec3& point, const Vec3& normal) const {
        return cluster_irradiance(nodes_[node], point, normal);
    }
    // The lights' whole irradiance (brightness) at the point, roughly: the cut at kLooseRatio,
    // single lights as points (at most their radiosity). To set a cut's tolerance.
    double rough_irradiance(const Vec3& point, const Vec3& normal) const;
    static constexpr double kLooseRatio = 0.5;
    // A light of `node` chosen in proportion to power for u in [0, 1); `remainder`, when
    // asked for, is u rescaled to [0, 1) within that light's share (to place a point on it).
    const Light& pick(std::uint32_t node, double u, double* remainder = nullptr) const;

    std::span<const Light> lights() const { return lights_; }
    // The lights under `node` (a cluster's).
    std::span<const Light> lights_of(std::uint32_t node) const {
        return std::span<const Light>(lights_).subspan(nodes_[node].first, nodes_[node].count);
    }
    // The first of `node`'s lights (where it falls in a cut's order, which is the tree's).
    std::uint32_t first_of(std::uint32_t node) const { return nodes_[node].first; }
    bool empty() const { return lights_.empty(); }

  private:
    struct Node {
        Vec3 centre{};      // bounding sphere of the lights' corners
        double radius = 0;  //
        Vec3 half_extent{}; // the corners' box, about `centre`
        Vec3 centroid{};    // power-weighted centre of the lights
        Vec3 axis{};        // normal cone: every light's normal within an angle of `axis`
        double cos_spread = -1, sin_spread = 0; // of that angle (pi when unknown)
        std::array<Vec3, 3> exitance_vector{};  // sum of radiosity_k x area x normal
        double power = 0;                       // sum of (r + g + b) x area
        std::uint32_t first = 0, count = 0;     // lights_[first, first + count)
        std::uint32_t left = 0, right = 0;      // children when count > 1
    };
    enum class Facing { All, None, Some }; // the node's lights towards a point
    static Facing facing_point(const Node& node, const Vec3& w, double distance);
    template <class Take> void visit(const Vec3& point, const Vec3& normal, Take take) const;
    std::uint32_t build(const radfmt::MeshData& mesh, std::uint32_t first, std::uint32_t count);
    Node summarise(const radfmt::MeshData& mesh, std::uint32_t first, std::uint32_t count) const;
    Rgb cluster_irradiance(const Node& node, const Vec3& point, const Vec3& normal) const;

    std::vector<Light> lights_;
    std::vector<Node> nodes_; // nodes_[0] is the root
};

} // namespace rad::gather
