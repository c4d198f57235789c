#include "radiosity/hierarchy.hpp"
#include "radiosity/solve_policy.hpp"

#include "radiosity/error.hpp"
#include "radiosity/materials.hpp"
#include "radiosity/numbers.hpp"

#include "radfmt/packed_rows.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace rad {

namespace {
radfmt::Material& find_material(radfmt::MeshData& mesh, const std::string& name) {
    for (auto& m : mesh.materials)
        if (m.name == name) return m;
    throw InputError("no material '" + name + "' in the mesh (it has: " + material_names(mesh) +
                     ")");
}

// --emission GROUP=r,g,b: the group's patches get, per material they have, a copy of it named
// GROUP (GROUP:MATERIAL when there are several) that emits `value`. False when no group has
// that name.
bool emit_group(radfmt::MeshData& mesh, const std::string& group, const radfmt::Rgb& value,
                std::vector<std::string>* notes) {
    const auto it = std::find(mesh.groups.begin(), mesh.groups.end(), group);
    if (it == mesh.groups.end()) return false;
    const auto g = static_cast<std::uint32_t>(it - mesh.groups.begin());
    std::map<std::uint32_t, std::uint32_t> copy_of; // material -> its emitting copy
    for (const auto& p : mesh.patches)
        if (p.group == g) copy_of[p.material] = 0;
    for (auto& [material, copy] : copy_of) {
        auto m = mesh.materials[material];
        m.name = copy_of.size() == 1 ? group : group + ":" + m.name;
        m.emission = value;
        copy = static_cast<std::uint32_t>(mesh.materials.size());
        mesh.materials.push_back(std::move(m));
    }
    std::size_t patches = 0;
    for (auto& p : mesh.patches)
        if (p.group == g) {
            p.material = copy_of[p.material];
            ++patches;
        }
    if (notes)
        notes->push_back("--emission " + group + ": no material has that name; group '" + group +
                         "' (" + std::to_string(patches) + " patches) emits " + rgb_text(value) +
                         " as material" +
                         (copy_of.size() == 1 ? " '" + group + "'" : "s '" + group + ":...'"));
    return true;
}
} // namespace

namespace {
// `value` rounded down to 3 significant digits, so that what a message calls usable is.
double down_to_3_digits(double value) {
    const double unit = std::pow(10.0, std::floor(std::log10(value)) - 2);
    double out = std::floor(value / unit) * unit;
    while (out > value) out = std::nextafter(out, 0.0);
    return out;
}

// Refuses a scale that takes a material past the emission limit (kMaxEmission), saying the
// largest scale that is accepted (and is, when given back).
void check_emission_scale(const radfmt::MeshData& mesh, double scale, const char* scale_text) {
    for (const auto& m : mesh.materials) {
        const double most = std::max({m.emission[0], m.emission[1], m.emission[2]});
        if (!(most > 0) || most * scale <= kMaxEmission) continue;
        char text[200];
        std::snprintf(text, sizeof text,
                      "' emit %.3g W/m^2, over the limit of %.0e: a scale of at most %.3g is "
                      "usable",
                      most * scale, kMaxEmission, down_to_3_digits(kMaxEmission / most));
        throw InputError(std::string("--emission-scale ") + scale_text + " makes material '" +
                         m.name + text);
    }
}
} // namespace

void apply_material_overrides(radfmt::MeshData& mesh, const SolveRequest& request,
                              radfmt::Header& header, std::vector<std::string>* notes) {
    for (const auto& spec : request.emission_overrides) {
        const auto o = parse_material_override(spec, "--emission");
        const bool material = std::any_of(mesh.materials.begin(), mesh.materials.end(),
                                          [&](const auto& m) { return m.name == o.material; });
        if (material) {
            find_material(mesh, o.material).emission = o.value;
        } else if (!emit_group(mesh, o.material, o.value, notes)) {
            std::string groups;
            for (const auto& g : mesh.groups) groups += (groups.empty() ? "" : ", ") + g;
            throw InputError("no material or group '" + o.material + "' in the mesh (materials: " +
                             material_names(mesh) + "; groups: " + groups + ")");
        }
        header.set("override.emission." + o.material, rgb_text(o.value));
    }
    for (const auto& spec : request.reflectance_overrides) {
        const auto o = parse_material_override(spec, "--reflectance");
        find_material(mesh, o.material).reflectance = o.value;
        header.set("override.reflectance." + o.material, rgb_text(o.value));
    }
    if (!(request.emission_scale >= 0) || !std::isfinite(request.emission_scale))
        throw InputError("--emission-scale must be finite and non-negative");
    if (request.emission_scale != 1) {
        char scale[32];
        std::snprintf(scale, sizeof scale, "%.9g", request.emission_scale);
        check_emission_scale(mesh, request.emission_scale, scale);
        for (auto& m : mesh.materials)
            for (auto& e : m.emission) e *= request.emission_scale;
        header.set("override.emission_scale", scale);
    }
    for (const auto& m : mesh.materials)
        check_emission_limit(m, "material '" + m.name + "'",
                             "give a smaller --emission or --emission-scale");
}

void apply_recorded_overrides(radfmt::MeshData& mesh, const radfmt::Header& solution_header) {
    SolveRequest request;
    const std::string emission = "override.emission.", reflectance = "override.reflectance.";
    for (const auto& [key, value] : solution_header.fields) {
        if (key.rfind(emission, 0) == 0)
            request.emission_overrides.push_back(key.substr(emission.size()) + "=" + value);
        else if (key.rfind(reflectance, 0) == 0)
            request.reflectance_overrides.push_back(key.substr(reflectance.size()) + "=" + value);
        else if (key == "override.emission_scale" && !parse_number(value, request.emission_scale))
            throw InputError("recorded emission scale '" + value + "' is not a number");
    }
    radfmt::Header ignored;
    apply_material_overrides(mesh, request, ignored);
}

void check_reflectances(const radfmt::MeshData& mesh, bool force) {
    if (force) return;
    std::string list;
    for (const auto& line : reflectance_problems(mesh)) list += "\n  " + line;
    if (!list.empty())
        throw InputError("a reflectance channel >= 1 may not converge (use --force to solve "
                         "anyway):" +
                         list);
}

RowSumReport check_row_sums(const radfmt::FormFactorData& ff, double tolerance) {
    RowSumReport report;
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        double sum = 0;
        radfmt::with_row_cursors(ff, i, [&](auto, auto values) {
            for (std::size_t k = 0; k < ff.row_size(i); ++k) sum += values.next();
        });
        if (sum > 1 + tolerance) ++report.rows_above;
        report.largest = std::max(report.largest, sum);
    }
    return report;
}

namespace {
std::vector<std::string> warnings_of(const radfmt::MeshData& mesh, const RowSumReport& rows,
                                     const std::string& ff_path, double row_sum_tolerance,
                                     const char* remedy) {
    std::vector<std::string> out;
    if (!any_emitter(mesh)) out.push_back("no patch emits light: the result is black");
    // Through mirrors and glass a surface is seen again (its image): rows add up past 1.
    if (rows.rows_above && !mesh.has_specular()) {
        std::ostringstream text;
        text << rows.rows_above << " form-factor row(s) of " << ff_path << " sum above 1 + "
             << row_sum_tolerance << " (largest " << rows.largest
             << "): the form factors are inaccurate; " << remedy;
        out.push_back(text.str());
    }
    return out;
}
} // namespace

RowSumReport check_row_sums(const radfmt::MeshData& mesh, const radfmt::LinkData& links,
                            double tolerance) {
    RowSumReport report;
    for (const double sum : link_row_sums(mesh, links)) {
        if (sum > 1 + tolerance) ++report.rows_above;
        report.largest = std::max(report.largest, sum);
    }
    return report;
}

std::vector<std::string> solve_warnings(const radfmt::MeshData& mesh,
                                        const radfmt::FormFactorData& ff,
                                        const std::string& ff_path, double row_sum_tolerance) {
    return warnings_of(mesh, check_row_sums(ff, row_sum_tolerance), ff_path, row_sum_tolerance,
                       "use more samples or rays");
}

std::vector<std::string> solve_warnings(const radfmt::MeshData& mesh, const radfmt::LinkData& links,
                                        const radfmt::Header& links_header,
                                        const std::string& ff_path, double row_sum_tolerance) {
    std::vector<std::string> out;
    for (const auto& name : emitters_not_refined_for(links_header, mesh))
        out.push_back("material '" + name + "' emits, but " + ff_path +
                      " was refined for the emitters of its mesh, not for it: its direct light "
                      "arrives over coarser links (rad-ff --method hierarchical --emitters " +
                      name + " refines for it)");
    // A patch's row through links is its quarter's share of each block above it, not its
    // own: a patch beside a wall, which fills half its view, gets its own links to the wall
    // and its blocks' links beside them (up to 1.34 on the living room fixture at the default
    // epsilon, its solution within 1.2% rms of analytic). A broken file shows far beyond.
    const double tolerance = std::max(row_sum_tolerance, kLinkRowSumSlack);
    for (auto& line : warnings_of(mesh, check_row_sums(mesh, links, tolerance), ff_path, tolerance,
                                  "use more --samples or a smaller --epsilon"))
        out.push_back(std::move(line));
    return out;
}

SolveControl stop_rule(const Solver& solver, const SolveRequest& request, std::size_t patches) {
    SolveControl control;
    long iterations = request.iterations;
    if (request.sweeps > 0) {
        if (!solver.shooting())
            throw InputError("--sweeps applies to shooting solvers (pr, apr); use --iterations "
                             "for " +
                             std::string(solver.name()));
        iterations = static_cast<long>(std::ceil(request.sweeps * double(patches)));
    }
    // Rounding keeps the change of a sweep above 0 forever: a zero tolerance alone would
    // only stop at the solver's safety cap, after hours on a large scene.
    if (request.tolerance_given && !(request.tolerance > 0) && iterations == 0)
        throw InputError("--tolerance 0 is never reached; give a tolerance in (0, 1] (e.g. "
                         "1e-6), or bound the run with --iterations N or --sweeps S");
    control.max_iterations = iterations;
    control.tolerance = (iterations > 0 && !request.tolerance_given) ? 0 : request.tolerance;
    if (control.max_iterations == 0)
        control.max_iterations = solver.default_max_iterations(patches);
    return control;
}

void record_solve_inputs(radfmt::Header& header, const SolveRequest& request,
                         const std::string& mesh_geometry_hash, const radfmt::Header& ff_header) {
    header.set("method", request.method);
    header.set("mesh_geometry_hash", mesh_geometry_hash);
    header.set("form_factor_hash", ff_header.body_hash);
}

void record_solve_result(radfmt::Header& header, const Solver& solver, const SolveResult& result) {
    header.set("iterations", std::to_string(result.iterations));
    char residual[32];
    std::snprintf(residual, sizeof residual, "%.6g", result.residual);
    header.set(std::string(solver.residual_name()), residual);
}

} // namespace rad
