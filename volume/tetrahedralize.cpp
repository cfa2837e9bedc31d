#include "volume/tetrahedralize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>

#include "core/error.h"
#include "core/tet_adjacency.h"
#include "core/tet_shape.h"
#include "surface/check_complex.h"
#include "volume/check_mesh.h"
#include "volume/detail/improver.h"
#include "volume/detail/layer_points.h"
#include "volume/detail/surface_reference.h"
#include "volume/detail/tetgen_adapter.h"

namespace tissuemesh::volume {
namespace {

constexpr Label unlabelled = std::numeric_limits<Label>::max();

std::string build_switches(const TetrahedralizeOptions& options, bool with_regions)
{
    // p: the input is a PLC; z: zero-based; Q: quiet; M: never merge coplanar facets, so every output
    // face keeps the marker of its own input triangle.
    std::string switches = "pzQM";
    if (options.preserve_interfaces) switches += "Y";
    if (options.improve_quality) switches += concat("q", options.max_radius_edge_ratio, "/", options.min_dihedral_deg);
    if (with_regions) switches += "Aa";
    if (options.max_volume_mm3 > 0) switches += concat("a", options.max_volume_mm3);
    switches += concat("O", options.optimisation_level);
    return switches;
}

Vec3 triangle_normal(const InterfaceComplex& complex, std::size_t t)
{
    const Triangle& tri = complex.triangles[t];
    const Vec3& a = complex.vertices[tri[0]];
    return cross(complex.vertices[tri[1]] - a, complex.vertices[tri[2]] - a);
}

/// One seed per closed shell of each sized tissue, just behind the shell's roomiest triangle: every connected
/// piece of the tissue gets its bound (a piece with cavities gets a seed per shell, all of the same region).
std::vector<detail::TetgenRegion> region_seeds(const InterfaceComplex& complex, const TetrahedralizeOptions& options)
{
    std::vector<detail::TetgenRegion> regions;
    for (const auto& [tissue, max_volume] : options.max_volume_per_tissue_mm3) {
        const std::vector<std::vector<std::uint32_t>> shells = surface::tissue_shells(complex, tissue);
        if (shells.empty())
            throw InputError(concat("--max-volume names tissue ", tissue, ", which the surface does not contain"));
        for (const std::vector<std::uint32_t>& shell : shells) {
            std::size_t best = shell.front();
            double best_area = 0;
            for (const std::uint32_t t : shell) {
                const double area = norm(triangle_normal(complex, t));
                if (area > best_area) best_area = area, best = t;
            }
            // A point a small fraction of the triangle's size away from its centroid, on the tissue's side.
            const Triangle& tri = complex.triangles[best];
            const Vec3 centroid =
                (1.0 / 3.0) * (complex.vertices[tri[0]] + complex.vertices[tri[1]] + complex.vertices[tri[2]]);
            Vec3 normal = triangle_normal(complex, best);
            normal = (1.0 / norm(normal)) * normal;
            const double offset = 0.05 * std::sqrt(best_area);
            const double side = complex.sides[best].to == tissue ? 1.0 : -1.0;
            regions.push_back({centroid + (side * offset) * normal, tissue, max_volume});
        }
    }
    return regions;
}

Vec3 point(const std::vector<double>& points, int index)
{
    return {points[3 * index], points[3 * index + 1], points[3 * index + 2]};
}

Vec3 tet_centroid(const detail::TetgenOutput& out, int t)
{
    Vec3 sum{0, 0, 0};
    for (const int v : out.tets[t]) sum = sum + point(out.points, v);
    return 0.25 * sum;
}

std::string place(const Vec3& where)
{
    return concat("(", format_mm(where[0], 1), ", ", format_mm(where[1], 1), ", ", format_mm(where[2], 1), ") mm");
}

/// The local face index (opposite vertex i) of tet t that has the three given vertices.
int local_face(const std::array<int, 4>& tet, const std::array<int, 3>& face)
{
    for (int i = 0; i < 4; ++i)
        if (std::find(face.begin(), face.end(), tet[i]) == face.end()) return i;
    return -1;
}

/// The tissue of tet t on its face `local` that lies on input triangle `source`: the side of the
/// triangle's plane its opposite vertex is on, decided exactly. (A centroid tested in doubles picks the
/// wrong side of nearly flat tets, which TetGen makes between close interfaces.)
Label tissue_on_side(const InterfaceComplex& complex, std::size_t source, const detail::TetgenOutput& out, int t,
                     int local)
{
    const Triangle& tri = complex.triangles[source];
    const int side = detail::exact_side(complex.vertices[tri[0]], complex.vertices[tri[1]], complex.vertices[tri[2]],
                                        point(out.points, out.tets[t][local]));
    if (side == 0)
        throw AlgorithmError(concat("TetGen made a tetrahedron without volume near ", place(tet_centroid(out, t)),
                                    " on the interface ", complex.sides[source].from, "|", complex.sides[source].to,
                                    " (input triangle ", source, "); please report this input"));
    return side > 0 ? complex.sides[source].to : complex.sides[source].from;
}

/// Labels every tet: tets on interface faces take the tissue on their side, the rest by flooding. `split_interfaces`:
/// TetGen was allowed to split interface triangles (TetrahedralizeOptions::preserve_interfaces off), for the advice of
/// an error.
std::vector<Label> label_tets(const InterfaceComplex& complex, const detail::TetgenOutput& out, bool split_interfaces)
{
    const std::size_t tet_count = out.tets.size();
    std::vector<Label> labels(tet_count, unlabelled);
    std::vector<std::uint8_t> interface_mask(tet_count, 0);
    std::deque<int> queue;
    // TetGen's own face-to-tet list is not reliable with every switch combination: build it here.
    const TetAdjacency adjacency(out.tets, out.points.size() / 3);
    for (std::size_t f = 0; f < out.faces.size(); ++f) {
        const int marker = out.face_markers[f];
        if (marker <= 0 || static_cast<std::size_t>(marker) > complex.triangles.size())
            throw AlgorithmError(concat("TetGen returned a boundary face without its input triangle (marker ", marker,
                                        "); please report this input"));
        const std::size_t source = static_cast<std::size_t>(marker - 1);
        const TetAdjacency::Face found =
            adjacency.find(static_cast<std::uint32_t>(out.faces[f][0]), static_cast<std::uint32_t>(out.faces[f][1]),
                           static_cast<std::uint32_t>(out.faces[f][2]));
        if (found.holders == 0) {
            // Seen with split interfaces on the 1 mm usc19-5 head (after 282 s and 2.3 GB); its default run meshes.
            const Vec3 centre = (1.0 / 3.0) * (point(out.points, out.faces[f][0]) + point(out.points, out.faces[f][1]) +
                                               point(out.points, out.faces[f][2]));
            throw AlgorithmError(concat("TetGen returned an interface face near ", place(centre),
                                        " that is no tetrahedron's face",
                                        split_interfaces ? "; run without --allow-steiner (every interface triangle "
                                                           "then becomes a tet face as it is)"
                                                         : "; please report this input"));
        }
        for (const std::uint32_t tet_index : found.tets) {
            if (tet_index == no_tet) continue;
            const int t = static_cast<int>(tet_index);
            const int local = local_face(out.tets[t], out.faces[f]);
            interface_mask[t] |= static_cast<std::uint8_t>(1u << local);
            const Label side = tissue_on_side(complex, source, out, t, local);
            if (labels[t] != unlabelled && labels[t] != side)
                throw AlgorithmError(concat("a tetrahedron near ", place(tet_centroid(out, t)),
                                            " lies between interfaces that "
                                            "disagree on its tissue (",
                                            labels[t], " from one face, ", side, " from interface ",
                                            complex.sides[source].from, "|", complex.sides[source].to,
                                            "); the surface "
                                            "orientation is inconsistent: run tm-check-surface"));
            if (labels[t] == unlabelled) queue.push_back(t);
            labels[t] = side;
        }
    }
    // Flood across faces that are not interfaces; such faces never separate tissues.
    while (!queue.empty()) {
        const int t = queue.front();
        queue.pop_front();
        for (int i = 0; i < 4; ++i) {
            if (interface_mask[t] >> i & 1u) continue;
            const std::uint32_t across = adjacency.across(static_cast<std::size_t>(t), i);
            if (across == no_tet) continue;
            const int n = static_cast<int>(across);
            if (labels[n] == unlabelled) {
                labels[n] = labels[t];
                queue.push_back(n);
            }
        }
    }
    if (std::count(labels.begin(), labels.end(), unlabelled) > 0)
        throw AlgorithmError("some tetrahedra are not enclosed by any interface; run tm-check-surface on the input");
    return labels;
}

/// Copies TetGen's arrays into a TetMesh: tets positively oriented, faces oriented as their input triangle.
TetMesh assemble(const InterfaceComplex& complex, const detail::TetgenOutput& out, const std::vector<Label>& labels,
                 bool keep_background)
{
    TetMesh mesh;
    mesh.names = complex.names;
    std::vector<std::uint32_t> new_index(out.points.size() / 3, std::numeric_limits<std::uint32_t>::max());
    auto use = [&](int v) {
        if (new_index[v] == std::numeric_limits<std::uint32_t>::max()) {
            new_index[v] = static_cast<std::uint32_t>(mesh.vertices.size());
            mesh.vertices.push_back(point(out.points, v));
        }
        return new_index[v];
    };
    for (std::size_t t = 0; t < out.tets.size(); ++t) {
        if (!keep_background && labels[t] == complex.background) continue;
        Tet tet{use(out.tets[t][0]), use(out.tets[t][1]), use(out.tets[t][2]), use(out.tets[t][3])};
        mesh.tets.push_back(tet);
        mesh.tet_labels.push_back(labels[t]);
        // The exact sign: a nearly flat tet whose volume rounds to the wrong sign would come out inverted.
        const auto& p = out.tets[t];
        if (detail::exact_side(point(out.points, p[0]), point(out.points, p[1]), point(out.points, p[2]),
                               point(out.points, p[3])) < 0)
            std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
    }
    for (std::size_t f = 0; f < out.faces.size(); ++f) {
        const std::size_t source = static_cast<std::size_t>(out.face_markers[f] - 1);
        // Every face has a non-background tissue on one side at least, so none is dropped with its tets.
        const LabelPair pair = complex.sides[source];
        Triangle face{use(out.faces[f][0]), use(out.faces[f][1]), use(out.faces[f][2])};
        const Vec3& a = mesh.vertices[face[0]];
        const Vec3 normal = cross(mesh.vertices[face[1]] - a, mesh.vertices[face[2]] - a);
        if (dot(normal, triangle_normal(complex, source)) < 0) std::swap(face[1], face[2]);
        mesh.faces.push_back(face);
        mesh.face_sides.push_back(pair);
    }
    return mesh;
}

/// TetGen keeps every interface triangle with -Y, and then sometimes leaves a flat tet between nearly
/// coplanar interface triangles, whose tissue the interfaces around it cannot settle: a mesh with tissues
/// touching across unmarked faces. Such a mesh is refused here rather than written (outputs are valid or absent).
/// `improved`: whether the improver ran; it turns most such tets over into the crease they fill (on two remeshed
/// surfaces of the 1 mm usc19-5 head that failed so without it, it left none), so without it that comes first.
void require_fit_for_fem(const TetMesh& mesh, bool improved)
{
    const MeshCheckReport check = check_mesh(mesh);
    if (check.ok()) return;
    std::string what;
    for (std::size_t i = 0, shown = 0; i < check.problems.size() && shown < 2; ++i) {
        if (i > 0 && check.problems[i] == check.problems[i - 1]) continue;
        what += (shown++ > 0 ? "; " : "") + check.problems[i];
    }
    throw AlgorithmError(
        concat("TetGen's mesh of this surface fails the mesh check (", what, "); ",
               improved ? "" : "let the improver mend it (tm-tetra without --no-improve), or ",
               "remesh the surface with shorter edges where the interfaces come close (tm-remesh), or let TetGen "
               "split interface triangles (tm-tetra --allow-steiner)"));
}

} // namespace

TetMesh tetrahedralize(const InterfaceComplex& complex, const TetrahedralizeOptions& options, const Progress& progress,
                       TetrahedralizeReport* report)
{
    const auto start = std::chrono::steady_clock::now();
    if (options.improve_quality && options.max_radius_edge_ratio < 1.0)
        throw InputError(concat("radius-edge ratio bound ", options.max_radius_edge_ratio,
                                " is below 1; TetGen needs >= 1 "
                                "(2 is a good default)"));
    if (options.optimisation_level < 0 || options.optimisation_level > 10)
        throw InputError(concat("mesh optimisation level ", options.optimisation_level,
                                " is outside 0..10 (TetGen -O; 2 is "
                                "the default)"));
    for (const auto& [tissue, volume] : options.max_volume_per_tissue_mm3)
        if (!(volume > 0))
            throw InputError(concat("maximum volume for tissue ", tissue, " is ", volume, "; give a positive mm^3"));
    validate_indices(complex, "surface");
    surface::require_fit_for_tetrahedralization(complex, "surface");

    detail::TetgenInput input;
    input.points.reserve(3 * complex.vertices.size());
    for (const Vec3& v : complex.vertices) input.points.insert(input.points.end(), v.begin(), v.end());
    const std::vector<Vec3> inside = options.layer_points ? detail::layer_points(complex) : std::vector<Vec3>{};
    for (const Vec3& p : inside) input.points.insert(input.points.end(), p.begin(), p.end());
    input.triangles.reserve(complex.triangles.size());
    for (const Triangle& tri : complex.triangles)
        input.triangles.push_back({static_cast<int>(tri[0]), static_cast<int>(tri[1]), static_cast<int>(tri[2])});
    input.regions = region_seeds(complex, options);
    input.switches = build_switches(options, !input.regions.empty());

    progress.info("tetra", concat("TetGen -", input.switches, " on ", complex.vertices.size(), " vertices, ",
                                  complex.triangles.size(), " triangles",
                                  options.layer_points ? concat(", ", inside.size(), " nodes inside the layers") : ""));
    // The improver's reference surface is built here while TetGen runs in its child process.
    std::optional<detail::SurfaceReference> reference;
    const detail::TetgenOutput out = detail::run_tetgen(input, [&] {
        if (options.improve) reference.emplace(complex);
    });
    progress.update("tetra", 0.8);
    const std::vector<Label> labels = label_tets(complex, out, !options.preserve_interfaces);
    TetMesh mesh = assemble(complex, out, labels, options.mesh_background_cavities);
    ImproveReport improvement;
    if (options.improve) {
        // The improver keeps the volume bounds TetGen was given.
        ImproveOptions improve_options = options.improvement;
        improve_options.max_tet_volume_mm3 = options.max_volume_mm3;
        improve_options.max_tet_volume_per_tissue_mm3 = options.max_volume_per_tissue_mm3;
        improvement = detail::improve_mesh_against(mesh, *reference, improve_options, progress);
    }
    require_fit_for_fem(mesh, options.improve);
    progress.update("tetra", 1.0);

    if (report != nullptr) {
        report->input_vertices = complex.vertices.size();
        report->input_triangles = complex.triangles.size();
        report->nodes = mesh.vertices.size();
        report->tets = mesh.tets.size();
        report->layer_points = inside.size();
        report->steiner_points = out.points.size() / 3 - complex.vertices.size() - inside.size();
        report->interface_faces = mesh.faces.size();
        std::vector<std::uint32_t> faces_of(complex.triangles.size(), 0);
        for (const int marker : out.face_markers) ++faces_of[static_cast<std::size_t>(marker - 1)];
        report->split_interface_triangles = static_cast<std::size_t>(
            std::count_if(faces_of.begin(), faces_of.end(), [](std::uint32_t n) { return n > 1; }));
        report->switches = input.switches;
        report->min_dihedral_deg = 180;
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
            const TetShape shape = tet_shape(mesh, t);
            report->min_dihedral_deg = std::min(report->min_dihedral_deg, shape.min_dihedral_deg);
            report->max_radius_edge_ratio = std::max(report->max_radius_edge_ratio, shape.radius_edge_ratio);
            const auto tissue_bound = options.max_volume_per_tissue_mm3.find(mesh.tet_labels[t]);
            const double bound =
                tissue_bound != options.max_volume_per_tissue_mm3.end() ? tissue_bound->second : options.max_volume_mm3;
            if (bound > 0 && signed_volume(mesh, t) > bound * (1 + 1e-9)) ++report->tets_over_volume_bound;
        }
        report->improved = options.improve;
        report->improvement = improvement;
        report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return mesh;
}

} // namespace tissuemesh::volume
