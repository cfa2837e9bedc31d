#include "tests/support/programs.h"

#include "tests/support/complexes.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::testing {

TetMesh nested_cubes_mesh()
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
    options.max_volume_mm3 = 0.5;  // a few hundred tets: several per tissue, fast everywhere
    return volume::tetrahedralize(complex, options);
}

std::map<Label, double> tissue_volumes(const TetMesh& mesh)
{
    std::map<Label, double> volumes;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) volumes[mesh.tet_labels[t]] += signed_volume(mesh, t);
    return volumes;
}

} // namespace tissuemesh::testing
