#include "fem/detail/amg_processes.h"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string_view>
#include <thread>
#include <vector>

#include "core/error.h"
#include "fem/detail/amg_exchange.h"

extern char** environ;

namespace tissuemesh::fem::detail {
namespace {

namespace fs = std::filesystem;

// MPI has this long to start the ranks; the solve itself is bounded by the iteration cap instead.
constexpr auto start_timeout = std::chrono::seconds(60);

// A private folder under the temporary directory, removed with its files.
class TemporaryFolder {
public:
    TemporaryFolder()
    {
        std::string pattern = (fs::temp_directory_path() / "tissuemesh-amg-XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw IoError(concat(pattern, ": cannot create a temporary folder (", std::strerror(errno), ")"));
        path_ = pattern;
    }
    ~TemporaryFolder()
    {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

std::optional<fs::path> find_program(const std::string& program)
{
    if (program.find('/') != std::string::npos)
        return access(program.c_str(), X_OK) == 0 ? std::optional<fs::path>(program) : std::nullopt;
    const char* path = std::getenv("PATH");
    std::string entries = path ? path : "/usr/bin:/bin";
    std::size_t at = 0;
    while (at <= entries.size()) {
        const std::size_t end = std::min(entries.find(':', at), entries.size());
        const fs::path candidate = fs::path(entries.substr(at, end - at)) / program;
        if (end > at && access(candidate.c_str(), X_OK) == 0) return candidate;
        at = end + 1;
    }
    return std::nullopt;
}

// The worker's environment: ours without the MPI runtime's own variables (an earlier in-process solve
// leaves its singleton's there, which would mislead the new job), plus what a 2-core machine, a container
// and root need: no binding to cores, more ranks than hwloc's cores if need be, no cross-memory attach
// (often forbidden in containers), and Open MPI's consent to run as root.
std::vector<std::string> worker_environment()
{
    std::vector<std::string> environment;
    for (char** entry = environ; *entry; ++entry) {
        const std::string_view text(*entry);
        const bool mpi_own = text.starts_with("OMPI_") || text.starts_with("PMIX_") || text.starts_with("OPAL_") ||
                             text.starts_with("ORTE_") || text.starts_with("OMP_NUM_THREADS=");
        if (!mpi_own) environment.emplace_back(text);
    }
    for (const char* setting : {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1",
                                "OMPI_MCA_rmaps_base_oversubscribe=1", "OMPI_MCA_hwloc_base_binding_policy=none",
                                "OMPI_MCA_btl_vader_single_copy_mechanism=none", "OMP_NUM_THREADS=1"})
        environment.emplace_back(setting);
    return environment;
}

std::vector<char*> pointers_to(std::vector<std::string>& texts)
{
    std::vector<char*> pointers;
    for (std::string& text : texts) pointers.push_back(text.data());
    pointers.push_back(nullptr);
    return pointers;
}

// The last non-empty line of the workers' output, for the reason of a failure.
std::string last_line(const fs::path& log)
{
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last.empty() ? "no output" : last;
}

// Starts mpiexec with its output in `log`; returns its process id.
pid_t start_mpiexec(std::vector<std::string> arguments, const fs::path& log)
{
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    std::vector<std::string> environment = worker_environment();
    std::vector<char*> argv = pointers_to(arguments), envp = pointers_to(environment);
    pid_t pid = 0;
    const int failed = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (failed) throw IoError(concat(arguments[0], ": cannot start (", std::strerror(failed), ")"));
    return pid;
}

// Waits for mpiexec; stops it when the ranks have not started in time. Returns its wait status, or
// nothing after a timeout.
std::optional<int> wait_for(pid_t pid, const fs::path& started)
{
    const auto begin = std::chrono::steady_clock::now();
    for (;;) {
        int status = 0;
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) return status;
        if (done < 0 && errno != EINTR) return std::nullopt;
        if (!fs::exists(started) && std::chrono::steady_clock::now() - begin > start_timeout) {
            kill(pid, SIGTERM);
            std::this_thread::sleep_for(std::chrono::seconds(2));
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return std::nullopt;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

} // namespace

int available_cores()
{
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) != 0) return 1;
    return std::max(1, CPU_COUNT(&set));
}

std::optional<HyprePcgResult> solve_on_processes(const SparseMatrix& matrix, const Eigen::VectorXd& rhs,
                                                 const SolveRequest& request, const ProcessLaunch& launch,
                                                 std::string& why_not)
{
    const std::optional<fs::path> mpiexec = find_program(launch.mpiexec);
    if (!mpiexec) {
        why_not = concat(launch.mpiexec, " is not found or not executable (Debian package openmpi-bin)");
        return std::nullopt;
    }
    const int processes = launch.processes;
    std::error_code error;
    const fs::path worker = fs::read_symlink("/proc/self/exe", error).parent_path() / "tm-amg-worker";
    if (error || access(worker.c_str(), X_OK) != 0) {
        why_not = concat(worker.string(), " is missing: it is built and installed next to tm-solve");
        return std::nullopt;
    }
    try {
        const TemporaryFolder folder;
        const fs::path system = folder.path() / "system.bin", result = folder.path() / "result.bin",
                       started = folder.path() / "started", log = folder.path() / "mpiexec.log";
        write_system_file(system, matrix, rhs, request);
        const pid_t pid = start_mpiexec({mpiexec->string(), "-n", std::to_string(processes), worker.string(),
                                         system.string(), result.string(), started.string()},
                                        log);
        const std::optional<int> status = wait_for(pid, started);
        if (!status) {
            why_not = concat("MPI did not start ", processes, " processes within ", start_timeout.count(), " s");
            return std::nullopt;
        }
        if (!WIFEXITED(*status) || WEXITSTATUS(*status) != 0 || !fs::exists(result)) {
            why_not = concat(launch.mpiexec, " ", WIFEXITED(*status) ? concat("exited with status ", WEXITSTATUS(*status))
                                                             : std::string("was killed"),
                             ": ", last_line(log));
            return std::nullopt;
        }
        return read_result_file(result, matrix.rows());
    } catch (const IoError& failure) {
        why_not = failure.what();
        return std::nullopt;
    }
}

} // namespace tissuemesh::fem::detail
