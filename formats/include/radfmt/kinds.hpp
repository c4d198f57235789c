// The concrete file kinds of the chain: patch mesh, sparse form factors, radiosity.
#pragma once
#include "radfmt/container.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace radfmt {

using Vec3 = std::array<double, 3>;
using Rgb = std::array<double, 3>;
inline constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

struct Material {
    std::string name;
    Rgb reflectance{}; // rho, diffuse reflectance per channel
    Rgb emission{};    // E, emitted exitance in W/m^2
};

// A patch is a planar triangle or quad over shared vertices (corner 3 is kNoVertex for
// triangles); area, centroid and unit normal are stored so no consumer recomputes them.
struct Patch {
    std::array<std::uint32_t, 4> corners{kNoVertex, kNoVertex, kNoVertex, kNoVertex};
    std::uint32_t group = 0;
    std::uint32_t material = 0;
    double area = 0;
    Vec3 centroid{};
    Vec3 normal{};
    int corner_count() const { return corners[3] == kNoVertex ? 3 : 4; }
};

struct MeshData {
    std::vector<Vec3> vertices;
    std::vector<Patch> patches;
    std::vector<std::string> groups;
    std::vector<Material> materials;

    double total_area() const;
    // Hash of the geometry alone (vertices and patch corners): form factors depend only on
    // it, so materials can change without invalidating a cached form-factor file.
    std::string geometry_hash() const;
};

// Compressed sparse rows: row i holds (column, F_ij) for its non-zero entries, columns
// ascending.
struct FormFactorData {
    std::uint64_t patch_count = 0;
    std::vector<std::uint64_t> row_start; // patch_count + 1 entries
    std::vector<std::uint32_t> columns;
    std::vector<float> values;
    std::uint64_t nonzeros() const { return columns.size(); }
};

struct RadiosityData {
    std::vector<Rgb> radiosity; // B per patch, W/m^2
};

// Each writer fills in the kind-specific header fields (counts, hashes) itself.
void write_mesh(const std::filesystem::path& path, Header header, const MeshData& mesh);
MeshData read_mesh(const std::filesystem::path& path, Header* header_out = nullptr);

void write_form_factors(const std::filesystem::path& path, Header header, const FormFactorData& ff);
FormFactorData read_form_factors(const std::filesystem::path& path, Header* header_out = nullptr);

void write_radiosity(const std::filesystem::path& path, Header header, const RadiosityData& rad);
RadiosityData read_radiosity(const std::filesystem::path& path, Header* header_out = nullptr);

// Decodes whichever kind `file` holds and writes it as CSV (columns in formats/README.md).
void write_csv(const std::filesystem::path& path, std::ostream& out);

} // namespace radfmt
