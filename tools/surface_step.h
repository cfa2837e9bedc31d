// Shared by the tools that edit an interface complex (tm-smooth, tm-decimate, tm-remesh): the output must keep
// the label pairs, the input must be fit for tetrahedralization, and so must the result (which is written
// with the stamp of its passed check: tools/check_stamp.h).
#pragma once

#include <chrono>
#include <string>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/surface_io.h"
#include "surface/check_complex.h"
#include "tools/check_stamp.h"
#include "tools/run_tool.h"

namespace tissuemesh::tools {

/// The files of a surface step: -i/--input (the complex), -o/--output (`output_help`, e.g. "Smoothed interface complex
/// (.ply or .vtp)") and --check-input (check even an input that carries the stamp of a passed check).
inline void add_step_files(CLI::App& app, std::string& input, std::string& output, bool& check_input,
                           const std::string& output_help)
{
    app.add_option("-i,--input", input, "Interface complex (.ply, .vtp)")->required();
    app.add_option("-o,--output", output, output_help)->required();
    app.add_flag("--check-input", check_input,
                 "Check the input in full even when it carries the stamp of a passed check");
}

/// Refuses output formats without label pairs per triangle, before any work is done.
inline void require_complex_output(const std::string& output)
{
    const std::string extension = full_extension(output);
    if (extension != ".ply" && extension != ".vtp")
        throw InputError(concat(output, ": the interface complex is written as .ply or .vtp (label pairs per "
                                        "triangle); other formats would lose the tissues"));
}

/// A surface step's --image goes with one option that reads it (`option`, given or not): refuses the option without an
/// image (`otherwise`: what to do instead) and an image without the option, before any work is done.
inline void require_image_with(const std::string& option, bool given, const std::string& image,
                               const std::string& otherwise)
{
    if (given && image.empty())
        throw InputError(concat(option, " needs the label image the surfaces come from: give --image clean.nii.gz (or ",
                                otherwise, ")"));
    if (!given && !image.empty())
        throw InputError(
            concat("--image ", image, " is read only for ", option, "; give that option, or leave --image out"));
}

/// The complex a surface step read, and whether its full check ran.
struct FitInput {
    InterfaceComplex complex;
    bool checked = true;
};

/// Reads `input` and checks that it is fit for tetrahedralization (InputError otherwise). The check is
/// skipped, and the tool says so, when the file carries the stamp of a passed check of exactly this complex
/// (written by write_checked()), unless `always_check`.
inline FitInput read_fit_complex(const std::string& input, bool always_check, const ToolContext& ctx)
{
    FitInput in{io::read_surface(input), true};
    const std::string stamp = always_check ? "" : read_check_stamp(input);
    if (!stamp.empty() && stamp == check_stamp(in.complex)) {
        in.checked = false;
        ctx.log(concat("input check skipped: ", input, " carries the stamp of a passed check of this very complex (",
                       stamp, "); --check-input checks it anyway"));
        return in;
    }
    surface::require_fit_for_tetrahedralization(in.complex, input);
    return in;
}

/// Writes a complex that passed its check (run_checked_step()), with the stamp of that check in a .ply header.
inline void write_checked(const InterfaceComplex& complex, const std::string& output)
{
    io::write_surface(complex, output, {check_stamp(complex)});
}

/// Runs `step()` (which edits the complex), checks the result as `output (what)` and returns the seconds
/// the step took.
template <class Step>
double run_checked_step(const InterfaceComplex& complex, const std::string& output, const std::string& what, Step step)
{
    const auto start = std::chrono::steady_clock::now();
    step();
    const double seconds = seconds_since(start);
    surface::require_fit_for_tetrahedralization(complex, concat(output, " (", what, ")"));
    return seconds;
}

} // namespace tissuemesh::tools
