// What a sensor sees of the sky directly (daylight.hpp, sensor_sky_path_list): the sky's cells
// traced from the sensor, finer where an opening's edge crosses the sky, and there, with a
// jitter stream, sampled unbiasedly where the edge runs so the quadrature carries its error.
#include "radiosity/daylight.hpp"

#include <algorithm>
#include <cmath>

namespace rad {
namespace {

// The tracing of one sensor: per sky patch, the paths out of the scene.
class SkyTracer {
  public:
    SkyTracer(const RayScene& scene, const SpecularSurfaces& specular, const SkyPatches& patches,
              int depth, const Vec3& point, const Vec3& normal)
        : scene_(scene), specular_(specular), patches_(patches), depth_(depth), point_(point),
          normal_(normal) {}

    // Direction d's paths out of the scene into `out`, each at `cell` x cos; whether any left.
    bool follow(const Vec3& d, double cell, std::int64_t slot, std::vector<SkyPath>& out) const {
        const double cosine = dot(d, normal_);
        bool left = false;
        follow_specular(
            scene_, specular_, point_, d, radfmt::Rgb{{1, 1, 1}}, depth_, [](const PathHit&) {},
            [&](const Vec3& direction, const radfmt::Rgb& w) {
                left = true;
                out.push_back({direction,
                               radfmt::Rgb{{w[0] * cell * cosine, w[1] * cell * cosine,
                                            w[2] * cell * cosine}},
                               slot});
            });
        return left;
    }

    // Patch p at the cells' centres; its state: 0 nothing facing, 1 closed, 2 partly open,
    // 3 open.
    int trace(std::size_t p, const std::vector<Vec3>& directions, std::vector<SkyPath>& out) const {
        out.clear();
        const double cell = patches_.solid_angle(p) / double(directions.size());
        int opened = 0, facing = 0;
        for (std::size_t c = 0; c < directions.size(); ++c) {
            if (dot(directions[c], normal_) <= 0) continue;
            ++facing;
            opened += follow(directions[c], cell, -1, out) ? 1 : 0;
        }
        return facing == 0 ? 0 : opened == 0 ? 1 : opened < facing ? 2 : 3;
    }

    // Patch p at its fine cells, those where the edge runs jittered (sensor_sky_path_list).
    void trace_jittered(std::size_t p, const SkyRefinement& refine, Rng& jitter,
                        std::int64_t& next_part, std::vector<SkyPath>& out) const {
        thread_local std::vector<SkyPath> centres;
        thread_local std::vector<std::size_t> first;
        thread_local std::vector<std::uint8_t> open;
        const auto& directions = refine.fine[p];
        const int side = refine.fine_side;
        // The centres' paths, cell by cell, kept until it is known which cells the edge crosses.
        centres.clear();
        first.assign(directions.size() + 1, 0);
        const double cell = patches_.solid_angle(p) / double(directions.size());
        for (std::size_t c = 0; c < directions.size(); ++c) {
            first[c] = centres.size();
            if (dot(directions[c], normal_) > 0) follow(directions[c], cell, -1, centres);
        }
        first[directions.size()] = centres.size();
        open_states(p, refine, first, open);
        out.clear();
        constexpr int kSplit = 2; // an edge cell's parts per side
        const double half_part = cell / (kSplit * kSplit) / 2;
        for (int a = 0; a < side; ++a)
            for (int z = 0; z < side; ++z) {
                const std::size_t c = std::size_t(a) * side + z;
                if (!on_edge(open, side, a, z)) {
                    out.insert(out.end(), centres.begin() + std::ptrdiff_t(first[c]),
                               centres.begin() + std::ptrdiff_t(first[c + 1]));
                    continue;
                }
                for (int i = 0; i < kSplit; ++i)
                    for (int j = 0; j < kSplit; ++j, ++next_part) {
                        const int part = (a * kSplit + i) * side * kSplit + z * kSplit + j;
                        for (int pass = 0; pass < 2; ++pass) {
                            const double u = jitter.uniform(), v = jitter.uniform();
                            const auto d =
                                patches_.cell_direction(refine.frame, p, side * kSplit, part, u, v);
                            if (dot(d, normal_) > 0)
                                follow(d, half_part, 2 * next_part + pass, out);
                        }
                    }
            }
    }

  private:
    // Whether each fine cell's centre leaves the scene, on a grid with a ring around it: the
    // centres half a cell beyond the patch's borders (in the neighbouring patches), so an edge
    // running along a border is found too. `first` delimits each cell's paths (none: closed).
    void open_states(std::size_t p, const SkyRefinement& refine,
                     const std::vector<std::size_t>& first, std::vector<std::uint8_t>& open) const {
        const int side = refine.fine_side, wide = side + 2;
        open.assign(std::size_t(wide) * wide, 0);
        for (int a = 0; a < side; ++a)
            for (int z = 0; z < side; ++z) {
                const std::size_t c = std::size_t(a) * side + z;
                open[std::size_t(a + 1) * wide + z + 1] = first[c + 1] > first[c];
            }
        thread_local std::vector<SkyPath> scratch;
        const auto beyond = [&](int a, int z, double u, double v) {
            const int inside_a = std::clamp(a, 0, side - 1), inside_z = std::clamp(z, 0, side - 1);
            const auto own = open[std::size_t(inside_a + 1) * wide + inside_z + 1];
            const auto d =
                patches_.cell_direction(refine.frame, p, side, inside_a * side + inside_z, u, v);
            // Past the zenith or the nadir there is no neighbour: the cell's own state.
            if (!std::isfinite(d[0]) || !std::isfinite(d[1]) || !std::isfinite(d[2])) return own;
            scratch.clear();
            return std::uint8_t(dot(d, normal_) > 0 && follow(d, 0, -1, scratch));
        };
        for (int k = 0; k < side; ++k) {
            open[std::size_t(k + 1)] = beyond(0, k, -0.5, 0.5);
            open[std::size_t(side + 1) * wide + k + 1] = beyond(side - 1, k, 1.5, 0.5);
            open[std::size_t(k + 1) * wide] = beyond(k, 0, 0.5, -0.5);
            open[std::size_t(k + 1) * wide + side + 1] = beyond(k, side - 1, 0.5, 1.5);
        }
    }

    // Whether cell (a, z)'s centre leaves the scene where one of its four neighbours' (on the
    // ringed grid) does not, or the other way.
    static bool on_edge(const std::vector<std::uint8_t>& open, int side, int a, int z) {
        const int wide = side + 2;
        const auto at = [&](int r, int c) { return open[std::size_t(r + 1) * wide + c + 1]; };
        const auto mine = at(a, z);
        return at(a - 1, z) != mine || at(a + 1, z) != mine || at(a, z - 1) != mine ||
               at(a, z + 1) != mine;
    }

    const RayScene& scene_;
    const SpecularSurfaces& specular_;
    const SkyPatches& patches_;
    int depth_;
    Vec3 point_, normal_;
};

// The patches to trace again finer: those partly open, or whose neighbours' state differs.
void patches_to_refine(const std::vector<std::uint8_t>& state, const SkyRefinement& refine,
                       std::vector<std::uint8_t>& again) {
    again.assign(state.size(), 0);
    for (std::size_t p = 0; p < state.size(); ++p) {
        if (state[p] == 0) continue;
        bool edge = state[p] == 2;
        for (const auto q : refine.neighbours[p])
            edge = edge || (state[q] != 0 && state[q] != state[p]);
        again[p] = edge;
    }
}

} // namespace

const std::vector<SkyPath>& sensor_sky_path_list(const RayScene& scene,
                                                 const SpecularSurfaces& specular,
                                                 const SkyPatches& patches,
                                                 const SkyPatches::Cells& cells, int depth,
                                                 const Vec3& point, const Vec3& normal,
                                                 const SkyRefinement* refine, Rng* jitter) {
    thread_local std::vector<std::vector<SkyPath>> found;
    thread_local std::vector<std::uint8_t> state, again;
    thread_local std::vector<SkyPath> out;
    const SkyTracer tracer(scene, specular, patches, depth, point, normal);
    const std::size_t count = patches.count();
    found.resize(count);
    state.assign(count, 0);
    for (std::size_t p = 0; p < count; ++p)
        state[p] = std::uint8_t(tracer.trace(p, cells[p], found[p]));
    if (refine && !refine->empty()) {
        patches_to_refine(state, *refine, again);
        std::int64_t next_part = 0;
        for (std::size_t p = 0; p < count; ++p) {
            if (!again[p]) continue;
            if (jitter)
                tracer.trace_jittered(p, *refine, *jitter, next_part, found[p]);
            else
                tracer.trace(p, refine->fine[p], found[p]);
        }
    }
    out.clear();
    for (std::size_t p = 0; p < count; ++p) out.insert(out.end(), found[p].begin(), found[p].end());
    return out;
}

} // namespace rad
