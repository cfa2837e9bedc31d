#include "io/read_vtu.h"

#include <charconv>
#include <cmath>
#include <map>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/msh_common.h"
#include "io/detail/text_records.h"
#include "io/detail/vtk_xml.h"

namespace tissuemesh::io {
namespace {

using detail::VtkDataArray;
using detail::VtkXmlFile;

[[noreturn]] void fail(const std::string& what, const std::string& problem, const std::string& fix)
{
    throw IoError(concat(what, ": ", problem, "; ", fix));
}

/// VTK's name of cell type `type` (vtkCellType.h), for messages.
std::string cell_type_name(double type)
{
    static const std::map<int, const char*> names{{1, "vertex"},
                                                  {2, "poly-vertex"},
                                                  {3, "line"},
                                                  {4, "poly-line"},
                                                  {5, "triangle"},
                                                  {6, "triangle strip"},
                                                  {7, "polygon"},
                                                  {8, "pixel"},
                                                  {9, "quad"},
                                                  {10, "tetra"},
                                                  {11, "voxel"},
                                                  {12, "hexahedron"},
                                                  {13, "wedge"},
                                                  {14, "pyramid"},
                                                  {21, "quadratic edge"},
                                                  {22, "quadratic triangle"},
                                                  {23, "quadratic quad"},
                                                  {24, "quadratic tetra"},
                                                  {25, "quadratic hexahedron"},
                                                  {42, "polyhedron"}};
    const auto found = std::isfinite(type) && std::abs(type) < 1e6 ? names.find(static_cast<int>(type)) : names.end();
    return found != names.end() ? concat(found->second, " (VTK type ", type, ")") : concat("VTK type ", type);
}

std::size_t piece_count(const VtkXmlFile& file, const std::string& key)
{
    const auto found = file.pieces.front().find(key);
    const std::string text = found == file.pieces.front().end() ? "" : found->second;
    unsigned long long value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size())
        fail(file.what, concat("<Piece ", key, "=\"", text.substr(0, 30), "\"> is not a count"),
             "the file is corrupt; write it again");
    return static_cast<std::size_t>(value);
}

/// The one array of `section` named `name` (any name when empty); null when `required` is false and there is none.
const VtkDataArray* find_array(const VtkXmlFile& file, const std::string& section, const std::string& name,
                               bool required = true)
{
    for (const VtkDataArray& array : file.arrays)
        if (array.section == section && (name.empty() || array.name() == name)) return &array;
    if (required)
        fail(file.what, concat("no <", section, "> DataArray", name.empty() ? "" : " \"" + name + "\""),
             "not a complete unstructured grid; write it again");
    return nullptr;
}

int components_of(const VtkXmlFile& file, const VtkDataArray& array)
{
    const std::string text = array.attribute("NumberOfComponents");
    int components = 1;
    if (!text.empty()) {
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), components);
        if (error != std::errc() || end != text.data() + text.size() || components < 1 || components > 64)
            fail(file.what, concat("DataArray \"", array.name(), "\" has ", text.substr(0, 20), " components"),
                 "the file is corrupt");
    }
    return components;
}

/// The tets from the <Cells> arrays: every cell a tetra, offsets 4, 8, ..., indices below `points`.
void read_cells(const VtkXmlFile& file, std::size_t cells, TetMesh& mesh)
{
    const std::vector<double> types =
        detail::decode_data_array(file, *find_array(file, "Cells", "types"), cells, "cells");
    for (std::size_t c = 0; c < cells; ++c)
        if (types[c] != 10)
            fail(file.what, concat("cell ", c, " is a ", cell_type_name(types[c]), "; only tetrahedra are read"),
                 "keep the tets only (ParaView: Extract Cells By Type; meshio: drop the other cell blocks)");
    const std::vector<double> offsets =
        detail::decode_data_array(file, *find_array(file, "Cells", "offsets"), cells, "cells");
    for (std::size_t c = 0; c < cells; ++c)
        if (offsets[c] != static_cast<double>(4 * (c + 1)))
            fail(file.what, concat("cell ", c, " ends at offset ", offsets[c], " where a tetra ends at ", 4 * (c + 1)),
                 "the file is corrupt");
    const std::vector<double> corners =
        detail::decode_data_array(file, *find_array(file, "Cells", "connectivity"), 4 * cells, "corners");
    const double points = static_cast<double>(mesh.vertices.size());
    mesh.tets.reserve(cells);
    for (std::size_t c = 0; c < cells; ++c) {
        std::array<std::uint32_t, 4> tet{};
        for (std::size_t i = 0; i < 4; ++i) {
            const double index = corners[4 * c + i];
            if (!(index >= 0 && index < points && index == std::floor(index)))
                throw InputError(concat(file.what, ": cell ", c, " refers to point ", index, " of ",
                                        mesh.vertices.size(), "; the file is corrupt"));
            tet[i] = static_cast<std::uint32_t>(index);
        }
        detail::add_tet(mesh, tet, 0);
    }
}

/// Every array of `section` (PointData or CellData) with `entries` entries.
std::vector<VtuArray> read_arrays(const VtkXmlFile& file, const std::string& section, std::size_t entries,
                                  const char* items)
{
    std::vector<VtuArray> arrays;
    for (const VtkDataArray& array : file.arrays) {
        if (array.section != section) continue;
        const int components = components_of(file, array);
        if (entries > 0 && static_cast<std::size_t>(components) > (std::size_t{1} << 40) / entries)
            fail(file.what, concat("DataArray \"", array.name(), "\" is too large"), "the file is corrupt");
        arrays.push_back({array.name(),
                          detail::decode_data_array(file, array, entries * static_cast<std::size_t>(components), items),
                          components, array.integer()});
    }
    return arrays;
}

/// Moves the first label array found (scalar, integer values 0..65535) into the tet labels.
void take_labels(const std::string& what, VtuContent& content)
{
    for (const char* name : {"tissue", "gmsh:physical", "medit:ref", "tetgen:ref"}) {
        const auto found = std::find_if(content.cell_arrays.begin(), content.cell_arrays.end(),
                                        [&](const VtuArray& a) { return a.name == name && a.components == 1; });
        if (found == content.cell_arrays.end()) continue;
        for (std::size_t t = 0; t < found->values.size(); ++t)
            content.mesh.tet_labels[t] = detail::checked_label(found->values[t], [&](double value) {
                throw InputError(
                    concat(what, ": cell ", t, " has ", name, " label ", value, "; labels are integers 0..65535"));
            });
        content.label_array = name;
        content.cell_arrays.erase(found);
        return;
    }
}

} // namespace

const VtuArray* VtuContent::point_array(const std::string& name) const
{
    for (const VtuArray& array : point_arrays)
        if (array.name == name) return &array;
    return nullptr;
}

const VtuArray* VtuContent::cell_array(const std::string& name) const
{
    for (const VtuArray& array : cell_arrays)
        if (array.name == name) return &array;
    return nullptr;
}

VtuContent read_vtu(const std::filesystem::path& path)
{
    const std::string bytes = read_file_bytes(path);
    const VtkXmlFile file = detail::scan_vtk_xml(bytes, path.string());
    const auto type = file.vtk_file.find("type");
    if (type == file.vtk_file.end() || type->second != "UnstructuredGrid")
        fail(file.what,
             concat("a VTK file of type \"", type == file.vtk_file.end() ? "" : type->second,
                    "\", not UnstructuredGrid"),
             "only tet meshes are read from .vtu (surfaces: .vtp)");
    if (file.pieces.size() != 1)
        fail(file.what, concat(file.pieces.size(), " pieces where one is read"),
             "merge them into one (ParaView: Merge Blocks) and save again");
    const std::size_t points = piece_count(file, "NumberOfPoints"), cells = piece_count(file, "NumberOfCells");
    VtuContent content;
    const VtkDataArray& coordinates = *find_array(file, "Points", "");
    if (components_of(file, coordinates) != 3)
        fail(file.what, "the points do not have 3 coordinates", "write 3-D points");
    const std::vector<double> xyz = detail::decode_data_array(file, coordinates, 3 * points, "points");
    content.mesh.vertices.resize(points);
    for (std::size_t p = 0; p < points; ++p) content.mesh.vertices[p] = {xyz[3 * p], xyz[3 * p + 1], xyz[3 * p + 2]};
    read_cells(file, cells, content.mesh);
    content.point_arrays = read_arrays(file, "PointData", points, "points");
    content.cell_arrays = read_arrays(file, "CellData", cells, "cells");
    take_labels(file.what, content);
    validate_indices(content.mesh, file.what);
    return content;
}

} // namespace tissuemesh::io
