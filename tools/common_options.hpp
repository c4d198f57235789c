// The options several tools share, declared in one place (#71): the same names, checks,
// defaults and help grammar in every tool; each tool binds the ones it takes to its own
// fields and says, in a few words, what the option governs there.
#pragma once
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace rad::tool {

struct CommonOptions {
    // --threads N (0: all cores).
    int* threads = nullptr;
    // --seed: `seed_help` says what it seeds.
    std::uint64_t* seed = nullptr;
    std::string seed_help{};
    // -q,--quiet: no summary, and no progress when the tool shows any.
    bool* quiet = nullptr;
    bool shows_progress = false;
    // -v,--verbose: `verbose_help` says what it prints.
    bool* verbose = nullptr;
    std::string verbose_help{};
    // --max-memory SIZE: "Refuse <max_memory_refuses> estimated to need more memory than
    // this" (e.g. "a run", "light groups whose channels are"); the default is every tool's
    // (memory_limit).
    std::string* max_memory = nullptr;
    std::string max_memory_refuses{};
    // --rows A:B|K/N and --merge (excluding each other): `rows_unit` names what is split
    // ("rows", "sensors", "image rows"), `rows_extra` any tool-specific note, `merge_result`
    // what --merge writes from the parts.
    std::string* rows = nullptr;
    bool* merge = nullptr;
    std::string tool{}, rows_unit{}, rows_extra{}, merge_result{};
};

// Declares every option `common` binds, in a "Common options" group of --help. Returns the
// --rows option (nullptr when not bound), whose count() says whether it was given.
CLI::Option* add_common_options(CLI::App& app, const CommonOptions& common);

} // namespace rad::tool
