#include "tests/cohort_cli/cohort_support.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

namespace tissuemesh::testing {
namespace fs = std::filesystem;

namespace {

void expect_ok(const CliResult& result, const std::string& what)
{
    if (result.exit_code != 0) throw std::runtime_error(what + " failed: " + result.err);
}

/// names.json ({"1": "scalp"} or {"labels": {...}}) as a BIDS dseg.tsv.
void write_dseg_tsv(const fs::path& names_json, const fs::path& tsv)
{
    nlohmann::json names = read_json(names_json);
    if (names.contains("labels")) names = names["labels"];
    std::ofstream out(tsv);
    out << "index\tname\n";
    for (const auto& [label, name] : names.items())
        if (label != "0") out << label << '\t' << name.get<std::string>() << '\n';
}

/// Moves `image` (and its names) into root/sub-XX/anat/ as sub-XX_dseg.nii.gz and sub-XX_dseg.tsv.
void add_subject(const fs::path& root, const std::string& subject, const fs::path& image, const fs::path& names)
{
    const fs::path anat = root / subject / "anat";
    fs::create_directories(anat);
    fs::copy_file(image, anat / (subject + "_dseg.nii.gz"));
    write_dseg_tsv(names, anat / (subject + "_dseg.tsv"));
}

} // namespace

fs::path snakemake_folder() { return data_path("workflows/snakemake"); }

void make_bids_cohort(const fs::path& root)
{
    const fs::path scratch = root.parent_path() / "phantoms";
    fs::create_directories(scratch);
    for (const auto& [subject, phantom] : {std::pair{"sub-01", "junction"}, std::pair{"sub-02", "boxes"}}) {
        const fs::path image = scratch / (std::string(phantom) + ".nii.gz");
        expect_ok(run_cli("tm-phantom", {phantom, "--voxel-mm", "4", "-o", image.string(), "-q"}), "tm-phantom");
        add_subject(root, subject, image, scratch / (std::string(phantom) + ".labels.json"));
    }
    const fs::path head = scratch / "head.nii.gz";
    expect_ok(run_cli("tm-prep", {"-i", data_path("samples/usc19-5_head.nii.gz").string(), "-o", head.string(),
                                  "--spacing-mm", "8", "-q"}),
              "tm-prep");
    add_subject(root, "sub-03", head, data_path("samples/usc19-5_head.json"));
}

std::vector<std::string> cohort_config() { return {"params={REMESH_ARGS: --edge-mm 8, REFINE_ARGS: --iterations 1}"}; }

std::vector<std::string> cohort_make_variables() { return {"REMESH_ARGS=--edge-mm 8", "REFINE_ARGS=--iterations 1"}; }

void add_broken_subject(const fs::path& root)
{
    const fs::path anat = root / "sub-04" / "anat";
    fs::create_directories(anat);
    const std::string whole = read_text(root / "sub-01" / "anat" / "sub-01_dseg.nii.gz");
    std::ofstream(anat / "sub-04_dseg.nii.gz", std::ios::binary) << whole.substr(0, whole.size() / 2);
    fs::copy_file(root / "sub-01" / "anat" / "sub-01_dseg.tsv", anat / "sub-04_dseg.tsv");
    const fs::path names = root / "sub-05" / "anat";
    fs::create_directories(names);
    fs::copy_file(root / "sub-02" / "anat" / "sub-02_dseg.nii.gz", names / "sub-05_dseg.nii.gz");
    std::ofstream(names / "sub-05_dseg.tsv") << "index\tlabel\n1\tcube\n";
}

CliResult run_snakemake(const fs::path& folder, const std::vector<std::string>& args,
                        const std::vector<std::string>& environment)
{
    std::vector<std::string> command = environment;
    command.insert(command.end(), {"snakemake", "-s", (snakemake_folder() / "Snakefile").string()});
    command.insert(command.end(), args.begin(), args.end());
    return run_program("env", command, folder);
}

CliResult run_make(const fs::path& image, const fs::path& labels, const fs::path& out,
                   const std::vector<std::string>& extra)
{
    std::vector<std::string> args{"-C",
                                  data_path("workflows").string(),
                                  "IMAGE=" + image.string(),
                                  "LABELS=" + labels.string(),
                                  "OUT=" + out.string(),
                                  "BIN=" TM_TOOLS_DIR};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_program("make", args);
}

std::vector<std::string> model_files(const fs::path& folder)
{
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && entry.path().extension() != ".json" && name != "report.html" &&
            name != "refine.csv")
            names.push_back(name);
        else if (entry.is_regular_file() && name == "clean.labels.json")
            names.push_back(name); // tm-prep's output, no times
    }
    std::sort(names.begin(), names.end());
    return names;
}

bool same_bytes(const fs::path& a, const fs::path& b)
{
    return fs::exists(a) && fs::exists(b) && read_text(a) == read_text(b);
}

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& path)
{
    const std::string text = read_text(path);
    std::vector<std::vector<std::string>> records(1, std::vector<std::string>(1));
    bool quoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') records.back().back() += '"', ++i;
            else if (c == '"') quoted = false;
            else records.back().back() += c;
        } else if (c == '"') quoted = true;
        else if (c == ',') records.back().emplace_back();
        else if (c == '\n') records.emplace_back(1);
        else if (c != '\r') records.back().back() += c;
    }
    if (records.back().size() == 1 && records.back()[0].empty()) records.pop_back();
    std::vector<std::map<std::string, std::string>> rows;
    for (std::size_t r = 1; r < records.size(); ++r) {
        std::map<std::string, std::string> row;
        for (std::size_t c = 0; c < records[0].size() && c < records[r].size(); ++c) row[records[0][c]] = records[r][c];
        rows.push_back(row);
    }
    return rows;
}

std::map<std::string, fs::file_time_type> json_times(const fs::path& folder)
{
    std::map<std::string, fs::file_time_type> times;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.is_regular_file() && entry.path().extension() == ".json")
            times[entry.path().string()] = entry.last_write_time();
    return times;
}

std::vector<std::string> shell_words(const std::string& line)
{
    std::vector<std::string> words;
    std::string word;
    bool in_word = false;
    char quote = 0;
    for (const char c : line) {
        if (quote) {
            if (c == quote) quote = 0;
            else word += c;
        } else if (c == '\'' || c == '"') {
            quote = c, in_word = true;
        } else if (c == ' ' || c == '\t') {
            if (in_word) words.push_back(word), word.clear(), in_word = false;
        } else {
            word += c, in_word = true;
        }
    }
    if (in_word) words.push_back(word);
    return words;
}

} // namespace tissuemesh::testing
