// Encoding and decoding the compact rows of formfactors version 3.
#include "compact_rows.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace radfmt::compact {

namespace {

void put_varint(std::uint64_t value, std::vector<std::uint8_t>& out) {
    while (value >= 0x80) {
        out.push_back(static_cast<std::uint8_t>(value | 0x80));
        value >>= 7;
    }
    out.push_back(static_cast<std::uint8_t>(value));
}

// Reads a LEB128 value of at most 35 bits; false past the end or when too long.
bool get_varint(const std::uint8_t*& at, const std::uint8_t* end, std::uint64_t& value) {
    value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
        if (at == end) return false;
        const std::uint8_t byte = *at++;
        value |= std::uint64_t(byte & 0x7F) << shift;
        if (!(byte & 0x80)) return true;
    }
    return false;
}

// The value of a count as the hemisphere method computes it.
float count_value(std::uint64_t count, std::uint64_t denominator) {
    return static_cast<float>(double(count) / double(denominator));
}

bool all_counts(std::span<const float> values, std::uint64_t denominator) {
    if (denominator == 0) return false;
    for (const float v : values) {
        const double count = std::nearbyint(double(v) * double(denominator));
        if (!(count >= 1 && count <= 1.5 * double(denominator)) ||
            std::bit_cast<std::uint32_t>(count_value(std::uint64_t(count), denominator)) !=
                std::bit_cast<std::uint32_t>(v))
            return false;
    }
    return true;
}

} // namespace

std::vector<float> packed_value_table(std::uint64_t denominator) {
    std::vector<float> table(CompactFormFactorRows::kOtherValue, 0.0f);
    if (denominator > 0)
        for (std::uint64_t count = 0; count < table.size(); ++count)
            table[count] = count_value(count, denominator);
    return table;
}

void pack_row(const std::uint32_t* columns, const float* values, std::uint64_t count,
              CompactFormFactorRows& rows) {
    std::uint32_t previous = ~std::uint32_t(0); // so that the first step is its column + 1
    for (std::uint64_t k = 0; k < count; ++k) {
        const std::uint32_t step = columns[k] - previous;
        previous = columns[k];
        if (step < CompactFormFactorRows::kFarStep) {
            rows.step.push_back(static_cast<std::uint16_t>(step));
        } else {
            rows.step.push_back(CompactFormFactorRows::kFarStep);
            rows.far_column.push_back(columns[k]);
        }
        const double hits = std::nearbyint(double(values[k]) * double(rows.denominator));
        const bool looked_up =
            rows.denominator > 0 && hits >= 1 && hits < CompactFormFactorRows::kOtherValue &&
            std::bit_cast<std::uint32_t>(rows.value_of_count[std::size_t(hits)]) ==
                std::bit_cast<std::uint32_t>(values[k]);
        if (looked_up) {
            rows.count.push_back(static_cast<std::uint8_t>(hits));
        } else {
            rows.count.push_back(CompactFormFactorRows::kOtherValue);
            rows.other_value.push_back(values[k]);
        }
    }
}

std::uint64_t hit_denominator(const Header& header) {
    const std::string* method = header.find("method");
    const std::string* rays = header.find("rays");
    if (!method || *method != "hemisphere" || !rays) return 0;
    try {
        return std::stoull(*rays);
    } catch (...) {
        return 0;
    }
}

void encode_row(std::span<const std::uint32_t> columns, std::span<const float> values,
                std::uint64_t denominator, std::vector<std::uint8_t>& out) {
    const bool counts = all_counts(values, denominator);
    out.push_back(counts ? 1 : 0);
    std::uint64_t previous = 0;
    for (std::size_t k = 0; k < columns.size(); ++k) {
        put_varint(k == 0 ? columns[k] : columns[k] - previous - 1, out);
        previous = columns[k];
        if (counts) {
            put_varint(std::uint64_t(std::nearbyint(double(values[k]) * double(denominator))), out);
        } else {
            std::uint8_t raw[4];
            std::memcpy(raw, &values[k], 4);
            out.insert(out.end(), raw, raw + 4);
        }
    }
}

std::string decode_row(const std::uint8_t* data, std::size_t size, std::uint64_t count,
                       std::uint64_t patch_count, std::uint64_t denominator, std::uint32_t* columns,
                       float* values, std::uint64_t row, std::uint64_t first_entry) {
    const std::string where = "row " + std::to_string(row) + " ";
    const std::uint8_t* at = data;
    const std::uint8_t* end = data + size;
    if (at == end) return where + "has no tag byte";
    const std::uint8_t tag = *at++;
    if (tag > 1 || (tag == 1 && denominator == 0)) return where + "has an unknown tag";
    std::uint64_t column = 0;
    for (std::uint64_t k = 0; k < count; ++k) {
        std::uint64_t delta = 0;
        if (!get_varint(at, end, delta)) return where + "ends inside an entry";
        column = k == 0 ? delta : column + delta + 1;
        if (column >= patch_count) return where + "has a column out of range";
        columns[k] = static_cast<std::uint32_t>(column);
        if (tag == 1) {
            std::uint64_t hits = 0;
            if (!get_varint(at, end, hits)) return where + "ends inside an entry";
            if (hits == 0 || double(hits) > 1.5 * double(denominator))
                return where + "has a hit count out of range";
            values[k] = count_value(hits, denominator);
        } else {
            if (end - at < 4) return where + "ends inside an entry";
            std::memcpy(&values[k], at, 4);
            at += 4;
            if (!(values[k] >= 0 && values[k] <= 1.5f))
                return "form factor " + std::to_string(first_entry + k) + " (" +
                       std::to_string(values[k]) + ") is not in [0, 1]";
        }
    }
    if (at != end) return where + "has bytes after its last entry";
    return {};
}

} // namespace radfmt::compact
