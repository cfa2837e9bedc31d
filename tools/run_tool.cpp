#include "tools/run_tool.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <new>
#include <sys/resource.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::tools {
namespace {

std::string one_line(std::string text)
{
    for (char& c : text)
        if (c == '\n' || c == '\r') c = ' ';
    return text;
}

/// Prints progress on stderr: a rewritten line on a terminal, a line per tenth otherwise.
class StderrProgress {
public:
    explicit StderrProgress(int verbosity) : verbosity_(verbosity), terminal_(::isatty(STDERR_FILENO) != 0) {}

    void fraction(std::string_view stage, double value)
    {
        if (verbosity_ < 1) return;
        std::lock_guard lock(mutex_);
        const int percent = static_cast<int>(value * 100.0 + 0.5);
        if (terminal_) {
            std::fprintf(stderr, "\r[%.*s] %3d%%%s", static_cast<int>(stage.size()), stage.data(), percent,
                         percent >= 100 ? "\n" : "");
            return;
        }
        // In logs, a line per tenth, and only for stages that run long enough for progress to matter.
        const auto now = std::chrono::steady_clock::now();
        auto [entry, inserted] = stages_.try_emplace(std::string(stage), StageState{now, -1});
        if (entry->second.last_decile < 0 && now - entry->second.start < std::chrono::seconds(2)) return;
        const int decile = percent / 10;
        if (decile > entry->second.last_decile) {
            entry->second.last_decile = decile;
            std::fprintf(stderr, "[%.*s] %d%%\n", static_cast<int>(stage.size()), stage.data(), decile * 10);
        }
    }

    void message(LogLevel level, std::string_view stage, std::string_view text)
    {
        if (level == LogLevel::debug && verbosity_ < 2) return;
        if (level == LogLevel::info && verbosity_ < 1) return;
        std::lock_guard lock(mutex_);
        std::fprintf(stderr, "[%.*s] %s%.*s\n", static_cast<int>(stage.size()), stage.data(),
                     level == LogLevel::warning ? "warning: " : "", static_cast<int>(text.size()), text.data());
    }

private:
    int verbosity_;
    bool terminal_;
    std::mutex mutex_;
    struct StageState {
        std::chrono::steady_clock::time_point start;
        int last_decile;
    };
    std::map<std::string, StageState> stages_;
};

/// Peak resident memory of this process so far, or of a child it waited for (TetGen runs in one) when that
/// was larger, in MiB. A forked child's pages are shared with the parent until written, so the larger of
/// the two peaks is the better guess of what the machine had to hold.
double peak_memory_mb()
{
    rusage self{}, children{};
    ::getrusage(RUSAGE_SELF, &self);
    ::getrusage(RUSAGE_CHILDREN, &children);
    return static_cast<double>(std::max(self.ru_maxrss, children.ru_maxrss)) / 1024.0; // ru_maxrss is in KiB on Linux
}

/// Why the --json summary cannot be written at `path`, or "" when its folder exists and takes files. Checked
/// before the work, so that a run never ends with its outputs written and its summary refused.
std::string summary_path_problem(const std::filesystem::path& path)
{
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored)) return "it is a folder; give a file name";
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(folder, ignored))
        return concat("its folder ", folder.string(), " does not exist; create it or give another path");
    if (::access(folder.c_str(), W_OK) != 0)
        return concat("its folder ", folder.string(), " is not writable; give a path in a folder you can write");
    return "";
}

/// Writes the --json summary; false (the error on stderr) when it cannot be written: the run then did not
/// deliver what was asked, and its exit code says so.
bool write_summary(const std::string& path, nlohmann::json summary, const std::string& tool)
{
    try {
        write_text_atomically(path, summary.dump(2) + "\n");
        return true;
    } catch (const Error& error) {
        std::fprintf(stderr, "%s: error: %s\n", tool.c_str(), one_line(error.what()).c_str());
        return false;
    }
}

} // namespace

void ToolContext::log(std::string_view text) const { progress.info(tool, text); }

int run_tool(int argc, char** argv, const ToolSpec& spec, const std::function<void(CLI::App&)>& add_options,
             const std::function<void(ToolContext&)>& body)
{
    CLI::App app(spec.description, spec.name);
    app.footer(spec.examples);
    app.set_version_flag("--version", std::string(spec.name) + " (tissuemesh) " TM_VERSION);
    app.get_formatter()->column_width(34);
    std::string json_path;
    bool verbose = false;
    bool quiet = false;
    app.add_option("--json", json_path, "Write a JSON summary (counts, measures, timings) to FILE")->type_name("FILE");
    app.add_flag("-v,--verbose", verbose, "More detail on stderr");
    app.add_flag("-q,--quiet", quiet, "Only errors on stderr");
    double max_memory_mib = 0;
    app.add_option("--max-memory", max_memory_mib,
                   "Refuse inputs that would need more than MIB MiB (default: the memory available at the start)")
        ->type_name("MIB")
        ->check(CLI::PositiveNumber);
    // Hidden: the test of every tool's --help examples parses them with the tool's own options (tests/help_cli).
    bool parse_only = false;
    app.add_flag("--parse-only", parse_only, "Check the command line, then exit without reading or writing")->group("");
    add_options(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: error: %s; see %s --help\n", spec.name.c_str(), one_line(e.what()).c_str(),
                     spec.name.c_str());
        return 2;
    }
    if (parse_only) return 0;
    if (!json_path.empty()) {
        if (const std::string problem = summary_path_problem(json_path); !problem.empty()) {
            std::fprintf(stderr, "%s: error: --json %s: %s\n", spec.name.c_str(), json_path.c_str(), problem.c_str());
            return 2;
        }
    }

    ToolContext context;
    context.tool = spec.name;
    context.verbosity = quiet ? 0 : (verbose ? 2 : 1);
    // The default: what the machine has available, plus what this program already holds of it.
    const std::uint64_t program_bytes = resident_memory_bytes(), available = available_memory_bytes();
    context.memory = max_memory_mib > 0
                         ? MemoryLimit{static_cast<std::uint64_t>(max_memory_mib * 1048576.0), true, program_bytes}
                         : MemoryLimit{available > 0 ? available + program_bytes : 0, false, program_bytes};
    auto printer = std::make_shared<StderrProgress>(context.verbosity);
    context.progress =
        Progress([printer](std::string_view stage, double fraction) { printer->fraction(stage, fraction); },
                 [printer](LogLevel level, std::string_view stage, std::string_view text) {
                     printer->message(level, stage, text);
                 });

    const auto start = std::chrono::steady_clock::now();
    int code = 0;
    std::string message;
    try {
        body(context);
    } catch (const InputError& e) {
        code = 2, message = e.what();
    } catch (const IoError& e) {
        code = 2, message = e.what();
    } catch (const AlgorithmError& e) {
        code = 1, message = e.what();
    } catch (const std::bad_alloc&) {
        code = 1, message = "out of memory; try a coarser spacing (tm-prep --spacing-mm) or a smaller crop";
    } catch (const std::exception& e) {
        code = 1, message = concat("internal error: ", e.what(), "; please report it with the input");
    }
    if (code == 0) code = context.exit_code;
    const double seconds = seconds_since(start);
    if (!message.empty()) std::fprintf(stderr, "%s: error: %s\n", spec.name.c_str(), one_line(message).c_str());

    if (!json_path.empty()) {
        nlohmann::json summary = {{"tool", spec.name}, {"version", TM_VERSION}, {"status", code == 0 ? "ok" : "failed"},
                                  {"exit_code", code}, {"seconds", seconds},    {"peak_memory_mb", peak_memory_mb()}};
        if (!message.empty()) summary["error"] = message;
        summary.update(context.summary);
        if (!write_summary(json_path, summary, spec.name) && code == 0) code = 2;
    }
    return code;
}

} // namespace tissuemesh::tools
