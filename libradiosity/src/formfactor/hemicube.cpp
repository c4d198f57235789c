// hemicube: Cohen and Greenberg's hemi-cube (1985), the method the paper calls the most
// common in real applications, cast as rays: one ray through the centre of every pixel of
// a hemi-cube (a top face of R x R pixels, four half side faces of R x R/2) over patch i, and
// F_ij = the sum of the delta form factors of the pixels that see j first. A z-buffer with
// one sample at each pixel centre sees what these rays see, so this is the hemi-cube's
// answer without rasterising; Embree finds the nearest surface.
//
// The paper's hemi-cube stands at the patch centre and so gives the form factor from that
// point, which is not the patch's (two unit squares at distance 1: 0.2395 from the centre,
// 0.1998 from the whole square), and it aliases: a patch smaller than a pixel's solid angle
// is missed or counted a whole pixel. By default every pixel's ray leaves from its own point
// of the patch (a low-discrepancy set over its area), which averages both away;
// --hemicube-origin centre gives the paper's. The hemi-cube turns about the normal by a
// seeded angle per patch, so its pixel grid does not line up with the scene's.
#include "radiosity/error.hpp"
#include "sampling.hpp"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>

namespace rad::ff {
namespace {

struct Pixel {
    Vec3 direction; // unit, in the hemi-cube's frame (z along the normal)
    double weight;  // its delta form factor, normalised so that all sum to 1
    double s, t;    // its point of the patch, before the patch's rotation
};

// Delta form factors (Cohen and Greenberg): a pixel of area dA at (x, y, 1) on the top face
// sees dA / (pi (x^2 + y^2 + 1)^2); at (1, y, z) on a side, z dA / (pi (y^2 + z^2 + 1)^2).
// Their sum is 1 only in the limit; normalised, a closed room's rows sum to 1 exactly.
std::vector<Pixel> hemicube_pixels(int resolution) {
    std::vector<Pixel> pixels;
    const double step = 2.0 / resolution, area = step * step;
    auto add = [&](const Vec3& on_cube, double cosine_on_face) {
        const double r2 = dot(on_cube, on_cube);
        pixels.push_back(
            {on_cube * (1 / std::sqrt(r2)), cosine_on_face * area / (kPi * r2 * r2), 0, 0});
    };
    for (int a = 0; a < resolution; ++a)
        for (int b = 0; b < resolution; ++b)
            add({-1 + (a + 0.5) * step, -1 + (b + 0.5) * step, 1}, 1);
    for (int side = 0; side < 4; ++side)
        for (int a = 0; a < resolution; ++a)
            for (int b = 0; b < resolution / 2; ++b) {
                const double y = -1 + (a + 0.5) * step, z = (b + 0.5) * step;
                const Vec3 p = side == 0   ? Vec3{1, y, z}
                               : side == 1 ? Vec3{-1, -y, z}
                               : side == 2 ? Vec3{-y, 1, z}
                                           : Vec3{y, -1, z};
                add(p, z);
            }
    double total = 0;
    for (const auto& p : pixels) total += p.weight;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        pixels[k].weight /= total;
        pixels[k].s = radical_inverse(k + 1, 2);
        pixels[k].t = radical_inverse(k + 1, 3);
    }
    return pixels;
}

class HemicubeKernel final : public RowKernel {
  public:
    HemicubeKernel(const FormFactorContext& context, const FormFactorOptions& options)
        : context_(context), pixels_(hemicube_pixels(options.resolution)),
          at_centre_(options.hemicube_origin == "centre") {}

    std::uint64_t compute_row(std::size_t i, Rng& rng, FormFactorRow& row, RayLog&) const override {
        const auto& pi = context_.mesh.patches[i];
        const auto poly = context_.polygons[i].points();
        const auto cdf = fan_cdf(poly);
        const double turn = 2 * kPi * rng.uniform(), shift_s = rng.uniform(),
                     shift_t = rng.uniform();
        const Vec3 u0 = orthogonal(pi.normal), v0 = cross(pi.normal, u0);
        const Vec3 tu = u0 * std::cos(turn) + v0 * std::sin(turn), tv = cross(pi.normal, tu);
        auto& tally = tally_.local();
        tally.resize(context_.mesh.patches.size());
        for (const auto& pixel : pixels_) {
            Vec3 origin = pi.centroid;
            if (!at_centre_) {
                double within = 0;
                const auto tri = pick_fan_triangle(cdf, wrap(pixel.s + shift_s), &within);
                origin = fan_triangle_point(poly, tri, within, wrap(pixel.t + shift_t));
            }
            const Vec3 d = pixel.direction;
            const Vec3 direction = tu * d[0] + tv * d[1] + pi.normal * d[2];
            if (context_.specular.any()) {
                add_specular_pixel(i, origin, direction, pixel.weight, tally);
                continue;
            }
            const auto hit = context_.scene.trace(origin, direction);
            if (hit.patch >= 0 && hit.front && static_cast<std::size_t>(hit.patch) != i)
                tally.add(static_cast<std::size_t>(hit.patch), pixel.weight);
        }
        tally.drain([&](std::size_t j, double sum) {
            row.emplace_back(static_cast<std::uint32_t>(j), static_cast<float>(sum));
        });
        return pixels_.size();
    }

  private:
    // A pixel's ray through mirrors and glass: every surface its path reaches adds the
    // pixel's delta form factor times the path's weight (the channels' mean).
    void add_specular_pixel(std::size_t i, const Vec3& origin, const Vec3& direction, double delta,
                            RowTally<double>& tally) const {
        follow_specular(context_.scene, context_.specular, origin, direction,
                        radfmt::Rgb{{1, 1, 1}}, context_.specular_depth, [&](const PathHit& h) {
                            const auto j = static_cast<std::size_t>(h.hit.patch);
                            if (!h.hit.front || (j == i && h.events == 0)) return;
                            tally.add(j, delta * (h.weight[0] + h.weight[1] + h.weight[2]) / 3);
                        });
    }

    const FormFactorContext& context_;
    std::vector<Pixel> pixels_;
    bool at_centre_;
    mutable tbb::enumerable_thread_specific<RowTally<double>> tally_; // delta form factors
};

class Hemicube final : public FormFactorMethod {
  public:
    std::string_view name() const override { return "hemicube"; }
    std::string_view summary() const override {
        return "the paper's hemi-cube as rays through its pixel centres (--resolution), "
               "F_ij = delta form factors of the pixels that see j";
    }
    void apply_defaults(FormFactorOptions& options) const override {
        if (options.resolution == 0) options.resolution = kDefaultHemicubeResolution;
        if (options.resolution < 2 || options.resolution > kMaxHemicubeResolution ||
            options.resolution % 2)
            throw InputError("--resolution " + std::to_string(options.resolution) +
                             ": the hemi-cube's resolution is an even number from 2 to " +
                             std::to_string(kMaxHemicubeResolution) +
                             " (its side faces are half as high)");
        if (options.hemicube_origin != "spread" && options.hemicube_origin != "centre")
            throw InputError("--hemicube-origin " + options.hemicube_origin + ": spread or centre");
    }
    std::vector<std::pair<std::string, std::string>>
    header_fields(const FormFactorOptions& options) const override {
        return {{"resolution", std::to_string(options.resolution)},
                {"hemicube_origin", options.hemicube_origin}};
    }
    std::uint64_t max_row_entries(const radfmt::MeshData& mesh,
                                  const FormFactorOptions& options) const override {
        // A path through mirrors and glass reaches several surfaces.
        if (mesh.has_specular()) return mesh.patches.size();
        return std::min<std::uint64_t>(mesh.patches.size(), hemicube_rays(options.resolution));
    }
    bool follows_specular() const override { return true; }
    std::uint64_t working_memory(const radfmt::MeshData& mesh, const FormFactorOptions& options,
                                 unsigned threads) const override {
        // The pixel table, and per thread a sum per patch with its bitmaps.
        return hemicube_rays(options.resolution) * sizeof(Pixel) +
               std::uint64_t(threads) *
                   (mesh.patches.size() * sizeof(double) + mesh.patches.size() / 8 + 64);
    }
    std::unique_ptr<RowKernel> prepare(const FormFactorContext& context,
                                       const FormFactorOptions& options) const override {
        return std::make_unique<HemicubeKernel>(context, options);
    }
};

} // namespace

const FormFactorMethod& hemicube_method() {
    static const Hemicube method;
    return method;
}

} // namespace rad::ff
