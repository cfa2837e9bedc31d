#include "core/tet_mesh.h"

#include "core/error.h"

namespace tissuemesh {

double signed_volume(const TetMesh& mesh, std::size_t t)
{
    const Tet& tet = mesh.tets[t];
    const Vec3& a = mesh.vertices[tet[0]];
    return dot(mesh.vertices[tet[1]] - a, cross(mesh.vertices[tet[2]] - a, mesh.vertices[tet[3]] - a)) / 6.0;
}

void validate_indices(const TetMesh& mesh, const std::string& what)
{
    if (mesh.tets.empty())
        throw InputError(concat(what, ": holds no tetrahedra (", mesh.faces.size(), " triangles, ",
                                mesh.vertices.size(), " nodes); give a volume mesh, e.g. from tm-tetra"));
    if (mesh.tet_labels.size() != mesh.tets.size())
        throw InputError(concat(what, ": ", mesh.tets.size(), " tetrahedra but ", mesh.tet_labels.size(),
                                " tissue labels; every tetrahedron needs a tissue"));
    if (mesh.face_sides.size() != mesh.faces.size())
        throw InputError(concat(what, ": ", mesh.faces.size(), " faces but ", mesh.face_sides.size(), " label pairs"));
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
        if (!is_finite(mesh.vertices[v]))
            throw InputError(concat(what, ": node ", v, " has a non-finite coordinate; the mesh file is corrupt"));
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        for (const std::uint32_t v : mesh.tets[t])
            if (v >= mesh.vertices.size())
                throw InputError(concat(what, ": tetrahedron ", t, " refers to node ", v, " but there are only ",
                                        mesh.vertices.size(), " nodes; the mesh file is corrupt"));
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (const std::uint32_t v : mesh.faces[f])
            if (v >= mesh.vertices.size())
                throw InputError(concat(what, ": face ", f, " refers to node ", v, " but there are only ",
                                        mesh.vertices.size(), " nodes; the mesh file is corrupt"));
}

} // namespace tissuemesh
