#include "radiosity/solver.hpp"

#include "radiosity/cli.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace rad {
using radfmt::Rgb;

SolveMethod parse_solve_method(const std::string& name) {
    if (name == "jacobi") return SolveMethod::Jacobi;
    if (name == "gs") return SolveMethod::GaussSeidel;
    if (name == "pr") return SolveMethod::Progressive;
    if (name == "apr") return SolveMethod::ProgressiveAmbient;
    throw InputError("unknown solver '" + name + "' (use jacobi, gs, pr or apr)");
}

std::string solve_method_name(SolveMethod method) {
    switch (method) {
    case SolveMethod::Jacobi:
        return "jacobi";
    case SolveMethod::GaussSeidel:
        return "gs";
    case SolveMethod::Progressive:
        return "pr";
    case SolveMethod::ProgressiveAmbient:
        return "apr";
    }
    return "?";
}

Problem make_problem(const radfmt::MeshData& mesh, const radfmt::FormFactorData& ff) {
    Problem p;
    p.form_factors = &ff;
    for (const auto& patch : mesh.patches) {
        p.area.push_back(patch.area);
        p.reflectance.push_back(mesh.materials[patch.material].reflectance);
        p.emission.push_back(mesh.materials[patch.material].emission);
    }
    return p;
}

Rgb total_power(const std::vector<double>& area, const std::vector<Rgb>& b) {
    Rgb sum{0, 0, 0};
    for (std::size_t i = 0; i < b.size(); ++i)
        for (int c = 0; c < 3; ++c) sum[c] += b[i][c] * area[i];
    return sum;
}

namespace {

// One sweep; Gauss-Seidel reads the values updated earlier in the same sweep, Jacobi only
// the previous sweep's. Returns sum |B_new - B_old| and sum |B_new| over patches and channels.
std::pair<double, double> sweep(const Problem& p, std::vector<Rgb>& b, std::vector<Rgb>& scratch,
                                bool in_place) {
    const auto& ff = *p.form_factors;
    const std::size_t n = b.size();
    const std::vector<Rgb>& source = in_place ? b : scratch;
    if (!in_place) scratch = b;
    double change = 0, magnitude = 0;
    for (std::size_t i = 0; i < n; ++i) {
        double gathered[3] = {0, 0, 0};
        for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) {
            const Rgb& bj = source[ff.columns[k]];
            const double f = ff.values[k];
            gathered[0] += f * bj[0];
            gathered[1] += f * bj[1];
            gathered[2] += f * bj[2];
        }
        for (int c = 0; c < 3; ++c) {
            const double value = p.emission[i][c] + p.reflectance[i][c] * gathered[c];
            change += std::abs(value - b[i][c]);
            magnitude += std::abs(value);
            b[i][c] = value;
        }
    }
    return {change, magnitude};
}

} // namespace

SolveResult solve(const Problem& p, const SolveOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = p.area.size();
    SolveResult result;
    std::vector<Rgb> b = p.emission; // start from B = E
    auto elapsed = [&] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    auto keep_going = [&](long done, double residual) {
        if (options.max_iterations > 0 && done >= options.max_iterations) return false;
        if (options.tolerance > 0 && done > 0 && residual < options.tolerance) return false;
        return true;
    };

    if (options.method == SolveMethod::Jacobi || options.method == SolveMethod::GaussSeidel) {
        std::vector<Rgb> scratch;
        long done = 0;
        double residual = 1;
        while (keep_going(done, residual)) {
            const auto [change, magnitude] =
                sweep(p, b, scratch, options.method == SolveMethod::GaussSeidel);
            residual = magnitude > 0 ? change / magnitude : 0;
            ++done;
            if (options.on_iteration)
                options.on_iteration({done, residual, total_power(p.area, b), elapsed()}, b);
            if (magnitude == 0) break; // nothing emits: the black solution is exact
        }
        result.radiosity = std::move(b);
        result.iterations = done;
        result.residual = residual;
        result.converged = options.tolerance > 0 && residual < options.tolerance;
        return result;
    }

    // Progressive refinement (Cohen et al. 1988): shoot the unshot radiosity of the patch
    // with the most unshot power. Row i of F holds F_ij; reciprocity gives the shares
    // F_ji = F_ij A_i / A_j that the receivers j take.
    const auto& ff = *p.form_factors;
    std::vector<Rgb> unshot = p.emission;
    double emitted = 0, total_area = 0;
    Rgb mean_reflectance{0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        emitted += (p.emission[i][0] + p.emission[i][1] + p.emission[i][2]) * p.area[i];
        total_area += p.area[i];
        for (int c = 0; c < 3; ++c) mean_reflectance[c] += p.reflectance[i][c] * p.area[i];
    }
    for (auto& r : mean_reflectance) r = total_area > 0 ? r / total_area : 0;
    const bool ambient = options.method == SolveMethod::ProgressiveAmbient;

    auto unshot_fraction = [&](double unshot_power) {
        return emitted > 0 ? unshot_power / emitted : 0;
    };
    // APR's display adds rho_i times Cohen's ambient estimate: the unshot power spread over
    // the scene and multiplied by the interreflection factor 1 / (1 - mean rho).
    auto displayed = [&]() {
        if (!ambient) return b;
        Rgb unshot_mean{0, 0, 0};
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) unshot_mean[c] += unshot[i][c] * p.area[i] / total_area;
        std::vector<Rgb> shown = b;
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c)
                shown[i][c] += p.reflectance[i][c] * unshot_mean[c] /
                               (1 - std::min(mean_reflectance[c], 0.999999));
        return shown;
    };

    long done = 0;
    double residual = 1;
    while (keep_going(done, residual)) {
        std::size_t shooter = 0;
        double best = -1, unshot_power = 0;
        for (std::size_t i = 0; i < n; ++i) {
            const double power = (unshot[i][0] + unshot[i][1] + unshot[i][2]) * p.area[i];
            unshot_power += power;
            if (power > best) {
                best = power;
                shooter = i;
            }
        }
        if (best <= 0) {
            residual = 0;
            break;
        }
        const Rgb shot = unshot[shooter];
        unshot[shooter] = {0, 0, 0};
        unshot_power -= best;
        const double a_i = p.area[shooter];
        for (auto k = ff.row_start[shooter]; k < ff.row_start[shooter + 1]; ++k) {
            const auto j = ff.columns[k];
            const double f_ji = ff.values[k] * a_i / p.area[j];
            for (int c = 0; c < 3; ++c) {
                const double received = p.reflectance[j][c] * shot[c] * f_ji;
                b[j][c] += received;
                unshot[j][c] += received;
                unshot_power += received * p.area[j];
            }
        }
        residual = unshot_fraction(std::max(0.0, unshot_power));
        ++done;
        if (options.on_iteration) {
            const auto shown = displayed();
            options.on_iteration({done, residual, total_power(p.area, shown), elapsed()}, shown);
        }
    }
    result.radiosity = displayed();
    result.iterations = done;
    result.residual = residual;
    result.converged = options.tolerance > 0 && residual < options.tolerance;
    return result;
}

} // namespace rad
