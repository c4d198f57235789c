// The luminaires kind (.lum): the sources it was made from as text, the light groups and the
// direct irradiance per patch and group.
#include "body_checks.hpp"
#include "kind_table.hpp"
#include "radfmt/kinds.hpp"

#include <cmath>
#include <cstdio>

namespace radfmt {
namespace fs = std::filesystem;

namespace {
// The header's light_groups field: the names, comma-separated.
std::string group_field(const std::vector<std::string>& groups) {
    std::string names;
    for (const auto& g : groups) names += (names.empty() ? "" : ",") + g;
    return names;
}
} // namespace

void write_luminaires(const fs::path& path, Header header, const LuminaireData& lum) {
    header.kind = Kind::Luminaires;
    if (lum.irradiance.size() != lum.patch_count * lum.groups.size())
        throw std::logic_error("luminaires written with an irradiance array of the wrong size");
    header.set("patches", std::to_string(lum.patch_count));
    header.set("light_groups", group_field(lum.groups));
    BodyWriter w;
    w.string(lum.layout_name);
    w.string(lum.layout_text);
    w.u64(lum.files.size());
    for (const auto& [name, text] : lum.files) {
        w.string(name);
        w.string(text);
    }
    w.u64(lum.groups.size());
    for (const auto& g : lum.groups) w.string(g);
    w.u64(lum.patch_count);
    w.array(lum.irradiance);
    write_file(path, std::move(header), w);
}

namespace {
// What a .lum embeds must be what its header records: its light groups, and the layout's and
// each photometric file's text, whose hashes the header keeps among its inputs. A file edited
// and given a new checksum passed before (an extra body group made 21,728 lm of 3,517 lm).
void check_against_header(const fs::path& path, const LuminaireData& lum, const Header& header) {
    const auto refuse = [&](const std::string& what) {
        throw FormatError(path.string() + ": " + what +
                          ": the file contradicts itself (edited?); make it again with rad-ff "
                          "--luminaires");
    };
    const auto names = group_field(lum.groups);
    if (const auto* recorded = header.find("light_groups"); recorded && *recorded != names)
        refuse("its light groups '" + names + "' are not the '" + *recorded +
               "' its header records");
    const auto text_hash = [](const std::string& text) {
        return "xxh64:" + hash_hex(hash_bytes(text.data(), text.size()));
    };
    const auto check_text = [&](const fs::path& source, const std::string& text) {
        for (const auto& input : header.inputs)
            if (fs::path(input.path).lexically_normal() == source.lexically_normal() &&
                input.hash != text_hash(text))
                refuse("the text of " + source.string() +
                       " it holds is not the one its header "
                       "records (" +
                       input.hash + ")");
    };
    check_text(lum.layout_name, lum.layout_text);
    const auto folder = fs::path(lum.layout_name).parent_path();
    for (const auto& [name, text] : lum.files) check_text(folder / name, text);
}
} // namespace

LuminaireData read_luminaires(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Luminaires;
    BodyReader r(path, &kind);
    LuminaireData lum;
    lum.layout_name = r.string();
    lum.layout_text = r.string();
    const auto files = r.count(16, "files");
    for (std::uint64_t k = 0; k < files; ++k) {
        auto name = r.string();
        lum.files.emplace_back(std::move(name), r.string());
    }
    const auto groups = r.count(8, "light groups");
    if (groups == 0) r.fail("no light group");
    lum.groups = detail::read_group_names(r, groups);
    lum.patch_count = r.count(24 * groups, "patches");
    lum.irradiance = r.array<Rgb>(lum.patch_count * groups, "irradiance");
    r.expect_end();
    detail::require_count(r.header(), "patches", lum.patch_count, r);
    for (std::size_t i = 0; i < lum.irradiance.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (!(lum.irradiance[i][c] >= 0 && std::isfinite(lum.irradiance[i][c])))
                r.fail("irradiance value " + std::to_string(i) + " is negative or not finite");
    check_against_header(path, lum, r.header());
    if (header_out) *header_out = r.take_header();
    return lum;
}

namespace detail {
void luminaires_csv(const fs::path& path, std::ostream& out) {
    const auto lum = read_luminaires(path);
    out << kind_info(Kind::Luminaires).csv_columns.substr(0, 22) << '\n';
    write_group_rows(out, lum.groups, lum.irradiance);
}

std::string luminaires_summary(const fs::path& path, Header& header) {
    const auto lum = read_luminaires(path, &header);
    std::string text = std::to_string(lum.patch_count) + " patches, " +
                       std::to_string(lum.groups.size()) + " light group(s):";
    for (const auto& g : lum.groups) text += " " + g;
    text += "; from " + lum.layout_name + " and";
    for (const auto& f : lum.files) text += " " + f.first;
    return text;
}
} // namespace detail

} // namespace radfmt
