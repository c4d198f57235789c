// An irradiance cache for gathered views (Ward, Rubinstein and Clear 1988): the indirect
// light is gathered with many rays at records spread over the view, and each sample between
// them takes a weighted mean of the records valid there instead of casting its own rays. The
// direct light stays per sample (sharp shadows). A record i is valid at x (normal n) while
// e_i = |x - x_i| / R_i + sqrt(1 - n . n_i) < a, R_i the harmonic mean distance of what its
// rays met (at most its light over its gradient's length, Krivanek et al. 2006; clamped to a
// pixel or two's footprint and to a share of the scene), and weighs 1 / e_i - 1 / a there,
// which falls to 0 at the edge of its validity (Tabellion and Lamorlette's smooth variant: no
// seams where records begin or end). Each record's light is extrapolated to x by its
// gradients (Ward and Heckbert 1992): near a corner or a shadow's edge, where the light
// changes fast, records a few pixels away agree instead of each pulling towards its own.
//
// Deterministic: the records sit at fixed pixels (every `spacing`-th, the image's own grid,
// the same for a whole image and for each --rows band) and each is computed from its own
// stream; a pixel's samples no record covers share a gather of their own.
#pragma once
#include "radiosity/vec.hpp"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace rad {

struct IrradianceCacheOptions {
    int spacing = 4;       // a record every `spacing` pixels, across and down
    int rays = 512;        // about this many indirect rays a record (a theta x phi grid)
    double accuracy = 0.2; // Ward's a: how far a record is reused
    // A record reaches at least this many pixels (its radius is at least that footprint over
    // the accuracy); nearer edges and corners (small harmonic distance) samples between records
    // no record reaches share a gather of their own, a pixel's.
    double min_reach_pixels = 0.5;
    // ... and at most this many (a record reaching far only slows every lookup it is in, and
    // its light is averaged over what it no longer sees).
    double max_reach_pixels = 32;
};

class IrradianceCache {
  public:
    struct Record {
        Vec3 position{0, 0, 0}, normal{0, 0, 0};
        Rgb indirect{0, 0, 0};
        double radius = 0;
        // Ward and Heckbert's gradients (IrradianceGradients): the record's light is
        // extrapolated to where it is used.
        std::array<Vec3, 3> translational{}, rotational{};
    };
    // `records`, each valid within accuracy x its radius; `cell` sizes the lookup grid.
    IrradianceCache(std::vector<Record> records, double accuracy);
    // The indirect light at `x` (shading normal `n`) interpolated from the records valid there;
    // false when none is.
    bool lookup(const Vec3& x, const Vec3& n, Rgb& out) const;
    std::size_t size() const { return records_.size(); }

  private:
    using Key = std::uint64_t;
    Key key(long i, long j, long k) const;
    long cell_of(double v) const;
    std::vector<Record> records_;
    double accuracy_, cell_ = 1;
    std::unordered_map<Key, std::vector<std::uint32_t>> grid_;
};

} // namespace rad
