#include "radiosity/transport.hpp"

#include "radiosity/hierarchy.hpp"

namespace rad {

Channels to_channels(std::span<const radfmt::Rgb> rgb) {
    Channels out(rgb.size(), 3);
    for (std::size_t i = 0; i < rgb.size(); ++i)
        for (int c = 0; c < 3; ++c) out.at(i, c) = rgb[i][c];
    return out;
}

std::vector<radfmt::Rgb> to_rgb(const Channels& values, std::size_t first_channel) {
    std::vector<radfmt::Rgb> out(values.patches());
    for (std::size_t i = 0; i < out.size(); ++i)
        for (int c = 0; c < 3; ++c) out[i][c] = values.at(i, first_channel + c);
    return out;
}

namespace {
// The patches' areas and reflectances, without F.
TransportOperator patch_operator(const radfmt::MeshData& mesh) {
    TransportOperator op;
    op.colours = 3;
    op.area.reserve(mesh.patches.size());
    op.reflectance.reserve(3 * mesh.patches.size());
    for (const auto& patch : mesh.patches) {
        op.area.push_back(patch.area);
        for (double rho : mesh.materials[patch.material].reflectance) op.reflectance.push_back(rho);
    }
    return op;
}
} // namespace

TransportOperator make_operator(const radfmt::MeshData& mesh, const radfmt::FormFactorData& ff) {
    auto op = patch_operator(mesh);
    op.form_factors = &ff;
    return op;
}

TransportOperator make_operator(const radfmt::MeshData& mesh, const radfmt::LinkData& links) {
    auto op = patch_operator(mesh);
    auto hierarchy = std::make_shared<LinkTransport>();
    hierarchy->links = &links;
    hierarchy->parent.assign(links.nodes.size(), radfmt::kNoNode);
    for (std::size_t i = 0; i < links.nodes.size(); ++i) {
        const auto& n = links.nodes[i];
        if (n.left != radfmt::kNoNode)
            hierarchy->parent[n.left] = hierarchy->parent[n.right] = static_cast<std::uint32_t>(i);
    }
    hierarchy->area = link_node_areas(mesh, links);
    hierarchy->slots.reserve(links.nodes.size());
    for (std::size_t i = 0; i < links.nodes.size(); ++i)
        hierarchy->slots.push_back(radfmt::share_slots(links, i));
    op.hierarchy = std::move(hierarchy);
    return op;
}

Channels emission_of(const radfmt::MeshData& mesh) {
    Channels e(mesh.patches.size(), 3);
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
        for (int c = 0; c < 3; ++c)
            e.at(i, c) = mesh.materials[mesh.patches[i].material].emission[c];
    return e;
}

std::vector<double> total_power(std::span<const double> area, const Channels& b) {
    std::vector<double> sum(b.channels, 0.0);
    const std::size_t n = b.patches();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < b.channels; ++c) sum[c] += b.at(i, c) * area[i];
    return sum;
}

} // namespace rad
