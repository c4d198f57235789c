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
// What this job may use: the least of physical memory, its cgroups' memory limits (v2
// memory.max, v1 memory.limit_in_bytes, up the hierarchy: a Slurm --mem, a container) and the
// address-space limit (ulimit -v, RLIMIT_AS); `source` says which it was.
std::uint64_t job_memory_bytes(std::string* source = nullptr);
// The share of it a tool takes for its own when given no limit (--max-memory,
// --import-memory): room for the rest of the job.
inline constexpr double kDefaultMemoryShare = 0.8;
std::string human_bytes(double bytes);

} // namespace rad
