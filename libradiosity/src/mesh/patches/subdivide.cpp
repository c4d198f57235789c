#include "mesh/patches/subdivide_parts.hpp"
#include "radiosity/error.hpp"
#include "radiosity/scene.hpp"
#include "radiosity/twins.hpp"
#include "radiosity/vec.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Utils/vector_cast.hh>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <unordered_map>

namespace rad {

namespace {

// The elements' patches: one each with no limits, else over the agreed edge counts.
radfmt::MeshData patches_of(const std::vector<subdivision::Element>& elements, const Scene& scene,
                            const SubdivisionOptions& options) {
    radfmt::MeshData mesh;
    if (subdivision::without_limits(options)) {
        subdivision::check_estimate(elements, scene, options);
        mesh = subdivision::make_whole_patches(elements, scene);
    } else {
        auto counts = subdivision::agree_edge_counts(elements, scene, options);
        mesh = subdivision::make_patches(elements, counts, scene);
    }
    if (mesh.patches.size() >= radfmt::kNoVertex)
        throw InputError(scene.path + ": too many patches for 32-bit indices");
    return mesh;
}

} // namespace

radfmt::MeshData subdivide(const Scene& scene, const SubdivisionOptions& options,
                           SubdivisionReport* report) {
    SubdivisionReport local;
    const auto elements = subdivision::make_elements(scene, options, report ? *report : local);
    return patches_of(elements, scene, options);
}

radfmt::MeshData clean_faces(Scene& scene, const SubdivisionOptions& options,
                             SubdivisionReport* report) {
    SubdivisionOptions whole = options;
    whole.max_edge = whole.max_area = 0;
    whole.max_edge_by_group.clear();
    whole.max_area_by_group.clear();
    SubdivisionReport local;
    const auto elements = subdivision::make_elements(scene, whole, report ? *report : local);
    std::vector<Polygon>().swap(scene.polygons); // the elements hold what is left of them
    auto mesh = patches_of(elements, scene, whole);
    std::vector<Vec3>().swap(scene.vertices);
    return mesh;
}

Topology analyze_topology(const radfmt::MeshData& mesh) {
    using OMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
    OMesh om;
    std::vector<OMesh::VertexHandle> handles;
    handles.reserve(mesh.vertices.size());
    for (const auto& v : mesh.vertices)
        handles.push_back(om.add_vertex(OMesh::Point(v[0], v[1], v[2])));
    Topology topo;
    omerr().disable(); // OpenMesh reports each non-manifold face; we count them instead
    // The back of a two-sided surface repeats its front's corners: one side is the surface.
    const auto twins = find_twins(mesh);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        if (twins[i] >= 0 && static_cast<std::size_t>(twins[i]) < i) continue;
        std::vector<OMesh::VertexHandle> face;
        for (const auto v : mesh.corners(i)) face.push_back(handles[v]);
        if (!om.add_face(face).is_valid()) ++topo.rejected_patches;
    }
    omerr().enable();
    for (auto e : om.edges()) {
        ++topo.edges;
        if (om.is_boundary(e)) ++topo.boundary_edges;
    }
    return topo;
}

} // namespace rad
