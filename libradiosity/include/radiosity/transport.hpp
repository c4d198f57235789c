// The transport operator that solvers work against, separate from how form factors are
// stored: rows of F, patch areas and reflectances. Right-hand sides and solutions have any
// number of channels (3 for RGB; light groups stack 3 per group).
#pragma once
#include "radfmt/kinds.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace rad {

// Values per patch and channel, patch-major: value(i, c) = values[i * channels + c].
struct Channels {
    std::size_t channels = 0;
    std::vector<double> values;

    Channels() = default;
    Channels(std::size_t patches, std::size_t channel_count)
        : channels(channel_count), values(patches * channel_count, 0.0) {}
    std::size_t patches() const { return channels ? values.size() / channels : 0; }
    double* row(std::size_t i) { return values.data() + i * channels; }
    const double* row(std::size_t i) const { return values.data() + i * channels; }
    double& at(std::size_t i, std::size_t c) { return values[i * channels + c]; }
    double at(std::size_t i, std::size_t c) const { return values[i * channels + c]; }
};

// RGB per patch <-> 3-channel values.
Channels to_channels(std::span<const radfmt::Rgb> rgb);
std::vector<radfmt::Rgb> to_rgb(const Channels& values, std::size_t first_channel = 0);

// F as a link hierarchy (rad-ff --method hierarchical), with what a sweep over it needs per
// node: its parent and area.
struct LinkTransport {
    const radfmt::LinkData* links = nullptr;
    std::vector<std::uint32_t> parent;               // per node; the root's is kNoNode
    std::vector<double> area;                        // per node: its patches' area
    std::vector<std::array<std::uint32_t, 4>> slots; // per node: radfmt::share_slots
};

// B = E + diag(rho) F B, F given as rows (form_factors) or as links (hierarchy). Channel c of a
// right-hand side reflects with colour c % colours.
struct TransportOperator {
    const radfmt::FormFactorData* form_factors = nullptr;
    std::shared_ptr<const LinkTransport> hierarchy;
    std::vector<double> area;        // per patch
    std::size_t colours = 3;         // reflectance channels per patch
    std::vector<double> reflectance; // patch-major, `colours` per patch

    std::size_t patch_count() const { return area.size(); }
    double rho(std::size_t i, std::size_t channel) const {
        return reflectance[i * colours + channel % colours];
    }
};

// The operator of a mesh (materials as they are in `mesh`) over its form factors.
TransportOperator make_operator(const radfmt::MeshData& mesh, const radfmt::FormFactorData& ff);
// The same over a link hierarchy: the sweep solvers (gs, jacobi) gather over its links.
TransportOperator make_operator(const radfmt::MeshData& mesh, const radfmt::LinkData& links);
// The emission of every patch, RGB.
Channels emission_of(const radfmt::MeshData& mesh);

// Power of a solution, per channel: sum_i B_i A_i.
std::vector<double> total_power(std::span<const double> area, const Channels& b);

} // namespace rad
