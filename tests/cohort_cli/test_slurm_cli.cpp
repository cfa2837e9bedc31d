// data/workflows/snakemake on a real SLURM: a one-node cluster started for the test (munged, slurmctld, slurmd as
// root on loopback, everything in a temporary folder, stopped at the end), the SLURM profile submitting every step
// with sbatch; the cohort of test_cohort_cli.cpp plus a broken subject. Long: about 5 min on 2 shared cores.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <unistd.h>

#include "tests/cohort_cli/cohort_support.h"

namespace tissuemesh::testing {
namespace {

namespace fs = std::filesystem;

class SlurmCohortLong : public ::testing::Test {
protected:
    void SetUp() override
    {
        ASSERT_EQ(::geteuid(), 0u) << "slurmd starts jobs as their users: the SLURM test runs as root (CI does)";
        const CliResult start =
            run_program((snakemake_folder() / "one-node-slurm").string(), {"start", cluster.string()});
        started = true;
        ASSERT_EQ(start.exit_code, 0) << start.out << start.err;
    }
    void TearDown() override
    {
        if (!started) return;
        const CliResult stop =
            run_program((snakemake_folder() / "one-node-slurm").string(), {"stop", cluster.string()});
        EXPECT_EQ(stop.exit_code, 0) << stop.err;
        for (const char* daemon : {"munged", "slurmctld", "slurmd"})
            EXPECT_FALSE(fs::exists(cluster / "run" / (std::string(daemon) + ".pid")))
                << daemon << " still recorded as running";
    }
    /// A SLURM client command against the test's cluster.
    CliResult slurm(const std::string& program, const std::vector<std::string>& args)
    {
        std::vector<std::string> command{"SLURM_CONF=" + (cluster / "slurm.conf").string(), program};
        command.insert(command.end(), args.begin(), args.end());
        return run_program("env", command);
    }
    TempDir dir;
    fs::path cluster = dir / "slurm";
    bool started = false;
};

TEST_F(SlurmCohortLong, ProfileRunsEveryStepThroughSbatch)
{
    const fs::path bids = dir / "bids", out = bids / "derivatives" / "tissuemesh";
    make_bids_cohort(bids);
    add_broken_subject(bids);
    std::vector<std::string> run{"--profile", (snakemake_folder() / "profiles" / "slurm").string(), "--config",
                                 "bids=" + bids.string(), "bin=" TM_TOOLS_DIR};
    for (const std::string& setting : cohort_config()) run.push_back(setting);
    const CliResult result = run_snakemake(dir.path(), run, {"SLURM_CONF=" + (cluster / "slurm.conf").string()});
    EXPECT_NE(result.exit_code, 0) << "sub-04's image is broken";
    EXPECT_NE(result.err.find("Submitted job"), std::string::npos) << result.err;

    // Every subject but the broken one to the end of its chain, fit for FEM; the broken one with tm-prep's line.
    auto rows = read_csv(out / "summary" / "cohort.csv");
    ASSERT_EQ(rows.size(), 5u) << result.err;
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(rows[i]["status"], "done") << rows[i]["subject"] << ": " << rows[i]["error"];
        EXPECT_EQ(rows[i]["fit_for_fem"], "yes") << rows[i]["subject"];
    }
    EXPECT_EQ(rows[3]["status"], "failed");
    EXPECT_EQ(rows[3]["failed_step"], "prep");
    EXPECT_EQ(rows[3]["error"].rfind("tm-prep: error: ", 0), 0u) << rows[3]["error"];
    EXPECT_EQ(rows[4]["failed_step"], "labels"); // run on the login node (a local rule): no job

    // The steps ran as SLURM jobs: the controller knows 14 completed jobs per finished subject (9 steps, 4 pictures,
    // the report), and sub-04's prep failed twice (the profile retries once); each job left its sbatch log.
    const CliResult jobs = slurm("scontrol", {"-o", "show", "job"});
    ASSERT_EQ(jobs.exit_code, 0) << jobs.err;
    const auto count = [&](const std::string& pattern) {
        const std::regex expression(pattern);
        return std::distance(std::sregex_iterator(jobs.out.begin(), jobs.out.end(), expression),
                             std::sregex_iterator());
    };
    // 13 jobs a subject: prep to check-mesh by surface nets (8, no smoothing step), tm-render 4 times, tm-report
    EXPECT_EQ(count("JobName=tm\\.[a-z_]+ .*JobState=COMPLETED"), 3 * 13) << jobs.out;
    EXPECT_EQ(count("JobName=tm\\.prep .*JobState=FAILED"), 2) << jobs.out;
    std::size_t logs = 0;
    for (const auto& entry : fs::directory_iterator(out / "logs" / "slurm")) logs += entry.path().extension() == ".log";
    EXPECT_EQ(logs, 3u * 13 + 2);

    // The same bytes as the Makefile for one subject (the local test compares all three).
    const fs::path made = dir / "make" / "sub-03";
    std::vector<std::string> variables = cohort_make_variables();
    variables.push_back("-j2");
    const CliResult make =
        run_make(bids / "sub-03" / "anat" / "sub-03_dseg.nii.gz", out / "labels" / "sub-03.json", made, variables);
    ASSERT_EQ(make.exit_code, 0) << make.err;
    for (const std::string& file : model_files(made))
        EXPECT_TRUE(same_bytes(made / file, out / "sub-03" / file)) << file;
}

} // namespace
} // namespace tissuemesh::testing
