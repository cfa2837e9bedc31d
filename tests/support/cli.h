// Test helpers: temporary folders and running the tm-<verb> programs as a user would.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tissuemesh::testing {

/// A fresh folder under the system's temporary directory, removed with its contents on destruction.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
    /// Names of the files in the folder, sorted (to check that failures leave nothing behind).
    std::vector<std::string> files() const;

private:
    std::filesystem::path path_;
};

struct CliResult {
    int exit_code = -1;
    std::string out; ///< standard output
    std::string err; ///< standard error
};

/// Runs the program `tool` (e.g. "tm-info") from the build's bin folder with `args` (no shell
/// interpretation) and returns its exit code and output.
CliResult run_cli(const std::string& tool, const std::vector<std::string>& args);

/// Runs any program (a path, or a name looked up in PATH, e.g. "make") with `args`, no shell, in
/// `working_dir` when given (exit code 126 when it cannot go there).
CliResult run_program(const std::string& program, const std::vector<std::string>& args,
                      const std::filesystem::path& working_dir = {});

/// Parses a JSON file (a --json summary); throws when it is missing or malformed.
nlohmann::json read_json(const std::filesystem::path& path);

/// The bytes of the file at `path` ("" when it cannot be read).
std::string read_text(const std::filesystem::path& path);

/// Writes `text` to `path` byte for byte (replacing the file).
void write_text(const std::filesystem::path& path, const std::string& text);

/// Path of a file under the repository's data/ folder.
std::filesystem::path data_path(const std::string& relative);

} // namespace tissuemesh::testing
