// run_isolated(): third-party code that aborts or crashes in a child process becomes an AlgorithmError.
#include <cassert>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "core/error.h"
#include "volume/detail/isolated_call.h"

namespace tissuemesh::volume::detail {
namespace {

std::string message_of(const std::function<std::string()>& work)
{
    try {
        run_isolated("the test library", work);
    } catch (const AlgorithmError& error) {
        return error.what();
    }
    return "no error";
}

TEST(IsolatedCall, ReturnsTheChildsBytesAndWhatItPrinted)
{
    const IsolatedResult result = run_isolated("the test library", [] {
        std::printf("working\n");
        return std::string("a\0b", 3);
    });
    EXPECT_EQ(result.bytes, std::string("a\0b", 3));
    EXPECT_EQ(result.printed, "working\n");
}

TEST(IsolatedCall, TheParentWorksMeanwhileAndItsErrorComesAfterTheChildEnded)
{
    // The child waits (up to 10 s) for a file the parent's `meanwhile` writes: it sees it only if both run at once.
    char path[] = "/tmp/tm-isolated-XXXXXX";
    const int fd = ::mkstemp(path);
    ASSERT_GE(fd, 0);
    ::close(fd);
    std::remove(path);
    const std::string flag = path;
    bool parent_worked = false;
    const IsolatedResult result = run_isolated(
        "the test library",
        [&flag] {
            for (int i = 0; i < 2000 && !std::filesystem::exists(flag); ++i) ::usleep(5000);
            return std::string(std::filesystem::exists(flag) ? "saw it" : "timed out");
        },
        [&] {
            std::ofstream(flag) << "x";
            parent_worked = true;
        });
    std::remove(path);
    EXPECT_TRUE(parent_worked);
    EXPECT_EQ(result.bytes, "saw it");

    // An error of `meanwhile` is thrown once the child has been waited for: no child is left behind.
    EXPECT_THROW(run_isolated(
                     "the test library", [] { return std::string("done"); },
                     [] { throw InputError("the parent's part failed"); }),
                 InputError);
    errno = 0;
    EXPECT_EQ(::waitpid(-1, nullptr, WNOHANG), -1);
    EXPECT_EQ(errno, ECHILD);
}

TEST(IsolatedCall, LargeResultsComeBackWhole)
{
    const std::size_t size = std::size_t{64} << 20;
    const IsolatedResult result = run_isolated("the test library", [size] { return std::string(size, 'x'); });
    ASSERT_EQ(result.bytes.size(), size);
    EXPECT_EQ(result.bytes.find_first_not_of('x'), std::string::npos);
}

TEST(IsolatedCall, AnAbortInTheChildIsAnErrorNamingTheSignalAndTheLastWords)
{
    // What Debian's TetGen does on a degenerate insphere test: print the assertion, then abort().
    const std::string message = message_of([]() -> std::string {
        std::fprintf(stderr, "tetgen.cxx:1234: insphere_s: Assertion `oriB != 0.0' failed.\n");
        std::abort();
    });
    EXPECT_NE(message.find("the test library crashed (SIGABRT"), std::string::npos) << message;
    EXPECT_NE(message.find("insphere_s: Assertion `oriB != 0.0' failed."), std::string::npos) << message;
}

TEST(IsolatedCall, ASegfaultInTheChildIsAnError)
{
    const std::string message = message_of([]() -> std::string {
        std::raise(SIGSEGV);
        return "unreachable";
    });
    // Under AddressSanitizer the child reports the SEGV itself and exits 1 instead of dying of the signal.
    EXPECT_NE(message.find("the test library"), std::string::npos) << message;
    EXPECT_NE(message.find("SEGV"), std::string::npos) << message;
}

TEST(IsolatedCall, AnExceptionInTheChildKeepsItsMessageAndAddsWhatWasPrinted)
{
    const std::string message = message_of([]() -> std::string {
        std::printf("facets 3 and 7 intersect\n");
        throw AlgorithmError("it found intersecting facets");
    });
    EXPECT_EQ(message, "it found intersecting facets (the test library said: facets 3 and 7 intersect)");
}

TEST(IsolatedCall, TheParentKeepsRunningAndItsOutputIsUntouched)
{
    std::fflush(stdout);
    testing::internal::CaptureStdout();
    std::printf("before ");
    EXPECT_THROW(run_isolated("the test library", []() -> std::string { std::abort(); }), AlgorithmError);
    std::printf("after");
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "before after");
}

} // namespace
} // namespace tissuemesh::volume::detail
