// tm-bench-cgal-tet-remesh: CGAL's tetrahedral remeshing (Tetrahedral_remeshing, CGAL 5.5) of one of our tet
// meshes with every interface kept (remesh_boundaries = false), to compare it with our improver on the same input:
// a `tm-tetra --no-improve` mesh, improved by `tm-improve` on one side and remeshed here on the other (issue 28 asks
// which wins). The remeshing splits, collapses, flips and smooths the tets inside each tissue towards a target edge
// length; here the target at a point is the mean edge length of the input's tets around it, so that the mesh keeps
// its sizes. The result is written in our tet mesh formats, so tm-check-mesh judges both with the same code.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_3/tet_soup_to_c3t3.h>
#include <CGAL/Tetrahedral_remeshing/Remeshing_triangulation_3.h>
#include <CGAL/tetrahedral_remeshing.h>

#include "core/error.h"
#include "io/tet_mesh_io.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "volume/improve_mesh.h"
#include "volume/mark_interfaces.h"

using namespace tissuemesh;

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Tr = CGAL::Tetrahedral_remeshing::Remeshing_triangulation_3<Kernel>;

/// The input's own sizes as a field: on a grid of `cell_mm` cubes, `factor` times the mean edge length of the tets
/// whose centroids lie in each cube; empty cubes take the mean of their filled neighbours, ring by ring.
class EdgeSizing {
public:
    EdgeSizing(const TetMesh& mesh, double cell_mm, double factor) : cell_mm_(cell_mm)
    {
        Vec3 low = mesh.vertices.front(), high = low;
        for (const Vec3& p : mesh.vertices)
            for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
        origin_ = low;
        for (int a = 0; a < 3; ++a) counts_[a] = static_cast<std::int64_t>((high[a] - low[a]) / cell_mm) + 1;
        std::vector<double> sum(cells(), 0);
        std::vector<int> count(cells(), 0);
        double total = 0;
        for (const Tet& tet : mesh.tets) {
            Vec3 centroid{0, 0, 0};
            double edges = 0;
            for (int i = 0; i < 4; ++i) {
                centroid = centroid + 0.25 * mesh.vertices[tet[i]];
                for (int j = i + 1; j < 4; ++j) edges += distance(mesh.vertices[tet[i]], mesh.vertices[tet[j]]);
            }
            const std::size_t c = cell_at(centroid);
            sum[c] += edges / 6, ++count[c], total += edges / 6;
        }
        size_.assign(cells(), 0);
        for (std::size_t c = 0; c < cells(); ++c)
            if (count[c] > 0) size_[c] = factor * sum[c] / count[c];
        fill_empty(factor * total / static_cast<double>(mesh.tets.size()));
    }

    double operator()(const Tr::Point& p) const { return size_[cell_at({p.x(), p.y(), p.z()})]; }

private:
    std::size_t cells() const { return static_cast<std::size_t>(counts_[0] * counts_[1] * counts_[2]); }

    std::size_t cell_at(const Vec3& p) const
    {
        std::array<std::int64_t, 3> c{};
        for (int a = 0; a < 3; ++a)
            c[a] = std::clamp(static_cast<std::int64_t>(std::floor((p[a] - origin_[a]) / cell_mm_)), std::int64_t{0},
                              counts_[a] - 1);
        return static_cast<std::size_t>(c[0] + counts_[0] * (c[1] + counts_[1] * c[2]));
    }

    /// Empty cubes from their filled face neighbours, ring by ring; what no ring reaches takes `mean`.
    void fill_empty(double mean)
    {
        constexpr std::array<std::array<std::int64_t, 3>, 6> steps{
            {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
        for (int ring = 0; ring < 8; ++ring) {
            std::vector<double> next = size_;
            bool empty_left = false;
            for (std::int64_t k = 0; k < counts_[2]; ++k)
                for (std::int64_t j = 0; j < counts_[1]; ++j)
                    for (std::int64_t i = 0; i < counts_[0]; ++i) {
                        const std::size_t c = static_cast<std::size_t>(i + counts_[0] * (j + counts_[1] * k));
                        if (size_[c] > 0) continue;
                        double sum = 0;
                        int n = 0;
                        for (const auto& s : steps) {
                            const std::int64_t a = i + s[0], b = j + s[1], d = k + s[2];
                            if (a < 0 || b < 0 || d < 0 || a >= counts_[0] || b >= counts_[1] || d >= counts_[2])
                                continue;
                            const double v = size_[static_cast<std::size_t>(a + counts_[0] * (b + counts_[1] * d))];
                            if (v > 0) sum += v, ++n;
                        }
                        if (n > 0) next[c] = sum / n;
                        else empty_left = true;
                    }
            size_ = std::move(next);
            if (!empty_left) return;
        }
        for (double& v : size_)
            if (!(v > 0)) v = mean;
    }

    double cell_mm_;
    Vec3 origin_{0, 0, 0};
    std::array<std::int64_t, 3> counts_{1, 1, 1};
    std::vector<double> size_;
};

/// CGAL's triangulation of the mesh: its tets as finite cells, each tissue a subdomain (label + 1, so that no
/// tissue is CGAL's exterior 0), the faces on the mesh's boundary closed by infinite cells.
void to_triangulation(const TetMesh& mesh, Tr& tr)
{
    std::vector<Tr::Point> points;
    points.reserve(mesh.vertices.size());
    for (const Vec3& p : mesh.vertices) points.emplace_back(p[0], p[1], p[2]);
    std::vector<std::array<int, 5>> cells;
    cells.reserve(mesh.tets.size());
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        Tet tet = mesh.tets[t];
        if (signed_volume(mesh, t) < 0) std::swap(tet[2], tet[3]);
        cells.push_back({static_cast<int>(tet[0]), static_cast<int>(tet[1]), static_cast<int>(tet[2]),
                         static_cast<int>(tet[3]), static_cast<int>(mesh.tet_labels[t]) + 1});
    }
    std::vector<Tr::Vertex_handle> handles;
    const std::map<std::array<int, 3>, Tr::Cell::Surface_patch_index> no_patches;
    if (!CGAL::build_triangulation<Tr, true>(tr, points, cells, no_patches, handles))
        throw AlgorithmError("CGAL could not build a triangulation of the mesh (a face in more than two tets?)");
}

/// Our mesh from the cells of the triangulation that lie in a subdomain, with its interface faces.
TetMesh from_triangulation(const Tr& tr, const TissueNames& names)
{
    TetMesh mesh;
    mesh.names = names;
    std::map<Tr::Vertex_handle, std::uint32_t> index;
    const auto node = [&](Tr::Vertex_handle v) {
        const auto [it, added] = index.try_emplace(v, static_cast<std::uint32_t>(mesh.vertices.size()));
        if (added) mesh.vertices.push_back({v->point().x(), v->point().y(), v->point().z()});
        return it->second;
    };
    for (const Tr::Cell_handle cell : tr.finite_cell_handles()) {
        if (cell->subdomain_index() == 0) continue;
        mesh.tets.push_back(
            {node(cell->vertex(0)), node(cell->vertex(1)), node(cell->vertex(2)), node(cell->vertex(3))});
        mesh.tet_labels.push_back(static_cast<Label>(cell->subdomain_index() - 1));
        if (signed_volume(mesh, mesh.tets.size() - 1) < 0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
    }
    volume::mark_interfaces(mesh);
    return mesh;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output;
    std::size_t iterations = 3;
    double target_edge_mm = 0, sizing_cell_mm = 4, size_factor = 1;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-cgal-tet-remesh",
         "Remeshes a labelled tet mesh with CGAL's tetrahedral remeshing, its interfaces kept (remesh_boundaries "
         "false), for benchmarks against tm-improve: edges split, collapsed and flipped and nodes smoothed inside each "
         "tissue towards a target edge length (by default the input's own mean edge length around each point). "
         "Writes the result with its labels and interface faces, in any tet mesh format of tm-convert.",
         "Examples:\n  tm-bench-cgal-tet-remesh -i noimp.msh -o cgal-remeshed.msh --json cgal-remesh.json\n"
         "  tm-bench-cgal-tet-remesh -i noimp.msh -o cgal-remeshed.msh --target-edge-mm 2 --iterations 5"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh (.msh, .mesh, .vtu, ...)")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "Tet mesh: .msh, .mesh, .vtu, .node, .inp")->required();
            app.add_option("--iterations", iterations, "CGAL's remeshing rounds (number_of_iterations)")
                ->check(CLI::Range(1, 100))
                ->capture_default_str();
            app.add_option("--target-edge-mm", target_edge_mm,
                           "One target edge length everywhere (0: the input's mean edge length around each point)")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--sizing-cell-mm", sizing_cell_mm, "Cube size of the input's edge length field")
                ->check(CLI::PositiveNumber)
                ->capture_default_str();
            app.add_option("--size-factor", size_factor,
                           "The target is this times the input's mean edge length (CGAL splits edges over 4/3 of "
                           "the target and collapses those under 4/5)")
                ->check(CLI::PositiveNumber)
                ->capture_default_str();
        },
        [&](tools::ToolContext& context) {
            const TetMesh mesh = io::read_tet_mesh(input);
            validate_indices(mesh, input);
            const volume::ShapeFigures before = volume::shape_figures(mesh);
            const auto start = std::chrono::steady_clock::now();
            Tr tr;
            to_triangulation(mesh, tr);
            const EdgeSizing sizing(mesh, sizing_cell_mm, size_factor);
            const double built_seconds = tools::seconds_since(start);
            const auto remesh_start = std::chrono::steady_clock::now();
            const auto parameters = CGAL::parameters::remesh_boundaries(false).number_of_iterations(iterations);
            if (target_edge_mm > 0) CGAL::tetrahedral_isotropic_remeshing(tr, target_edge_mm, parameters);
            else CGAL::tetrahedral_isotropic_remeshing(tr, sizing, parameters);
            const double remesh_seconds = tools::seconds_since(remesh_start);
            const TetMesh result = from_triangulation(tr, mesh.names);
            if (result.tets.empty()) throw AlgorithmError(concat(input, ": CGAL's remeshing left no tet"));
            const volume::ShapeFigures after = volume::shape_figures(result);
            io::write_tet_mesh(result, output);
            context.log(concat(before.tets, " -> ", after.tets, " tets; smallest dihedral ",
                               format_mm(before.min_dihedral_deg, 2), " -> ", format_mm(after.min_dihedral_deg, 2),
                               " deg, 1st percentile ", format_mm(before.p1_min_dihedral_deg, 1), " -> ",
                               format_mm(after.p1_min_dihedral_deg, 1), " deg (", format_mm(remesh_seconds, 2),
                               " s remeshing, ", format_mm(built_seconds, 2), " s building)"));
            context.summary = {{"before", before},
                               {"after", after},
                               {"iterations", iterations},
                               {"target_edge_mm", target_edge_mm},
                               {"size_factor", size_factor},
                               {"build_seconds", built_seconds},
                               {"remesh_seconds", remesh_seconds}};
        });
}
