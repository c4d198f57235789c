// The daylight kinds: the sky-view file (.sky, rad-ff --sky) and a year of illuminance at
// sensors (.ill, rad-gather --annual).
#include "body_checks.hpp"
#include "kind_table.hpp"
#include "radfmt/kinds.hpp"

#include <cmath>
#include <cstdio>

namespace radfmt {
namespace fs = std::filesystem;

namespace {
template <class T>
void require_finite_nonnegative(BodyReader& r, const std::vector<T>& values, const char* what) {
    for (std::size_t k = 0; k < values.size(); ++k)
        if (!(values[k] >= 0 && std::isfinite(values[k])))
            r.fail(std::string(what) + " value " + std::to_string(k) +
                   " is negative or not finite");
}
} // namespace

void write_sky(const fs::path& path, Header header, const SkyData& sky) {
    header.kind = Kind::Sky;
    if (sky.coefficients.size() != sky.patch_count * sky.sky_patches * 3)
        throw std::logic_error("sky written with a coefficient array of the wrong size");
    header.set("patches", std::to_string(sky.patch_count));
    header.set("sky_patches", std::to_string(sky.sky_patches));
    header.set("subdivision", sky.subdivision);
    char north[32];
    std::snprintf(north, sizeof north, "%.17g", sky.north_deg);
    header.set("north", north);
    BodyWriter w;
    w.string(sky.subdivision);
    w.u64(sky.sky_patches);
    w.u64(sky.patch_count);
    w.array(sky.coefficients);
    write_file(path, std::move(header), w);
}

SkyData read_sky(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Sky;
    BodyReader r(path, &kind);
    SkyData sky;
    sky.subdivision = r.string();
    sky.sky_patches = r.u64();
    if (sky.sky_patches < 2 || sky.sky_patches > (1u << 20))
        r.fail("a sky of " + std::to_string(sky.sky_patches) + " patches");
    sky.patch_count = r.count(12 * sky.sky_patches, "patches");
    sky.coefficients = r.array<float>(sky.patch_count * sky.sky_patches * 3, "coefficients");
    r.expect_end();
    detail::require_count(r.header(), "patches", sky.patch_count, r);
    detail::require_count(r.header(), "sky_patches", sky.sky_patches, r);
    if (r.header().get("subdivision", path.string()) != sky.subdivision)
        r.fail("the header's subdivision is not the body's");
    const auto& north = r.header().get("north", path.string());
    char* end = nullptr;
    sky.north_deg = std::strtod(north.c_str(), &end);
    if (end == north.c_str() || *end || !std::isfinite(sky.north_deg))
        r.fail("north '" + north + "' is not a number");
    // As rad-ff --north allows: a file that passes its checksum may still say 1e308.
    if (!(sky.north_deg >= -360 && sky.north_deg <= 360))
        r.fail("north " + north + " is outside -360 to 360 degrees, which rad-ff writes");
    require_finite_nonnegative(r, sky.coefficients, "coefficient");
    if (header_out) *header_out = r.take_header();
    return sky;
}

void write_annual(const fs::path& path, Header header, const AnnualData& year) {
    header.kind = Kind::Annual;
    const std::size_t n = year.sensors(), hours = year.hours.size();
    if (year.normals.size() != n || year.occupied.size() != hours || year.lux.size() != n * hours ||
        year.sun_lux.size() != n * hours)
        throw std::logic_error("annual illuminance written with arrays of the wrong sizes");
    header.set("sensors", std::to_string(n));
    header.set("hours", std::to_string(hours));
    BodyWriter w;
    w.u64(n);
    w.u64(hours);
    w.array(year.positions);
    w.array(year.normals);
    w.array(year.hours);
    w.array(year.occupied);
    w.array(year.lux);
    w.array(year.sun_lux);
    write_file(path, std::move(header), w);
}

AnnualData read_annual(const fs::path& path, Header* header_out) {
    const Kind kind = Kind::Annual;
    BodyReader r(path, &kind);
    AnnualData year;
    const auto n = r.count(48, "sensors");
    const auto hours = r.count(5, "hours");
    year.positions = r.array<Vec3>(n, "positions");
    year.normals = r.array<Vec3>(n, "normals");
    year.hours = r.array<std::uint32_t>(hours, "hours");
    year.occupied = r.array<std::uint8_t>(hours, "occupancy");
    year.lux = r.array<float>(n * hours, "illuminance");
    year.sun_lux = r.array<float>(n * hours, "sun illuminance");
    r.expect_end();
    detail::require_count(r.header(), "sensors", n, r);
    detail::require_count(r.header(), "hours", hours, r);
    for (std::size_t h = 0; h < hours; ++h) {
        const auto code = year.hours[h];
        const auto month = code / 10000, day = code / 100 % 100, hour = code % 100;
        if (month < 1 || month > 12 || day < 1 || day > 31 || hour < 1 || hour > 24 ||
            year.occupied[h] > 1)
            r.fail("hour " + std::to_string(h) + " is not a month, day and hour of a year");
    }
    require_finite_nonnegative(r, year.lux, "illuminance");
    require_finite_nonnegative(r, year.sun_lux, "sun illuminance");
    if (header_out) *header_out = r.take_header();
    return year;
}

namespace detail {
void sky_csv(const fs::path& path, std::ostream& out) {
    const auto sky = read_sky(path);
    out << "patch,sky_patch,d_r,d_g,d_b\n";
    char line[160];
    for (std::size_t i = 0; i < sky.patch_count; ++i) {
        for (std::size_t s = 0; s < sky.sky_patches; ++s) {
            const auto c = sky.of(i, s);
            if (c[0] == 0 && c[1] == 0 && c[2] == 0) continue;
            std::snprintf(line, sizeof line, "%zu,%zu,%.8g,%.8g,%.8g\n", i, s, c[0], c[1], c[2]);
            out << line;
        }
        if (!out) return;
    }
}

std::string sky_summary(const fs::path& path, Header& header) {
    const auto sky = read_sky(path, &header);
    std::size_t seeing = 0;
    for (std::size_t i = 0; i < sky.patch_count; ++i) {
        bool any = false;
        for (std::size_t k = 0; k < sky.sky_patches * 3 && !any; ++k)
            any = sky.coefficients[i * sky.sky_patches * 3 + k] > 0;
        seeing += any;
    }
    char north[32];
    std::snprintf(north, sizeof north, "%g", sky.north_deg);
    return std::to_string(sky.patch_count) + " patches, " + std::to_string(seeing) +
           " of them see the sky or the ground; " + sky.subdivision + " (" +
           std::to_string(sky.sky_patches) + " sky patches with the ground), north " + north +
           " deg";
}

void annual_csv(const fs::path& path, std::ostream& out) {
    const auto year = read_annual(path);
    out << "month,day,hour,occupied";
    for (std::size_t k = 0; k < year.sensors(); ++k) out << ",s" << k;
    out << '\n';
    char text[64];
    for (std::size_t h = 0; h < year.hours.size(); ++h) {
        const auto code = year.hours[h];
        std::snprintf(text, sizeof text, "%u,%u,%u,%u", code / 10000, code / 100 % 100, code % 100,
                      unsigned(year.occupied[h]));
        out << text;
        for (std::size_t k = 0; k < year.sensors(); ++k) {
            std::snprintf(text, sizeof text, ",%.6g", year.lux[h * year.sensors() + k]);
            out << text;
        }
        out << '\n';
        if (!out) return;
    }
}

std::string annual_summary(const fs::path& path, Header& header) {
    const auto year = read_annual(path, &header);
    std::size_t occupied = 0;
    for (auto o : year.occupied) occupied += o;
    return std::to_string(year.sensors()) + " sensors x " + std::to_string(year.hours.size()) +
           " hours (" + std::to_string(occupied) + " occupied) of illuminance in lux";
}
} // namespace detail

} // namespace radfmt
