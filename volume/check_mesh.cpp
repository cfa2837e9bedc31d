#include "volume/check_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "core/tet_shape.h"
#include "core/union_find.h"
#include "surface/detail/cgal_intersections.h"
#include "volume/detail/face_map.h"
#include "volume/rasterize.h"

namespace tissuemesh::volume {
namespace {

using detail::face_key;
using detail::local_faces;

constexpr std::size_t max_problems = 20;

std::string where(const Vec3& p)
{
    return concat("(", format_mm(p[0], 1), ", ", format_mm(p[1], 1), ", ", format_mm(p[2], 1), ") mm");
}

void note(MeshCheckReport& report, std::string text)
{
    if (report.problems.size() < max_problems) report.problems.push_back(std::move(text));
}

/// Whether the vertices of tets a and b opposite their shared face lie on different sides of it.
bool on_opposite_sides(const TetMesh& mesh, const detail::FaceKey& key, std::size_t a, std::size_t b)
{
    const Vec3& p = mesh.vertices[key.v[0]];
    const Vec3 normal = cross(mesh.vertices[key.v[1]] - p, mesh.vertices[key.v[2]] - p);
    auto side = [&](std::size_t t) {
        for (const std::uint32_t v : mesh.tets[t])
            if (v != key.v[0] && v != key.v[1] && v != key.v[2]) return dot(mesh.vertices[v] - p, normal) > 0;
        return false;
    };
    return side(a) != side(b);
}

double longest_edge(const TetMesh& mesh, const Tet& tet)
{
    double longest = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j)
            longest = std::max(longest, distance(mesh.vertices[tet[i]], mesh.vertices[tet[j]]));
    return longest;
}

/// Counts and notes the pairs of outer-boundary faces that cross (exact predicates). A face with collinear corners
/// belongs to a flat tet, counted already, and is left out.
void count_boundary_crossings(const TetMesh& mesh, const std::vector<Triangle>& outer_faces, MeshCheckReport& report)
{
    std::vector<std::uint32_t> candidates;
    for (std::uint32_t f = 0; f < outer_faces.size(); ++f) {
        const Triangle& c = outer_faces[f];
        if (!surface::detail::are_collinear(mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]]))
            candidates.push_back(f);
    }
    const auto crossings = surface::detail::find_intersecting_pairs(mesh.vertices, outer_faces, candidates);
    report.boundary_crossings = crossings.size();
    const auto corners = [&](std::uint32_t f) {
        const Triangle& c = outer_faces[f];
        return std::array<Vec3, 3>{mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]]};
    };
    for (const auto& [a, b] : crossings)
        note(report, concat("the outer boundary passes through itself near ",
                            where(surface::detail::intersection_point(corners(a), corners(b))),
                            ": the tetrahedra behind its two faces there overlap"));
}

} // namespace

MeshCheckReport check_mesh(const TetMesh& mesh, const LabelImage* image, const Progress& progress)
{
    validate_indices(mesh, "mesh");
    MeshCheckReport report;
    report.nodes = mesh.vertices.size(), report.tets = mesh.tets.size(), report.faces = mesh.faces.size();

    std::vector<bool> used(mesh.vertices.size(), false);
    const TetAdjacency adjacency(mesh.tets, mesh.vertices.size());
    double ratio_sum = 0;
    std::vector<float> smallest(mesh.tets.size());
    report.quality.min_dihedral_deg = 180;
    // Each tet's volume, longest edge and shape side by side; summed and reported in order below.
    std::vector<double> volumes(mesh.tets.size()), longest(mesh.tets.size());
    std::vector<TetShape> shapes(mesh.tets.size());
#pragma omp parallel for schedule(static)
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        volumes[t] = signed_volume(mesh, t);
        longest[t] = longest_edge(mesh, mesh.tets[t]);
        shapes[t] = tet_shape(mesh, t);
    }
    const auto tissue_name = [&](Label label) {
        return mesh.names.count(label) ? mesh.names.at(label) : std::to_string(label);
    };
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const Tet& tet = mesh.tets[t];
        for (const std::uint32_t v : tet) used[v] = true;
        const double volume = volumes[t];
        TissueMeshStats& tissue = report.tissues[mesh.tet_labels[t]];
        ++tissue.tets, tissue.volume_mm3 += volume;
        if (!(volume > 0)) {
            ++report.inverted_tets;
            note(report, concat("tetrahedron ", t, " (", tissue_name(mesh.tet_labels[t]), ") has volume ", volume,
                                " mm^3 at ", where(mesh.vertices[tet[0]])));
        } else if (const double edge = longest[t]; volume < flat_volume_ratio * edge * edge * edge) {
            ++report.flat_tets;
            note(report, concat("tetrahedron ", t, " (", tissue_name(mesh.tet_labels[t]), ") is flat: volume ", volume,
                                " mm^3 with edges up to ", edge, " mm at ", where(mesh.vertices[tet[0]]),
                                "; its four nodes are coplanar"));
        }
        const TetShape& shape = shapes[t];
        smallest[t] = static_cast<float>(shape.min_dihedral_deg);
        report.quality.min_dihedral_deg = std::min(report.quality.min_dihedral_deg, shape.min_dihedral_deg);
        report.quality.max_dihedral_deg = std::max(report.quality.max_dihedral_deg, shape.max_dihedral_deg);
        report.quality.max_radius_edge_ratio = std::max(report.quality.max_radius_edge_ratio, shape.radius_edge_ratio);
        ratio_sum += shape.radius_edge_ratio;
        ++report.quality
              .min_dihedral_histogram[std::min<std::size_t>(17, static_cast<std::size_t>(shape.min_dihedral_deg / 10))];
    }
    report.quality.mean_radius_edge_ratio = mesh.tets.empty() ? 0 : ratio_sum / static_cast<double>(mesh.tets.size());
    if (mesh.tets.empty()) report.quality.min_dihedral_deg = 0;
    if (!smallest.empty()) {
        const auto nth = smallest.begin() + static_cast<std::ptrdiff_t>(smallest.size() / 100);
        std::nth_element(smallest.begin(), nth, smallest.end());
        report.quality.p1_min_dihedral_deg = *nth;
    }
    report.unused_nodes = static_cast<std::size_t>(std::count(used.begin(), used.end(), false));
    if (report.unused_nodes > 0) note(report, concat(report.unused_nodes, " nodes belong to no tetrahedron"));
    progress.update("check-mesh", 0.3);

    // Marked faces: each must be a tet face with `from` behind and `to` in front (or nothing / background). The
    // faces are looked up and judged side by side, then counted and noted in order.
    std::vector<char> marked(adjacency.id_count(), 0);
    std::vector<TetAdjacency::Face> found(mesh.faces.size());
    std::vector<std::uint32_t> wrong_tet(mesh.faces.size(), no_tet); // the first tet on the wrong side
    std::vector<Label> expected_label(mesh.faces.size(), 0);
#pragma omp parallel for schedule(static)
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Triangle& tri = mesh.faces[f];
        found[f] = adjacency.find(tri[0], tri[1], tri[2]);
        if (found[f].holders == 0) continue;
        const Vec3& a = mesh.vertices[tri[0]];
        const Vec3 normal = cross(mesh.vertices[tri[1]] - a, mesh.vertices[tri[2]] - a);
        for (const std::uint32_t t : found[f].tets) {
            if (t == no_tet) continue;
            Vec3 centroid{0, 0, 0};
            for (const std::uint32_t v : mesh.tets[static_cast<std::size_t>(t)])
                centroid = centroid + 0.25 * mesh.vertices[v];
            const Label expected = dot(centroid - a, normal) > 0 ? mesh.face_sides[f].to : mesh.face_sides[f].from;
            if (mesh.tet_labels[static_cast<std::size_t>(t)] != expected) {
                wrong_tet[f] = t, expected_label[f] = expected;
                break;
            }
        }
    }
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Vec3& a = mesh.vertices[mesh.faces[f][0]];
        if (found[f].holders == 0) {
            ++report.missing_interface_faces;
            note(report, concat("interface face ", f, " near ", where(a), " is not a face of any tetrahedron"));
            continue;
        }
        marked[found[f].id] = 1;
        if (const std::uint32_t t = wrong_tet[f]; t != no_tet) {
            ++report.mislabelled_interface_faces;
            note(report,
                 concat("interface face ", f, " (", mesh.face_sides[f].from, "|", mesh.face_sides[f].to, ") near ",
                        where(a), " has a tetrahedron of tissue ", mesh.tet_labels[static_cast<std::size_t>(t)],
                        " on the side of tissue ", expected_label[f]));
        }
    }

    // Conformity, tissue changes across unmarked faces, closed outer boundary, tissue components. Whether the two
    // tets of each inner face lie on its two sides is judged side by side first (per face id: 1 when they overlap).
    std::vector<char> overlapping(adjacency.id_count(), 0);
    const auto buckets = static_cast<std::int64_t>(adjacency.vertex_count());
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t v = 0; v < buckets; ++v)
        adjacency.for_each_face_at(static_cast<std::uint32_t>(v), [&](const TetAdjacency::Face& face) {
            if (face.holders == 2)
                overlapping[face.id] =
                    !on_opposite_sides(mesh, detail::FaceKey{face.vertices}, face.tets[0], face.tets[1]);
        });
    UnionFind pieces(mesh.tets.size());
    std::unordered_map<std::uint64_t, int> boundary_edges;
    std::vector<Triangle> outer_faces;
    const auto judge = [&](const TetAdjacency::Face& face) {
        const detail::FaceKey key{face.vertices};
        if (face.holders > 2) {
            ++report.nonconforming_faces;
            note(report,
                 concat("a face near ", where(mesh.vertices[key.v[0]]), " is shared by ", face.holders, " tetrahedra"));
        } else if (face.holders == 2) {
            const std::size_t t0 = face.tets[0], t1 = face.tets[1];
            if (overlapping[face.id]) {
                ++report.nonconforming_faces;
                note(report, concat("tetrahedra ", t0, " and ", t1, " overlap across a face near ",
                                    where(mesh.vertices[key.v[0]])));
            }
            if (mesh.tet_labels[t0] == mesh.tet_labels[t1])
                pieces.unite(static_cast<std::uint32_t>(t0), static_cast<std::uint32_t>(t1));
            else if (!marked[face.id]) {
                ++report.unmarked_interfaces;
                note(report,
                     concat("tissues ", mesh.tet_labels[t0], " and ", mesh.tet_labels[t1], " meet near ",
                            where(mesh.vertices[key.v[0]]), " across a face that is not marked as an interface"));
            }
        } else {
            // An outer-boundary face: count its directed edges (all faces are oriented alike, inward), so a
            // closed boundary matches every edge with its reverse.
            const Tet& tet = mesh.tets[face.tets[0]];
            for (const auto& local : local_faces) {
                if (face_key(tet[local[0]], tet[local[1]], tet[local[2]]) != key) continue;
                outer_faces.push_back({tet[local[0]], tet[local[1]], tet[local[2]]});
                for (int e = 0; e < 3; ++e) {
                    const std::uint64_t from = tet[local[e]], to = tet[local[(e + 1) % 3]];
                    boundary_edges[from << 32 | to] += 1;
                    boundary_edges[to << 32 | from] -= 1;
                }
            }
        }
    };
    for (std::uint32_t v = 0; v < adjacency.vertex_count(); ++v) adjacency.for_each_face_at(v, judge);
    for (const auto& [edge, balance] : boundary_edges)
        if (balance != 0) ++report.open_boundary_edges;
    report.open_boundary_edges /= 2; // each unmatched edge was counted in both directions
    if (report.open_boundary_edges > 0)
        note(report, concat(report.open_boundary_edges, " edges of the outer boundary are open"));
    count_boundary_crossings(mesh, outer_faces, report);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
        if (pieces.find(static_cast<std::uint32_t>(t)) == t) ++report.tissues[mesh.tet_labels[t]].components;
    progress.update("check-mesh", 0.6);

    if (image != nullptr && !image->empty()) {
        const std::vector<std::int32_t> owner = rasterize_tets(mesh, *image, adjacency, progress);
        std::map<Label, std::size_t> in_image, in_mesh, both;
        for (std::size_t v = 0; v < owner.size(); ++v) {
            const Label truth = image->labels()[v];
            ++in_image[truth];
            if (owner[v] < 0) continue;
            const Label meshed = mesh.tet_labels[static_cast<std::size_t>(owner[v])];
            ++in_mesh[meshed];
            if (meshed == truth) ++both[truth];
        }
        for (auto& [label, stats] : report.tissues) {
            const double a = static_cast<double>(in_image[label]), b = static_cast<double>(in_mesh[label]);
            stats.voxel_volume_mm3 = a * image->voxel_volume_mm3();
            stats.dice = a + b > 0 ? 2.0 * static_cast<double>(both[label]) / (a + b) : 1.0;
        }
    }
    progress.update("check-mesh", 1.0);
    return report;
}

} // namespace tissuemesh::volume
