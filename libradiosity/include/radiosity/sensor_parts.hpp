// Shards of rad-gather's sensors (rad-gather --rows, then --merge): each part is a text file
// of the values of sensors [begin, end) of `total`, behind a few '#?' lines that say which
// sensors, of which inputs and command; the merge writes what one run would have written.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace rad {

struct SensorPart {
    std::uint64_t begin = 0, end = 0, total = 0;
    std::string inputs;      // the inputs' hashes (mesh, radiosity, points or grid)
    std::string command;     // the command without --rows, -o's value a placeholder
    std::string header_line; // the '#' line one run would start with (--header), or empty
};

// The '#?' lines that start a part, each ending in a newline.
std::string sensor_part_preamble(const SensorPart& part);

// Joins parts into `output` (atomically): every sensor exactly once (InputError naming the
// sensors in no part, or in two, and the --rows that computes them), the parts of one run
// (same inputs and command), values in order. Returns the number of sensors.
std::uint64_t merge_sensor_parts(const std::vector<std::string>& paths, const std::string& output);

} // namespace rad
