// numpy <-> tissuemesh types for the Python module: every array is checked (shape, integer range, finite values)
// and refused with InputError, which Python sees as tissuemesh.InputError (a ValueError).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/tet_mesh.h"

namespace tissuemesh::python {

namespace py = pybind11;

/// A label image from a 3-D integer array indexed [i, j, k] (as nibabel's) and a 4x4 voxel-to-world affine
/// (RAS mm, voxel centres at integer indices); its columns must be orthogonal (no shear).
LabelImage to_image(const py::array& labels, const py::array& affine, const py::dict& names);
/// The labels as a uint16 array [i, j, k], the affine and the names of `image`.
py::tuple from_image(const LabelImage& image);

/// {"vertices": (N, 3) float64, "triangles": (M, 3) uint32, "sides": (M, 2) uint16 (from, to), "names": {label: str},
/// "background": int}
py::dict from_complex(const InterfaceComplex& complex);
InterfaceComplex to_complex(const py::dict& surface);

/// {"vertices": (N, 3), "tets": (T, 4) uint32, "tet_labels": (T,) uint16, "faces": (F, 3) uint32,
/// "face_sides": (F, 2) uint16, "names": {label: str}}
py::dict from_mesh(const TetMesh& mesh);
TetMesh to_mesh(const py::dict& mesh);

/// {label: name} from a Python dict of int -> str.
TissueNames to_names(const py::handle& names);
py::dict from_names(const TissueNames& names);

/// Points (N, 3) as Vec3.
std::vector<Vec3> to_points(const py::handle& array, const char* what);

} // namespace tissuemesh::python
