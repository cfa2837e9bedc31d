// TetMesh: a labelled tetrahedral mesh with its tissue-interface faces.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/vec3.h"

namespace tissuemesh {

using Tet = std::array<std::uint32_t, 4>;

/// Tetrahedra in world mm with a tissue per tet (#tets == #tet_labels), and the faces that lie on tissue
/// interfaces or on the outer boundary (#faces == #face_sides; orientation as in LabelPair: the normal
/// points from `from` into `to`). Tets are positively oriented: det[v1-v0, v2-v0, v3-v0] > 0.
struct TetMesh {
    std::vector<Vec3> vertices;        ///< #V positions, mm
    std::vector<Tet> tets;             ///< #T vertex indices
    std::vector<Label> tet_labels;     ///< #T tissue of each tet
    std::vector<Triangle> faces;       ///< #F interface and boundary faces
    std::vector<LabelPair> face_sides; ///< #F tissues on both sides of each face
    TissueNames names;                 ///< tissue names by label

    std::size_t vertex_count() const { return vertices.size(); }
    std::size_t tet_count() const { return tets.size(); }
};

/// Signed volume (mm^3) of tet `t`: positive when it is positively oriented.
double signed_volume(const TetMesh& mesh, std::size_t t);

/// Throws InputError when the mesh has no tet, indices are out of range, sizes disagree, or a coordinate is
/// not finite.
void validate_indices(const TetMesh& mesh, const std::string& what);

} // namespace tissuemesh
