// The one place where tools parse common flags, report progress, write the JSON summary and turn
// errors into exit codes: 0 done, 1 the step failed on valid input, 2 bad usage or bad input.
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/progress.h"
#include "tools/memory_limit.h"

namespace tissuemesh::tools {

/// What a tool's body gets: a Progress that prints on stderr, and a summary it fills with counts,
/// measures and timings (written to --json FILE when asked, with "tool", "version", "status", "seconds").
struct ToolContext {
    Progress progress;
    nlohmann::json summary = nlohmann::json::object();
    int verbosity = 1; ///< 0 with -q, 1 by default, 2 with -v
    std::string tool;
    /// A checker that ran to the end but found the input unfit sets 1 here (errors still throw).
    int exit_code = 0;
    /// --max-memory MIB, else the memory available when the tool started: steps whose needs follow from
    /// their input check it before their big allocations (require_memory, image_memory_check).
    MemoryLimit memory;

    /// Prints "[tool] text" on stderr unless quiet.
    void log(std::string_view text) const;
};

/// Seconds since `start` on the steady clock, for the timings of the summaries and the log.
inline double seconds_since(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Runs `step` on data read from `source` (a file name): an InputError it throws about the data gets the
/// file's name in front, so the one error line says which file is at fault.
template <typename Step>
auto with_source(const std::string& source, Step&& step) -> decltype(step())
{
    try {
        return step();
    } catch (const InputError& error) {
        throw InputError(concat(source, ": ", error.what()));
    }
}

struct ToolSpec {
    std::string name;        ///< "tm-info"
    std::string description; ///< one paragraph for --help
    std::string examples;    ///< shown at the end of --help; every command in it (a line "  tm-...") must parse
                             ///< (tests/help_cli)
};

/// Parses the command line (adding -v/-q/--json/--version/--max-memory, and the hidden --parse-only that stops
/// after parsing, to the tool's own options), runs `body`,
/// writes the summary, and maps exceptions to exit codes with one line on stderr:
///     tm-info: error: head.nii: spacing along axis 2 is 0 mm; ...
int run_tool(int argc, char** argv, const ToolSpec& spec, const std::function<void(CLI::App&)>& add_options,
             const std::function<void(ToolContext&)>& body);

} // namespace tissuemesh::tools
