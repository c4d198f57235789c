#include "common_options.hpp"

#include "radiosity/numbers.hpp"
#include "radiosity/progress.hpp"

#include <cmath>

namespace rad::tool {
namespace {

void add_shard_options(CLI::App& group, const CommonOptions& c, CLI::Option*& rows) {
    rows = group
               .add_option("--rows", *c.rows,
                           "Compute only these " + c.rows_unit + " into a part file: A:B (" +
                               c.rows_unit +
                               " A to B, B excluded, from 0) or K/N (shard K of "
                               "N, e.g. $SLURM_ARRAY_TASK_ID/16" +
                               c.rows_extra + "); " + c.tool + " --merge joins the parts")
               ->check(CLI::Validator(
                   [](const std::string& text) {
                       return text.empty() ? std::string("empty: give A:B or K/N (leave --rows "
                                                         "out for all of them)")
                                           : std::string();
                   },
                   "A:B|K/N"));
    auto* merge = group.add_flag("--merge", *c.merge,
                                 "Join part files (" + c.tool + " --rows) into " + c.merge_result +
                                     ", byte for byte; every part once");
    merge->excludes(rows);
}

} // namespace

CLI::Option* add_common_options(CLI::App& app, const CommonOptions& c) {
    auto* group = app.add_option_group("Common options",
                                       "Declared once for every tool that takes them: the same "
                                       "names, checks and defaults");
    CLI::Option* rows = nullptr;
    if (c.rows && c.merge) add_shard_options(*group, c, rows);
    if (c.seed)
        group->add_option("--seed", *c.seed, "Seed for " + c.seed_help)->capture_default_str();
    if (c.threads)
        group->add_option("--threads", *c.threads, "Worker threads (0: all cores)")
            ->capture_default_str()
            ->check(CLI::Range(0, ThreadLimit::max_threads()));
    if (c.max_memory)
        group->add_option("--max-memory", *c.max_memory,
                          "Refuse " + c.max_memory_refuses +
                              " estimated to need more memory than this, before the work "
                              "starts (e.g. 4G, 512M; default: " +
                              std::to_string(std::lround(100 * kDefaultMemoryShare)) +
                              "% of what the job may use: physical memory, its cgroup limit or "
                              "ulimit -v, the least)");
    if (c.quiet)
        group->add_flag("-q,--quiet", *c.quiet,
                        c.shows_progress ? "No progress and no summary (progress shows only "
                                           "on a terminal)"
                                         : "No summary");
    if (c.verbose) group->add_flag("-v,--verbose", *c.verbose, c.verbose_help);
    return rows;
}

} // namespace rad::tool
