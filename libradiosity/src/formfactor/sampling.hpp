// Quadrature and sampling on patches, shared by the form-factor methods (internal header).
#pragma once
#include "radiosity/formfactor_method.hpp"
#include "radiosity/vec.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

namespace rad::ff {

inline constexpr double kPi = std::numbers::pi;

// Gauss-Legendre nodes and weights on [0,1].
void gauss_legendre(int m, std::vector<double>& nodes, std::vector<double>& weights);

struct Sample {
    Vec3 point;
    double weight; // fraction of the patch's area this sample stands for; weights sum to 1
};

// A point of the patch for (s,t) in [0,1]^2 and the area the unit square maps to there:
// bilinear for quads, the collapsed (Duffy) square for triangles. Not for polygons: take
// their fan_triangles.
Vec3 patch_point(const PatchPolygon& g, double s, double t, double& jacobian);

// A polygon's fan from its corner 0 as triangles (a triangle or quad: the same split).
std::vector<PatchPolygon> fan_triangles(const PatchPolygon& g);

// Quadrature points (Gauss-Legendre product rule) for smooth integrands; on a polygon, the
// rule on each triangle of its fan (weights still summing to 1).
std::vector<Sample> gauss_samples(const PatchPolygon& g, double area,
                                  const std::vector<double>& nodes,
                                  const std::vector<double>& weights);

// The fan triangle (of a convex polygon) that u in [0,1) falls in by area; `remainder`, when
// asked for, is u rescaled to [0,1) within that triangle, so one number can serve twice.
// (Inline, as fan_triangle_point: the hierarchy's oracle draws tens of millions of points.)
inline std::size_t pick_fan_triangle(std::span<const double> fan_cdf, double u,
                                     double* remainder = nullptr) {
    std::size_t tri = 0;
    double lo = 0;
    while (tri + 1 < fan_cdf.size() && u > fan_cdf[tri]) lo = fan_cdf[tri++];
    if (remainder) *remainder = (u - lo) / std::max(1e-300, fan_cdf[tri] - lo);
    return tri;
}
// An area-uniform point of fan triangle `tri` (vertices 0, tri+1, tri+2) for u, v in [0,1).
inline Vec3 fan_triangle_point(std::span<const Vec3> poly, std::size_t tri, double u, double v) {
    const double r = std::sqrt(u);
    return poly[0] * (1 - r) + poly[tri + 1] * (r * (1 - v)) + poly[tri + 2] * (r * v);
}
// An area-uniform point on a convex polygon (fan of triangles).
Vec3 uniform_point(std::span<const Vec3> poly, std::span<const double> fan_cdf, double u0,
                   double u1, double u2);
std::vector<double> fan_cdf(std::span<const Vec3> poly);
// The same into `few` for a triangle or a quad (no allocation: a shadow ray's), else `many`.
std::span<const double> fan_cdf(std::span<const Vec3> poly, std::array<double, 2>& few,
                                std::vector<double>& many);

// F_ij by the analytic method's rule: at the quadrature `samples` of patch i (the
// `samples_close` when the patches are within twice their size), the exact form factor of j
// clipped to i's front, times the visible fraction from `visibility_rays` rays to points of
// j drawn from `rng`. 0 when either faces away from the other; adds the rays cast to `rays`.
double analytic_pair_form_factor(const FormFactorContext& context, std::size_t i, std::size_t j,
                                 std::span<const Sample> samples,
                                 std::span<const Sample> samples_close, int visibility_rays,
                                 Rng& rng, std::uint64_t& rays);

// Keeps the part of `poly` on the positive side of the plane (point, normal).
std::vector<Vec3> clip_to_front(std::span<const Vec3> poly, const Vec3& point, const Vec3& normal);
// The same into `out` (whose storage is reused); `out` must not be `poly`.
void clip_to_front(std::span<const Vec3> poly, const Vec3& point, const Vec3& normal,
                   std::vector<Vec3>& out);

// The patches a row has reached, as a two-level bitmap (a bit per patch, and a bit per word
// of those): marked in any order, read back in column order without a sort, and cleared as
// they are read, so a row costs its hits, not a pass over every patch.
class ColumnMarks {
  public:
    void resize(std::size_t patches) {
        if (words_.size() == (patches + 63) / 64) return;
        words_.assign((patches + 63) / 64, 0);
        summary_.assign((patches + 4095) / 4096, 0);
    }
    void mark(std::size_t j) {
        words_[j / 64] |= std::uint64_t(1) << (j % 64);
        summary_[j / 4096] |= std::uint64_t(1) << (j / 64 % 64);
    }
    // Calls visit(j) for every marked patch, ascending, and clears the marks.
    template <class Visit> void drain(Visit&& visit) {
        for (std::size_t s = 0; s < summary_.size(); ++s) {
            for (auto summary = summary_[s]; summary; summary &= summary - 1) {
                const std::size_t w = 64 * s + static_cast<std::size_t>(std::countr_zero(summary));
                for (auto bits = words_[w]; bits; bits &= bits - 1)
                    visit(64 * w + static_cast<std::size_t>(std::countr_zero(bits)));
                words_[w] = 0;
            }
            summary_[s] = 0;
        }
    }

  private:
    std::vector<std::uint64_t> words_, summary_;
};

// A row's sums by patch (zero between rows) and the patches reached: add in any order,
// drain in column order (each sum handed on and reset). Per thread, sized to the mesh.
template <class T> class RowTally {
  public:
    void resize(std::size_t patches) {
        if (sum_.size() != patches) sum_.assign(patches, T{});
        reached_.resize(patches);
    }
    void add(std::size_t j, T amount) {
        if (sum_[j] == T{}) reached_.mark(j);
        sum_[j] += amount;
    }
    // Calls visit(j, sum) for every patch reached, ascending, and resets it.
    template <class Visit> void drain(Visit&& visit) {
        reached_.drain([&](std::size_t j) {
            visit(j, sum_[j]);
            sum_[j] = T{};
        });
    }

  private:
    std::vector<T> sum_;
    ColumnMarks reached_;
};

// Radical inverse in base b: the Halton sequence.
double radical_inverse(std::uint64_t i, std::uint64_t base);

inline double wrap(double x) {
    return x - std::floor(x);
}

// Casts `rays` cosine-weighted rays from area-uniform points of patch i (their own random
// stream, so the form factors do not change) and records them in `log`.
void probe_back_faces(const FormFactorContext& context, std::size_t i, std::uint64_t seed, int rays,
                      RayLog& log);

// The threads compute_form_factors may use (TBB's allowed parallelism).
unsigned active_threads();

// Points per axis for `samples` points per patch (rounded to a square).
int points_per_axis(int samples);

} // namespace rad::ff
