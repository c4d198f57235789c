// numbers: the one strict number grammar, sizes for humans.
#include "radiosity/numbers.hpp"

#include <catch2/catch.hpp>

TEST_CASE("parse_number takes decimal numbers with an optional exponent and nothing else") {
    double v = -1;
    for (const auto& [text, value] :
         std::vector<std::pair<std::string, double>>{{"0", 0},
                                                     {"1.5", 1.5},
                                                     {"-2", -2},
                                                     {"+3", 3},
                                                     {".5", 0.5},
                                                     {"5.", 5},
                                                     {"1e3", 1000},
                                                     {"-2.5E-2", -0.025},
                                                     {"1e+2", 100}}) {
        CAPTURE(text);
        REQUIRE(rad::parse_number(text, v));
        CHECK(v == value);
    }
    for (const char* text : {"",     " 1",       "1 ",    "0x2",    "0x1p3", "nan", "NaN", "inf",
                             "-inf", "infinity", "1e",    "1e+",    "e5",    ".",   "-",   "+-1",
                             "1,5",  "1.2.3",    "1e999", "-1e400", "1_000", "abc", "2a"}) {
        CAPTURE(text);
        v = 42;
        CHECK_FALSE(rad::parse_number(text, v));
        CHECK(v == 42); // untouched on failure
    }
}

TEST_CASE("non-finite spellings are recognised for clearer messages") {
    CHECK(rad::spells_non_finite("nan"));
    CHECK(rad::spells_non_finite("-INF"));
    CHECK(rad::spells_non_finite("Infinity"));
    CHECK_FALSE(rad::spells_non_finite("1e999"));
    CHECK_FALSE(rad::spells_non_finite("banana"));
}

TEST_CASE("human_bytes uses binary units") {
    CHECK(rad::human_bytes(512) == "512.0 B");
    CHECK(rad::human_bytes(1536) == "1.5 KiB");
    CHECK(rad::human_bytes(3.0 * 1024 * 1024 * 1024) == "3.0 GiB");
}

#include "radiosity/text_input.hpp"

#include <filesystem>
#include <fstream>
#include <unistd.h>

TEST_CASE("text inputs: lines, ends, folders, devices and overlong lines told apart") {
    const auto dir =
        std::filesystem::temp_directory_path() / ("radiosity-lines-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name, std::ios::binary) << text;
        return (dir / name).string();
    };
    const auto lines_of = [](const std::string& path) {
        rad::LineReader in(path);
        std::vector<std::string> out;
        for (std::string line; in.next(line);) out.push_back(line);
        return out;
    };
    CHECK(lines_of(write("a.txt", "one\r\ntwo\n\nlast")) ==
          std::vector<std::string>{"one", "two", "", "last"});
    CHECK(lines_of(write("empty.txt", "")).empty());
    // A lone CR ends a line too, as tinyobjloader reads an OBJ (the lint and the reader agree).
    CHECK(lines_of(write("cr.txt", "f 1 2 3\r-1\r\nlast\r")) ==
          std::vector<std::string>{"f 1 2 3", "-1", "last"});
    // Lines longer than the reader's first buffer (64 KiB) and just under the limit are read.
    const std::string big(rad::kMaxLineBytes, 'x');
    CHECK(lines_of(write("big.txt", "a\n" + big + "\nb\n")) ==
          std::vector<std::string>{"a", big, "b"});
    CHECK_THROWS_WITH(lines_of(write("huge.txt", "a\n" + big + "y\n")),
                      Catch::Matchers::Contains("huge.txt:2: a line longer than 1.0 MiB") &&
                          Catch::Matchers::Contains("'xxxxxxxxxx"));
    CHECK_THROWS_WITH(lines_of(dir.string()), Catch::Matchers::Contains("is a folder"));
    CHECK_THROWS_WITH(lines_of("/dev/zero"),
                      Catch::Matchers::Contains("/dev/zero:1: holds a NUL byte"));
    CHECK_THROWS_WITH(lines_of((dir / "missing.txt").string()),
                      Catch::Matchers::Contains("missing.txt: cannot open it"));
    // A message quotes a short prefix of a line, never the whole.
    CHECK(rad::quoted_prefix(std::string(1000, 'q')).size() == 60 + 5);
    std::filesystem::remove_all(dir);
}

TEST_CASE("parse_count takes digits alone, up to 15 of them") {
    std::uint64_t v = 7;
    CHECK(rad::parse_count("0", v));
    CHECK(v == 0);
    CHECK(rad::parse_count("123456789012345", v));
    CHECK(v == 123456789012345ull);
    for (const char* bad : {"", "-1", "+1", "1.0", "1e3", " 1", "1 ", "0x10", "1234567890123456"}) {
        v = 7;
        CHECK_FALSE(rad::parse_count(bad, v));
        CHECK(v == 7);
    }
}
