// data/workflows/snakemake on one machine: a BIDS cohort of three subjects (two phantoms and the real head at 8 mm)
// meshed by `snakemake --cores 2` into the same bytes as the Makefile, a second run that does nothing, a broken
// subject listed in the summary with its error while the others stay done; and the Snakefile's command lines
// against the Makefile's for defaults, a preset, per-subject flags and overrides.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tests/cohort_cli/cohort_support.h"

namespace tissuemesh::testing {
namespace {

namespace fs = std::filesystem;

const char* const subjects[] = {"sub-01", "sub-02", "sub-03"};

TEST(CohortCli, SnakemakeMeshesLikeTheMakefileAndABrokenSubjectStaysInTheSummary)
{
    TempDir dir;
    const fs::path bids = dir / "bids", out = bids / "derivatives" / "tissuemesh";
    make_bids_cohort(bids);
    std::vector<std::string> run{"--cores",          "2", "--keep-going", "--config", "bids=" + bids.string(),
                                 "bin=" TM_TOOLS_DIR};
    for (const std::string& setting : cohort_config()) run.push_back(setting);
    CliResult result = run_snakemake(dir.path(), run);
    ASSERT_EQ(result.exit_code, 0) << result.out << result.err;

    // BIDS-derivatives top level, and every subject to the end of the chain.
    EXPECT_EQ(read_json(out / "dataset_description.json")["DatasetType"], "derivative");
    for (const char* subject : subjects) {
        EXPECT_EQ(read_json(out / subject / "check-mesh.json")["ok"], true) << subject;
        EXPECT_TRUE(fs::exists(out / subject / "report.html")) << subject;
    }
    auto rows = read_csv(out / "summary" / "cohort.csv");
    ASSERT_EQ(rows.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(rows[i]["subject"], subjects[i]);
        EXPECT_EQ(rows[i]["status"], "done") << rows[i]["error"];
        EXPECT_EQ(rows[i]["fit_for_fem"], "yes");
        EXPECT_GT(std::stol(rows[i]["tets"]), 1000) << subjects[i];
        EXPECT_GT(std::stod(rows[i]["min_dihedral_deg"]), 0.0) << subjects[i];
        EXPECT_GT(std::stod(rows[i]["seconds_tetra"]), 0.0) << subjects[i];
    }
    // The head's six tissues by their names from its dseg.tsv; at 4 mm every one keeps a Dice over 0.7.
    for (const char* tissue : {"scalp", "skull", "CSF", "grey matter", "white matter", "air cavities"})
        EXPECT_GT(std::stod(rows[2][std::string("dice_") + tissue]), 0.7) << tissue;
    const std::string page = [&] {
        std::ifstream in(out / "summary" / "cohort.html");
        return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }();
    EXPECT_NE(page.find("<svg"), std::string::npos);
    EXPECT_NE(page.find("3 done"), std::string::npos);

    // The Makefile, subject by subject with the names the Snakefile made of the dseg.tsv: the same files, byte for byte.
    for (const char* subject : subjects) {
        const fs::path made = dir / "make" / subject;
        const std::string name = std::string(subject) + "_dseg.nii.gz";
        std::vector<std::string> variables = cohort_make_variables();
        variables.push_back("-j2");
        const CliResult make = run_make(bids / subject / "anat" / name,
                                        out / "labels" / (std::string(subject) + ".json"), made, variables);
        ASSERT_EQ(make.exit_code, 0) << make.out << make.err;
        const std::vector<std::string> files = model_files(made);
        EXPECT_EQ(model_files(out / subject), files) << subject;
        EXPECT_EQ(files.size(), 12u); // clean.nii.gz, clean.labels.json, 3 surfaces (surface nets: no smooth.ply),
                                      // tetra.msh, refined.msh, assessed.vtu, 4 pictures
        for (const std::string& file : files)
            EXPECT_TRUE(same_bytes(made / file, out / subject / file)) << subject << "/" << file;
    }

    // A second run does nothing.
    const auto before = json_times(out);
    result = run_snakemake(dir.path(), run);
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_NE((result.out + result.err).find("Nothing to be done"), std::string::npos) << result.out << result.err;
    EXPECT_EQ(json_times(out), before);

    // A broken image and a broken names table: those subjects fail at their first step with its one line; the
    // others are left as they were.
    add_broken_subject(bids);
    result = run_snakemake(dir.path(), run);
    EXPECT_NE(result.exit_code, 0) << result.out << result.err;
    rows = read_csv(out / "summary" / "cohort.csv");
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_EQ(rows[4]["status"], "failed");
    EXPECT_EQ(rows[4]["failed_step"], "labels");
    EXPECT_NE(rows[4]["error"].find("sub-05_dseg.tsv: a BIDS dseg.tsv needs the columns index and name"),
              std::string::npos)
        << rows[4]["error"];
    for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(rows[i]["status"], "done") << rows[i]["subject"];
    EXPECT_EQ(rows[3]["subject"], "sub-04");
    EXPECT_EQ(rows[3]["status"], "failed");
    EXPECT_EQ(rows[3]["failed_step"], "prep");
    EXPECT_EQ(rows[3]["error"].rfind("tm-prep: error: ", 0), 0u) << rows[3]["error"];
    EXPECT_NE(rows[3]["error"].find("sub-04_dseg.nii.gz"), std::string::npos) << rows[3]["error"];
    EXPECT_FALSE(fs::exists(out / "sub-04" / "prep.json"));
    auto after = json_times(out);
    for (const auto& [path, time] : before) {
        if (path.find("/summary/") == std::string::npos) {
            EXPECT_EQ(after[path], time) << path;
        }
    }
}

/// The tm- command lines of a `make -n -B` or `snakemake -n -p` output, as words, with the subject's folder
/// written @ and Snakemake's OMP_NUM_THREADS and log redirection left out.
std::multiset<std::vector<std::string>> commands(const std::string& output, const std::string& folder)
{
    std::multiset<std::vector<std::string>> found;
    std::istringstream lines(output);
    std::string line, joined;
    while (std::getline(lines, line)) {
        joined += line;
        if (!joined.empty() && joined.back() == '\\') { // make prints a recipe's continued lines as they are written
            joined.pop_back();
            continue;
        }
        std::vector<std::string> words = shell_words(joined);
        joined.clear();
        if (!words.empty() && words[0].rfind("OMP_NUM_THREADS=", 0) == 0) words.erase(words.begin());
        if (words.empty() || words[0].find("/tm-") == std::string::npos) continue;
        words.erase(std::find(words.begin(), words.end(), ">"), words.end());
        for (std::string& word : words) {
            if (word.rfind(folder, 0) == 0 && (word.size() == folder.size() || word[folder.size()] == '/')) {
                std::string short_word(1, '@'); // built, not replaced in place: GCC 12 warns of a false overlap
                short_word.append(word, folder.size(), std::string::npos);
                word.swap(short_word);
            }
        }
        found.insert(words);
    }
    return found;
}

TEST(CohortCli, SnakefileRunsTheMakefilesCommandLines)
{
    TempDir dir;
    // Two subjects from a table, the second in a session and with flags of its own. Nothing runs (dry runs),
    // so the images need only exist.
    for (const char* file : {"a.nii.gz", "b.nii.gz"}) std::ofstream(dir / file) << "image";
    std::ofstream(dir / "names.json") << R"({"1": "scalp", "2": "brain"})";
    const std::string electrodes = "--electrode 1,2,3,4,1e-3 --electrode 5,6,7,4,-1e-3";
    std::ofstream(dir / "subjects.tsv") << "participant_id\tsession_id\timage\tlabels\tSOLVE_ARGS\n"
                                        << "sub-01\t\ta.nii.gz\tnames.json\t\n"
                                        << "sub-02\tses-A\tb.nii.gz\tnames.json\t" << electrodes << "\n";
    const fs::path out = dir / "derivatives";
    struct Case {
        std::string name;
        std::vector<std::string> config; // --config for Snakemake
        std::vector<std::string> make;   // the same as make variables
    };
    const std::vector<Case> cases{
        {"defaults", {}, {}},
        {"preset and an override",
         {"preset=usc19-5-head", "params={REMESH_ARGS: --edge-mm 5}"},
         {"PRESET=usc19-5-head", "REMESH_ARGS=--edge-mm 5"}},
        {"surfaces only", {"params={STOP_AFTER: remesh}"}, {"STOP_AFTER=remesh"}},
    };
    for (const Case& c : cases) {
        std::vector<std::string> args{"-n",
                                      "-p",
                                      "--forceall",
                                      "--cores",
                                      "2",
                                      "--config",
                                      "subjects=" + (dir / "subjects.tsv").string(),
                                      "out=" + out.string(),
                                      "bin=" TM_TOOLS_DIR};
        args.insert(args.end(), c.config.begin(), c.config.end());
        const CliResult snake = run_snakemake(dir.path(), args);
        ASSERT_EQ(snake.exit_code, 0) << c.name << "\n" << snake.out << snake.err;
        for (const auto& [subject, image, solve] :
             {std::tuple{"sub-01", "a.nii.gz", ""}, std::tuple{"sub-02/ses-A", "b.nii.gz", "yes"}}) {
            std::vector<std::string> extra = c.make;
            extra.insert(extra.end(), {"-n", "-B"});
            if (*solve) extra.push_back("SOLVE_ARGS=" + electrodes);
            const fs::path made = dir / "make" / subject;
            const CliResult make = run_make(dir / image, dir / "names.json", made, extra);
            ASSERT_EQ(make.exit_code, 0) << c.name << "\n" << make.err;
            const auto expected = commands(make.out, made.string());
            // Snakemake prints the jobs of both subjects: keep this subject's (its folder, or its image for tm-prep).
            std::multiset<std::vector<std::string>> own;
            for (const auto& words : commands(snake.out, subject))
                if (std::any_of(words.begin(), words.end(), [&](const std::string& w) {
                        return w.rfind("@", 0) == 0 || w == (dir / image).string();
                    }))
                    own.insert(words);
            EXPECT_EQ(own, expected) << c.name << ", " << subject << ":\n" << snake.out << "\n---\n" << make.out;
            EXPECT_GE(expected.size(), std::string(c.name) == "surfaces only" ? 6u : 13u)
                << c.name; // surface nets: no smoothing step
        }
    }

    // A misspelt parameter is refused as such.
    CliResult refused =
        run_snakemake(dir.path(), {"-n", "--cores", "1", "--config", "subjects=" + (dir / "subjects.tsv").string(),
                                   "out=" + out.string(), "params={REMSH_ARGS: --edge-mm 2}"});
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE((refused.out + refused.err).find("params: REMSH_ARGS are no parameters of the Makefile"),
              std::string::npos)
        << refused.err;

    // When the Makefile gains a step variable (here a copy of data/workflows with one more), the Snakefile stops
    // before anything runs and says which.
    const fs::path copy = dir / "workflows";
    fs::create_directories(copy);
    fs::copy(data_path("workflows/snakemake"), copy / "snakemake", fs::copy_options::recursive);
    fs::copy_file(data_path("workflows/Makefile"), copy / "Makefile");
    std::ofstream(copy / "Makefile", std::ios::app) << "NETS_ARGS ?= --level 1\n";
    refused = run_program("snakemake",
                          {"-s", (copy / "snakemake" / "Snakefile").string(), "-n", "--cores", "1", "--config",
                           "subjects=" + (dir / "subjects.tsv").string(), "out=" + out.string()},
                          dir.path());
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_NE((refused.out + refused.err).find("the Makefile has NETS_ARGS, which no rule here takes"),
              std::string::npos)
        << refused.err;
}

} // namespace
} // namespace tissuemesh::testing
