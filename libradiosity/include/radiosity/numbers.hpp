// The one grammar for numbers read from text (OBJ coordinates, options, overrides, views):
// an optional sign, digits with an optional fraction, an optional exponent. Nothing else:
// no leading or trailing spaces, no hex, no nan or inf, nothing out of double's range.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace rad {

// True when all of `text` is a finite decimal number; `value` is set only then.
bool parse_number(std::string_view text, double& value);
// True when all of `text` is a whole number of at most 15 digits (a count, a row, a shard:
// digits only, no sign); `value` is set only then.
bool parse_count(std::string_view text, std::uint64_t& value);
// True when `text` spells nan or inf in a way other parsers accept: for a clearer message.
bool spells_non_finite(std::string_view text);

std::uint64_t physical_memory_bytes();
std::string human_bytes(double bytes);

} // namespace rad
