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
