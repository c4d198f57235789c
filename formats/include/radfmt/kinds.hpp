// The concrete file kinds of the chain: patch mesh, sparse form factors, radiosity.
#pragma once
#include "radfmt/container.hpp"

#include <array>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace radfmt {

// A point or direction in space, metres.
using Vec3 = std::array<double, 3>;

// A colour triple (reflectance, exitance in W/m^2): its own type, so that a colour cannot be
// passed where a position is expected or the other way round. Same bytes as double[3].
struct Rgb {
    std::array<double, 3> c{};
    double& operator[](std::size_t k) { return c[k]; }
    const double& operator[](std::size_t k) const { return c[k]; }
    double* begin() { return c.data(); }
    double* end() { return c.data() + 3; }
    const double* begin() const { return c.data(); }
    const double* end() const { return c.data() + 3; }
    bool operator==(const Rgb&) const = default;
};
static_assert(sizeof(Rgb) == 24 && std::is_trivially_copyable_v<Rgb>);
inline constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// The smooth specular part of a material (mirrors and glass): how light that meets it goes on
// without being scattered. Radiosity keeps the diffuse part (Material::reflectance); this
// part is geometry-like (it bends paths), so form factors depend on it.
enum class SpecularKind : std::uint32_t {
    none = 0,
    mirror = 1,     // reflects `reflectance` at every angle
    fresnel = 2,    // reflects `reflectance` at normal incidence, rising to 1 at grazing
    pane = 3,       // a thin sheet of glass of index `ior` (Radiance's glass): `transmittance`
                    // at normal incidence, without displacement, and its own reflection
    dielectric = 4, // the boundary of a medium of index `ior` behind its back: refracts
                    // (Fresnel), `transmittance` filtering what enters
};
inline constexpr std::uint32_t kSpecularKinds = 5;

struct Specular {
    SpecularKind kind = SpecularKind::none;
    Rgb reflectance{};    // mirror, fresnel: at normal incidence
    Rgb transmittance{};  // pane: at normal incidence; dielectric: the filter of what enters
    double ior = 1.5;     // pane, dielectric
    double roughness = 0; // as the scene gave it (0 smooth); treated as smooth
    bool any() const { return kind != SpecularKind::none; }
    // Reflects as a mirror (plain or Fresnel).
    bool mirrors() const { return kind == SpecularKind::mirror || kind == SpecularKind::fresnel; }
    // Lets light through (a thin pane or a refracting boundary).
    bool transmits() const {
        return kind == SpecularKind::pane || kind == SpecularKind::dielectric;
    }
    bool operator==(const Specular&) const = default;
};

struct Material {
    std::string name;
    Rgb reflectance{}; // rho, diffuse reflectance per channel
    Rgb emission{};    // E, emitted exitance in W/m^2
    Specular specular; // mirrors and glass (mesh version 3)
    bool emits() const { return emission[0] > 0 || emission[1] > 0 || emission[2] > 0; }
};

// "mirror", "fresnel", "pane", "dielectric" ("none").
const char* specular_kind_name(SpecularKind kind);

// Corner 3 of a polygon patch: its corners are listed in MeshData::polygon_corners.
inline constexpr std::uint32_t kPolygon = kNoVertex - 1;

// A patch is a planar triangle, convex quad or polygon over shared vertices; area, centroid
// and unit normal are stored so no consumer recomputes them. A triangle's corner 3 is
// kNoVertex. A polygon (of 4 or more corners: what the mesher makes of a speck and the
// neighbour it joins) is simple and star-shaped from its corner 0, so the fan of triangles
// {0, k, k + 1} covers it, each wound as the patch or flat; it holds {first, count,
// kNoVertex, kPolygon}, its corners being MeshData::polygon_corners[first, first + count):
// read them with MeshData::corners.
struct Patch {
    std::array<std::uint32_t, 4> corners{kNoVertex, kNoVertex, kNoVertex, kNoVertex};
    std::uint32_t group = 0;
    std::uint32_t material = 0;
    double area = 0;
    Vec3 centroid{};
    Vec3 normal{};
    bool is_polygon() const { return corners[3] == kPolygon; }
    int corner_count() const {
        return is_polygon() ? static_cast<int>(corners[1]) : corners[3] == kNoVertex ? 3 : 4;
    }
};

// A patch's corners in order (counter-clockwise seen from its normal's side): its own for a
// triangle or quad, a polygon's in `polygon_corners` (its mesh's).
inline std::span<const std::uint32_t>
patch_corners(const Patch& patch, std::span<const std::uint32_t> polygon_corners) {
    if (patch.is_polygon()) return polygon_corners.subspan(patch.corners[0], patch.corners[1]);
    return {patch.corners.data(), static_cast<std::size_t>(patch.corner_count())};
}

struct MeshData {
    std::vector<Vec3> vertices;
    std::vector<Patch> patches;
    std::vector<std::string> groups;
    std::vector<Material> materials;
    std::vector<std::uint32_t> polygon_corners; // the corners of the polygon patches

    // A patch's corners in order (patch_corners); the mutable one to renumber them.
    std::span<const std::uint32_t> corners(const Patch& patch) const {
        return patch_corners(patch, polygon_corners);
    }
    std::span<const std::uint32_t> corners(std::size_t patch) const {
        return corners(patches[patch]);
    }
    std::span<std::uint32_t> corners(Patch& patch) {
        const auto view = patch_corners(patch, polygon_corners);
        return {const_cast<std::uint32_t*>(view.data()), view.size()};
    }
    // Makes `patch` a polygon of `corners` (appended to polygon_corners), or a triangle or
    // quad when there are 3 or 4 of them and `as_polygon` is false.
    void set_corners(Patch& patch, std::span<const std::uint32_t> corners, bool as_polygon);
    std::size_t polygon_count() const;

    double total_area() const;
    // Hash of the geometry alone (vertices and patch corners) and, when any patch's material
    // is a mirror or glass, of each patch's specular part: form factors depend only on these,
    // so diffuse reflectances and emission can change without invalidating a cached
    // form-factor file (a mesh without specular parts keeps the hash it always had).
    std::string geometry_hash() const;
    bool has_specular() const; // some patch's material has a specular part
    // The materials with a specular part that some patch uses, ascending.
    std::vector<std::uint32_t> specular_materials() const;
};

// A hemisphere matrix's rows packed in memory (read with FormFactorLayout::compact): 3 bytes
// a non-zero instead of 8, fixed widths so that a row decodes without a chain of lengths.
// Per entry the step from the previous column (the first from -1) and the hit count; a step
// of 0xFFFF takes its column from far_column, a count of 0xFF its value from other_value
// (rare: a step past 65534, a count past 254 or a value that is no count).
struct CompactFormFactorRows {
    static constexpr std::uint16_t kFarStep = 0xFFFF;
    static constexpr std::uint8_t kOtherValue = 0xFF;
    std::vector<std::uint16_t> step;
    std::vector<std::uint8_t> count;
    std::vector<std::uint32_t> far_column;
    std::vector<float> other_value;
    std::vector<std::uint64_t> far_start, other_start; // per row, into the two lists (n + 1)
    std::uint64_t denominator = 0;                     // the method's rays
    std::vector<float> value_of_count;                 // count / denominator, for 0..254
};

// Compressed sparse rows: row i holds (column, F_ij) for its non-zero entries, columns
// ascending. Either plain (columns and values) or packed (`compact`, read with
// FormFactorLayout::compact); radfmt/packed_rows.hpp reads a row of either in order.
struct FormFactorData {
    std::uint64_t patch_count = 0;
    std::vector<std::uint64_t> row_start; // patch_count + 1 entries
    std::vector<std::uint32_t> columns;
    std::vector<float> values;
    CompactFormFactorRows compact;
    // Per row, the fraction of patch i's cosine-weighted rays that arrived at the back of a
    // surface (version 2 on; empty when read from a version 1 file): rows near 1 belong to
    // patches that probably face the wrong way.
    std::vector<float> back_fraction;
    // Per row, the standard error of the row as a vector (sqrt of the sum of its entries'
    // variances), estimated from independent batches of rays (rad-ff --error); empty when
    // the file has none (header field row_errors).
    std::vector<float> row_error;
    std::uint64_t nonzeros() const { return row_start.empty() ? 0 : row_start.back(); }
    bool is_compact() const { return !compact.far_start.empty(); }
    std::size_t row_size(std::uint64_t i) const { return row_start[i + 1] - row_start[i]; }
};

// How read_form_factors keeps the rows: as plain arrays (8 bytes a non-zero), or packed (3
// bytes) when the file is version 3 with hit counts (what rad-solve keeps in memory).
enum class FormFactorLayout { plain, compact };

// A link hierarchy (rad-ff --method hierarchical): a binary tree over the mesh's patches
// (its leaves) and the links between its nodes, the hierarchical form of F. A node gathers
// over its links, sum_l factor_l B(source_l), B of a node being the area-weighted mean of
// its patches; what a node gathers every patch under it receives.
struct LinkNode {
    std::uint32_t first = 0, count = 0; // its patches: leaf_order[first, first + count)
    std::uint32_t left = 0, right = 0;  // children (kNoNode for a leaf, a single patch)
    bool operator==(const LinkNode&) const = default;
};
inline constexpr std::uint32_t kNoNode = std::numeric_limits<std::uint32_t>::max();

// Where a link's light goes within its receiver and comes from within its source: the
// share of the pair's transfer through each of a node's parts two levels down (slots 0 and 1
// under its left child, 2 and 3 under its right; a child that is a single patch is slot 0 or
// 2 alone, a single patch slot 0), in 65535ths that sum to 65535. A link to a block then gives
// each quarter of it its own irradiance, and weights the source's quarters by how much each
// sends, where one number per link would spread the block's mean over all of it.
using LinkShares = std::array<std::uint16_t, 4>;
inline constexpr std::uint32_t kShareTotal = 65535;

struct LinkData {
    std::uint64_t patch_count = 0;
    std::vector<std::uint32_t> leaf_order; // the patches in tree order
    // In depth-first order: nodes[0] is the root, every node comes after its parent and a
    // left subtree before its right sibling.
    std::vector<LinkNode> nodes;
    std::vector<std::uint64_t> link_start;  // per node + 1: the links the node gathers over
    std::vector<std::uint32_t> source;      // the node the light comes from
    std::vector<float> factor;              // F: the node's mean form factor to the source
    std::vector<LinkShares> receiver_share; // per link: its light's share into each part
    std::vector<LinkShares> source_share;   // per link: each part's share of what it sends
    std::uint64_t links() const { return source.size(); }
    bool is_leaf(std::size_t node) const { return nodes[node].left == kNoNode; }
};

// The nodes of `node`'s share slots (see LinkShares), kNoNode where it has none.
std::array<std::uint32_t, 4> share_slots(const LinkData& links, std::size_t node);

void write_links(const std::filesystem::path& path, Header header, const LinkData& links);
LinkData read_links(const std::filesystem::path& path, Header* header_out = nullptr);

struct RadiosityData {
    std::vector<Rgb> radiosity; // B per patch, W/m^2 (every light group at its own emission)
    // Light groups (version 2 on, may be none): each group's own radiosity, as if only its
    // emitters shone, so that any mix of them is a weighted sum. Patch-major:
    // group_radiosity[i * groups + g] is patch i's radiosity from group g.
    std::vector<std::string> group_names = {};
    std::vector<Rgb> group_radiosity = {};
    std::size_t group_count() const { return group_names.size(); }
    const Rgb& of_group(std::size_t patch, std::size_t group) const {
        return group_radiosity[patch * group_names.size() + group];
    }
};

// Each writer fills in the kind-specific header fields (counts, hashes) itself.
void write_mesh(const std::filesystem::path& path, Header header, const MeshData& mesh);
MeshData read_mesh(const std::filesystem::path& path, Header* header_out = nullptr);

void write_form_factors(const std::filesystem::path& path, Header header, const FormFactorData& ff);
FormFactorData read_form_factors(const std::filesystem::path& path, Header* header_out = nullptr,
                                 FormFactorLayout layout = FormFactorLayout::plain);
// A shard of the matrix (rad-ff --rows): every row is present, only [rows_begin, rows_end)
// filled; the range is recorded in the header, checked on reading and returned.
void write_form_factor_part(const std::filesystem::path& path, Header header,
                            const FormFactorData& ff, std::uint64_t rows_begin,
                            std::uint64_t rows_end);
FormFactorData read_form_factor_part(const std::filesystem::path& path,
                                     Header* header_out = nullptr,
                                     std::uint64_t* rows_begin = nullptr,
                                     std::uint64_t* rows_end = nullptr);

// A form-factor matrix gathered row by row into the arrays of its file, without a second
// copy: columns and values go into chunks in memory while they fit in `memory_budget`
// bytes, and past it to two unnamed temporary files (in `spill_folder`, gone when the spool
// is, even after a crash), so a matrix larger than memory costs O(rows) of it. Row starts
// and back-face fractions stay in memory, 12 bytes a row. The file written from a spool is
// byte-identical to the one from a FormFactorData of the same rows. Rows are added in
// order, every row of the matrix (empty ones too).
class FormFactorSpool {
  public:
    // With `compact` (the hit denominator of formfactors_hit_denominator, 0 for floats), rows
    // are encoded as formfactors version 3 as they come: the spool then holds what the file
    // will (2-5 bytes a non-zero instead of 8), and can only be written as formfactors.
    static constexpr std::uint64_t kNoLimit = std::numeric_limits<std::uint64_t>::max();
    FormFactorSpool(std::uint64_t patch_count, const std::filesystem::path& spill_folder,
                    std::uint64_t memory_budget = kNoLimit,
                    std::optional<std::uint64_t> compact = std::nullopt);
    ~FormFactorSpool();
    FormFactorSpool(const FormFactorSpool&) = delete;
    FormFactorSpool& operator=(const FormFactorSpool&) = delete;

    void add_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                 float back_fraction);
    void add_row(std::span<const std::pair<std::uint32_t, float>> entries, float back_fraction);
    // Where to spill the rows of `output`: beside it (it will need the room anyway), or the
    // temporary folder when the output is a device or pipe.
    static std::filesystem::path folder_for(const std::filesystem::path& output);
    std::uint64_t patch_count() const { return patch_count_; }
    std::uint64_t rows() const { return row_start_.size() - 1; }
    std::uint64_t nonzeros() const { return row_start_.back(); }
    bool spilled() const { return columns_fd_ >= 0 || code_fd_ >= 0; }
    bool compact() const { return compact_.has_value(); }
    const std::vector<float>& back_fraction() const { return back_fraction_; }
    // Each row's standard error (FormFactorData::row_error), added after its row: for every
    // row or for none.
    void add_row_error(float error);
    const std::vector<float>& row_error() const { return row_error_; }
    // Lays out the body (rows must all be in; spilled entries are flushed first): the plain
    // arrays (a formfactor-part), or compact rows (formfactors version 3, hit counts over
    // `denominator` where they are exact; 0: floats). Compact, the entries are released as
    // they are encoded.
    void fill_body(BodyWriter& body);
    void fill_compact_body(BodyWriter& body, std::uint64_t denominator);

  private:
    void add_entry(std::uint32_t column, float value);
    void fill_row_errors(BodyWriter& body) const;
    void add_compact_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                         float back_fraction);
    void encode_code_row(std::span<const std::uint32_t> columns, std::span<const float> values);
    void store_code(std::size_t bytes);
    void reencode_rows(std::uint64_t denominator);
    void chunk_full();
    void spill();
    std::uint64_t patch_count_;
    std::filesystem::path folder_;
    std::uint64_t memory_budget_;
    std::vector<std::uint64_t> row_start_{0};
    std::vector<float> back_fraction_, row_error_;
    // In memory: every chunk; spilled: the one being filled.
    std::vector<std::vector<std::uint32_t>> column_chunks_;
    std::vector<std::vector<float>> value_chunks_;
    int columns_fd_ = -1, values_fd_ = -1;
    // Compact rows: their offsets and code (in memory, or in code_fd_ when spilled).
    std::optional<std::uint64_t> compact_;
    std::vector<std::uint64_t> row_offset_{0};
    std::vector<std::vector<std::uint8_t>> code_blocks_; // full blocks of 4 MiB, then the rest
    std::vector<std::uint8_t> code_;                     // rows not yet in a block
    std::uint64_t code_stored_ = 0;                      // bytes in blocks or in code_fd_
    std::vector<std::uint32_t> scratch_columns_;         // a row of pairs, split
    std::vector<float> scratch_values_;
    int code_fd_ = -1;
};
void write_form_factors(const std::filesystem::path& path, Header header, FormFactorSpool& ff);
// The denominator formfactors version 3 stores hit counts over: the rays of a hemisphere
// method's header (fields method and rays), else 0 (values stored as floats).
std::uint64_t formfactors_hit_denominator(const Header& header);
void write_form_factor_part(const std::filesystem::path& path, Header header, FormFactorSpool& ff,
                            std::uint64_t rows_begin, std::uint64_t rows_end);

// A luminaires file (rad-ff --luminaires, .lum): the layout and the photometric files it was
// made from (their text, by their paths relative to the layout's folder), the light groups,
// and per patch and group the mean direct irradiance (W/m^2, RGB) the luminaires give it.
struct LuminaireData {
    std::string layout_name, layout_text;
    std::vector<std::pair<std::string, std::string>> files;
    std::vector<std::string> groups;
    std::uint64_t patch_count = 0;
    std::vector<Rgb> irradiance; // patch-major: irradiance[i * groups + g]
    const Rgb& of(std::size_t patch, std::size_t group) const {
        return irradiance[patch * groups.size() + group];
    }
};
void write_luminaires(const std::filesystem::path& path, Header header, const LuminaireData& lum);
LuminaireData read_luminaires(const std::filesystem::path& path, Header* header_out = nullptr);

// A sky-view file (rad-ff --sky, .sky): the sky's subdivision and compass, and per patch and
// sky patch (the ground first) the irradiance on the patch's front from that sky patch at
// unit radiance, RGB (glass may tint it), as floats.
struct SkyData {
    std::string subdivision; // "reinhart:M"
    double north_deg = 0;    // true north is -Z turned this far towards +X
    std::uint64_t patch_count = 0;
    std::uint64_t sky_patches = 0;
    std::vector<float> coefficients; // [(i * sky_patches + s) * 3 + c]
    Rgb of(std::size_t patch, std::size_t sky) const {
        const float* c = &coefficients[(patch * sky_patches + sky) * 3];
        return {{c[0], c[1], c[2]}};
    }
};
void write_sky(const std::filesystem::path& path, Header header, const SkyData& sky);
SkyData read_sky(const std::filesystem::path& path, Header* header_out = nullptr);

// A year of illuminance at sensors (rad-gather --annual, .ill): the sensors, the hours (month,
// day, hour 1..24 and whether occupied), and per hour and sensor the illuminance and the
// part of it the sun's beam gives directly, lux, as floats.
struct AnnualData {
    std::vector<Vec3> positions, normals;
    std::vector<std::uint32_t> hours;   // month * 10000 + day * 100 + hour
    std::vector<std::uint8_t> occupied; // per hour, 0 or 1
    std::vector<float> lux, sun_lux;    // [hour * sensors + sensor]
    std::size_t sensors() const { return positions.size(); }
};
void write_annual(const std::filesystem::path& path, Header header, const AnnualData& year);
AnnualData read_annual(const std::filesystem::path& path, Header* header_out = nullptr);

void write_radiosity(const std::filesystem::path& path, Header header, const RadiosityData& rad);
RadiosityData read_radiosity(const std::filesystem::path& path, Header* header_out = nullptr);

// Decodes whichever kind `file` holds and writes it as CSV (columns in formats/README.md).
void write_csv(const std::filesystem::path& path, std::ostream& out);

// What the chain knows about each kind of file, as data: the container validates names and
// versions against it and rad-info prints through it. A new kind is one more row.
struct KindInfo {
    Kind kind;
    std::string_view name;
    std::string_view description;
    std::uint32_t version;        // the version written
    std::uint32_t oldest_version; // the oldest version still read
    std::string_view csv_columns;
    // Reads and validates the whole file, then writes its data as CSV.
    void (*write_csv)(const std::filesystem::path& path, std::ostream& out);
    // Reads and validates the whole file; returns a one-line summary and its header.
    std::string (*summary)(const std::filesystem::path& path, Header& header);
};
std::span<const KindInfo> kind_table();
const KindInfo& kind_info(Kind kind);

} // namespace radfmt
