#include "tests/support/programs.h"

#include <utility>

#include "image/phantom.h"
#include "surface/extract_interfaces.h"
#include "tests/support/complexes.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::testing {

namespace {

TetMesh make_nested_cubes_mesh()
{
    VoxelBlock block;
    block.nx = block.ny = block.nz = 4;
    block.labels.assign(64, 1);
    for (std::size_t k = 1; k < 3; ++k)
        for (std::size_t j = 1; j < 3; ++j)
            for (std::size_t i = 1; i < 3; ++i) block.labels[i + 4 * (j + 4 * k)] = 2;
    InterfaceComplex complex = voxel_faces(block);
    complex.names = {{1, "outer"}, {2, "inner"}};
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = 0.5; // a few hundred tets: several per tissue, fast everywhere
    return volume::tetrahedralize(complex, options);
}

} // namespace

const TetMesh& nested_cubes_mesh()
{
    static const TetMesh mesh = make_nested_cubes_mesh();
    return mesh;
}

const MeshedPhantom& meshed_phantom(const std::string& name, double voxel_mm)
{
    static std::map<std::pair<std::string, double>, MeshedPhantom> made;
    const auto [it, fresh] = made.try_emplace({name, voxel_mm});
    if (fresh) {
        it->second.image = image::make_phantom(name, {.voxel_mm = voxel_mm}).image;
        it->second.mesh = volume::tetrahedralize(surface::extract_interfaces(it->second.image));
    }
    return it->second;
}

void orient_positively(TetMesh& mesh)
{
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (signed_volume(mesh, t) < 0) std::swap(mesh.tets[t][2], mesh.tets[t][3]);
}

TetMesh single_tet(const std::array<Vec3, 4>& corners, Label tissue)
{
    TetMesh mesh;
    mesh.vertices.assign(corners.begin(), corners.end());
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_labels = {tissue};
    orient_positively(mesh);
    return mesh;
}

TetMesh kuhn_cube(double s)
{
    TetMesh mesh;
    for (int c = 0; c < 8; ++c) mesh.vertices.push_back({s * (c & 1), s * (c >> 1 & 1), s * (c >> 2 & 1)});
    for (const auto& order : kuhn_axis_orders) {
        const std::uint32_t a = 1u << order[0], b = a | 1u << order[1];
        mesh.tets.push_back({0, a, b, 7});
        mesh.tet_labels.push_back(1);
    }
    orient_positively(mesh);
    return mesh;
}

std::map<Label, double> tissue_volumes(const TetMesh& mesh)
{
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) volumes[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return volumes;
}

} // namespace tissuemesh::testing
