// The room's summary for the report: its size and each material's area and reflectance.
#include "radiosity/report.hpp"

#include "radiosity/rays.hpp"

namespace rad {

RoomSummary room_summary(const radfmt::MeshData& mesh, double metres_per_unit) {
    RoomSummary room;
    const Box box = bounds(mesh.vertices);
    room.bounds = box;
    for (int k = 0; k < 3; ++k) room.size_m[k] = (box.hi[k] - box.lo[k]) * metres_per_unit;
    std::vector<double> area(mesh.materials.size(), 0);
    for (const auto& p : mesh.patches) area[p.material] += p.area;
    for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
        if (!(area[m] > 0)) continue;
        const auto& material = mesh.materials[m];
        room.materials.push_back({material.name, area[m] * metres_per_unit * metres_per_unit,
                                  luminous(material.reflectance), material.emits()});
    }
    return room;
}

} // namespace rad
