// Base64 (RFC 4648, with padding), in lines of 76 characters: bytes inside an HTML page (the
// viewer's glb, a report's images as data: URLs, whose parser drops the line breaks).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rad {

std::string base64(const std::vector<std::uint8_t>& bytes);

} // namespace rad
