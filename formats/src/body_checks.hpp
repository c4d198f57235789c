// Checks a reader makes of a body against its header (internal to radformats).
#pragma once
#include "radfmt/container.hpp"

#include <cstdint>

namespace radfmt::detail {

// The header's count of `key`, when it has one, must be what the body holds.
void require_count(const Header& header, const char* key, std::uint64_t count, BodyReader& r);

} // namespace radfmt::detail
