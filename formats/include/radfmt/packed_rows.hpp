// Reading the entries of a packed form-factor row (CompactFormFactorRows) one by one, for
// loops that decode as they go (rad-solve's sweep) instead of into a row buffer.
#pragma once
#include "radfmt/kinds.hpp"

namespace radfmt {

// The columns of packed row i in order. Two cursors over one row may run apart (one ahead
// to prefetch what the other will reach).
class PackedColumns {
  public:
    PackedColumns(const CompactFormFactorRows& rows, const FormFactorData& ff, std::uint64_t i)
        : step_(rows.step.data() + ff.row_start[i]),
          far_(rows.far_column.data() + rows.far_start[i]) {}
    std::uint32_t next() {
        const std::uint16_t step = *step_++;
        column_ = step != CompactFormFactorRows::kFarStep ? column_ + step : *far_++;
        return column_;
    }

  private:
    const std::uint16_t* step_;
    const std::uint32_t* far_;
    std::uint32_t column_ = ~std::uint32_t(0); // the first step is the first column + 1
};

// The values of packed row i in order.
class PackedValues {
  public:
    PackedValues(const CompactFormFactorRows& rows, const FormFactorData& ff, std::uint64_t i)
        : count_(rows.count.data() + ff.row_start[i]),
          other_(rows.other_value.data() + rows.other_start[i]),
          table_(rows.value_of_count.data()) {}
    float next() {
        const std::uint8_t count = *count_++;
        return count != CompactFormFactorRows::kOtherValue ? table_[count] : *other_++;
    }

  private:
    const std::uint8_t* count_;
    const float* other_;
    const float* table_;
};

// A plain row's columns or values, read in order as the packed cursors are.
template <class T> struct ArrayCursor {
    const T* at;
    T next() { return *at++; }
};

// Moves a cursor of columns n entries on.
inline void skip(PackedColumns& columns, std::uint64_t n) {
    for (std::uint64_t k = 0; k < n; ++k) columns.next();
}
template <class T> void skip(ArrayCursor<T>& cursor, std::uint64_t n) {
    cursor.at += n;
}

// Calls f(columns, values) with cursors over row i, packed or plain; the loop inside f is
// compiled once for each layout.
template <class F> void with_row_cursors(const FormFactorData& ff, std::uint64_t i, F&& f) {
    if (ff.is_compact())
        f(PackedColumns(ff.compact, ff, i), PackedValues(ff.compact, ff, i));
    else
        f(ArrayCursor<std::uint32_t>{ff.columns.data() + ff.row_start[i]},
          ArrayCursor<float>{ff.values.data() + ff.row_start[i]});
}

} // namespace radfmt
