#include "volume/write_assessment_vtu.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"

namespace tissuemesh::volume {
namespace {

void write_points_and_cells(const TetMesh& mesh, std::ostream& out)
{
    out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n" << std::setprecision(17);
    for (const Vec3& v : mesh.vertices) out << v[0] << ' ' << v[1] << ' ' << v[2] << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const Tet& tet : mesh.tets) out << tet[0] << ' ' << tet[1] << ' ' << tet[2] << ' ' << tet[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) out << 4 * (t + 1) << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) out << "10\n";
    out << "</DataArray>\n</Cells>\n";
}

template <typename Value>
void write_integers(std::ostream& out, const char* type, const char* name, const std::vector<Value>& values)
{
    out << "<DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n";
    for (const Value value : values) out << static_cast<unsigned long long>(value) << '\n';
    out << "</DataArray>\n";
}

void write_reals(std::ostream& out, const char* name, const std::vector<double>& values)
{
    out << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n" << std::setprecision(9);
    for (const double value : values) out << (std::isfinite(value) ? value : (value > 0 ? 1e30 : -1e30)) << '\n';
    out << "</DataArray>\n";
}

} // namespace

void write_assessment_vtu(const TetMesh& mesh, const Assessment& assessment, const std::filesystem::path& path)
{
    const std::size_t tets = mesh.tets.size();
    if (assessment.majority.size() != tets || assessment.quality_key.size() != tets)
        throw InputError(concat(path.string(), ": the assessment has ", assessment.majority.size(), " tets, the mesh ", tets,
                                "; assess this mesh before writing it"));
    write_atomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        if (!out) throw IoError(concat(path.string(), ": cannot open for writing; check the folder and permissions"));
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            << "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" << mesh.vertices.size() << "\" NumberOfCells=\"" << tets << "\">\n";
        write_points_and_cells(mesh, out);
        out << "<CellData Scalars=\"tissue\">\n";
        write_integers(out, "UInt16", "tissue", mesh.tet_labels);
        write_integers(out, "UInt16", "majority", assessment.majority);
        write_reals(out, "error_volume_mm3", assessment.error_volume_mm3);
        write_reals(out, "majority_error_volume_mm3", assessment.majority_error_volume_mm3);
        write_reals(out, "quality_key", assessment.quality_key);
        write_integers(out, "UInt32", "voxel_count", assessment.voxel_count);
        write_integers(out, "UInt8", "sampled", assessment.sampled);
        write_reals(out, "volume_mm3", assessment.volume_mm3);
        write_reals(out, "min_dihedral_deg", assessment.min_dihedral_deg);
        write_reals(out, "radius_edge_ratio", assessment.radius_edge_ratio);
        write_reals(out, "aspect_ratio", assessment.aspect_ratio);
        out << "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
        out.close();
        if (!out) throw IoError(concat(path.string(), ": write failed (disk full?)"));
    });
}

} // namespace tissuemesh::volume
