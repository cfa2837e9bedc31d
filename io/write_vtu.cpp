#include "io/write_vtu.h"

#include <cmath>
#include <fstream>
#include <iomanip>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::io {
namespace {

void check_size(const VtuArray& array, std::size_t entries, const char* what, const std::filesystem::path& path)
{
    if (array.components < 1 || array.values.size() != entries * static_cast<std::size_t>(array.components))
        throw InputError(concat(path.string(), ": array \"", array.name, "\" has ", array.values.size(), " values for ",
                                entries, " ", what, " x ", array.components, " components"));
}

void write_array(std::ostream& out, const VtuArray& array)
{
    out << "<DataArray type=\"" << (array.integer ? "Int64" : "Float64") << "\" Name=\"" << array.name
        << "\" NumberOfComponents=\"" << array.components << "\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < array.values.size(); ++i) {
        const double value = array.values[i];
        if (array.integer) out << static_cast<long long>(value);
        else out << (std::isfinite(value) ? value : (value > 0 ? 1e30 : -1e30));
        out << ((i + 1) % static_cast<std::size_t>(array.components) == 0 ? '\n' : ' ');
    }
    out << "</DataArray>\n";
}

void write_grid(std::ostream& out, const TetMesh& mesh, const std::vector<VtuArray>& point_arrays,
                const std::vector<VtuArray>& cell_arrays)
{
    out << std::setprecision(17)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.vertices.size() << "\" NumberOfCells=\""
        << mesh.tets.size() << "\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& v : mesh.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const Tet& tet : mesh.tets) out << tet[0] << ' ' << tet[1] << ' ' << tet[2] << ' ' << tet[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 1; t <= mesh.tets.size(); ++t) out << 4 * t << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) out << "10\n";  // VTK_TETRA
    out << "</DataArray>\n</Cells>\n";
    if (!point_arrays.empty()) {
        out << "<PointData Scalars=\"" << point_arrays.front().name << "\">\n";
        for (const VtuArray& array : point_arrays) write_array(out, array);
        out << "</PointData>\n";
    }
    out << "<CellData Scalars=\"tissue\">\n<DataArray type=\"UInt16\" Name=\"tissue\" format=\"ascii\">\n";
    for (const Label label : mesh.tet_labels) out << label << '\n';
    out << "</DataArray>\n";
    for (const VtuArray& array : cell_arrays) write_array(out, array);
    out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

} // namespace

void write_vtu(const TetMesh& mesh, const std::filesystem::path& path, const std::vector<VtuArray>& point_arrays,
               const std::vector<VtuArray>& cell_arrays)
{
    validate_indices(mesh, path.string());
    for (const VtuArray& array : point_arrays) check_size(array, mesh.vertices.size(), "points", path);
    for (const VtuArray& array : cell_arrays) check_size(array, mesh.tets.size(), "cells", path);
    write_atomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        if (!out) throw IoError(concat(path.string(), ": cannot open for writing; check the folder and permissions"));
        write_grid(out, mesh, point_arrays, cell_arrays);
        out.close();
        if (!out) throw IoError(concat(path.string(), ": write failed (disk full?)"));
    });
}

} // namespace tissuemesh::io
