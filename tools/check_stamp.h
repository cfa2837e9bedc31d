// The stamp of a passed check. tm-smooth, tm-decimate and tm-remesh check their input and their output in full
// (surface/check_complex.h): in a chain, each output is checked twice, once by the tool that wrote it and again
// by the next one. So when the check of its output has passed, a tool writes a stamp into the .ply header: the
// checker's version and a digest of everything the check looks at. The next tool computes the digest of what
// it read; when both match, the same checker has already passed exactly this complex, and the full check of
// the input is skipped (the tool says so; --check-input checks anyway). Any change to the file's geometry,
// triangles or tissue pairs changes the digest, and the input is checked again.
#pragma once

#include <string>

#include "core/interface_complex.h"

namespace tissuemesh::tools {

/// "tissuemesh-checked <version> <digest>": the digest (64 bits, hex) of the vertices, triangles, tissue pairs
/// and background of `complex`.
std::string check_stamp(const InterfaceComplex& complex);

/// The stamp in the header of the .ply file `path` ("" when there is none, or the file is not a .ply).
std::string read_check_stamp(const std::string& path);

} // namespace tissuemesh::tools
