// The one place where tools parse common flags, report progress, write the JSON summary and turn
// errors into exit codes: 0 done, 1 the step failed on valid input, 2 bad usage or bad input.
#pragma once

#include <functional>
#include <string>
#include <string_view>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/progress.h"

namespace tissuemesh::tools {

/// What a tool's body gets: a Progress that prints on stderr, and a summary it fills with counts,
/// measures and timings (written to --json FILE when asked, with "tool", "version", "status", "seconds").
struct ToolContext {
    Progress progress;
    nlohmann::json summary = nlohmann::json::object();
    int verbosity = 1;  ///< 0 with -q, 1 by default, 2 with -v
    std::string tool;
    /// A checker that ran to the end but found the input unfit sets 1 here (errors still throw).
    int exit_code = 0;

    /// Prints "[tool] text" on stderr unless quiet.
    void log(std::string_view text) const;
};

struct ToolSpec {
    std::string name;         ///< "tm-info"
    std::string description;  ///< one paragraph for --help
    std::string examples;     ///< shown at the end of --help
};

/// Parses the command line (adding -v/-q/--json/--version to the tool's own options), runs `body`,
/// writes the summary, and maps exceptions to exit codes with one line on stderr:
///     tm-info: error: head.nii: spacing along axis 2 is 0 mm; ...
int run_tool(int argc, char** argv, const ToolSpec& spec, const std::function<void(CLI::App&)>& add_options,
             const std::function<void(ToolContext&)>& body);

} // namespace tissuemesh::tools
