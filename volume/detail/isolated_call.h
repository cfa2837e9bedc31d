// Runs a piece of third-party code in a child process, so that an assertion or a crash inside it
// becomes an error of ours instead of the end of the program (TetGen 1.5 as Debian builds it keeps its
// asserts and calls abort() on some nearly degenerate inputs).
#pragma once

#include <functional>
#include <string>

namespace tissuemesh::volume::detail {

/// What the child printed and returned.
struct IsolatedResult {
    std::string bytes;   ///< what `work` returned
    std::string printed; ///< everything the child wrote to stdout and stderr
};

/// Forks; the child runs `work` with its stdout and stderr captured and hands the bytes `work` returns
/// back to the parent through an unlinked temporary file. The parent runs `meanwhile` (when given), then waits
/// for it. The fork happens before `meanwhile` starts, so that the child is made from a process of one thread.
/// `what` names the work in messages ("TetGen").
/// @throws AlgorithmError when the child died of a signal (naming it and the child's last printed lines)
///         or when `work` threw (its message, then the child's last printed lines)
/// @throws IoError when the temporary files or the child process cannot be made
/// What `meanwhile` throws is thrown once the child has ended.
IsolatedResult run_isolated(const std::string& what, const std::function<std::string()>& work,
                            const std::function<void()>& meanwhile = {});

} // namespace tissuemesh::volume::detail
