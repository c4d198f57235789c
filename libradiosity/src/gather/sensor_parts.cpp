// Shards of rad-gather's sensors: the parts' preamble, and their merge into one run's output.
#include "radiosity/sensor_parts.hpp"

#include "radfmt/container.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/numbers.hpp"
#include "radiosity/text_input.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace rad {

namespace {
constexpr const char* kMagic = "#?rad-gather part 1";

// "#?key=value": the value, or InputError naming the file and line.
std::string preamble_value(LineReader& in, const std::string& path, const std::string& key) {
    std::string line;
    const std::string prefix = "#?" + key + "=";
    if (!in.next(line) || line.rfind(prefix, 0) != 0)
        throw InputError(path + ":" + std::to_string(in.line_number()) + ": expected '" + prefix +
                         "...' (is it a part from rad-gather --rows?)");
    return line.substr(prefix.size());
}

std::uint64_t whole(const std::string& text, const std::string& path, long line) {
    std::uint64_t value = 0;
    if (!parse_count(text, value))
        throw InputError(path + ":" + std::to_string(line) + ": '" + text +
                         "' is not a sensor number");
    return value;
}

struct ReadPart {
    std::string path;
    SensorPart part;
};

ReadPart read_preamble(const std::string& path, LineReader& in) {
    std::string line;
    if (!in.next(line) || line != kMagic)
        throw InputError(path + ":1: not a part from rad-gather --rows (its first line is not '" +
                         std::string(kMagic) + "')");
    ReadPart r{path, {}};
    const auto rows = preamble_value(in, path, "rows");
    const auto colon = rows.find(':'), of = rows.find(" of ");
    if (colon == std::string::npos || of == std::string::npos || of < colon)
        throw InputError(path + ":2: expected 'rows=A:B of N'");
    r.part.begin = whole(rows.substr(0, colon), path, 2);
    r.part.end = whole(rows.substr(colon + 1, of - colon - 1), path, 2);
    r.part.total = whole(rows.substr(of + 4), path, 2);
    if (r.part.begin > r.part.end || r.part.end > r.part.total)
        throw InputError(path + ":2: rows " + rows + " are not a range of the sensors");
    r.part.inputs = preamble_value(in, path, "inputs");
    r.part.command = preamble_value(in, path, "command");
    r.part.header_line = preamble_value(in, path, "header");
    return r;
}
} // namespace

namespace {
// A line of values as rad-gather writes them: one lux or three irradiances, numbers or nan.
bool is_value_line(const std::string& line) {
    std::istringstream words(line);
    int count = 0;
    for (std::string word; words >> word; ++count) {
        double value = 0;
        if (word != "nan" && !parse_number(word, value)) return false;
    }
    return count == 1 || count == 3;
}
} // namespace

std::string sensor_part_preamble(const SensorPart& part) {
    return std::string(kMagic) + "\n#?rows=" + std::to_string(part.begin) + ":" +
           std::to_string(part.end) + " of " + std::to_string(part.total) +
           "\n#?inputs=" + part.inputs + "\n#?command=" + part.command +
           "\n#?header=" + part.header_line + "\n";
}

std::uint64_t merge_sensor_parts(const std::vector<std::string>& paths, const std::string& output) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    std::vector<ReadPart> parts;
    for (const auto& path : paths) {
        LineReader in(path);
        parts.push_back(read_preamble(path, in));
    }
    const auto& first = parts.front();
    for (const auto& p : parts)
        if (p.part.inputs != first.part.inputs || p.part.command != first.part.command ||
            p.part.total != first.part.total || p.part.header_line != first.part.header_line)
            throw InputError(p.path + " and " + first.path +
                             " are parts of different runs (other mesh, radiosity, points or "
                             "options): compute every part with one command");
    std::vector<RowPart> cover;
    for (const auto& p : parts) cover.push_back({p.path, p.part.begin, p.part.end});
    require_row_cover(cover, first.part.total, "sensors");
    std::sort(parts.begin(), parts.end(),
              [](const auto& a, const auto& b) { return a.part.begin < b.part.begin; });

    radfmt::write_atomically(output, [&](const std::filesystem::path& temp) {
        std::FILE* out = std::fopen(temp.c_str(), "w");
        if (!out) throw SystemError(output + ": cannot open for writing: " + std::strerror(errno));
        bool ok = true;
        try {
            if (!first.part.header_line.empty()) {
                const auto line = command_with_output(first.part.header_line, output, first.path);
                ok = std::fprintf(out, "%s\n", line.c_str()) >= 0;
            }
            for (const auto& p : parts) {
                LineReader in(p.path);
                read_preamble(p.path, in);
                std::string line;
                std::uint64_t values = 0;
                const std::uint64_t want = p.part.end - p.part.begin;
                while (ok && in.next(line)) {
                    if (!is_value_line(line))
                        throw InputError(p.path + ":" + std::to_string(in.line_number()) +
                                         ": not a value line as rad-gather writes them (numbers "
                                         "or nan): the part was changed after it was written; "
                                         "compute it again");
                    ok = std::fprintf(out, "%s\n", line.c_str()) >= 0;
                    ++values;
                }
                if (values != want)
                    throw InputError(p.path + ": holds " + std::to_string(values) +
                                     " value line(s) for the " + std::to_string(want) +
                                     " sensors " + std::to_string(p.part.begin) + ":" +
                                     std::to_string(p.part.end) +
                                     (values < want ? " (it was cut short: compute it again)"
                                                    : " (lines were added after it was written: "
                                                      "compute it again)"));
            }
        } catch (...) {
            std::fclose(out);
            throw;
        }
        if (std::fclose(out) != 0 || !ok)
            throw SystemError(output + ": cannot write: " + std::strerror(errno));
    });
    return first.part.total;
}

} // namespace rad
