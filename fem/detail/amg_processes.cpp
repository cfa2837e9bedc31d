#include "fem/detail/amg_processes.h"

#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <functional>
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

// Variables an MPI singleton (an earlier in-process solve) leaves in our environment; passed on, they would
// tell mpiexec's ranks that they are that singleton's.
bool singleton_own(std::string_view text)
{
    if (text.starts_with("PMIX_")) return true;
    if (!text.starts_with("OMPI_")) return false;
    if (!text.starts_with("OMPI_MCA_"))
        return !text.starts_with("OMPI_ALLOW_RUN_AS_ROOT"); // OMPI_COMMAND, OMPI_APP_CTX_...
    return text.starts_with("OMPI_MCA_ess") || text.starts_with("OMPI_MCA_orte_") || text.starts_with("OMPI_MCA_pmix");
}

// The worker's environment: ours without the singleton's variables (the user's own OMPI_MCA_ settings and
// OPAL_PREFIX stay), plus, where the user has not set them, what a 2-core machine, a container and root
// need: no binding to cores, more ranks than hwloc's cores if need be, no cross-memory attach (often
// forbidden in containers), Open MPI's consent to run as root, and one OpenMP thread per rank.
std::vector<std::string> worker_environment()
{
    std::vector<std::string> environment;
    for (char** entry = environ; *entry; ++entry) {
        const std::string_view text(*entry);
        if (!singleton_own(text) && !text.starts_with("OMP_NUM_THREADS=")) environment.emplace_back(text);
    }
    for (const std::string_view setting :
         {"OMPI_ALLOW_RUN_AS_ROOT=1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1", "OMPI_MCA_rmaps_base_oversubscribe=1",
          "OMPI_MCA_hwloc_base_binding_policy=none", "OMPI_MCA_btl_vader_single_copy_mechanism=none",
          "OMP_NUM_THREADS=1"}) {
        const std::string_view name = setting.substr(0, setting.find('=') + 1);
        if (std::none_of(environment.begin(), environment.end(),
                         [&](const std::string& kept) { return kept.starts_with(name); }))
            environment.emplace_back(setting);
    }
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

// Starts mpiexec with its output in `log`; returns its process id. mpiexec gets SIGTERM (on which it takes its
// ranks down) when this process ends, however it ends (PR_SET_PDEATHSIG): a lead field's solves run for minutes,
// and a killed tm-leadfield must not leave them running (they did, with posix_spawn).
pid_t start_mpiexec(std::vector<std::string> arguments, const fs::path& log)
{
    std::vector<std::string> environment = worker_environment();
    std::vector<char*> argv = pointers_to(arguments), envp = pointers_to(environment);
    const int input = open("/dev/null", O_RDONLY | O_CLOEXEC);
    const int output = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (input < 0 || output < 0) {
        const int error = errno;
        if (input >= 0) close(input);
        if (output >= 0) close(output);
        throw IoError(concat(log.string(), ": cannot open (", std::strerror(error), ")"));
    }
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid == 0) { // only async-signal-safe calls until exec: other threads may hold locks
        prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (getppid() != parent) _exit(127); // the parent ended before the line above took effect
        if (dup2(input, STDIN_FILENO) < 0 || dup2(output, STDOUT_FILENO) < 0 || dup2(output, STDERR_FILENO) < 0)
            _exit(127);
        execve(argv[0], argv.data(), envp.data());
        _exit(127);
    }
    const int error = errno;
    close(input);
    close(output);
    if (pid < 0) throw IoError(concat(arguments[0], ": cannot start (", std::strerror(error), ")"));
    return pid;
}

// How mpiexec ended.
struct Ending {
    bool started = true;       ///< false: the ranks had not started within start_timeout, and mpiexec was stopped
    std::optional<int> status; ///< its wait status; unknown when it was reaped elsewhere (SIGCHLD ignored)
};

// Stops mpiexec (SIGTERM, on which it takes its ranks down; SIGKILL after 5 s) and reaps it.
void stop(pid_t pid)
{
    kill(pid, SIGTERM);
    for (int k = 0; k < 500; ++k) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) != 0) return;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
}

// "exited with status 1", "was killed", or "ended without a result" (status unknown, or 0 but no result).
std::string how_it_ended(const Ending& ending)
{
    if (!ending.status || (WIFEXITED(*ending.status) && WEXITSTATUS(*ending.status) == 0))
        return "ended without a result";
    return WIFEXITED(*ending.status) ? concat("exited with status ", WEXITSTATUS(*ending.status)) : "was killed";
}

// Waits for mpiexec, calling `tick` every 10 ms; stops it when the ranks have not started in time, or when
// `tick` throws (then rethrows).
Ending wait_for(pid_t pid, const fs::path& started, const std::function<void()>& tick)
{
    const auto begin = std::chrono::steady_clock::now();
    for (;;) {
        int status = 0;
        const pid_t done = waitpid(pid, &status, WNOHANG);
        if (done == pid) return {true, status};
        try {
            tick();
        } catch (...) {
            stop(pid);
            throw;
        }
        if (done < 0 && errno != EINTR) return {true, std::nullopt}; // ECHILD: reaped by an ignored SIGCHLD
        std::error_code ignored;
        if (!fs::exists(started, ignored) && std::chrono::steady_clock::now() - begin > start_timeout) {
            stop(pid);
            return {false, std::nullopt};
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
}

// The core count of the cgroup's CPU quota (cgroup v2 cpu.max: "QUOTA PERIOD" or "max PERIOD"), if any.
std::optional<int> cgroup_cores()
{
    std::ifstream in("/sys/fs/cgroup/cpu.max");
    std::string quota;
    double period = 0;
    if (!(in >> quota >> period) || quota == "max" || !(period > 0)) return std::nullopt;
    try {
        return static_cast<int>(std::ceil(std::stod(quota) / period));
    } catch (const std::exception&) {
        return std::nullopt;
    }
}

// An exception from the caller's filler or sink, carried past the handlers of the exchange's own failures.
struct CallerFailure {
    std::exception_ptr error;
};

template <typename Call>
void as_caller(Call&& call)
{
    try {
        call();
    } catch (...) {
        throw CallerFailure{std::current_exception()};
    }
}

} // namespace

int available_cores()
{
    cpu_set_t set;
    CPU_ZERO(&set);
    const int mask = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : 1;
    return std::max(1, std::min(mask, cgroup_cores().value_or(mask)));
}

std::optional<ColumnsResult> solve_columns_on_processes(const SparseMatrix& matrix, std::size_t columns,
                                                        const ColumnFiller& rhs,
                                                        const std::vector<std::uint32_t>& kept_rows,
                                                        const ColumnSink& sink, const SolveRequest& request,
                                                        const ProcessLaunch& launch, std::string& why_not)
{
    const std::optional<fs::path> mpiexec = find_program(launch.mpiexec);
    if (!mpiexec) {
        why_not = concat(launch.mpiexec, " is not found or not executable (Debian package openmpi-bin)");
        return std::nullopt;
    }
    std::error_code error;
    const fs::path worker = fs::read_symlink("/proc/self/exe", error).parent_path() / "tm-amg-worker";
    if (error || access(worker.c_str(), X_OK) != 0) {
        why_not = concat(worker.string(), " is missing: it is built and installed next to tm-solve");
        return std::nullopt;
    }
    const auto kept =
        static_cast<std::int64_t>(kept_rows.empty() ? static_cast<std::size_t>(matrix.rows()) : kept_rows.size());
    try {
        const TemporaryFolder folder;
        const fs::path system = folder.path() / "system.bin", result = folder.path() / "result.bin",
                       started = folder.path() / "started", log = folder.path() / "mpiexec.log";
        SystemFileWriter writer(system, matrix, request, static_cast<std::int64_t>(columns), kept_rows);
        Eigen::VectorXd b(matrix.rows());
        for (std::size_t k = 0; k < columns; ++k) {
            b.setZero();
            as_caller([&] { rhs(k, b); });
            writer.add_column(b);
        }
        writer.finish();
        const pid_t pid = start_mpiexec({mpiexec->string(), "-n", std::to_string(launch.processes), worker.string(),
                                         system.string(), result.string(), started.string()},
                                        log);
        ColumnsResult solved;
        ResultFileReader reader;
        std::vector<double> values;
        // Hands every whole record in the result file to the sink, in column order.
        const auto collect = [&] {
            if (!reader.is_open() && !reader.open(result, static_cast<std::int64_t>(columns), kept)) return;
            PcgSolve solve;
            while (solved.solves.size() < columns && reader.next(solve, values)) {
                as_caller([&] { sink(solved.solves.size(), solve, values.data()); });
                solved.solves.push_back(solve);
            }
        };
        const Ending ending = wait_for(pid, started, collect);
        if (!ending.started) {
            why_not = concat("MPI did not start ", launch.processes, " processes within ", start_timeout.count(), " s");
            return std::nullopt;
        }
        const bool exited_cleanly = !ending.status || (WIFEXITED(*ending.status) && WEXITSTATUS(*ending.status) == 0);
        if (exited_cleanly) collect();
        if (!exited_cleanly || solved.solves.size() != columns) {
            why_not = concat(launch.mpiexec, " ", how_it_ended(ending), ": ", last_line(log));
            return std::nullopt;
        }
        solved.copy_seconds = reader.copy_seconds();
        solved.setup_seconds = reader.setup_seconds();
        return solved;
    } catch (const CallerFailure& failure) { // not a reason to try again in one process
        std::rethrow_exception(failure.error);
    } catch (
        const std::exception& failure) { // IoError of the exchange files, a filesystem error (no temporary directory)
        why_not = failure.what();
        return std::nullopt;
    }
}

} // namespace tissuemesh::fem::detail
