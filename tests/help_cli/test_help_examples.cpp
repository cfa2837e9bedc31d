// Every command in every tool's --help examples parses with the tool's own options. Found by issue 32: the
// example of tm-tetra --help used --max-volume-tissue, which no version of tm-tetra had.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

namespace fs = std::filesystem;

/// tm-<verb> for every tools/tm_<verb>.cpp, as tools/CMakeLists.txt makes them.
std::vector<std::string> tool_names()
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(data_path("../tools"))) {
        std::string stem = entry.path().stem().string();
        if (!stem.starts_with("tm_") || entry.path().extension() != ".cpp") continue;
        std::replace(stem.begin(), stem.end(), '_', '-');
        names.push_back(stem);
    }
    std::sort(names.begin(), names.end());
    return names;
}

/// The words of a command line as a shell would split them: blanks separate, "..." groups, " #" starts a comment.
std::vector<std::string> shell_words(const std::string& line)
{
    std::vector<std::string> words;
    std::string word;
    bool quoted = false, in_word = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (c == '"') {
            quoted = !quoted, in_word = true;
        } else if (!quoted && (c == ' ' || c == '\t')) {
            if (in_word) words.push_back(word);
            word.clear(), in_word = false;
        } else if (!quoted && c == '#' && !in_word) {
            break;
        } else {
            word += c, in_word = true;
        }
    }
    if (in_word) words.push_back(word);
    return words;
}

/// The commands after "Examples:" in a --help text: lines starting "tm-", with their "\" continuations.
std::vector<std::vector<std::string>> example_commands(const std::string& help)
{
    std::vector<std::vector<std::string>> commands;
    std::istringstream lines(help.substr(std::min(help.find("Examples:"), help.size())));
    for (std::string line; std::getline(lines, line);) {
        line.erase(0, line.find_first_not_of(' '));
        if (!line.starts_with("tm-")) continue;
        for (std::string next; !line.empty() && line.back() == '\\' && std::getline(lines, next);)
            line = line.substr(0, line.size() - 1) + " " + next;
        commands.push_back(shell_words(line));
    }
    return commands;
}

/// A word that names a file or folder of the example (head.ply, out/head), not a number list (0,10,40 or 2.9).
bool is_path(const std::string& word)
{
    if (word.starts_with('-') || word.find_first_of("./") == std::string::npos) return false;
    return word.find_first_not_of("0123456789.,+-e") != std::string::npos;
}

TEST(HelpExamples, EveryExampleOfEveryToolParsesWithItsOptions)
{
    const std::vector<std::string> tools = tool_names();
    ASSERT_GE(tools.size(), 19u) << "the tools folder was not found";
    for (const std::string& tool : tools) {
        const CliResult help = run_cli(tool, {"--help"});
        ASSERT_EQ(help.exit_code, 0) << tool << ": " << help.err;
        const auto commands = example_commands(help.out);
        EXPECT_FALSE(commands.empty()) << tool << " --help shows no example";
        for (const std::vector<std::string>& command : commands) {
            // The files the example names exist (empty) in a folder of its own, so that options checking that a
            // file exists accept them; --parse-only then stops the tool before it reads anything.
            TempDir dir;
            std::vector<std::string> args(command.begin() + 1, command.end());
            for (const std::string& word : args)
                if (is_path(word)) {
                    const fs::path path = dir / word;
                    fs::create_directories(path.parent_path());
                    if (path.has_extension()) std::ofstream(path).put('\n');
                    else fs::create_directories(path);
                }
            args.push_back("--parse-only");
            const CliResult run = run_program(std::string(TM_TOOLS_DIR) + "/" + command.front(), args, dir.path());
            std::string shown = command.front();
            for (const std::string& arg : args) shown += " " + arg;
            EXPECT_EQ(run.exit_code, 0) << "example of " << tool << " --help: " << shown << "\n" << run.err;
        }
    }
}

} // namespace
} // namespace tissuemesh::testing
