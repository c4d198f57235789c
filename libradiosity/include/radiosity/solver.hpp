// Solving B_i = E_i + rho_i sum_j F_ij B_j per RGB channel from cached form factors.
#pragma once
#include "radfmt/kinds.hpp"

#include <functional>
#include <string>
#include <vector>

namespace rad {

enum class SolveMethod { Jacobi, GaussSeidel, Progressive, ProgressiveAmbient };
SolveMethod parse_solve_method(const std::string& name);
std::string solve_method_name(SolveMethod method);

struct Problem {
    std::vector<double> area;
    std::vector<radfmt::Rgb> reflectance;
    std::vector<radfmt::Rgb> emission;
    const radfmt::FormFactorData* form_factors = nullptr;
};

// The materials of the mesh, patch by patch, after solve-time overrides.
Problem make_problem(const radfmt::MeshData& mesh, const radfmt::FormFactorData& ff);

struct IterationRecord {
    long iteration = 0;  // sweeps for jacobi/gs, shots for pr/apr
    double residual = 0; // relative change per sweep (jacobi/gs), unshot power fraction (pr/apr)
    radfmt::Rgb power{}; // sum_i B_i A_i of the displayed solution, per channel
    double seconds = 0;
};

struct SolveOptions {
    SolveMethod method = SolveMethod::GaussSeidel;
    long max_iterations = 0; // 0: no limit besides the tolerance
    double tolerance = 0;    // 0: run max_iterations exactly
    // Called after every iteration with the displayed state (APR includes its ambient term).
    std::function<void(const IterationRecord&, const std::vector<radfmt::Rgb>&)> on_iteration;
};

struct SolveResult {
    std::vector<radfmt::Rgb> radiosity; // what to display: APR includes the ambient term
    long iterations = 0;
    double residual = 0;
    bool converged = false;
};

SolveResult solve(const Problem& problem, const SolveOptions& options);

// Power of a solution, per channel: sum_i B_i A_i.
radfmt::Rgb total_power(const std::vector<double>& area, const std::vector<radfmt::Rgb>& b);

} // namespace rad
