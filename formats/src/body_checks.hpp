// Checks a reader makes of a body against its header (internal to radformats).
#pragma once
#include "radfmt/kinds.hpp"

#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <vector>

namespace radfmt::detail {

// The header's count of `key`, when it has one, must be what the body holds.
void require_count(const Header& header, const char* key, std::uint64_t count, BodyReader& r);

// `count` light-group names read from the body, each a name of the chain (radfmt/names.hpp) or
// the file is refused.
std::vector<std::string> read_group_names(BodyReader& r, std::uint64_t count);

// CSV rows "patch,group,r,g,b", patch-major over `values` (groups per patch); stops when the
// reader goes away.
void write_group_rows(std::ostream& out, const std::vector<std::string>& groups,
                      std::span<const Rgb> values);

} // namespace radfmt::detail
