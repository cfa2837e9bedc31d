// Shared by the tools that edit an interface complex (tm-smooth, tm-decimate, tm-remesh): the output must keep
// the label pairs, the input must be fit for tetrahedralization, and so must the result.
#pragma once

#include <chrono>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/surface_io.h"
#include "surface/check_complex.h"

namespace tissuemesh::tools {

/// Refuses output formats without label pairs per triangle, before any work is done.
inline void require_complex_output(const std::string& output)
{
    const std::string extension = full_extension(output);
    if (extension != ".ply" && extension != ".vtp")
        throw InputError(concat(output, ": the interface complex is written as .ply or .vtp (label pairs per "
                                        "triangle); other formats would lose the tissues"));
}

/// Reads `input` and checks that it is fit for tetrahedralization (InputError otherwise).
inline InterfaceComplex read_fit_complex(const std::string& input)
{
    InterfaceComplex complex = io::read_surface(input);
    surface::require_fit_for_tetrahedralization(complex, input);
    return complex;
}

/// Runs `step()` (which edits the complex), checks the result as `output (what)` and returns the seconds
/// the step took.
template <class Step>
double run_checked_step(const InterfaceComplex& complex, const std::string& output, const std::string& what, Step step)
{
    const auto start = std::chrono::steady_clock::now();
    step();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    surface::require_fit_for_tetrahedralization(complex, concat(output, " (", what, ")"));
    return seconds;
}

} // namespace tissuemesh::tools
