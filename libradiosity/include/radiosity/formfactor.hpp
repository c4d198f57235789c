// Form factors F_ij (equation 5 of the paper) for every pair of patches, three ways.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/vec.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rad {

enum class FormFactorMethod { Pairwise, Analytic, Hemisphere };
FormFactorMethod parse_method(const std::string& name);
std::string method_name(FormFactorMethod method);

struct FormFactorOptions {
    FormFactorMethod method = FormFactorMethod::Analytic;
    int samples = 16;        // points per patch (analytic, pairwise), rounded to a square;
                             // pairwise uses a quarter of the resolution for distant pairs
    int visibility_rays = 1; // analytic: rays per sample point towards the other patch
    int rays = 8192;         // hemisphere: rays per patch
    std::uint64_t seed = 1;
    bool quiet = false;
};

struct FormFactorStats {
    std::uint64_t rays_cast = 0;
    double seconds = 0;       // all of compute_form_factors
    double trace_seconds = 0; // the parallel row phase alone (rays and integrals)
    double mean_row_sum = 0;
    double max_row_sum = 0;
};

// Upper bound of the memory compute_form_factors needs for `mesh`, in bytes.
std::uint64_t estimate_form_factor_memory(const radfmt::MeshData& mesh,
                                          const FormFactorOptions& options);

// Rows are computed in parallel (TBB); each row draws its random numbers from (seed, row)
// alone, so the result is identical for any number of threads.
radfmt::FormFactorData compute_form_factors(const radfmt::MeshData& mesh,
                                            const FormFactorOptions& options,
                                            FormFactorStats* stats = nullptr);

// Exact form factor from a differential area at `point` with unit normal `normal` to a
// planar polygon (contour integral, Lambert/Sparrow); the polygon must lie in front of the
// point's tangent plane (clip it first) and face the point.
double point_to_polygon_form_factor(const Vec3& point, const Vec3& normal,
                                    std::span<const Vec3> polygon);

// Closed forms for tests and checks (Howell's catalogue, C-11 and C-14).
double parallel_rectangles_form_factor(double a, double b, double c);      // a x b, distance c
double perpendicular_rectangles_form_factor(double h, double l, double w); // common edge l

} // namespace rad
