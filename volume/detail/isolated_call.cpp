#include "volume/detail/isolated_call.h"

#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "core/error.h"

namespace tissuemesh::volume::detail {
namespace {

// Exit codes of the child (anything else is unexpected).
constexpr int kChildDone = 0;
constexpr int kChildThrew = 3;

/// An unlinked temporary file, closed when the object goes.
class TempFile {
public:
    TempFile() : file_(std::tmpfile())
    {
        if (file_ == nullptr)
            throw IoError(concat("cannot create a temporary file (", std::strerror(errno),
                                 "); check that TMPDIR or /tmp is writable"));
    }
    ~TempFile() { std::fclose(file_); }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    int fd() const { return ::fileno(file_); }

    /// Everything in the file (written through fd() by the child).
    std::string contents() const
    {
        std::string text;
        char buffer[1 << 16];
        off_t offset = 0;
        for (ssize_t n; (n = ::pread(fd(), buffer, sizeof buffer, offset)) > 0; offset += n)
            text.append(buffer, static_cast<std::size_t>(n));
        return text;
    }

private:
    std::FILE* file_;
};

bool write_all(int fd, const std::string& bytes)
{
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += static_cast<std::size_t>(n);
    }
    return true;
}

/// The child's side: runs `work`, writes its result or its error message, and leaves without running
/// the parent's exit handlers or destructors (they belong to the parent).
[[noreturn]] void run_child(const std::function<std::string()>& work, int result_fd, int printed_fd)
{
    ::dup2(printed_fd, STDOUT_FILENO);
    ::dup2(printed_fd, STDERR_FILENO);
    int code = kChildDone;
    std::string bytes;
    try {
        bytes = work();
    } catch (const std::exception& error) {
        bytes = error.what();
        code = kChildThrew;
    } catch (...) {
        bytes = "an unknown exception";
        code = kChildThrew;
    }
    std::fflush(stdout);
    std::fflush(stderr);
    if (!write_all(result_fd, bytes)) code = 4;
    ::_exit(code);
}

int wait_for(pid_t child)
{
    int status = 0;
    while (::waitpid(child, &status, 0) < 0)
        if (errno != EINTR) throw IoError(concat("waiting for a child process failed (", std::strerror(errno), ")"));
    return status;
}

/// The last `count` non-empty lines of `text`, trimmed and joined by " / ".
std::string last_lines(const std::string& text, int count)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        if (line.find_first_not_of(" \t\r") != std::string::npos)
            lines.push_back(line.substr(line.find_first_not_of(" \t\r")));
    std::string joined;
    const std::size_t first =
        lines.size() > static_cast<std::size_t>(count) ? lines.size() - static_cast<std::size_t>(count) : 0;
    for (std::size_t i = first; i < lines.size(); ++i) joined += (joined.empty() ? "" : " / ") + lines[i];
    return joined;
}

} // namespace

IsolatedResult run_isolated(const std::string& what, const std::function<std::string()>& work,
                            const std::function<void()>& meanwhile)
{
    TempFile result;
    TempFile printed;
    std::fflush(nullptr); // nothing buffered in the parent may be written twice
    const pid_t child = ::fork();
    if (child < 0)
        throw IoError(concat("cannot start a process for ", what, " (", std::strerror(errno),
                             "); the machine may be out of memory or processes"));
    if (child == 0) run_child(work, result.fd(), printed.fd());

    std::exception_ptr failure; // thrown once the child has ended, so that no child is left behind
    if (meanwhile) {
        try {
            meanwhile();
        } catch (...) {
            failure = std::current_exception();
        }
    }
    const int status = wait_for(child);
    if (failure) std::rethrow_exception(failure);
    IsolatedResult out{result.contents(), printed.contents()};
    if (WIFSIGNALED(status)) {
        const int signal = WTERMSIG(status);
        const char* name = ::sigabbrev_np(signal);
        throw AlgorithmError(
            concat(what, " crashed (SIG", name != nullptr ? name : "?", ", ", ::strsignal(signal), ")",
                   out.printed.empty() ? std::string() : concat("; it said: ", last_lines(out.printed, 2))));
    }
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == kChildThrew)
        throw AlgorithmError(out.printed.empty()
                                 ? out.bytes
                                 : concat(out.bytes, " (", what, " said: ", last_lines(out.printed, 3), ")"));
    if (code != kChildDone)
        throw AlgorithmError(
            concat(what, " ended with exit code ", code, " before it returned its result",
                   out.printed.empty() ? std::string() : concat("; it said: ", last_lines(out.printed, 2))));
    return out;
}

} // namespace tissuemesh::volume::detail
