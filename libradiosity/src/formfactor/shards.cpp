// Shards of the form-factor matrix: rows computed apart (rad-ff --rows, on many machines)
// and merged into the file one run would have written, byte for byte.
#include "radfmt/chain.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/numbers.hpp"

#include <algorithm>
#include <cmath>

namespace rad {

namespace {
constexpr const char* kOutputPlaceholder = "@@RAD_FF_MERGED_OUTPUT@@";
// Header fields only a part has; the rest must agree between parts and go into the merge.
bool part_only(const std::string& key) {
    return key == "rows_begin" || key == "rows_end" || key == "unsharded_command";
}

// A row number or count: a whole number from 0 to 1e15.
bool parse_whole_number(const std::string& text, std::uint64_t& out) {
    double value = 0;
    if (!parse_number(text, value) || value < 0 || value != std::floor(value) || value > 1e15)
        return false;
    out = static_cast<std::uint64_t>(value);
    return true;
}

std::uint64_t whole_number(const std::string& text, const std::string& what) {
    std::uint64_t value = 0;
    if (!parse_whole_number(text, value))
        throw InputError("--rows: " + what + " '" + text + "' is not a row number");
    return value;
}

// A count recorded in a part's header (checked against its body when the body is read).
std::uint64_t header_number(const radfmt::Header& header, const std::string& key,
                            const std::string& path) {
    const auto& text = header.get(key, path);
    std::uint64_t value = 0;
    if (!parse_count(text, value))
        throw radfmt::FormatError(path + ": corrupt header: " + key + " '" + text +
                                  "' is not a whole number");
    return value;
}
} // namespace

Shard parse_shard(const std::string& text, std::uint64_t patches, const std::string& what) {
    const auto slash = text.find('/');
    if (slash == std::string::npos || text.find(':') != std::string::npos)
        throw InputError("--rows '" + text + "' is not K/N (shard K of N, from 0)");
    const auto shard = whole_number(text.substr(0, slash), "shard");
    const auto shards = whole_number(text.substr(slash + 1), "shard count");
    if (shards == 0 || shard >= shards || shards > patches)
        throw InputError("--rows " + text + ": shard K/N needs 0 <= K < N <= " +
                         std::to_string(patches) + " (" + what + ")");
    return {shard, shards};
}

RowRange parse_rows(const std::string& text, std::uint64_t patches, const std::string& what) {
    const auto colon = text.find(':'), slash = text.find('/');
    RowRange range;
    if (colon != std::string::npos && slash == std::string::npos) {
        range.begin = whole_number(text.substr(0, colon), "first row");
        range.end = whole_number(text.substr(colon + 1), "end row");
        if (!(range.begin < range.end) || range.end > patches)
            throw InputError("--rows " + text + ": rows A:B need 0 <= A < B <= " +
                             std::to_string(patches) + " (" + what + "; B is excluded)");
        return range;
    }
    if (slash != std::string::npos && colon == std::string::npos) {
        const auto [shard, shards] = parse_shard(text, patches, what);
        // Shard k of n: rows [k p / n, (k + 1) p / n), so the shards cover every row once.
        range.begin = shard * patches / shards;
        range.end = (shard + 1) * patches / shards;
        return range;
    }
    throw InputError("--rows '" + text +
                     "' is neither A:B (rows A to B, B excluded) nor K/N "
                     "(shard K of N, from 0)");
}

std::string unsharded_command(int argc, const char* const* argv) {
    std::vector<const char*> kept;
    for (int i = 0; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--rows") {
            ++i;
            continue;
        }
        if (arg.rfind("--rows=", 0) == 0) continue;
        if ((arg == "-o" || arg == "--output") && i + 1 < argc) {
            kept.push_back(argv[i]);
            kept.push_back(kOutputPlaceholder);
            ++i;
            continue;
        }
        if (arg.rfind("--output=", 0) == 0 || (arg.rfind("-o", 0) == 0 && arg.size() > 2)) {
            kept.push_back("-o");
            kept.push_back(kOutputPlaceholder);
            continue;
        }
        kept.push_back(argv[i]);
    }
    return radfmt::command_line(static_cast<int>(kept.size()), kept.data());
}

void require_row_cover(std::vector<RowPart> parts, std::uint64_t n, const std::string& what) {
    std::sort(parts.begin(), parts.end(),
              [](const auto& a, const auto& b) { return a.begin < b.begin; });
    std::uint64_t next = 0;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const auto& p = parts[k];
        if (p.begin > next)
            throw InputError(what + " " + std::to_string(next) + " to " +
                             std::to_string(p.begin - 1) +
                             " are in no part (compute them with --rows " + std::to_string(next) +
                             ":" + std::to_string(p.begin) + ")");
        if (p.begin < next)
            throw InputError(what + " " + std::to_string(p.begin) + " to " +
                             std::to_string(std::min(next, p.end) - 1) +
                             " are in two parts: " + parts[k - 1].path + " and " + p.path);
        next = p.end;
    }
    if (next < n)
        throw InputError(what + " " + std::to_string(next) + " to " + std::to_string(n - 1) +
                         " are in no part (compute them with --rows " + std::to_string(next) + ":" +
                         std::to_string(n) + ")");
}

std::string command_with_output(std::string command, const std::string& output,
                                const std::string& part_path) {
    const char* quoted[] = {"x", output.c_str()};
    const auto output_text = radfmt::command_line(2, quoted).substr(2);
    const auto at = command.find(kOutputPlaceholder);
    if (at == std::string::npos)
        throw InputError(part_path + ": its recorded command has no output to replace");
    command.replace(at, std::string(kOutputPlaceholder).size(), output_text);
    return command;
}

std::string merged_command(const radfmt::Header& part, const std::string& part_path,
                           const std::string& output) {
    return command_with_output(part.get("unsharded_command", part_path), output, part_path);
}

std::uint64_t part_row(const radfmt::Header& header, const std::string& key,
                       const std::string& path) {
    return header_number(header, key, path);
}

MergedFormFactors merge_form_factor_parts(const std::vector<std::string>& paths,
                                          const std::string& output, std::uint64_t memory_budget) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    // The headers say what each part is; the bodies are read one at a time, at the end.
    std::vector<FormFactorPart> parts;
    for (const auto& path : paths) {
        const auto kind = radfmt::Kind::FormFactorPart;
        FormFactorPart part{path, radfmt::read_header(path, &kind)};
        part.begin = header_number(part.header, "rows_begin", path);
        part.end = header_number(part.header, "rows_end", path);
        parts.push_back(std::move(part));
    }
    const auto& first = parts.front();
    // The same matrix: same mesh, method, options, seed and tool, field for field.
    for (const auto& p : parts) {
        auto differs = [&](const std::string& what, const std::string& a, const std::string& b) {
            if (a != b)
                throw InputError(p.path + " and " + first.path + " are parts of different " +
                                 "form factors: " + what + " " + b + " against " + a +
                                 " (compute every part with the same mesh and options)");
        };
        differs("tool", first.header.tool, p.header.tool);
        differs("mesh", first.header.inputs.empty() ? "" : first.header.inputs[0].hash,
                p.header.inputs.empty() ? "" : p.header.inputs[0].hash);
        for (const auto& [key, value] : first.header.fields)
            if (!part_only(key) && key != "nonzeros" && key != "rays_started_inside")
                differs(key, value, p.header.get(key, p.path));
        for (const auto& [key, value] : p.header.fields)
            if (!first.header.find(key)) differs(key, "(none)", value);
        differs("command (without --rows and -o)",
                first.header.get("unsharded_command", first.path),
                p.header.get("unsharded_command", p.path));
    }
    // Every row exactly once.
    std::vector<RowPart> cover;
    for (const auto& p : parts) cover.push_back({p.path, p.begin, p.end});
    const std::uint64_t n = header_number(first.header, "patches", first.path);
    require_row_cover(cover, n);
    std::sort(parts.begin(), parts.end(),
              [](const auto& a, const auto& b) { return a.begin < b.begin; });

    std::uint64_t started_inside = 0;
    for (const auto& p : parts)
        if (p.header.find("rays_started_inside"))
            started_inside += header_number(p.header, "rays_started_inside", p.path);
    // The header one run would have written: its command, its fields in its order.
    MergedFormFactors out;
    out.header = first.header;
    out.header.kind = radfmt::Kind::FormFactors;
    out.header.version = 0;
    std::erase_if(out.header.fields, [](const auto& f) { return part_only(f.first); });
    out.header.set("rays_started_inside", std::to_string(started_inside));
    const auto command = merged_command(first.header, first.path, output);
    out.header.command = command;

    // The rows, part after part, through a spool: one part is read at a time, and what does
    // not fit in the budget beside it waits on disk.
    radfmt::FormFactorSpool spool(n, radfmt::FormFactorSpool::folder_for(output), memory_budget,
                                  radfmt::formfactors_hit_denominator(out.header));
    for (const auto& p : parts) {
        std::uint64_t begin = 0, end = 0;
        const auto ff = radfmt::read_form_factor_part(p.path, nullptr, &begin, &end);
        if (begin != p.begin || end != p.end || ff.patch_count != n)
            throw InputError(p.path + ": changed while it was merged");
        for (std::uint64_t i = begin; i < end; ++i) {
            const auto from = ff.row_start[i], count = ff.row_start[i + 1] - from;
            spool.add_row(std::span(ff.columns).subspan(from, count),
                          std::span(ff.values).subspan(from, count), ff.back_fraction[i]);
            if (!ff.row_error.empty()) spool.add_row_error(ff.row_error[i]);
        }
    }
    out.rows = spool.rows();
    out.nonzeros = spool.nonzeros();
    radfmt::write_form_factors(output, out.header, spool);
    return out;
}

std::vector<RowPart> patch_row_parts(const std::vector<std::string>& paths, radfmt::Kind kind,
                                     const std::string& what,
                                     std::vector<radfmt::Header>& headers) {
    if (paths.empty()) throw InputError("--merge needs the part files to merge");
    headers.clear();
    std::vector<RowPart> cover;
    for (const auto& path : paths) {
        headers.push_back(radfmt::read_header(path, &kind));
        if (!headers.back().find("rows_begin"))
            throw InputError(path + " is a whole " + std::string(radfmt::kind_name(kind)) +
                             " file, not a part (rad-ff --rows)");
        cover.push_back({path, part_row(headers.back(), "rows_begin", path),
                         part_row(headers.back(), "rows_end", path)});
    }
    const auto& first = headers.front();
    for (std::size_t k = 0; k < headers.size(); ++k) {
        const auto& h = headers[k];
        auto same = h.tool == first.tool && h.inputs.size() == first.inputs.size();
        for (std::size_t i = 0; same && i < h.inputs.size(); ++i)
            same = h.inputs[i].hash == first.inputs[i].hash;
        for (const auto& [key, value] : first.fields)
            if (same && !part_only(key)) same = h.find(key) && *h.find(key) == value;
        same = same && h.get("unsharded_command", paths[k]) ==
                           first.get("unsharded_command", paths.front());
        if (!same)
            throw InputError(paths[k] + " and " + paths.front() + " are parts of different " +
                             what + " (other mesh, inputs or options): compute every part alike");
    }
    return cover;
}

radfmt::Header merged_part_header(const radfmt::Header& first, const std::string& first_path,
                                  const std::string& output) {
    auto header = first;
    header.version = 0;
    header.command = merged_command(first, first_path, output);
    std::erase_if(header.fields, [&](const auto& f) { return part_only(f.first); });
    return header;
}

} // namespace rad
