// Typed errors shared by every library. Tools map them to exit codes in run_tool():
// InputError and IoError exit 2, AlgorithmError exits 1.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace tissuemesh {

/// Base of every tissuemesh error. The message is one line: the file or object, the problem, the fix.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// The caller's data or options are wrong (bad spacing, unknown tissue, open surface, ...).
class InputError : public Error {
public:
    using Error::Error;
};

/// A file cannot be read, parsed or written.
class IoError : public Error {
public:
    using Error::Error;
};

/// The input was valid but the method could not finish (TetGen failed, solver diverged, ...).
class AlgorithmError : public Error {
public:
    using Error::Error;
};

/// Concatenates streamable values into one string: concat("a", 3, 'b') == "a3b".
template <typename... Parts>
std::string concat(Parts&&... parts)
{
    std::ostringstream out;
    out.precision(10);
    (out << ... << std::forward<Parts>(parts));
    return out.str();
}

/// Formats a length in mm with at most `digits` decimals and no trailing zeros ("1.5", "92").
std::string format_mm(double value, int digits = 3);

} // namespace tissuemesh
