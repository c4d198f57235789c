// The two-sided pass: back patches for the surfaces named by --two-sided.
#include "radiosity/build_mesh.hpp"
#include "radiosity/error.hpp"
#include "radiosity/two_sided.hpp"

namespace rad {

void two_sided_pass(radfmt::MeshData& mesh, const MeshOptions& options, MeshReport& report) {
    if (options.two_sided.empty()) return;
    const auto sides = make_two_sided(mesh, options.two_sided, options.two_sided_emission);
    report.add(MeshReport::Kind::Note,
               "--two-sided added " + std::to_string(sides.back_patches) + " back patch(es)");
    for (const auto& name : sides.unlit_back_materials)
        report.add(MeshReport::Kind::Note, "the back of emitting material " + name +
                                               " does not emit (material " + name +
                                               ".back; --two-sided-emission to change)");
}

} // namespace rad
