// What rad-solve decides before and after solving, as library code with unit tests:
// material overrides, reflectance checks, form-factor row-sum warnings, stopping rules, and
// what is recorded in the .rad header.
#pragma once
#include "radfmt/kinds.hpp"
#include "radiosity/material_overrides.hpp"
#include "radiosity/solver.hpp"

#include <string>
#include <vector>

namespace rad {

struct SolveRequest {
    std::string method = "gs";
    std::vector<std::string> emission_overrides;    // MATERIAL=r,g,b
    std::vector<std::string> reflectance_overrides; // MATERIAL=r,g,b
    double emission_scale = 1;
    long iterations = 0; // 0: the solver's default (or until the tolerance)
    double sweeps = 0;   // shooting solvers: sweeps-equivalent (x patches shots)
    double tolerance = 1e-6;
    bool tolerance_given = false; // with iterations and no tolerance, exactly N are run
    double row_sum_tolerance = 0.01;
    bool force = false; // solve even with a reflectance >= 1
};

// Applies the overrides and the emission scale to `mesh`'s materials and records each in
// `header` (override.emission.M, override.reflectance.M, override.emission_scale). An
// --emission NAME that no material has but a group has (an OBJ without materials lit by its
// `g` or `o` name) lights that group's patches: they get a copy of their material named NAME
// (NAME:MATERIAL when the group has several) that emits; `notes` says so. Throws InputError for
// names that are neither (listing both) and malformed values.
void apply_material_overrides(radfmt::MeshData& mesh, const SolveRequest& request,
                              radfmt::Header& header, std::vector<std::string>* notes = nullptr);

// Applies to `mesh` the overrides a radiosity file's header records (what rad-solve used),
// so that what reads the solution (rad-gather, rad-shade --gather) splits it into E and
// rho with the values it was solved with.
void apply_recorded_overrides(radfmt::MeshData& mesh, const radfmt::Header& solution_header);

// Throws InputError listing every material (used by a patch) with a reflectance channel >= 1
// at once, with the override that would fix each, unless `force`.
void check_reflectances(const radfmt::MeshData& mesh, bool force);

struct RowSumReport {
    std::size_t rows_above = 0; // rows summing above 1 + tolerance
    double largest = 0;
};
RowSumReport check_row_sums(const radfmt::FormFactorData& ff, double tolerance);
// The same through a link hierarchy: a patch's row is its node's links and its ancestors'.
RowSumReport check_row_sums(const radfmt::MeshData& mesh, const radfmt::LinkData& links,
                            double tolerance);

// Warnings a solve of `mesh` over `ff` deserves (no emitter, heavy rows), as message lines.
std::vector<std::string> solve_warnings(const radfmt::MeshData& mesh,
                                        const radfmt::FormFactorData& ff,
                                        const std::string& ff_path, double row_sum_tolerance);
// Over links: first a line per material that emits but was no emitter when `links_header`
// was computed (its light travels over coarser links); rows are checked against
// 1 + max(tolerance, kLinkRowSumSlack).
inline constexpr double kLinkRowSumSlack = 0.3;
std::vector<std::string> solve_warnings(const radfmt::MeshData& mesh, const radfmt::LinkData& links,
                                        const radfmt::Header& links_header,
                                        const std::string& ff_path, double row_sum_tolerance);

// The stopping rule for `request` on `patches` patches: --sweeps into shots, the solver's
// default iteration count, and the tolerance (off when iterations are set without one).
SolveControl stop_rule(const Solver& solver, const SolveRequest& request, std::size_t patches);

// Header fields of a solution: method and the hashes tying it to its inputs (after any
// override fields), then, once solved, iterations and the residual.
void record_solve_inputs(radfmt::Header& header, const SolveRequest& request,
                         const std::string& mesh_geometry_hash, const radfmt::Header& ff_header);
void record_solve_result(radfmt::Header& header, const Solver& solver, const SolveResult& result);

} // namespace rad
