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

} // namespace radfmt
