// compute_links: links refined top down from the root's interaction with itself. A direction
// of a pair of nodes is linked when the oracle says its transfer is smooth enough to treat as
// one number: its form factor (sampled, or integrated where a node allows it), grown by how
// unevenly the receiver faces the source and by varying visibility, at most epsilon (less for
// light from an emitter), and its form factor times how much the emitters' direct light
// varies inside the source's parts small against the receiver's light; otherwise a node is
// split. Two patches are linked by the analytic method's integral.
#include "formfactor/sampling.hpp"
#include "hierarchy/direct_light.hpp"
#include "hierarchy/link_shares.hpp"
#include "hierarchy/node_geometry.hpp"
#include "hierarchy/surfaces.hpp"
#include "radiosity/hierarchy.hpp"
#include "radiosity/rays.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace rad {

namespace {
using hierarchy::kWholeShare;
using hierarchy::NodeGeometries;
using hierarchy::NodePoint;

// Per material: emits in the mesh, or is named in options.emitters.
std::vector<bool> emitter_materials(const radfmt::MeshData& mesh, const HierarchyOptions& options) {
    std::vector<bool> out(mesh.materials.size(), false);
    for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
        out[m] = mesh.materials[m].emits();
        for (const auto& name : options.emitters)
            if (name == mesh.materials[m].name) out[m] = true;
    }
    return out;
}

// The names of the materials used by a patch for which `emitter` holds.
std::vector<std::string> emitter_names(const radfmt::MeshData& mesh,
                                       const std::vector<bool>& emitter) {
    std::vector<bool> used(mesh.materials.size(), false);
    for (const auto& p : mesh.patches) used[p.material] = true;
    std::vector<std::string> names;
    for (std::size_t m = 0; m < mesh.materials.size(); ++m)
        if (used[m] && emitter[m]) names.push_back(mesh.materials[m].name);
    return names;
}

struct Link {
    std::uint32_t receiver, source;
    float factor;
    radfmt::LinkShares receiver_share, source_share;
};

// Where a pair's transfer passes through each node (hierarchy::link_shares).
struct PairShares {
    radfmt::LinkShares a = kWholeShare, b = kWholeShare;
};

struct ThreadWork {
    std::vector<Link> links;
    HierarchyStats stats;
};

// Below this many patches in a pair, its refinement runs on the thread that found it.
constexpr std::uint32_t kSerialPatches = 64;
constexpr int kPatchPairPoints = 16;
// A flat node of at most this many patches that fills no convex outline is integrated patch
// by patch.
constexpr std::uint32_t kFewPatches = 16;
// Sample pairs that decide whether a pair of nodes is linked; a pair whose sampled form
// factor is over kClearly times epsilon in every direction wanted is split at once.
constexpr int kDecisionSamples = 16;
constexpr double kClearly = 4;
// A link valued from sample pairs alone (no node integrable) carries at most this share of
// epsilon: its value is noisier than an integral's.
constexpr double kSampledShare = 0.25;
// Light from a node with an emitter (a material that emits in the mesh) is kept to this
// share of epsilon: a lamp is tens of times brighter than what it lights, and a link's error
// is its form factor's times the source's radiosity.
constexpr double kEmitterShare = 1.0 / 64;
// A link's error from light varying inside its source's parts (uneven_light) is kept to this
// share of epsilon, about the emitters' (kEmitterShare): where the variation is as large as
// the light its receiver gets, the source's parts are as bright against the receiver as a
// lamp is. On the Cornell variants (bench/cornell-variants) 1/50 brings the worst surface
// from 0.54% to 0.28% of the analytic solution and the per-patch rms from 2.14% to 1.91%,
// for a fifth more links (1/56 of the analytic matrix's non-zeros, was 1/66).
constexpr double kLightShare = 1.0 / 50;
// Light a link may put where its source is hidden from part of the receiver (shadowed_light)
// is kept to this share of epsilon. On 50 random Cornell boxes (bench/cornell-random) half
// took the worst surface from 1.99% to 0.90% for 1.3% more links (pandora-cut: 2.4% more);
// a tenth gave 0.94% and a better rms on hanging lamps (2.07% against 2.37%) for 8% more
// (pandora-cut: 18% more, and a third more time). Where it was found (a lamp up a recess,
// 1.99%), a global epsilon of 0.01 with 76% more links left it at 2.15%.
constexpr double kShadowShare = 0.5;
// Points on the receiving side of a contour-integral link value.
constexpr int kOutlinePoints = 16;
// ... and when the nodes are further apart than the larger one's size, where F varies little
// over the points (on the Cornell box and the living room, as accurate and a third faster).
constexpr int kFarOutlinePoints = 4;
// Visibility is traced first for every kScoutStride-th sample pair; when at least
// kMinScouts of them face and all agree, the rest are not traced.
constexpr std::size_t kScoutStride = 4;
constexpr int kMinScouts = 8;
// A pair with fewer sample pairs facing each other is not linked (their visibility is too
// few rays' word: a strip beside a wall, most of it behind the strip's plane, was linked
// with 0.02 to 1.7 times its form factor).
constexpr int kMinFacing = 16;
// How much a side's uneven facing adds to the oracle's estimate.
constexpr double kSpreadWeight = 4;

// A shard's tasks (HierarchyOptions::shard): a pair of nodes (or a node's interactions with
// itself) of at most `cut` patches whose parent pair is larger. Above the cut every shard
// walks the same decisions (each drawn from (seed, pair) alone) and keeps the links of the
// pairs it owns; below it, a shard refines only the tasks it owns. Owners are spread by a hash
// of the pair, so the tasks' sizes even out over the shards.
struct ShardWalk {
    std::uint32_t shard = 0, shards = 1;
    std::uint64_t cut = 0;
    bool owns(std::uint32_t a, std::uint32_t b) const {
        std::uint64_t x = (std::uint64_t(a) << 32 | b) + 0x9e3779b97f4a7c15ull; // splitmix64
        x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
        x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
        return (x ^ (x >> 31)) % shards == shard;
    }
};

// About this many tasks a shard, so that their sizes even out.
constexpr std::uint64_t kTasksPerShard = 16;

class LinkRefiner {
  public:
    LinkRefiner(const FormFactorContext& context, const radfmt::LinkData& tree,
                const std::vector<std::uint32_t>& surface, const HierarchyOptions& options)
        : context_(context), tree_(tree),
          geometry_(context.mesh, context.polygons, tree, emitter_materials(context.mesh, options),
                    surface),
          light_(hierarchy::estimate_direct_light(context.mesh, tree, geometry_, context.scene,
                                                  options.seed)),
          options_(options), samples_(std::max(1, options.samples)) {
        walk_.shard = options.shard;
        walk_.shards = std::max<std::uint32_t>(1, options.shards);
        walk_.cut = std::max<std::uint64_t>(2, tree.patch_count / (kTasksPerShard * walk_.shards));
        // Two patches: the analytic method's default quadrature (16 points, 64 when close).
        const int m = ff::points_per_axis(kPatchPairPoints);
        ff::gauss_legendre(m, nodes_, weights_);
        ff::gauss_legendre(2 * m, close_nodes_, close_weights_);
    }

    // Every interaction between patches of `node` (of those this shard owns).
    void refine_within(std::uint32_t node) { refine_within(node, walk_.shards == 1); }

    // The links, by receiver then source, into the tree's arrays.
    void collect(radfmt::LinkData& out, HierarchyStats& stats) {
        std::vector<Link> all;
        for (auto& work : work_) {
            all.insert(all.end(), work.links.begin(), work.links.end());
            work.links = {};
            stats.pairs += work.stats.pairs;
            stats.culled += work.stats.culled;
            stats.rays += work.stats.rays;
            stats.leaf_links += work.stats.leaf_links;
            stats.outline_pairs += work.stats.outline_pairs;
        }
        std::sort(all.begin(), all.end(), [](const Link& a, const Link& b) {
            return a.receiver < b.receiver || (a.receiver == b.receiver && a.source < b.source);
        });
        out.link_start.assign(out.nodes.size() + 1, 0);
        out.source.resize(all.size());
        out.factor.resize(all.size());
        out.receiver_share.resize(all.size());
        out.source_share.resize(all.size());
        for (std::size_t l = 0; l < all.size(); ++l) {
            ++out.link_start[all[l].receiver + 1];
            out.source[l] = all[l].source;
            out.factor[l] = all[l].factor;
            out.receiver_share[l] = all[l].receiver_share;
            out.source_share[l] = all[l].source_share;
        }
        for (std::size_t i = 0; i < out.nodes.size(); ++i)
            out.link_start[i + 1] += out.link_start[i];
    }

  private:
    // `inside`: within a task this shard owns (always, unsharded).
    void refine_within(std::uint32_t node, bool inside) {
        const auto& n = tree_.nodes[node];
        if (!enter(node, node, n.count, inside)) return;
        if (n.left == radfmt::kNoNode) return; // a flat patch does not see itself
        run_both([&] { refine_within(n.left, inside); },
                 [&] {
                     refine_within(n.right, inside);
                     refine_pair(n.left, n.right, kIntoA | kIntoB, inside);
                 },
                 n.count);
    }

    // Whether this shard refines the pair (a, b) of `patches` patches, and from there on
    // `inside` one of its tasks.
    bool enter(std::uint32_t a, std::uint32_t b, std::uint64_t patches, bool& inside) const {
        if (inside || patches > walk_.cut) return true;
        inside = walk_.owns(a, b);
        return inside;
    }

    template <class A, class B> void run_both(A&& a, B&& b, std::uint64_t patches) {
        if (patches < kSerialPatches) {
            a();
            b();
        } else {
            tbb::parallel_invoke(a, b);
        }
    }

    bool is_leaf(std::uint32_t node) const { return tree_.nodes[node].left == radfmt::kNoNode; }

    // The directions of a pair: light into a (a link a <- b) and into b.
    static constexpr unsigned kIntoA = 1, kIntoB = 2;

    // Patches a and b see each other through nodes a and b (disjoint); `wanted` says which
    // directions still need links. A link's receiver must be (part of) one surface: a node
    // receives one irradiance for all its patches, wrong for those turned another way or
    // standing apart, which see other things (a cluster may be a source: its mean radiosity,
    // with each sample's own cosine).
    bool receives(std::uint32_t node) const { return geometry_[node].one_surface; }
    void refine_pair(std::uint32_t a, std::uint32_t b, unsigned wanted, bool inside) {
        if (!enter(a, b, std::uint64_t(tree_.nodes[a].count) + tree_.nodes[b].count, inside))
            return;
        auto& work = work_.local();
        ++work.stats.pairs;
        if (geometry_.all_behind(a, b) || geometry_.all_behind(b, a)) {
            ++work.stats.culled;
            return;
        }
        Rng rng(options_.seed, (std::uint64_t(a) << 32) | b);
        if (is_leaf(a) && is_leaf(b)) return link_patches(a, b, wanted, rng, work);
        const PairEstimate estimate = estimate_pair(a, b, rng, kDecisionSamples);
        const double area_ratio = geometry_[a].area / geometry_[b].area;
        // Light from an emitter is kept to a smaller share of epsilon (see kEmitterShare).
        const double epsilon_a = options_.epsilon * (geometry_[b].emits ? kEmitterShare : 1);
        const double epsilon_b = options_.epsilon * (geometry_[a].emits ? kEmitterShare : 1);
        // Every direction wanted far above epsilon (or into a node that cannot receive):
        // split at once, without integrating.
        const double sampled_a = estimate.unoccluded, sampled_b = sampled_a * area_ratio;
        const bool split_a = !receives(a) || sampled_a > kClearly * epsilon_a;
        const bool split_b = !receives(b) || sampled_b > kClearly * epsilon_b;
        if ((!(wanted & kIntoA) || split_a) && (!(wanted & kIntoB) || split_b))
            return split(a, b, wanted, inside);
        const auto exact = exact_form_factor(a, b, rng, work);
        // Sampled alone, or integrated from points of the larger node, a near pair is not
        // trusted (see near): a few points of the larger miss the part of it near the other.
        if ((!exact.known || exact.from_larger) && (geometry_[a].planar || geometry_[b].planar) &&
            near(a, b))
            return split(a, b, wanted, inside);
        const double f_ab = exact.known ? exact.factor : estimate.unoccluded;
        const double f_ba = f_ab * area_ratio;
        // Each direction's form factor, grown by how unevenly its receiver faces the source,
        // or how much it varies over the receiver's points where those were integrated from.
        const double error_a =
            std::max(f_ab * (1 + kSpreadWeight * estimate.spread_a), exact.spread_a);
        const double error_b =
            std::max(f_ba * (1 + kSpreadWeight * estimate.spread_b), exact.spread_b);
        // Nothing faces: a small facing part may have been missed between the samples.
        // Dropped only when it could not matter (bounded by each node's solid angle seen from
        // the other at their boxes' distance).
        if (f_ab <= 0) {
            if (largest_possible(a, b) > options_.epsilon) split(a, b, wanted, inside);
            return;
        }
        unsigned ready = 0;
        if ((wanted & kIntoA) && receives(a) && error_a <= epsilon_a &&
            uneven_light(f_ab, a, b) <= kLightShare * epsilon_a)
            ready |= kIntoA;
        if ((wanted & kIntoB) && receives(b) && error_b <= epsilon_b &&
            uneven_light(f_ba, b, a) <= kLightShare * epsilon_b)
            ready |= kIntoB;
        if (ready) {
            // Visibility (and a sampled value) from samples of their own: those that decided
            // to link are biased low (a pair whose draw came out high was split instead).
            const auto sampled = estimate_pair(a, b, rng, samples_);
            const auto traced = trace_pair(sampled, work);
            const double visible = traced.visible;
            const double value_ab =
                exact.known ? exact_form_factor(a, b, rng, work).factor * traced.weighted
                            : traced.factor;
            const double value_ba = value_ab * area_ratio;
            // Visibility that varies across the pair (a shadow's edge) counts up to double.
            const double varies = visible > 0 && visible < 1 ? 1 + 4 * visible * (1 - visible) : 1;
            // A sampled value must pass the test the estimate passed: a near sample pair the
            // estimate missed shows here, and the pair is split rather than linked with it.
            // A value from samples alone carries their noise: it is kept to a smaller share.
            const double share = exact.known ? 1.0 : kSampledShare;
            if (std::max(error_a, value_ab) * varies > share * epsilon_a) ready &= ~kIntoA;
            if (std::max(error_b, value_ba) * varies > share * epsilon_b) ready &= ~kIntoB;
            if (shadowed_light(f_ab, visible, a, b) > kShadowShare * epsilon_a) ready &= ~kIntoA;
            if (shadowed_light(f_ba, visible, b, a) > kShadowShare * epsilon_b) ready &= ~kIntoB;
            // Visibility judged from a few facing pairs is no judgement: where most pairs
            // face away (a node mostly behind the other's plane), split.
            if (traced.facing < kMinFacing) ready = 0;
            // Above the cut, the pair's links are its owner's.
            if (inside || walk_.owns(a, b))
                add_links(a, b, value_ab, ready, shares(a, b, sampled, traced), work);
        }
        if (wanted & ~ready) split(a, b, wanted & ~ready, inside);
    }

    // What a link into `receiver` misses of the direct light's variation inside the source's
    // parts, against the light the receiver gets (its own direct light and the scene's mean
    // as a stand-in for what is reflected): a floor bright under the lamp, read as its parts'
    // means, undercounts what the ceiling above the lamp gets and overcounts its corners.
    // A cluster too: now that split keeps a group of surfaces whole as a source, a block lit
    // on its top and dark at its sides, 15 mm from a wall, lit the wall as one mean (a random
    // Cornell box's wall -0.73 -> -1.05% without this). (When clusters were split jointly, this
    // for clusters darkened the upward faces of rpkCpp's corridor's torus by 2-4%; with split
    // per direction, every surface of the corridor is within 1.3% of hemisphere's.)
    double uneven_light(double factor, std::uint32_t receiver, std::uint32_t source) const {
        if (light_.empty()) return 0;
        const double level = light_.mean[receiver] + light_.reference;
        return level > 0 ? factor * light_.spread[source] / level : 0;
    }

    // What a link into `receiver` may put where the source is hidden, when only part of the
    // pair sees each other (a shadow's edge inside it), against the light the receiver gets
    // (as uneven_light): the top of a wall that cannot see into a lamp's recess, lit by a link
    // from the recess's bright sides to the whole wall, came out 13-33% bright.
    double shadowed_light(double factor, double visible, std::uint32_t receiver,
                          std::uint32_t source) const {
        if (light_.empty() || !(visible > 0 && visible < 1)) return 0;
        const double level = light_.mean[receiver] + light_.reference;
        return level > 0 ? factor * 4 * visible * (1 - visible) * light_.mean[source] / level : 0;
    }

    // The squared distance between the boxes of nodes a and b (0 when they overlap).
    double gap_squared(std::uint32_t a, std::uint32_t b) const {
        const auto& ba = geometry_[a].box;
        const auto& bb = geometry_[b].box;
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
            const double gap = std::max({0.0, ba.lo[c] - bb.hi[c], bb.lo[c] - ba.hi[c]});
            d2 += gap * gap;
        }
        return d2;
    }

    // Nodes nearer each other than half the larger one's size: a near part of one may fill
    // much of the other's view, and a few samples miss it.
    bool near(std::uint32_t a, std::uint32_t b) const {
        const double d2 = gap_squared(a, b);
        const double size =
            0.5 * std::max(geometry_[a].box.diagonal(), geometry_[b].box.diagonal());
        return d2 < size * size;
    }

    // Nodes further apart than the larger one's size.
    bool far(std::uint32_t a, std::uint32_t b) const {
        const double size = std::max(geometry_[a].box.diagonal(), geometry_[b].box.diagonal());
        return gap_squared(a, b) > size * size;
    }

    // Refines the children of one node against the other for the directions left: a
    // receiver that cannot receive is split, else the larger node.
    void split(std::uint32_t a, std::uint32_t b, unsigned directions, bool inside) {
        // Two groups of surfaces, neither able to receive: each direction splits its own
        // receiver and keeps the other whole as its source. Split together, each side's
        // surfaces would come to receive from the other's surfaces one by one: a link for
        // every pair of surfaces that see each other (near groups above all: on pandora-cut, doing
        // this for far groups alone saved nothing).
        if (directions == (kIntoA | kIntoB) && !receives(a) && !receives(b)) {
            const auto patches = std::uint64_t(tree_.nodes[a].count) + tree_.nodes[b].count;
            run_both([&] { split(a, b, kIntoA, inside); }, [&] { split(a, b, kIntoB, inside); },
                     patches);
            return;
        }
        bool split_a;
        if ((directions & kIntoA) && !receives(a))
            split_a = true;
        else if ((directions & kIntoB) && !receives(b))
            split_a = false;
        else
            split_a = !is_leaf(a) && (is_leaf(b) || geometry_[a].area >= geometry_[b].area);
        const auto& n = tree_.nodes[split_a ? a : b];
        const auto patches = std::uint64_t(tree_.nodes[a].count) + tree_.nodes[b].count;
        if (split_a)
            run_both([&] { refine_pair(n.left, b, directions, inside); },
                     [&] { refine_pair(n.right, b, directions, inside); }, patches);
        else
            run_both([&] { refine_pair(a, n.left, directions, inside); },
                     [&] { refine_pair(a, n.right, directions, inside); }, patches);
    }

    struct PairEstimate {
        std::vector<NodePoint> from, to;
        std::vector<double> from_u, to_u; // where each point was drawn (NodeGeometries::point)
        // Per side, the spread (largest less smallest) of its points' cosines towards the
        // other node's centre: 0 for a flat node far away, up to 1 for a cluster.
        double spread_a = 0, spread_b = 0;
        std::vector<double> kernel; // per sample pair: cos cos A_b / (pi r^2)
        double unoccluded = 0;      // F_ab without occlusion: the kernels' mean
    };

    // Stratified sample pairs of a and b and the unoccluded kernel between them, each pair
    // standing for all of b: an unbiased estimate of F_ab. Near pairs, where it varies
    // wildly, come out large and are refined.
    PairEstimate estimate_pair(std::uint32_t a, std::uint32_t b, Rng& rng, int samples) const {
        PairEstimate e;
        // Sized once: growing five vectors a sample at a time was most of the oracle's
        // allocations (a pair is estimated twice, on 5.5M pairs of pandora-cut).
        e.from.reserve(samples);
        e.to.reserve(samples);
        e.from_u.reserve(samples);
        e.to_u.reserve(samples);
        e.kernel.reserve(samples);
        const double area_b = geometry_[b].area;
        std::vector<int> strata(samples);
        for (int k = 0; k < samples; ++k) strata[k] = k;
        for (int k = samples - 1; k > 0; --k)
            std::swap(strata[k], strata[static_cast<int>(rng.uniform() * (k + 1))]);
        for (int k = 0; k < samples; ++k) {
            const double ua = (k + rng.uniform()) / samples;
            const double ub = (strata[k] + rng.uniform()) / samples;
            const auto x = geometry_.point(a, ua, rng.uniform(), rng.uniform());
            const auto y = geometry_.point(b, ub, rng.uniform(), rng.uniform());
            const Vec3 d = y.point - x.point;
            const double r2 = dot(d, d);
            const double r = std::sqrt(r2);
            const double ca = r > 0 ? dot(x.normal, d) / r : 0;
            const double cb = r > 0 ? -dot(y.normal, d) / r : 0;
            const double kernel =
                ca > 0 && cb > 0 ? ca * cb * area_b / (ff::kPi * r2 + area_b / samples) : 0.0;
            e.from.push_back(x);
            e.to.push_back(y);
            e.from_u.push_back(ua);
            e.to_u.push_back(ub);
            e.kernel.push_back(kernel);
            e.unoccluded += kernel;
        }
        e.unoccluded /= samples;
        e.spread_a = cosine_spread(e.from, geometry_[b].box.centre());
        e.spread_b = cosine_spread(e.to, geometry_[a].box.centre());
        return e;
    }

    // The most F_ab or F_ba can be: the other node's area over pi d^2, d the distance
    // between the nodes' boxes.
    double largest_possible(std::uint32_t a, std::uint32_t b) const {
        const double d2 = gap_squared(a, b);
        if (d2 <= 0) return 1e300;
        return std::max(geometry_[a].area, geometry_[b].area) / (ff::kPi * d2);
    }

    static double cosine_spread(const std::vector<NodePoint>& points, const Vec3& towards) {
        double lo = 1, hi = 0;
        for (const auto& p : points) {
            const double c = std::max(0.0, dot(p.normal, normalized(towards - p.point)));
            lo = std::min(lo, c);
            hi = std::max(hi, c);
        }
        return std::max(0.0, hi - lo);
    }

    struct Traced {
        double factor = 0;              // F_ab with occlusion, from the sample pairs alone
        double visible = 0;             // the fraction of facing pairs that see each other
        double weighted = 0;            // the same, each pair weighted by its kernel
        std::vector<std::uint8_t> seen; // per sample pair
        int facing = 0;                 // sample pairs that face each other
    };
    // Every kScoutStride-th pair is traced first (a quarter of them, spread over both nodes'
    // strata); when those that face all agree, seen or hidden, so are the rest taken to be:
    // most pairs of an interior see each other whole, and a shadow that no scout ray meets
    // is small. Otherwise the rest are traced too.
    Traced trace_pair(const PairEstimate& e, ThreadWork& work) const {
        Traced t;
        const std::size_t n = e.kernel.size();
        t.seen.assign(n, 0);
        int scouts = 0, scouts_seen = 0;
        for (std::size_t k = 0; k < n; k += kScoutStride) {
            if (e.kernel[k] <= 0) continue;
            ++scouts;
            ++work.stats.rays;
            t.seen[k] = context_.scene.visible(e.from[k].point, e.to[k].point);
            scouts_seen += t.seen[k];
        }
        const bool agree = scouts >= kMinScouts && (scouts_seen == 0 || scouts_seen == scouts);
        int facing = 0, seen = 0;
        double total = 0;
        for (std::size_t k = 0; k < n; ++k) {
            if (e.kernel[k] <= 0) continue;
            if (k % kScoutStride != 0) {
                if (agree) {
                    t.seen[k] = scouts_seen > 0;
                } else {
                    ++work.stats.rays;
                    t.seen[k] = context_.scene.visible(e.from[k].point, e.to[k].point);
                }
            }
            ++facing;
            total += e.kernel[k];
            if (t.seen[k]) {
                ++seen;
                t.factor += e.kernel[k];
            }
        }
        t.facing = facing;
        t.visible = facing ? double(seen) / facing : 0.0;
        t.weighted = total > 0 ? t.factor / total : 0.0;
        t.factor /= double(n);
        return t;
    }

    // F_ab unoccluded, exact when either node is integrable: the contour integrals over its
    // outline (the larger one's, when both are) from points of the other, with how much it
    // varies over those points (largest less smallest, on that side).
    struct ExactFactor {
        bool known = false;
        bool from_larger = false; // integrated from the points of the larger node
        double factor = 0;
        double spread_a = 0, spread_b = 0;
    };
    ExactFactor exact_form_factor(std::uint32_t a, std::uint32_t b, Rng& rng,
                                  ThreadWork& work) const {
        const bool integrable_a = integrable(a);
        const bool integrable_b = integrable(b);
        ExactFactor exact;
        if (!integrable_a && !integrable_b) return exact;
        ++work.stats.outline_pairs;
        exact.known = true;
        if (integrable_b && (!integrable_a || geometry_[b].area >= geometry_[a].area)) {
            const auto f = outline_form_factor(a, b, rng);
            exact.factor = f.mean;
            exact.spread_a = f.spread;
            exact.from_larger = geometry_[a].area > geometry_[b].area;
        } else {
            const auto f = outline_form_factor(b, a, rng);
            exact.factor = f.mean * geometry_[b].area / geometry_[a].area;
            exact.spread_b = f.spread;
            exact.from_larger = geometry_[b].area > geometry_[a].area;
        }
        return exact;
    }

    // The form factor from point x to `polygon` clipped to x's front.
    static double clipped_form_factor(const NodePoint& x, std::span<const Vec3> polygon,
                                      std::vector<Vec3>& clipped) {
        ff::clip_to_front(polygon, x.point, x.normal, clipped);
        return clipped.size() >= 3 ? point_to_polygon_form_factor(x.point, x.normal, clipped) : 0.0;
    }

    // Whether F to `node` is a sum of contour integrals: a flat node that fills a convex
    // outline, or has few patches.
    bool integrable(std::uint32_t node) const {
        return !geometry_.outline(node).empty() ||
               (geometry_[node].planar && tree_.nodes[node].count <= kFewPatches);
    }

    struct OutlineFactor {
        double mean = 0, spread = 0;
    };
    // F from node `from` to integrable node `to`, unoccluded: over stratified points of
    // `from`, the point-to-polygon form factor of `to`'s outline (or of each of its patches)
    // clipped to each point's front.
    OutlineFactor outline_form_factor(std::uint32_t from, std::uint32_t to, Rng& rng) const {
        const auto outline = geometry_.outline(to);
        const auto& plane = geometry_[to];
        std::vector<Vec3> clipped;
        double sum = 0, lo = 1e300, hi = 0;
        const int points = far(from, to) ? kFarOutlinePoints : kOutlinePoints;
        for (int k = 0; k < points; ++k) {
            const auto x =
                geometry_.point(from, (k + rng.uniform()) / points, rng.uniform(), rng.uniform());
            double f = 0;
            if (dot(plane.normal, x.point) - plane.offset > 0) { // in front of its plane
                if (!outline.empty()) {
                    f = clipped_form_factor(x, outline, clipped);
                } else { // a few patches that fill no convex outline: each of them
                    const auto& n = tree_.nodes[to];
                    for (auto k2 = n.first; k2 < n.first + n.count; ++k2)
                        f += clipped_form_factor(
                            x, context_.polygons[tree_.leaf_order[k2]].points(), clipped);
                }
            }
            sum += f;
            lo = std::min(lo, f);
            hi = std::max(hi, f);
        }
        return {sum / points, hi - lo};
    }

    // Two patches: the analytic integral from the smaller one's points (the larger's form
    // factor would be multiplied up by the ratio of their areas, its error with it).
    void link_patches(std::uint32_t a, std::uint32_t b, unsigned directions, Rng& rng,
                      ThreadWork& work) const {
        const bool from_a = geometry_[a].area <= geometry_[b].area;
        const auto p = tree_.leaf_order[tree_.nodes[from_a ? a : b].first];
        const auto q = tree_.leaf_order[tree_.nodes[from_a ? b : a].first];
        const auto& polygon = context_.polygons[p];
        const double area = context_.mesh.patches[p].area;
        const auto samples = ff::gauss_samples(polygon, area, nodes_, weights_);
        const auto close = ff::gauss_samples(polygon, area, close_nodes_, close_weights_);
        const double f =
            ff::analytic_pair_form_factor(context_, p, q, samples, close, 1, rng, work.stats.rays);
        if (f <= 0) return;
        work.stats.leaf_links += std::popcount(directions);
        add_links(a, b, from_a ? f : f * geometry_[b].area / geometry_[a].area, directions, {},
                  work);
    }

    // Each node's shares of the pair's transfer, from the traced sample pairs.
    PairShares shares(std::uint32_t a, std::uint32_t b, const PairEstimate& e,
                      const Traced& traced) const {
        const double visible = traced.facing > 0 ? traced.weighted : 1.0;
        return {hierarchy::link_shares(tree_, geometry_, a, b,
                                       {e.from_u, e.kernel, traced.seen, visible}),
                hierarchy::link_shares(tree_, geometry_, b, a,
                                       {e.to_u, e.kernel, traced.seen, visible})};
    }

    // Links in `directions`, reciprocal: A_a F_ab = A_b F_ba, part by part.
    void add_links(std::uint32_t a, std::uint32_t b, double factor_ab, unsigned directions,
                   const PairShares& shares, ThreadWork& work) const {
        if (!(factor_ab > 0)) return;
        const double factor_ba = factor_ab * geometry_[a].area / geometry_[b].area;
        if (directions & kIntoA)
            work.links.push_back({a, b, static_cast<float>(factor_ab), shares.a, shares.b});
        if (directions & kIntoB)
            work.links.push_back({b, a, static_cast<float>(factor_ba), shares.b, shares.a});
    }

    const FormFactorContext& context_;
    const radfmt::LinkData& tree_;
    NodeGeometries geometry_;
    hierarchy::DirectLight light_;
    HierarchyOptions options_;
    ShardWalk walk_;
    int samples_;
    std::vector<double> nodes_, weights_, close_nodes_, close_weights_;
    tbb::enumerable_thread_specific<ThreadWork> work_;
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
} // namespace

radfmt::LinkData compute_links(const radfmt::MeshData& mesh, const HierarchyOptions& options,
                               HierarchyStats* stats) {
    require_specular_support("hierarchical", false, mesh);
    HierarchyStats local;
    auto start = std::chrono::steady_clock::now();
    const auto surface = hierarchy::connected_surfaces(mesh); // for the tree and the refiner
    auto tree = hierarchy::build_surface_tree(mesh, surface);
    local.tree_seconds = seconds_since(start);
    if (!mesh.patches.empty()) {
        start = std::chrono::steady_clock::now();
        const RayScene scene(mesh);
        const FormFactorContext context(mesh, scene);
        LinkRefiner refiner(context, tree, surface, options);
        refiner.refine_within(0);
        refiner.collect(tree, local);
        local.link_seconds = seconds_since(start);
    }
    if (stats) *stats = local;
    return tree;
}

std::vector<std::pair<std::string, std::string>> link_header_fields(const HierarchyOptions& options,
                                                                    const radfmt::MeshData& mesh) {
    char epsilon[32];
    std::snprintf(epsilon, sizeof epsilon, "%.9g", options.epsilon);
    std::string emitters;
    for (const auto& name : emitter_names(mesh, emitter_materials(mesh, options)))
        emitters += (emitters.empty() ? "" : ",") + name;
    return {{"method", "hierarchical"},
            {"epsilon", epsilon},
            {"samples", std::to_string(options.samples)},
            {"seed", std::to_string(options.seed)},
            {"emitters", emitters}};
}

std::vector<std::string> emitters_not_refined_for(const radfmt::Header& links_header,
                                                  const radfmt::MeshData& mesh) {
    const auto* recorded = links_header.find("emitters");
    const std::string list = "," + (recorded ? *recorded : std::string()) + ",";
    std::vector<std::string> out;
    for (const auto& name : emitter_names(mesh, emitter_materials(mesh, HierarchyOptions{})))
        if (list.find("," + name + ",") == std::string::npos) out.push_back(name);
    return out;
}

} // namespace rad
