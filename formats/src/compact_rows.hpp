// The compact form-factor rows of formfactors version 3 (internal to radformats): per row a
// tag byte, then per entry the column as a LEB128 delta from the previous one (the first as
// is) and the value, either a LEB128 hit count (tag 1: the value is count / denominator, the
// exact float a hemisphere method stores) or the float's 4 bytes (tag 0).
#pragma once
#include "radfmt/container.hpp"
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace radfmt::compact {

// The denominator that turns hit counts into form factors (the hemisphere method's rays), or 0
// when the header's method does not store hit counts.
std::uint64_t hit_denominator(const Header& header);

// Appends a row's code to `out`: as counts when every value is exactly count / denominator.
void encode_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                std::uint64_t denominator, std::vector<std::uint8_t>& out);

// Decodes `count` entries from exactly the bytes [data, data + size) into columns and values;
// returns an empty string, or what is wrong (columns must rise and stay below patch_count,
// counts be at most 1.5 x the denominator, floats within [0, 1.5]).
// `row` and `first_entry` (the row's first entry in the matrix) name the place in messages.
std::string decode_row(const std::uint8_t* data, std::size_t size, std::uint64_t count,
                       std::uint64_t patch_count, std::uint64_t denominator, std::uint32_t* columns,
                       float* values, std::uint64_t row, std::uint64_t first_entry);

// Appends a row (columns ascending, count entries) to packed rows; the caller records the
// row's far_start and other_start before it.
void pack_row(const std::uint32_t* columns, const float* values, std::uint64_t count,
              CompactFormFactorRows& rows);

// The value of each count that packed rows look up: count / denominator for 0..254.
std::vector<float> packed_value_table(std::uint64_t denominator);

} // namespace radfmt::compact
