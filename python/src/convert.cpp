#include "python/src/convert.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/error.h"

namespace tissuemesh::python {
namespace {

/// A C-ordered float64 copy of `object` with `columns` columns (0: a vector).
py::array_t<double, py::array::c_style | py::array::forcecast> floats(const py::handle& object, std::size_t columns,
                                                                      const char* what)
{
    const py::array array = py::array::ensure(object);
    if (!array || array.dtype().kind() == 'O' || array.dtype().kind() == 'U' || array.dtype().kind() == 'S')
        throw InputError(concat(what, " must be a numeric array"));
    auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    if (columns > 0 && (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != columns))
        throw InputError(concat(what, " must have shape (n, ", columns, "), not ",
                                py::str(py::tuple(array.attr("shape"))).cast<std::string>()));
    for (py::ssize_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values.data()[i])) throw InputError(concat(what, " holds a value that is not finite"));
    return values;
}

/// The integer entries of `object` (any integer dtype), C order, each checked against 0..max.
std::vector<std::int64_t> integers(const py::handle& object, std::size_t columns, std::int64_t max, const char* what)
{
    const py::array array = py::array::ensure(object);
    if (!array || (array.dtype().kind() != 'i' && array.dtype().kind() != 'u' && array.dtype().kind() != 'b'))
        throw InputError(concat(what, " must be an integer array"));
    const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    if (columns > 0 && (values.ndim() != 2 || static_cast<std::size_t>(values.shape(1)) != columns))
        throw InputError(concat(what, " must have shape (n, ", columns, ")"));
    if (columns == 0 && values.ndim() != 1) throw InputError(concat(what, " must be one-dimensional"));
    std::vector<std::int64_t> result(values.data(), values.data() + values.size());
    for (const std::int64_t v : result)
        if (v < 0 || v > max) throw InputError(concat(what, " holds ", v, ", outside 0..", max));
    return result;
}

template <typename T, std::size_t N>
py::array_t<T> table(const std::vector<std::array<T, N>>& rows)
{
    py::array_t<T> out({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(N)});
    T* data = out.mutable_data();
    for (std::size_t r = 0; r < rows.size(); ++r)
        for (std::size_t c = 0; c < N; ++c) data[N * r + c] = rows[r][c];
    return out;
}

py::array_t<Label> pairs(const std::vector<LabelPair>& sides)
{
    std::vector<std::array<Label, 2>> rows;
    rows.reserve(sides.size());
    for (const LabelPair& side : sides) rows.push_back({side.from, side.to});
    return table(rows);
}

template <std::size_t N>
std::vector<std::array<std::uint32_t, N>> indices(const py::handle& object, std::size_t vertices, const char* what)
{
    const std::vector<std::int64_t> flat = integers(object, N, static_cast<std::int64_t>(vertices) - 1, what);
    std::vector<std::array<std::uint32_t, N>> rows(flat.size() / N);
    for (std::size_t i = 0; i < flat.size(); ++i) rows[i / N][i % N] = static_cast<std::uint32_t>(flat[i]);
    return rows;
}

std::vector<LabelPair> to_pairs(const py::handle& object, const char* what)
{
    const std::vector<std::int64_t> flat = integers(object, 2, 65535, what);
    std::vector<LabelPair> sides(flat.size() / 2);
    for (std::size_t i = 0; i < sides.size(); ++i)
        sides[i] = {static_cast<Label>(flat[2 * i]), static_cast<Label>(flat[2 * i + 1])};
    return sides;
}

py::handle item(const py::dict& dict, const char* key, const char* what)
{
    if (!dict.contains(key)) throw InputError(concat(what, " has no \"", key, "\"; pass the dict tissuemesh returned"));
    return dict[key];
}

} // namespace

std::vector<Vec3> to_points(const py::handle& array, const char* what)
{
    const auto values = floats(array, 3, what);
    std::vector<Vec3> points(static_cast<std::size_t>(values.shape(0)));
    for (std::size_t i = 0; i < points.size(); ++i) points[i] = {values.at(i, 0), values.at(i, 1), values.at(i, 2)};
    return points;
}

TissueNames to_names(const py::handle& names)
{
    TissueNames result;
    if (names.is_none()) return result;
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(names)) {
        const auto label = key.cast<long long>();
        if (label < 0 || label > 65535) throw InputError(concat("names: label ", label, " is outside 0..65535"));
        result[static_cast<Label>(label)] = py::str(value).cast<std::string>();
    }
    return result;
}

py::dict from_names(const TissueNames& names)
{
    py::dict result;
    for (const auto& [label, name] : names) result[py::int_(label)] = name;
    return result;
}

LabelImage to_image(const py::array& labels, const py::array& affine, const py::dict& names)
{
    if (labels.ndim() != 3) throw InputError(concat("labels must be a 3-D array [i, j, k], not ", labels.ndim(), "-D"));
    const auto matrix = floats(affine, 4, "affine");
    if (matrix.shape(0) != 4 || matrix.at(3, 0) != 0 || matrix.at(3, 1) != 0 || matrix.at(3, 2) != 0 ||
        matrix.at(3, 3) != 1)
        throw InputError("affine must be 4 x 4 with last row 0 0 0 1 (voxel index to world mm, as nibabel's)");
    Vec3 spacing{}, origin{};
    Mat3 direction{};
    for (std::size_t c = 0; c < 3; ++c) {
        const Vec3 column{matrix.at(0, c), matrix.at(1, c), matrix.at(2, c)};
        spacing[c] = norm(column);
        if (!(spacing[c] > 0))
            throw InputError(concat("affine column ", c, " is zero: voxel axis ", c, " has no length"));
        for (std::size_t r = 0; r < 3; ++r) direction[3 * r + c] = column[r] / spacing[c];
        origin[c] = matrix.at(c, 3);
    }
    const Dims dims{static_cast<std::size_t>(labels.shape(0)), static_cast<std::size_t>(labels.shape(1)),
                    static_cast<std::size_t>(labels.shape(2))};
    validate_geometry("affine", dims, spacing, direction);
    // [i, j, k] in any memory order -> x fastest.
    const py::array fortran = py::module_::import("numpy").attr("asfortranarray")(labels);
    const std::vector<std::int64_t> values = integers(fortran.attr("ravel")("F"), 0, 65535, "labels");
    LabelImage image(dims, spacing, origin, direction);
    for (std::size_t v = 0; v < values.size(); ++v) image.labels()[v] = static_cast<Label>(values[v]);
    image.names() = to_names(names);
    return image;
}

py::tuple from_image(const LabelImage& image)
{
    const Dims& d = image.dims();
    py::array_t<Label, py::array::f_style> labels(
        {static_cast<py::ssize_t>(d[0]), static_cast<py::ssize_t>(d[1]), static_cast<py::ssize_t>(d[2])});
    std::copy(image.labels().begin(), image.labels().end(), labels.mutable_data());
    py::array_t<double> affine({4, 4});
    auto a = affine.mutable_unchecked<2>();
    for (py::ssize_t r = 0; r < 4; ++r)
        for (py::ssize_t c = 0; c < 4; ++c) a(r, c) = r == 3 ? (c == 3 ? 1.0 : 0.0) : 0.0;
    for (std::size_t r = 0; r < 3; ++r) {
        for (std::size_t c = 0; c < 3; ++c) a(r, c) = image.direction()[3 * r + c] * image.spacing_mm()[c];
        a(r, 3) = image.origin_mm()[r];
    }
    return py::make_tuple(labels, affine, from_names(image.names()));
}

py::dict from_complex(const InterfaceComplex& complex)
{
    py::dict surface;
    surface["vertices"] = table(complex.vertices);
    surface["triangles"] = table(complex.triangles);
    surface["sides"] = pairs(complex.sides);
    surface["names"] = from_names(complex.names);
    surface["background"] = complex.background;
    return surface;
}

InterfaceComplex to_complex(const py::dict& surface)
{
    InterfaceComplex complex;
    complex.vertices = to_points(item(surface, "vertices", "surface"), "surface vertices");
    complex.triangles = indices<3>(item(surface, "triangles", "surface"), complex.vertices.size(), "surface triangles");
    complex.sides = to_pairs(item(surface, "sides", "surface"), "surface sides");
    if (surface.contains("names")) complex.names = to_names(surface["names"]);
    if (surface.contains("background")) {
        const auto background = surface["background"].cast<long long>();
        if (background < 0 || background > 65535)
            throw InputError(concat("surface background ", background, " is outside 0..65535"));
        complex.background = static_cast<Label>(background);
    }
    validate_indices(complex, "surface");
    return complex;
}

py::dict from_mesh(const TetMesh& mesh)
{
    py::dict out;
    out["vertices"] = table(mesh.vertices);
    out["tets"] = table(mesh.tets);
    out["tet_labels"] = py::array_t<Label>(static_cast<py::ssize_t>(mesh.tet_labels.size()), mesh.tet_labels.data());
    out["faces"] = table(mesh.faces);
    out["face_sides"] = pairs(mesh.face_sides);
    out["names"] = from_names(mesh.names);
    return out;
}

TetMesh to_mesh(const py::dict& dict)
{
    TetMesh mesh;
    mesh.vertices = to_points(item(dict, "vertices", "mesh"), "mesh vertices");
    mesh.tets = indices<4>(item(dict, "tets", "mesh"), mesh.vertices.size(), "mesh tets");
    for (const std::int64_t label : integers(item(dict, "tet_labels", "mesh"), 0, 65535, "mesh tet_labels"))
        mesh.tet_labels.push_back(static_cast<Label>(label));
    if (dict.contains("faces")) mesh.faces = indices<3>(dict["faces"], mesh.vertices.size(), "mesh faces");
    if (dict.contains("face_sides")) mesh.face_sides = to_pairs(dict["face_sides"], "mesh face_sides");
    if (dict.contains("names")) mesh.names = to_names(dict["names"]);
    validate_indices(mesh, "mesh");
    return mesh;
}

} // namespace tissuemesh::python
