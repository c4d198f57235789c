// Round trips of every file kind and rejection of damaged files.
#include "helpers.hpp"
#include "radfmt/chain.hpp"
#include "radfmt/packed_rows.hpp"

#include <catch2/catch.hpp>
#include <cstring>

#include <functional>
#include <limits>
#include <unistd.h>

using namespace testing_helpers;
using Catch::Matchers::Contains;

namespace {
radfmt::Header header_for(const std::string& tool) {
    radfmt::Header h;
    h.tool = tool + " test";
    h.command = tool + " in.x -o 'out file'";
    h.provenance = {"rad-mesh a.obj -o a.mesh"};
    h.inputs = {{"in.x", "xxh64:0123456789abcdef"}};
    return h;
}

// rad-ff's header for hemisphere form factors at `rays` (its values are hit counts).
radfmt::Header hemisphere_header(int rays) {
    auto header = header_for("rad-ff");
    header.set("method", "hemisphere");
    header.set("rays", std::to_string(rays));
    return header;
}

// Row i's entries, read as rad-solve's sweep reads them (packed or plain).
std::vector<std::pair<std::uint32_t, float>> row_entries(const radfmt::FormFactorData& ff,
                                                         std::uint64_t i) {
    std::vector<std::pair<std::uint32_t, float>> entries;
    radfmt::with_row_cursors(ff, i, [&](auto columns, auto values) {
        for (std::size_t k = 0; k < ff.row_size(i); ++k)
            entries.emplace_back(columns.next(), values.next());
    });
    return entries;
}

radfmt::MeshData small_mesh() {
    radfmt::MeshData m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    radfmt::Patch q;
    q.corners = {0, 1, 2, 3};
    q.area = 1;
    q.centroid = {0.5, 0.5, 0};
    q.normal = {0, 0, 1};
    radfmt::Patch t;
    t.corners = {0, 1, 2, radfmt::kNoVertex};
    t.group = 1;
    t.material = 1;
    t.area = 0.5;
    t.centroid = {2.0 / 3, 1.0 / 3, 0};
    t.normal = {0, 0, 1};
    m.patches = {q, t};
    m.groups = {"floor", "wall"};
    m.materials = {{"grey", {0.5, 0.5, 0.5}, {0, 0, 0}, {}},
                   {"lamp", {0.1, 0.2, 0.3}, {10, 20, 30}, {}}};
    return m;
}

std::string read_all(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}
} // namespace

TEST_CASE("mesh files round-trip with header and provenance") {
    const auto dir = temp_dir("formats");
    const auto path = dir / "a.mesh";
    const auto mesh = small_mesh();
    radfmt::write_mesh(path, header_for("rad-mesh"), mesh);
    radfmt::Header h;
    const auto back = radfmt::read_mesh(path, &h);
    REQUIRE(back.vertices == mesh.vertices);
    REQUIRE(back.patches.size() == 2);
    CHECK(back.patches[1].corner_count() == 3);
    CHECK(back.patches[1].material == 1);
    CHECK(back.materials[1].emission == radfmt::Rgb{10, 20, 30});
    CHECK(back.groups == mesh.groups);
    CHECK(h.command == "rad-mesh in.x -o 'out file'");
    CHECK(h.provenance == std::vector<std::string>{"rad-mesh a.obj -o a.mesh"});
    CHECK(h.get("patches", "") == "2");
    CHECK(h.get("geometry_hash", "") == mesh.geometry_hash());
    CHECK(h.file_hash == radfmt::hash_file(path)); // hashed while read, same as a re-read
    // The body starts 64-byte aligned.
    const auto text = read_all(path);
    const auto body_at = text.size() - h.body_size;
    CHECK(body_at % 64 == 0);
}

namespace {
// small_mesh with an L-shaped hexagon (star-shaped from its corner 0, not convex) as patch 2.
radfmt::MeshData mesh_with_polygon() {
    auto m = small_mesh();
    add_polygon_patch(m, {{0, 0, 5}, {2, 0, 5}, {2, 1, 5}, {1, 1, 5}, {1, 2, 5}, {0, 2, 5}}, 3,
                      {5.0 / 6, 5.0 / 6, 5}, {0, 0, 1});
    return m;
}
} // namespace

TEST_CASE("polygon patches: version 2 round-trips them, a mesh without is version 1 as before") {
    const auto dir = temp_dir("polygons");
    const auto mesh = mesh_with_polygon();
    radfmt::write_mesh(dir / "p.mesh", header_for("rad-mesh"), mesh);
    radfmt::Header h;
    const auto back = radfmt::read_mesh(dir / "p.mesh", &h);
    CHECK(h.version == 2);
    CHECK(h.get("polygons", "") == "1");
    REQUIRE(back.patches.size() == 3);
    CHECK(back.patches[2].is_polygon());
    CHECK(back.patches[2].corner_count() == 6);
    const auto corners = back.corners(2);
    CHECK(std::vector<std::uint32_t>(corners.begin(), corners.end()) ==
          std::vector<std::uint32_t>{4, 5, 6, 7, 8, 9});
    CHECK(back.corners(0).size() == 4);
    CHECK(back.corners(1).size() == 3);
    CHECK(back.geometry_hash() == mesh.geometry_hash());
    CHECK(h.get("geometry_hash", "") == mesh.geometry_hash());
    // The hash sees the polygon's corners: the same slots over other corners differ.
    auto moved = mesh;
    std::swap(moved.polygon_corners[1], moved.polygon_corners[5]);
    CHECK(moved.geometry_hash() != mesh.geometry_hash());
    // rad-info's line counts it.
    radfmt::Header ignored;
    CHECK_THAT(radfmt::kind_info(radfmt::Kind::Mesh).summary(dir / "p.mesh", ignored),
               Contains("3 patches (1 quads, 1 polygons, 1 triangles)"));

    // Without polygons: version 1 and the body of before (no polygon array), so the files and
    // form-factor caches of every mesh made before stay valid byte for byte.
    radfmt::write_mesh(dir / "q.mesh", header_for("rad-mesh"), small_mesh());
    radfmt::Header h1;
    radfmt::read_mesh(dir / "q.mesh", &h1);
    CHECK(h1.version == 1);
    CHECK(h1.find("polygons") == nullptr);
    CHECK(h1.body_size ==
          8 + 4 * 24 + 8 + 2 * (16 + 4 + 4 + 8 + 24 + 24) + 8 + 2 * 16 + 8 + 2 * (16 + 48));
}

TEST_CASE("polygon patches that consumers could not split are refused") {
    const auto dir = temp_dir("polygons");
    auto error = [&](const std::function<void(radfmt::MeshData&)>& spoil) {
        auto mesh = mesh_with_polygon();
        spoil(mesh);
        radfmt::write_mesh(dir / "bad.mesh", header_for("rad-mesh"), mesh);
        try {
            radfmt::read_mesh(dir / "bad.mesh");
        } catch (const radfmt::FormatError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error([](auto&) {}) == "no error");
    // Listed from (1, 2), a neighbour of the reflex corner, its fan overlaps itself.
    CHECK_THAT(error([](auto& m) {
                   std::rotate(m.polygon_corners.begin(), m.polygon_corners.begin() + 4,
                               m.polygon_corners.end());
               }),
               Contains("bad.mesh") && Contains("polygon patch 2 is not star-shaped") &&
                   Contains("wound backwards"));
    CHECK_THAT(error([](auto& m) { m.patches[2].corners[1] = 7; }),
               Contains("patch 2 is a polygon of corners 0 to 7 of 6"));
    CHECK_THAT(error([](auto& m) { m.patches[2].corners[1] = 3; }),
               Contains("a polygon has 4 corners or more"));
    CHECK_THAT(error([](auto& m) { m.polygon_corners[2] = 99; }),
               Contains("polygon corner 2 refers to vertex 99 of 10"));
    // A polygon whose corners are all one point (#55).
    CHECK_THAT(error([](auto& m) {
                   const auto first = m.polygon_corners[0];
                   for (auto& c : m.polygon_corners) c = first;
               }),
               Contains("patch 2 stores an area of") && Contains("its corners enclose 0"));
}

namespace {
// A 3 x 3 form-factor matrix with an empty middle row.
radfmt::FormFactorData three_rows() {
    radfmt::FormFactorData ff;
    ff.patch_count = 3;
    ff.row_start = {0, 2, 2, 3};
    ff.columns = {1, 2, 0};
    ff.values = {0.25f, 0.5f, 0.125f};
    ff.back_fraction = {0.0f, 0.75f, 0.5f};
    return ff;
}
} // namespace

TEST_CASE("form-factor and radiosity files round-trip") {
    const auto dir = temp_dir("formats");
    const auto ff = three_rows();
    radfmt::write_form_factors(dir / "a.ff", header_for("rad-ff"), ff);
    const auto ff2 = radfmt::read_form_factors(dir / "a.ff");
    CHECK(ff2.row_start == ff.row_start);
    CHECK(ff2.columns == ff.columns);
    CHECK(ff2.values == ff.values);
    CHECK(ff2.back_fraction == ff.back_fraction);
    radfmt::Header summary_header;
    CHECK_THAT(radfmt::kind_info(radfmt::Kind::FormFactors).summary(dir / "a.ff", summary_header),
               Contains("mean 41.67%, max 75.00%, 1 row(s) above 50%"));

    // Version 1 files (no back-face fractions) are still read.
    {
        radfmt::BodyWriter w;
        w.u64(ff.patch_count);
        w.u64(ff.nonzeros());
        w.array(ff.row_start);
        w.array(ff.columns);
        w.array(ff.values);
        auto header = header_for("rad-ff");
        header.kind = radfmt::Kind::FormFactors;
        header.version = 1;
        header.set("patches", "3");
        radfmt::write_file(dir / "v1.ff", header, w);
        const auto old = radfmt::read_form_factors(dir / "v1.ff");
        CHECK(old.values == ff.values);
        CHECK(old.back_fraction.empty());
        CHECK_THAT(
            radfmt::kind_info(radfmt::Kind::FormFactors).summary(dir / "v1.ff", summary_header),
            Contains("no back-face data"));
    }
    // A fraction outside [0, 1] is refused.
    {
        auto bad = ff;
        bad.back_fraction[1] = std::numeric_limits<float>::quiet_NaN();
        radfmt::write_form_factors(dir / "bad.ff", header_for("rad-ff"), bad);
        REQUIRE_THROWS_WITH(radfmt::read_form_factors(dir / "bad.ff"),
                            Contains("bad.ff") && Contains("back-face fraction of row 1"));
    }

    radfmt::RadiosityData rad{{{1, 2, 3}, {0.5, 0.25, 0.125}}};
    radfmt::write_radiosity(dir / "a.rad", header_for("rad-solve"), rad);
    CHECK(radfmt::read_radiosity(dir / "a.rad").radiosity == rad.radiosity);
    CHECK(radfmt::read_radiosity(dir / "a.rad").group_count() == 0);

    // With light groups: names, per-group values and their sum, and a CSV row per group.
    radfmt::RadiosityData grouped;
    grouped.radiosity = {{{3, 3, 3}}, {{1, 0, 0}}};
    grouped.group_names = {"lamp", "sun"};
    grouped.group_radiosity = {{{1, 1, 1}}, {{2, 2, 2}}, {{1, 0, 0}}, {{0, 0, 0}}};
    radfmt::Header grouped_header;
    radfmt::write_radiosity(dir / "g.rad", header_for("rad-solve"), grouped);
    const auto back = radfmt::read_radiosity(dir / "g.rad", &grouped_header);
    CHECK(back.group_names == grouped.group_names);
    CHECK(back.group_radiosity == grouped.group_radiosity);
    CHECK(back.of_group(0, 1) == radfmt::Rgb{{2, 2, 2}});
    CHECK(grouped_header.get("light_groups", "") == "lamp,sun");
    std::ostringstream grouped_csv;
    radfmt::write_csv(dir / "g.rad", grouped_csv);
    CHECK(grouped_csv.str() == "patch,group,b_r,b_g,b_b\n0,lamp,1,1,1\n0,sun,2,2,2\n"
                               "1,lamp,1,0,0\n1,sun,0,0,0\n");
    radfmt::Header info;
    CHECK_THAT(radfmt::kind_info(radfmt::Kind::Radiosity).summary(dir / "g.rad", info),
               Contains("2 light group(s): lamp sun"));
    // A version 1 radiosity file (no group section) is still read.
    {
        radfmt::BodyWriter w;
        w.u64(rad.radiosity.size());
        w.array(rad.radiosity);
        auto header = header_for("rad-solve");
        header.kind = radfmt::Kind::Radiosity;
        header.version = 1;
        radfmt::write_file(dir / "v1.rad", header, w);
        const auto old = radfmt::read_radiosity(dir / "v1.rad");
        CHECK(old.radiosity == rad.radiosity);
        CHECK(old.group_count() == 0);
    }

    std::ostringstream csv;
    radfmt::write_csv(dir / "a.ff", csv);
    CHECK(csv.str() == "row,col,f\n0,1,0.25\n0,2,0.5\n2,0,0.125\n");
    std::ostringstream csv2;
    radfmt::write_csv(dir / "a.rad", csv2);
    CHECK(csv2.str() == "patch,b_r,b_g,b_b\n0,1,2,3\n1,0.5,0.25,0.125\n");
}

TEST_CASE("a spooled form-factor file is byte-identical to one written from memory") {
    const auto dir = temp_dir("formats");
    // Enough entries (3.3M) to pass through the spool's 1M-entry buffers several times, with
    // empty rows at the start, between and at the end.
    radfmt::FormFactorData ff;
    ff.patch_count = 5000;
    ff.row_start = {0};
    std::uint32_t state = 12345;
    // In memory, and spilled to disk past a budget of 8 MiB (one chunk).
    radfmt::FormFactorSpool spool(ff.patch_count, dir);
    radfmt::FormFactorSpool spilled(ff.patch_count, dir, std::uint64_t(8) << 20);
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        const std::size_t length = (i < 3 || i % 97 == 0 || i + 2 >= ff.patch_count) ? 0 : 700;
        std::vector<std::uint32_t> columns;
        std::vector<float> values;
        for (std::size_t k = 0; k < length; ++k) {
            state = state * 1664525u + 1013904223u;
            columns.push_back(static_cast<std::uint32_t>(k * 7));
            values.push_back(float(state >> 8) / float(1 << 24) * 1e-3f);
        }
        const float back = float(i % 10) / 10;
        ff.columns.insert(ff.columns.end(), columns.begin(), columns.end());
        ff.values.insert(ff.values.end(), values.begin(), values.end());
        ff.row_start.push_back(ff.columns.size());
        ff.back_fraction.push_back(back);
        if (i % 2) {
            spool.add_row(columns, values, back);
            spilled.add_row(columns, values, back);
        } else { // the other overload, as rad-ff uses it
            std::vector<std::pair<std::uint32_t, float>> entries;
            for (std::size_t k = 0; k < length; ++k) entries.emplace_back(columns[k], values[k]);
            spool.add_row(entries, back);
            spilled.add_row(entries, back);
        }
    }
    REQUIRE(spool.nonzeros() > 3 * (std::size_t(1) << 20));
    radfmt::write_form_factors(dir / "memory.ff", header_for("rad-ff"), ff);
    radfmt::write_form_factors(dir / "spool.ff", header_for("rad-ff"), spool);
    radfmt::write_form_factors(dir / "spilled.ff", header_for("rad-ff"), spilled);
    CHECK_FALSE(spool.spilled());
    CHECK(spilled.spilled());
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "spool.ff"));
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "spilled.ff"));
    const auto back = radfmt::read_form_factors(dir / "spool.ff");
    CHECK(back.values == ff.values);
    // The spilled files are unnamed: nothing is left in the folder but the outputs.
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 3);
    CHECK(radfmt::FormFactorSpool::folder_for("/dev/null") == fs::temp_directory_path());
    CHECK(radfmt::FormFactorSpool::folder_for("x.ff") == fs::path("."));
}

TEST_CASE("rows' standard errors are written, read and spooled alike, and only when given") {
    const auto dir = temp_dir("formats");
    auto ff = three_rows();
    ff.row_error = {0.0125f, 0, 0.03f};
    radfmt::FormFactorSpool spool(ff.patch_count, dir);
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        const auto b = ff.row_start[i], n = ff.row_start[i + 1] - b;
        spool.add_row(std::span(ff.columns).subspan(b, n), std::span(ff.values).subspan(b, n),
                      ff.back_fraction[i]);
        spool.add_row_error(ff.row_error[i]);
    }
    radfmt::write_form_factors(dir / "memory.ff", header_for("rad-ff"), ff);
    radfmt::write_form_factors(dir / "spool.ff", header_for("rad-ff"), spool);
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "spool.ff"));
    radfmt::Header header;
    const auto back = radfmt::read_form_factors(dir / "spool.ff", &header);
    CHECK(back.row_error == ff.row_error);
    REQUIRE(header.find("row_errors"));
    // A header carried over from a file with errors does not promise them for one without.
    auto plain = ff;
    plain.row_error.clear();
    radfmt::write_form_factors(dir / "plain.ff", header, plain);
    radfmt::Header plain_header;
    CHECK(radfmt::read_form_factors(dir / "plain.ff", &plain_header).row_error.empty());
    CHECK_FALSE(plain_header.find("row_errors"));
    // An error for no row, or one short, is the caller's bug.
    radfmt::FormFactorSpool short_spool(2, dir);
    CHECK_THROWS(short_spool.add_row_error(0.1f));
    ff.row_error.pop_back();
    CHECK_THROWS(radfmt::write_form_factors(dir / "short.ff", header_for("rad-ff"), ff));
}

TEST_CASE("damaged files are refused with a clear message") {
    const auto dir = temp_dir("formats");
    const auto good = dir / "good.mesh";
    radfmt::write_mesh(good, header_for("rad-mesh"), small_mesh());
    const auto bytes = read_all(good);
    const auto bad = dir / "bad.mesh";
    auto expect_error = [&](const std::string& content, const std::string& fragment) {
        write_text(bad, content);
        CAPTURE(fragment);
        REQUIRE_THROWS_WITH(radfmt::read_mesh(bad), Contains(bad.string()) && Contains(fragment));
    };
    SECTION("truncated at several offsets") {
        for (std::size_t cut : {std::size_t(0), std::size_t(10), bytes.find("\n\n"),
                                bytes.size() / 2, bytes.size() - 1})
            expect_error(bytes.substr(0, cut), cut == 0 ? "empty" : "truncated");
    }
    SECTION("a flipped byte in the header") {
        auto copy = bytes;
        copy[copy.find("command=") + 10] ^= 0x20;
        expect_error(copy, "checksum mismatch");
    }
    SECTION("a flipped byte in the body") {
        auto copy = bytes;
        copy[copy.size() - 20] ^= 0x01;
        expect_error(copy, "corrupt body");
    }
    SECTION("a damaged count is reported as damage, not as a wrong value") {
        // The body is read in one pass and its checksum checked at the end: a count made
        // huge by the damage must still give the checksum mismatch.
        auto copy = bytes;
        const auto body = (copy.find("\n\n") + 2 + 63) / 64 * 64;
        copy[body + 7] = char(0x7f); // the vertex count's top byte
        expect_error(copy, "checksum mismatch");
    }
    SECTION("wrong magic") {
        expect_error("P6\n" + bytes.substr(3), "wrong magic");
    }
    SECTION("wrong kind version") {
        auto copy = bytes;
        const auto at = copy.find("version=1\n");
        copy.replace(at, 10, "version=9\n");
        // Re-sign the header so only the version is wrong.
        const auto end = copy.find("header_hash=");
        const auto hash = "xxh64:" + radfmt::hash_hex(radfmt::hash_bytes(copy.data(), end));
        copy.replace(end + 12, hash.size(), hash);
        expect_error(copy, "version 9 is not supported");
    }
    SECTION("trailing garbage") {
        expect_error(bytes + "xx", "unexpected bytes");
    }
    SECTION("wrong kind") {
        radfmt::write_radiosity(bad, header_for("rad-solve"), {{{1, 1, 1}}});
        REQUIRE_THROWS_WITH(radfmt::read_mesh(bad),
                            Contains("radiosity solution") && Contains("patch mesh"));
    }
}

TEST_CASE("writes are atomic: a failed write leaves no file") {
    const auto dir = temp_dir("formats");
    const auto path = dir / "out.rad";
    REQUIRE_THROWS(radfmt::write_atomically(path, [](const fs::path& temp) {
        write_text(temp, "partial");
        throw std::runtime_error("interrupted");
    }));
    CHECK_FALSE(fs::exists(path));
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 0);
    REQUIRE_THROWS_WITH(radfmt::write_radiosity(dir / "missing" / "x.rad", {}, {}),
                        Contains("does not exist"));
}

TEST_CASE("derived headers record every parent and the longest history") {
    radfmt::Header mesh;
    mesh.command = "rad-mesh a.obj -o a.mesh";
    mesh.file_hash = "xxh64:1111111111111111";
    radfmt::Header ff;
    ff.command = "rad-ff a.mesh -o a.ff";
    ff.provenance = {mesh.command};
    ff.file_hash = "xxh64:2222222222222222";
    const radfmt::Parent parents[] = {{"a.mesh", &mesh}, {"a.ff", &ff}};
    const auto h = radfmt::derived_header("rad-solve 9", "rad-solve a.mesh a.ff -o a.rad", parents);
    CHECK(h.tool == "rad-solve 9");
    CHECK(h.provenance == std::vector<std::string>{mesh.command, ff.command});
    REQUIRE(h.inputs.size() == 2);
    CHECK(h.inputs[0].path == "a.mesh");
    CHECK(h.inputs[0].hash == mesh.file_hash);
    CHECK(h.inputs[1].hash == ff.file_hash);
    const char* argv[] = {"/usr/bin/rad-ff", "in.mesh", "--threads", "8", "-q", "-o", "my file"};
    CHECK(radfmt::command_line(7, argv) == "rad-ff in.mesh -o 'my file'");
}

TEST_CASE("a file made for other geometry is refused as stale, naming both files") {
    const auto mesh = small_mesh();
    radfmt::Header h;
    h.set("mesh_geometry_hash", mesh.geometry_hash());
    CHECK(radfmt::require_same_geometry("a.ff", h, 2, "a.mesh", mesh, "run rad-ff") ==
          mesh.geometry_hash());
    CHECK_THROWS_WITH(radfmt::require_same_geometry("a.ff", h, 3, "a.mesh", mesh, "run rad-ff"),
                      Contains("a.ff is stale: it does not belong to a.mesh") &&
                          Contains("run rad-ff"));
    h.set("mesh_geometry_hash", "xxh64:0000000000000000");
    CHECK_THROWS_AS(radfmt::require_same_geometry("a.ff", h, 2, "a.mesh", mesh, "x"),
                    radfmt::FormatError);
}

TEST_CASE("the kind table names every kind once, with its CSV columns") {
    std::vector<std::string> names;
    for (const auto& k : radfmt::kind_table()) {
        names.emplace_back(k.name);
        CHECK(radfmt::kind_info(k.kind).name == k.name);
        CHECK_FALSE(k.csv_columns.empty());
    }
    CHECK(names == std::vector<std::string>{"mesh", "formfactors", "formfactor-part", "radiosity",
                                            "links", "luminaires", "sky", "annual"});
}

TEST_CASE("checksum-valid files with nonsense values are refused by the readers") {
    const auto dir = temp_dir("hostile");
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto mesh_error = [&](const std::function<void(radfmt::MeshData&)>& spoil) {
        auto mesh = small_mesh();
        spoil(mesh);
        radfmt::write_mesh(dir / "h.mesh", header_for("rad-mesh"), mesh);
        try {
            radfmt::read_mesh(dir / "h.mesh");
        } catch (const radfmt::FormatError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK_THAT(mesh_error([&](auto& m) { m.vertices[1][2] = nan; }),
               Contains("h.mesh") && Contains("vertex 1 is not a finite point"));
    CHECK_THAT(mesh_error([&](auto& m) { m.patches[1].area = 0; }),
               Contains("patch 1 has a non-positive area"));
    CHECK_THAT(mesh_error([&](auto& m) {
                   m.patches[0].normal = {0, 0, 2};
               }),
               Contains("patch 0") && Contains("unit length"));
    CHECK_THAT(mesh_error([&](auto& m) { m.materials[1].emission[0] = -1; }),
               Contains("material 'lamp' has a negative or non-finite"));
    CHECK_THAT(mesh_error([&](auto& m) { m.materials[0].reflectance[2] = nan; }),
               Contains("material 'grey'"));
    // A stored area far from what the corners enclose (#55): a million times, or a patch whose
    // corners are one point.
    CHECK_THAT(mesh_error([&](auto& m) { m.patches[1].area *= 1e6; }),
               Contains("patch 1 stores an area of") && Contains("but its corners enclose"));
    CHECK_THAT(mesh_error([&](auto& m) {
                   for (auto& c : m.patches[0].corners)
                       if (c != radfmt::kNoVertex) c = m.patches[0].corners[0];
               }),
               Contains("patch 0 stores an area of") && Contains("its corners enclose 0"));
    CHECK(mesh_error([](auto&) {}) == "no error");
    // A warped quad (#66 item 4): its area is the vector area the mesher stores (Newell's, the
    // patch's area as the form factors see it), 1% under the sum of its fan's triangles; it
    // was refused by every reader though rad-mesh wrote it.
    CHECK(mesh_error([](auto& m) {
              m.vertices[2] = {1, 1, 0.2};
              m.patches[0].area = 0.5 * std::sqrt(0.2 * 0.2 + 0.2 * 0.2 + 2 * 2);
              m.patches[1].area = 0.5 * std::sqrt(0.2 * 0.2 + 1);
          }) == "no error");

    radfmt::FormFactorData ff;
    ff.patch_count = 2;
    ff.row_start = {0, 1, 2};
    ff.columns = {1, 0};
    ff.back_fraction = {0, 0};
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), -0.25f,
                      std::numeric_limits<float>::infinity(), 7.0f}) {
        ff.values = {0.5f, bad};
        radfmt::write_form_factors(dir / "h.ff", header_for("rad-ff"), ff);
        CHECK_THROWS_WITH(radfmt::read_form_factors(dir / "h.ff"),
                          Contains("h.ff") && Contains("form factor 1") && Contains("[0, 1]"));
    }
    for (double bad : {nan, -1.0, std::numeric_limits<double>::infinity()}) {
        radfmt::RadiosityData rad{{{{1, 1, 1}}, {{bad, 0, 0}}}};
        radfmt::write_radiosity(dir / "h.rad", header_for("rad-solve"), rad);
        CHECK_THROWS_WITH(radfmt::read_radiosity(dir / "h.rad"),
                          Contains("h.rad") && Contains("radiosity value 1"));
    }
    // A header whose counts disagree with its body.
    auto header = header_for("rad-solve");
    header.set("patches", "5"); // the writer sets the real count: write the body by hand
    radfmt::BodyWriter w;
    const std::vector<radfmt::Rgb> one{{{1, 1, 1}}};
    w.u64(1);
    w.array(one);
    w.u64(0);
    header.kind = radfmt::Kind::Radiosity;
    radfmt::write_file(dir / "count.rad", header, w);
    CHECK_THROWS_WITH(radfmt::read_radiosity(dir / "count.rad"),
                      Contains("the header says patches=5 but the body holds 1"));
}

TEST_CASE("a symlink planted at the temporary name does not redirect the write") {
    const auto dir = temp_dir("symlink");
    const auto victim = dir / "victim.txt";
    write_text(victim, "precious");
    // The writer's temporary name is predictable up to a random tag (".NAME.tmp.PID.TAG"
    // beside the output); a link planted at ".NAME.tmp.PID", holding no lock, is removed.
    const auto temp = dir / (".out.mesh.tmp." + std::to_string(::getpid()));
    fs::create_symlink(victim, temp);
    radfmt::write_mesh(dir / "out.mesh", header_for("rad-mesh"), small_mesh());
    CHECK(read_all(victim) == "precious");
    CHECK(radfmt::read_mesh(dir / "out.mesh").patches.size() == 2);
    CHECK_FALSE(fs::exists(fs::symlink_status(temp)));
}

TEST_CASE("a header larger than readers accept is refused by the writer") {
    const auto dir = temp_dir("bigheader");
    auto header = header_for("rad-mesh");
    header.provenance.assign(2000, std::string(1000, 'x')); // 2 MB of history
    REQUIRE_THROWS_WITH(radfmt::write_mesh(dir / "big.mesh", header, small_mesh()),
                        Contains("readers accept"));
    CHECK_FALSE(fs::exists(dir / "big.mesh"));
    header.provenance.resize(100); // 100 kB is fine
    radfmt::write_mesh(dir / "ok.mesh", header, small_mesh());
    CHECK(radfmt::read_mesh(dir / "ok.mesh").patches.size() == 2);
}

TEST_CASE("form-factor parts round-trip, and are refused when they fill rows not theirs") {
    const auto dir = temp_dir("part");
    radfmt::FormFactorData ff;
    ff.patch_count = 3;
    ff.row_start = {0, 0, 2, 2}; // only row 1 filled
    ff.columns = {0, 2};
    ff.values = {0.25f, 0.5f};
    ff.back_fraction = {0, 0.5f, 0};
    radfmt::write_form_factor_part(dir / "p.part", header_for("rad-ff"), ff, 1, 2);
    radfmt::Header header;
    const auto back = radfmt::read_form_factor_part(dir / "p.part", &header);
    CHECK(back.values == ff.values);
    CHECK(*header.find("rows_begin") == "1");
    // The same rows claimed as 2..3: row 1 is filled outside them.
    radfmt::write_form_factor_part(dir / "q.part", header_for("rad-ff"), ff, 2, 3);
    REQUIRE_THROWS_WITH(radfmt::read_form_factor_part(dir / "q.part"),
                        Contains("row 1 is filled but outside its rows"));
    radfmt::write_form_factor_part(dir / "r.part", header_for("rad-ff"), ff, 1, 4);
    REQUIRE_THROWS_WITH(radfmt::read_form_factor_part(dir / "r.part"),
                        Contains("are not a range of the 3 rows"));
    // A part is not a matrix, nor a matrix a part.
    REQUIRE_THROWS_WITH(radfmt::read_form_factors(dir / "p.part"), Contains("was expected"));
}

TEST_CASE("formfactors version 3: hit counts exact, other values as they are, spool identical") {
    const auto dir = temp_dir("compact");
    const auto header = hemisphere_header(1000);
    radfmt::FormFactorData ff;
    ff.patch_count = 3000;
    ff.row_start = {0};
    std::uint32_t state = 777;
    auto next = [&] { return state = state * 1664525u + 1013904223u; };
    radfmt::FormFactorSpool spool(ff.patch_count, dir);
    radfmt::FormFactorSpool spilled(ff.patch_count, dir, std::uint64_t(8) << 20);
    // Encoding as the rows come (as rad-ff does), in memory and past a budget of one block.
    REQUIRE(radfmt::formfactors_hit_denominator(header) == 1000);
    radfmt::FormFactorSpool encoding(ff.patch_count, dir, radfmt::FormFactorSpool::kNoLimit, 1000);
    radfmt::FormFactorSpool encoding_spilled(ff.patch_count, dir, std::uint64_t(4) << 20, 1000);
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        std::vector<std::uint32_t> columns;
        std::vector<float> values;
        std::uint32_t column = next() % 50;
        const std::size_t length = i % 101 == 0 ? 0 : 300 + next() % 700;
        for (std::size_t k = 0; k < length && column < ff.patch_count; ++k) {
            columns.push_back(column);
            // Hit counts over 1000 rays as hemisphere stores them; every 7th row a value that
            // is no count (a float row).
            values.push_back(i % 7 == 3 ? 0.1234567f
                                        : static_cast<float>(double(1 + next() % 6) / 1000));
            column += 1 + next() % 4;
        }
        ff.columns.insert(ff.columns.end(), columns.begin(), columns.end());
        ff.values.insert(ff.values.end(), values.begin(), values.end());
        ff.row_start.push_back(ff.columns.size());
        ff.back_fraction.push_back(0.25f);
        spool.add_row(columns, values, 0.25f);
        spilled.add_row(columns, values, 0.25f);
        encoding.add_row(columns, values, 0.25f);
        std::vector<std::pair<std::uint32_t, float>> entries;
        for (std::size_t k = 0; k < columns.size(); ++k)
            entries.emplace_back(columns[k], values[k]);
        encoding_spilled.add_row(entries, 0.25f);
    }
    REQUIRE(ff.nonzeros() > 1'000'000);
    radfmt::write_form_factors(dir / "memory.ff", header, ff);
    radfmt::write_form_factors(dir / "spool.ff", header, spool);
    radfmt::write_form_factors(dir / "spilled.ff", header, spilled);
    radfmt::write_form_factors(dir / "encoding.ff", header, encoding);
    radfmt::write_form_factors(dir / "encoding-spilled.ff", header, encoding_spilled);
    CHECK(spilled.spilled());
    CHECK_FALSE(encoding.spilled());
    CHECK(encoding_spilled.spilled());
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "spool.ff"));
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "spilled.ff"));
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "encoding.ff"));
    CHECK(read_all(dir / "memory.ff") == read_all(dir / "encoding-spilled.ff"));
    // An encoding spool is a whole matrix: it is not written as a part.
    CHECK_THROWS_AS(radfmt::write_form_factor_part(dir / "p.ff", header, encoding, 0, 1),
                    std::logic_error);
    radfmt::Header read_header;
    const auto back = radfmt::read_form_factors(dir / "memory.ff", &read_header);
    CHECK(read_header.version == 3);
    CHECK(back.row_start == ff.row_start);
    CHECK(back.columns == ff.columns);
    CHECK(std::memcmp(back.values.data(), ff.values.data(), ff.values.size() * 4) == 0);
    // Packed (rad-solve's layout), the rows decode to the same bits.
    const auto kept =
        radfmt::read_form_factors(dir / "memory.ff", nullptr, radfmt::FormFactorLayout::compact);
    REQUIRE(kept.is_compact());
    CHECK(kept.columns.empty());
    CHECK(kept.nonzeros() == ff.nonzeros());
    CHECK(kept.back_fraction == ff.back_fraction);
    bool rows_same = true;
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        const auto row = row_entries(kept, i);
        const auto b = ff.row_start[i];
        rows_same = rows_same && row.size() == ff.row_start[i + 1] - b;
        for (std::size_t k = 0; rows_same && k < row.size(); ++k)
            rows_same = row[k].first == ff.columns[b + k] &&
                        std::memcmp(&row[k].second, &ff.values[b + k], 4) == 0;
    }
    CHECK(rows_same);
    // A compact matrix is written from plain arrays only (rad-solve never writes one).
    CHECK_THROWS_AS(radfmt::write_form_factors(dir / "again.ff", header, kept), std::logic_error);
    // Small deltas and counts take a byte each: 2 bytes a count entry, 5 a float one.
    const double bytes_per_entry = double(read_header.body_size) / double(ff.nonzeros());
    CHECK(bytes_per_entry < 3);
    // Without the method's rays every value is a float: still exact, larger.
    radfmt::write_form_factors(dir / "floats.ff", header_for("rad-ff"), ff);
    const auto floats = radfmt::read_form_factors(dir / "floats.ff", &read_header);
    CHECK(std::memcmp(floats.values.data(), ff.values.data(), ff.values.size() * 4) == 0);
    CHECK(double(read_header.body_size) / double(ff.nonzeros()) > 4.5);
}

TEST_CASE("packed rows: far columns, large counts and non-count values decode exactly") {
    // rad-solve's packed layout stores a step past 65534 and a count past 254 (or a value
    // that is no count) out of line; every such entry must come back bit for bit.
    const auto dir = temp_dir("packed");
    const auto header = hemisphere_header(1000);
    radfmt::FormFactorData ff;
    ff.patch_count = 200000;
    ff.row_start = {0};
    const std::vector<std::vector<std::pair<std::uint32_t, float>>> rows = {
        {{0, 0.001f}, {70000, 0.3f}, {70001, 0.254f}, {199999, 0.255f}},
        {{65534, 0.002f}, {131069, 0.1234567f}, {131070, 1.2f}},
        {},
        {{199999, 0.001f}}};
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        if (i < rows.size())
            for (const auto& [column, value] : rows[i]) {
                ff.columns.push_back(column);
                ff.values.push_back(value);
            }
        ff.row_start.push_back(ff.columns.size());
        ff.back_fraction.push_back(0);
    }
    radfmt::write_form_factors(dir / "far.ff", header, ff);
    const auto packed =
        radfmt::read_form_factors(dir / "far.ff", nullptr, radfmt::FormFactorLayout::compact);
    REQUIRE(packed.is_compact());
    // Steps of 65535 or more: 70000, 199999, 65534, 131069 and 199999.
    CHECK(packed.compact.far_column.size() == 5);
    CHECK(packed.compact.other_value.size() == 4); // 0.3, 0.255, 0.1234567, 1.2
    for (std::uint64_t i = 0; i < rows.size(); ++i) {
        CAPTURE(i);
        const auto row = row_entries(packed, i);
        REQUIRE(row.size() == rows[i].size());
        for (std::size_t k = 0; k < row.size(); ++k) {
            CHECK(row[k].first == rows[i][k].first);
            CHECK(std::memcmp(&row[k].second, &rows[i][k].second, 4) == 0);
        }
    }
    // Without hit counts (no rays in the header) nothing would get smaller: plain arrays.
    radfmt::write_form_factors(dir / "floats.ff", header_for("rad-ff"), ff);
    CHECK_FALSE(
        radfmt::read_form_factors(dir / "floats.ff", nullptr, radfmt::FormFactorLayout::compact)
            .is_compact());
}

TEST_CASE("formfactors version 2 files (plain arrays) are still read") {
    const auto dir = temp_dir("v2");
    radfmt::FormFactorData ff;
    ff.patch_count = 3;
    ff.row_start = {0, 2, 2, 3};
    ff.columns = {1, 2, 0};
    ff.values = {0.25f, 0.5f, 0.125f};
    ff.back_fraction = {0.0f, 0.75f, 0.5f};
    radfmt::BodyWriter w;
    w.u64(ff.patch_count);
    w.u64(ff.nonzeros());
    w.array(ff.row_start);
    w.array(ff.columns);
    w.array(ff.values);
    w.array(ff.back_fraction);
    auto header = header_for("rad-ff");
    header.kind = radfmt::Kind::FormFactors;
    header.version = 2;
    header.set("patches", "3");
    header.set("nonzeros", "3");
    radfmt::write_file(dir / "v2.ff", header, w);
    const auto old = radfmt::read_form_factors(dir / "v2.ff");
    CHECK(old.row_start == ff.row_start);
    CHECK(old.columns == ff.columns);
    CHECK(old.values == ff.values);
    CHECK(old.back_fraction == ff.back_fraction);
}

#include "radfmt/names.hpp"

TEST_CASE("names: one rule for every output, and readers refuse what breaks it") {
    CHECK(radfmt::name_problem("café").empty());
    CHECK(radfmt::clean_name("caf\xe9") == "café"); // Latin-1
    CHECK(radfmt::clean_name("a\nb\tc") == "a?b?c");
    CHECK(radfmt::clean_name("") == "unnamed");
    CHECK(radfmt::clean_name(std::string(300, 'x')).size() == radfmt::kMaxNameBytes);
    // Cut on a character's boundary, never inside one.
    const auto cut = radfmt::clean_name(std::string(199, 'x') + "é");
    CHECK(cut == std::string(199, 'x'));
    CHECK(radfmt::name_problem(radfmt::clean_name("\xff\xfe\n")).empty());
    CHECK(radfmt::name_problem("caf\xe9").rfind("a name that is not UTF-8", 0) == 0);
    CHECK(radfmt::name_problem("\xed\xa0\x80").rfind("a name that is not UTF-8", 0) ==
          0); // surrogate
    CHECK(radfmt::shown_name("caf\xe9\n") == "caf\\xE9\\n");

    const auto dir = temp_dir("names");
    auto mesh = small_mesh();
    mesh.materials[0].name = "grey\nkey=value";
    radfmt::write_mesh(dir / "n.mesh", header_for("rad-mesh"), mesh);
    CHECK_THROWS_WITH(radfmt::read_mesh(dir / "n.mesh"),
                      Contains("material 0 has a name holding a control character"));
    // A header field whose name would break its line is never written.
    auto header = header_for("rad-solve");
    header.set("light_group.x\ny", "1");
    radfmt::RadiosityData rad{{{{1, 1, 1}}}};
    CHECK_THROWS_WITH(radfmt::write_radiosity(dir / "k.rad", header, rad),
                      Contains("a header field's name"));
    CHECK_FALSE(fs::exists(dir / "k.rad"));
    fs::remove_all(dir);
}

TEST_CASE("a .sky that passes its checksums but says north 1e308 is refused (#70 item 8)") {
    const auto dir = temp_dir("sky-north");
    radfmt::SkyData sky;
    sky.subdivision = "reinhart:1";
    sky.patch_count = 1;
    sky.sky_patches = 146;
    sky.coefficients.assign(146 * 3, 0.01f);
    sky.north_deg = 30;
    radfmt::write_sky(dir / "ok.sky", header_for("rad-ff"), sky);
    CHECK(radfmt::read_sky(dir / "ok.sky").north_deg == 30);
    sky.north_deg = 1e308; // written whole, hashes and all: only its range tells
    radfmt::write_sky(dir / "far.sky", header_for("rad-ff"), sky);
    CHECK_THROWS_WITH(radfmt::read_sky(dir / "far.sky"),
                      Contains("is outside -360 to 360 degrees, which rad-ff writes"));
    fs::remove_all(dir);
}

TEST_CASE("a .lum whose embedded photometry is not the text its header records is refused "
          "(#70 item 8)") {
    const auto dir = temp_dir("lum-text");
    radfmt::LuminaireData lum;
    lum.layout_name = "room/layout.csv";
    lum.layout_text = "name,photometry,x,y,z\nL,lamp.ies,0,2,0\n";
    lum.files = {{"lamp.ies", "IESNA:LM-63-2002\nTILT=NONE\n"}};
    lum.groups = {"all"};
    lum.patch_count = 1;
    lum.irradiance = {radfmt::Rgb{{1, 1, 1}}};
    const auto hash = [](const std::string& text) {
        return "xxh64:" + radfmt::hash_hex(radfmt::hash_bytes(text.data(), text.size()));
    };
    auto header = header_for("rad-ff");
    header.inputs = {{"room/layout.csv", hash(lum.layout_text)},
                     {"room/lamp.ies", hash(lum.files[0].second)}};
    radfmt::write_luminaires(dir / "ok.lum", header, lum);
    CHECK(radfmt::read_luminaires(dir / "ok.lum").files.size() == 1);
    // The photometry swapped for other text, the file written whole, hashes and all.
    lum.files[0].second = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1e300";
    radfmt::write_luminaires(dir / "swapped.lum", header, lum);
    CHECK_THROWS_WITH(radfmt::read_luminaires(dir / "swapped.lum"),
                      Contains("the text of room/lamp.ies it holds is not the one its header "
                               "records") &&
                          Contains("contradicts itself"));
    fs::remove_all(dir);
}
