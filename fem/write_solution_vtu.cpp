#include "fem/write_solution_vtu.h"

#include <fstream>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::fem {
namespace {

void write_vectors(std::ostream& out, const char* name, const std::vector<Vec3>& values)
{
    out << "<DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& v : values) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    out << "</DataArray>\n";
}

void write_body(std::ostream& out, const TetMesh& mesh, const std::vector<double>& potential_v, const TetFields& fields,
                const std::vector<double>& error_indicator)
{
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.vertex_count() << "\" NumberOfCells=\""
        << mesh.tet_count() << "\">\n<Points>\n";
    write_vectors(out, "points_mm", mesh.vertices);
    out << "</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const Tet& tet : mesh.tets) out << tet[0] << ' ' << tet[1] << ' ' << tet[2] << ' ' << tet[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 1; t <= mesh.tet_count(); ++t) out << 4 * t << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) out << "10\n";  // VTK_TETRA
    out << "</DataArray>\n</Cells>\n<PointData Scalars=\"potential_V\">\n"
        << "<DataArray type=\"Float64\" Name=\"potential_V\" format=\"ascii\">\n";
    for (double value : potential_v) out << value << '\n';
    out << "</DataArray>\n</PointData>\n<CellData Scalars=\"tissue\">\n"
        << "<DataArray type=\"UInt16\" Name=\"tissue\" format=\"ascii\">\n";
    for (Label label : mesh.tet_labels) out << label << '\n';
    out << "</DataArray>\n";
    write_vectors(out, "E_V_per_m", fields.electric_v_per_m);
    write_vectors(out, "J_A_per_m2", fields.current_a_per_m2);
    out << "<DataArray type=\"Float64\" Name=\"E_magnitude_V_per_m\" format=\"ascii\">\n";
    for (const Vec3& e : fields.electric_v_per_m) out << norm(e) << '\n';
    out << "</DataArray>\n";
    if (!error_indicator.empty()) {
        out << "<DataArray type=\"Float64\" Name=\"error_indicator\" format=\"ascii\">\n";
        for (double value : error_indicator) out << value << '\n';
        out << "</DataArray>\n";
    }
    out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
}

} // namespace

void write_solution_vtu(const std::filesystem::path& path, const TetMesh& mesh, const std::vector<double>& potential_v,
                        const TetFields& fields, const std::vector<double>& error_indicator)
{
    if (potential_v.size() != mesh.vertex_count() || fields.electric_v_per_m.size() != mesh.tet_count() ||
        fields.current_a_per_m2.size() != mesh.tet_count() ||
        (!error_indicator.empty() && error_indicator.size() != mesh.tet_count()))
        throw InputError(concat(path.string(), ": solution arrays do not match the mesh (", mesh.vertex_count(),
                                " nodes, ", mesh.tet_count(), " tets); compute them on this mesh"));
    write_atomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        if (!out) throw IoError(concat(path.string(), ": cannot open for writing; check the folder's permissions"));
        write_body(out, mesh, potential_v, fields, error_indicator);
        out.flush();
        if (!out) throw IoError(concat(path.string(), ": write failed (disk full?)"));
    });
}

} // namespace tissuemesh::fem
