// tm-amg-worker is started by tm-solve, not by users: run by hand or on a damaged exchange file it says
// so and exits non-zero, and writes no result.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/support/cli.h"

namespace tissuemesh::testing {
namespace {

TEST(AmgWorkerCli, WithoutItsArgumentsPointsToTmSolve)
{
    const CliResult result = run_cli("tm-amg-worker", {});
    EXPECT_EQ(result.exit_code, 2);
    EXPECT_NE(result.err.find("internal to tm-solve"), std::string::npos) << result.err;
}

TEST(AmgWorkerCli, TruncatedSystemFileIsAnErrorWithNoResult)
{
    const TempDir dir;
    std::ofstream(dir.path() / "system.bin", std::ios::binary) << "TMAMGSY2" << std::string(12, '\0');
    const CliResult result =
        run_cli("tm-amg-worker", {(dir.path() / "system.bin").string(), (dir.path() / "result.bin").string(),
                                  (dir.path() / "started").string()});
    EXPECT_NE(result.exit_code, 0);
    EXPECT_NE(result.err.find("truncated solver exchange file"), std::string::npos) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "result.bin"));
}

} // namespace
} // namespace tissuemesh::testing
