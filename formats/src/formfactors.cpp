// The form-factor kinds (formfactors, formfactor-part): their writers and readers, plain or
// compact rows, and their CSV and summaries for rad-info.
#include "radfmt/kinds.hpp"
#include "radfmt/names.hpp"

#include "body_checks.hpp"
#include "compact_rows.hpp"
#include "kind_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ostream>

namespace radfmt {
namespace fs = std::filesystem;
using detail::require_count;

namespace {
constexpr const char* kRowErrorsField = "row_errors";

// The header says whether the body ends in the rows' standard errors (a header copied from a
// file with them must not promise them for one without).
void mark_row_errors(Header& header, bool present) {
    std::erase_if(header.fields, [](const auto& f) { return f.first == kRowErrorsField; });
    if (present) header.set(kRowErrorsField, "yes");
}

void write_form_factor_body(const fs::path& path, Header header, const FormFactorData& ff,
                            Kind kind) {
    header.kind = kind;
    header.set("patches", std::to_string(ff.patch_count));
    header.set("nonzeros", std::to_string(ff.nonzeros()));
    if (ff.back_fraction.size() != ff.patch_count)
        throw std::logic_error("form factors written without one back-face fraction per row");
    if (ff.is_compact()) throw std::logic_error("form factors written from their compact rows");
    if (!ff.row_error.empty() && ff.row_error.size() != ff.patch_count)
        throw std::logic_error("form factors written with some rows' errors missing");
    mark_row_errors(header, !ff.row_error.empty());
    BodyWriter w;
    w.u64(ff.patch_count);
    w.u64(ff.nonzeros());
    // Version 3 of formfactors: compact rows (parts keep the plain arrays).
    std::vector<std::uint64_t> row_offset;
    std::vector<std::uint8_t> code;
    if (kind == Kind::FormFactors) {
        const auto denominator = compact::hit_denominator(header);
        w.u64(denominator);
        w.array(ff.row_start);
        row_offset.reserve(ff.patch_count + 1);
        for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
            row_offset.push_back(code.size());
            const auto b = ff.row_start[i], n = ff.row_start[i + 1] - b;
            compact::encode_row({ff.columns.data() + b, n}, {ff.values.data() + b, n}, denominator,
                                code);
        }
        row_offset.push_back(code.size());
        w.array(row_offset);
        w.array(code);
    } else {
        w.array(ff.row_start);
        w.array(ff.columns);
        w.array(ff.values);
    }
    w.array(ff.back_fraction);
    if (!ff.row_error.empty()) w.array(ff.row_error);
    write_file(path, std::move(header), w);
}

// Version 3's row offsets, checked against the row starts.
std::vector<std::uint64_t> read_row_offsets(BodyReader& r, const FormFactorData& ff,
                                            std::uint64_t nnz) {
    auto row_offset = r.array<std::uint64_t>(ff.patch_count + 1, "row offsets");
    if (ff.row_start.front() != 0 || ff.row_start.back() != nnz)
        r.fail("row starts do not span the non-zeros");
    if (row_offset.front() != 0) r.fail("row offsets do not start at 0");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i)
        if (ff.row_start[i] > ff.row_start[i + 1] || row_offset[i] > row_offset[i + 1])
            r.fail("row starts or offsets decrease at row " + std::to_string(i));
    return row_offset;
}

// Where read_compact_rows puts each decoded row: into the plain arrays, or packed (then
// decoded into a scratch row first).
class DecodedRows {
  public:
    DecodedRows(FormFactorData& ff, std::uint64_t nnz, std::uint64_t denominator, bool packed)
        : ff_(ff), packed_(packed) {
        if (!packed_) {
            ff_.columns.resize(nnz);
            ff_.values.resize(nnz);
            return;
        }
        auto& rows = ff_.compact;
        rows.denominator = denominator;
        rows.value_of_count = compact::packed_value_table(denominator);
        rows.step.reserve(nnz);
        rows.count.reserve(nnz);
        rows.far_start = {0};
        rows.other_start = {0};
    }
    std::uint32_t* columns(std::uint64_t i) {
        return packed_ ? fit(scratch_columns_, i) : ff_.columns.data() + ff_.row_start[i];
    }
    float* values(std::uint64_t i) {
        return packed_ ? fit(scratch_values_, i) : ff_.values.data() + ff_.row_start[i];
    }
    void done(std::uint64_t i) {
        if (!packed_) return;
        auto& rows = ff_.compact;
        compact::pack_row(scratch_columns_.data(), scratch_values_.data(), ff_.row_size(i), rows);
        rows.far_start.push_back(rows.far_column.size());
        rows.other_start.push_back(rows.other_value.size());
    }

  private:
    // The scratch row, long enough for row i.
    template <class T> T* fit(std::vector<T>& scratch, std::uint64_t i) {
        if (scratch.size() < ff_.row_size(i)) scratch.resize(ff_.row_size(i));
        return scratch.data();
    }
    FormFactorData& ff_;
    bool packed_;
    std::vector<std::uint32_t> scratch_columns_;
    std::vector<float> scratch_values_;
};

// Version 3's rows: offsets checked, then the codes read in pieces and decoded into the
// arrays or packed (never the whole code and the rows at once).
void read_compact_rows(BodyReader& r, FormFactorData& ff, std::uint64_t nnz,
                       std::uint64_t denominator, bool packed) {
    const auto row_offset = read_row_offsets(r, ff, nnz);
    const std::uint64_t code_size = row_offset.back();
    r.begin_pieces(code_size, "row codes");
    DecodedRows rows(ff, nnz, denominator, packed);
    std::vector<std::uint8_t> buffer;
    std::size_t begin = 0, have = 0; // valid bytes: buffer[begin, begin + have)
    std::uint64_t left = code_size;
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        const auto length = static_cast<std::size_t>(row_offset[i + 1] - row_offset[i]);
        if (have < length) {
            if (have > 0) std::memmove(buffer.data(), buffer.data() + begin, have);
            begin = 0;
            const std::size_t capacity = std::max<std::size_t>(length, std::size_t(1) << 20);
            if (buffer.size() < capacity) buffer.resize(capacity);
            const auto more =
                static_cast<std::size_t>(std::min<std::uint64_t>(capacity - have, left));
            r.read_piece(buffer.data() + have, more);
            have += more;
            left -= more;
        }
        const auto b = ff.row_start[i];
        const std::string why =
            compact::decode_row(buffer.data() + begin, length, ff.row_start[i + 1] - b,
                                ff.patch_count, denominator, rows.columns(i), rows.values(i), i, b);
        if (!why.empty()) r.fail(why);
        rows.done(i);
        begin += length;
        have -= length;
    }
    r.end_pieces();
}

// The same bytes from a spool (FormFactorSpool::fill_body lays out the body as above).
void write_form_factor_body(const fs::path& path, Header header, FormFactorSpool& ff, Kind kind) {
    header.kind = kind;
    header.set("patches", std::to_string(ff.patch_count()));
    header.set("nonzeros", std::to_string(ff.nonzeros()));
    mark_row_errors(header, !ff.row_error().empty());
    BodyWriter w;
    if (kind == Kind::FormFactors)
        ff.fill_compact_body(w, compact::hit_denominator(header));
    else
        ff.fill_body(w);
    write_file(path, std::move(header), w);
}

FormFactorData read_form_factor_body(const fs::path& path, Header* header_out, Kind kind,
                                     std::uint64_t* rows_begin = nullptr,
                                     std::uint64_t* rows_end = nullptr,
                                     FormFactorLayout layout = FormFactorLayout::plain) {
    BodyReader r(path, &kind);
    FormFactorData ff;
    ff.patch_count = r.count(8, "rows");
    const bool compact = kind == Kind::FormFactors && r.header().version >= 3;
    // A compact non-zero takes at least two bytes (column delta and count).
    const auto nnz = r.count(compact ? 2 : 8, "non-zeros");
    const std::uint64_t denominator = compact ? r.u64() : 0;
    ff.row_start = r.array<std::uint64_t>(ff.patch_count + 1, "row starts");
    if (compact) {
        // Packed only where the values are hit counts: other rows would not get smaller.
        const bool packed = layout == FormFactorLayout::compact && denominator > 0;
        read_compact_rows(r, ff, nnz, denominator, packed);
    } else {
        ff.columns = r.array<std::uint32_t>(nnz, "columns");
        ff.values = r.array<float>(nnz, "values");
    }
    // Parts have them from their version 1 on.
    if (r.header().version >= 2 || kind == Kind::FormFactorPart) {
        ff.back_fraction = r.array<float>(ff.patch_count, "back-face fractions");
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            if (!(ff.back_fraction[i] >= 0 && ff.back_fraction[i] <= 1))
                r.fail("back-face fraction of row " + std::to_string(i) + " is not in [0, 1]");
    }
    if (r.header().find(kRowErrorsField)) {
        ff.row_error = r.array<float>(ff.patch_count, "rows' standard errors");
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            if (!(ff.row_error[i] >= 0 && ff.row_error[i] <= 1))
                r.fail("standard error of row " + std::to_string(i) + " is not in [0, 1]");
    }
    r.expect_end();
    if (ff.row_start.front() != 0 || ff.row_start.back() != nnz)
        r.fail("row starts do not span the non-zeros");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        if (ff.row_start[i] > ff.row_start[i + 1])
            r.fail("row starts decrease at row " + std::to_string(i));
    }
    for (auto c : ff.columns)
        if (c >= ff.patch_count) r.fail("column " + std::to_string(c) + " out of range");
    // A form factor is a fraction of what leaves a patch: finite, in [0, 1] (a little over
    // for estimator noise).
    for (std::uint64_t k = 0; k < ff.values.size(); ++k)
        if (!(ff.values[k] >= 0 && ff.values[k] <= 1.5f))
            r.fail("form factor " + std::to_string(k) + " (" + std::to_string(ff.values[k]) +
                   ") is not in [0, 1]");
    require_count(r.header(), "patches", ff.patch_count, r);
    require_count(r.header(), "nonzeros", nnz, r);
    if (kind == Kind::FormFactorPart) {
        // Its rows, [rows_begin, rows_end): within the matrix, and the only ones filled.
        std::uint64_t begin = 0, end = 0;
        try {
            begin = std::stoull(r.header().get("rows_begin", path.string()));
            end = std::stoull(r.header().get("rows_end", path.string()));
        } catch (const FormatError&) {
            throw;
        } catch (...) {
            r.fail("rows_begin or rows_end is not a row number");
        }
        if (!(begin < end && end <= ff.patch_count))
            r.fail("its rows " + std::to_string(begin) + ".." + std::to_string(end) +
                   " are not a range of the " + std::to_string(ff.patch_count) + " rows");
        for (std::uint64_t i = 0; i < ff.patch_count; ++i)
            if ((i < begin || i >= end) && ff.row_start[i] != ff.row_start[i + 1])
                r.fail("row " + std::to_string(i) + " is filled but outside its rows");
        if (rows_begin) *rows_begin = begin;
        if (rows_end) *rows_end = end;
    }
    if (header_out) *header_out = r.take_header();
    return ff;
}
} // namespace

std::uint64_t formfactors_hit_denominator(const Header& header) {
    return compact::hit_denominator(header);
}

void write_form_factors(const fs::path& path, Header header, const FormFactorData& ff) {
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactors);
}
FormFactorData read_form_factors(const fs::path& path, Header* header_out,
                                 FormFactorLayout layout) {
    return read_form_factor_body(path, header_out, Kind::FormFactors, nullptr, nullptr, layout);
}

void write_form_factor_part(const fs::path& path, Header header, const FormFactorData& ff,
                            std::uint64_t rows_begin, std::uint64_t rows_end) {
    header.set("rows_begin", std::to_string(rows_begin));
    header.set("rows_end", std::to_string(rows_end));
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactorPart);
}
void write_form_factors(const fs::path& path, Header header, FormFactorSpool& ff) {
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactors);
}
void write_form_factor_part(const fs::path& path, Header header, FormFactorSpool& ff,
                            std::uint64_t rows_begin, std::uint64_t rows_end) {
    header.set("rows_begin", std::to_string(rows_begin));
    header.set("rows_end", std::to_string(rows_end));
    write_form_factor_body(path, std::move(header), ff, Kind::FormFactorPart);
}
FormFactorData read_form_factor_part(const fs::path& path, Header* header_out,
                                     std::uint64_t* rows_begin, std::uint64_t* rows_end) {
    return read_form_factor_body(path, header_out, Kind::FormFactorPart, rows_begin, rows_end);
}

namespace detail {
void form_factor_rows_csv(const FormFactorData& ff, std::ostream& out);

void form_factor_csv(const fs::path& path, std::ostream& out) {
    form_factor_rows_csv(read_form_factors(path), out);
}

void form_factor_part_csv(const fs::path& path, std::ostream& out) {
    form_factor_rows_csv(read_form_factor_part(path), out);
}

std::string form_factor_part_summary(const fs::path& path, Header& header) {
    const auto ff = read_form_factor_part(path, &header);
    return "rows " + header.get("rows_begin", path.string()) + " to " +
           header.get("rows_end", path.string()) + " (end excluded) of " +
           std::to_string(ff.patch_count) + ", " + std::to_string(ff.nonzeros()) +
           " non-zeros; rad-ff --merge joins the parts into the matrix";
}

void form_factor_rows_csv(const FormFactorData& ff, std::ostream& out) {
    char line[128];
    // A file with the rows' standard errors gets a column of them (the row's, on each entry).
    const bool errors = !ff.row_error.empty();
    out << kind_info(Kind::FormFactors).csv_columns << (errors ? ",row_error\n" : "\n");
    for (std::uint64_t i = 0; i < ff.patch_count; ++i) {
        for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k) {
            std::snprintf(line, sizeof line, "%llu,%u,%.9g", static_cast<unsigned long long>(i),
                          ff.columns[k], static_cast<double>(ff.values[k]));
            out << line;
            if (errors) {
                std::snprintf(line, sizeof line, ",%.9g", double(ff.row_error[i]));
                out << line;
            }
            out << '\n';
        }
        if (!out) return;
    }
}

std::string form_factor_summary(const fs::path& path, Header& header) {
    const auto ff = read_form_factors(path, &header);
    const double n = static_cast<double>(ff.patch_count);
    char text[160];
    std::snprintf(text, sizeof text, "%llu x %llu, %llu non-zeros (%.2f%% dense)",
                  static_cast<unsigned long long>(ff.patch_count),
                  static_cast<unsigned long long>(ff.patch_count),
                  static_cast<unsigned long long>(ff.nonzeros()),
                  n > 0 ? 100.0 * ff.nonzeros() / (n * n) : 0.0);
    std::string out = text;
    if (ff.back_fraction.empty()) {
        out += "; no back-face data (version 1 file)";
    } else {
        std::uint64_t mostly_back = 0;
        double sum = 0, max = 0;
        for (const float f : ff.back_fraction) {
            mostly_back += f > 0.5f;
            sum += f;
            max = std::max(max, double(f));
        }
        std::snprintf(text, sizeof text,
                      "; rays arriving at back faces: mean %.2f%%, max %.2f%%, %llu row(s) "
                      "above 50%%",
                      n > 0 ? 100.0 * sum / n : 0.0, 100.0 * max,
                      static_cast<unsigned long long>(mostly_back));
        out += text;
    }
    if (!ff.row_error.empty()) {
        double sum = 0, max = 0;
        for (const float e : ff.row_error) {
            sum += e;
            max = std::max(max, double(e));
        }
        std::snprintf(text, sizeof text,
                      "; rows' standard errors (rad-ff --error): mean %.3g, max %.3g",
                      n > 0 ? sum / n : 0.0, max);
        out += text;
    }
    return out;
}
} // namespace detail

} // namespace radfmt
