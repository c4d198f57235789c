// Names in the chain's files (groups, materials, light groups): one rule for every output.
// A name is UTF-8 text of 1 to kMaxNameBytes bytes with no control character (no newline, no
// tab, no NUL), so that every writer (headers' key=value lines, glTF's JSON, EXR channel names
// "NAME.R" of at most 255 bytes, CSV) can take it as it is, and every file reads back.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace radfmt {

inline constexpr std::size_t kMaxNameBytes = 200;

// Why `name` is not a name of the chain ("" when it is one).
std::string name_problem(std::string_view name);

// The name made one: bytes that are not UTF-8 read as Latin-1 (each byte its code point, as
// older exporters write them), control characters as '?', cut at kMaxNameBytes on a
// character's boundary (an empty name: "unnamed"). A name that is one comes back unchanged.
std::string clean_name(std::string_view name);

// A name as a message shows it: at most 40 bytes, bytes that are not UTF-8 as \xHH, control
// characters as \n, \t or \xHH.
std::string shown_name(std::string_view name);

} // namespace radfmt
