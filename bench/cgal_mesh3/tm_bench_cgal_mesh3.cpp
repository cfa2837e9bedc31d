// tm-bench-cgal-mesh3: CGAL Mesh_3 on one of our label images, for side-by-side benchmarks (bench/run).
// The only file of the project that includes Mesh_3 (it takes about a minute to compile). The result is
// written as one of our tet mesh formats, so that tm-check-mesh and the bench measures judge both meshers
// with the same code.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Image_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/make_mesh_3.h>
#include <tbb/global_control.h>

#include "core/error.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/run_tool.h"
#include "volume/mark_interfaces.h"

using namespace tissuemesh;

namespace {

/// Mesh_3 criteria and optimisers. Lengths in mm, angles in degrees (0: the criterion is off).
struct CgalOptions {
    double facet_angle_deg = 30;       ///< lower bound on surface triangle angles
    double facet_size_mm = 3;          ///< upper bound on surface Delaunay ball radii
    double facet_distance_mm = 0.5;    ///< upper bound on surface triangle centre to true surface
    double cell_radius_edge_ratio = 3; ///< upper bound on circumradius / shortest edge
    double cell_size_mm = 5;           ///< upper bound on circumradius of tets
    bool perturb = true;               ///< sliver perturbation
    bool exude = false;                ///< sliver exudation (slow; CGAL's default is on)
    int threads = 1;                   ///< 1: sequential Mesh_3; more: TBB-parallel Mesh_3 with that many threads
    double perturb_time_s = 0;         ///< time limit of the perturber (0: none)
    double exude_time_s = 0;           ///< time limit of the exuder (0: none)
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Domain = CGAL::Labeled_mesh_domain_3<Kernel>;

/// The image in CGAL's own structure, in index space scaled by the spacing (origin 0, axes as stored):
/// the world position of a CGAL point p is image.index_to_world(p / spacing), whatever the direction.
CGAL::Image_3 to_cgal_image(const LabelImage& image)
{
    const Dims& dims = image.dims();
    const Vec3& spacing = image.spacing_mm();
    _image* raw = _createImage(dims[0], dims[1], dims[2], 1, spacing[0], spacing[1], spacing[2], sizeof(Label),
                               WK_FIXED, SGN_UNSIGNED);
    if (raw == nullptr) throw AlgorithmError("CGAL could not allocate the image; free some memory");
    std::memcpy(raw->data, image.labels().data(), image.voxel_count() * sizeof(Label));
    return CGAL::Image_3(raw);
}

/// Our TetMesh from the cells of the complex, in world mm, positively oriented, with interface faces.
template <typename C3t3>
TetMesh to_tet_mesh(const C3t3& c3t3, const LabelImage& image)
{
    using Vertex_handle = typename C3t3::Vertex_handle;
    TetMesh mesh;
    std::map<Vertex_handle, std::uint32_t> index;
    const Vec3& spacing = image.spacing_mm();
    auto node = [&](Vertex_handle v) {
        auto [it, added] = index.try_emplace(v, static_cast<std::uint32_t>(mesh.vertices.size()));
        if (added) {
            const auto& p = v->point().point();
            mesh.vertices.push_back(image.index_to_world({p.x() / spacing[0], p.y() / spacing[1], p.z() / spacing[2]}));
        }
        return it->second;
    };
    for (auto cell = c3t3.cells_in_complex_begin(); cell != c3t3.cells_in_complex_end(); ++cell) {
        Tet tet{node(cell->vertex(0)), node(cell->vertex(1)), node(cell->vertex(2)), node(cell->vertex(3))};
        mesh.tets.push_back(tet);
        mesh.tet_labels.push_back(static_cast<Label>(c3t3.subdomain_index(cell)));
        if (signed_volume(mesh, mesh.tets.size() - 1) < 0) std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
    }
    mesh.names = image.names();
    volume::mark_interfaces(mesh);
    return mesh;
}

/// Runs Mesh_3 with the given concurrency tag and returns our mesh.
template <typename Concurrency>
TetMesh run_mesh3(const LabelImage& image, const CgalOptions& options)
{
    using Tr = typename CGAL::Mesh_triangulation_3<Domain, CGAL::Default, Concurrency>::type;
    using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
    using Criteria = CGAL::Mesh_criteria_3<Tr>;
    namespace p = CGAL::parameters;
    const CGAL::Image_3 cgal_image = to_cgal_image(image);
    const Domain domain = Domain::create_labeled_image_mesh_domain(cgal_image);
    const Criteria criteria(p::facet_angle = options.facet_angle_deg, p::facet_size = options.facet_size_mm,
                            p::facet_distance = options.facet_distance_mm,
                            p::cell_radius_edge_ratio = options.cell_radius_edge_ratio,
                            p::cell_size = options.cell_size_mm);
    const auto perturb = options.perturb ? p::perturb(p::time_limit = options.perturb_time_s) : p::no_perturb();
    const auto exude = options.exude ? p::exude(p::time_limit = options.exude_time_s) : p::no_exude();
    const C3t3 c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, perturb, exude);
    return to_tet_mesh(c3t3, image);
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output;
    CgalOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-cgal-mesh3",
         "Meshes a label image with CGAL Mesh_3 (Labeled_mesh_domain_3), for benchmarks against the tissuemesh "
         "pipeline: every non-zero label becomes a subdomain; the tets are written with their labels and interface "
         "faces, in any tet mesh format of tm-convert, so tm-check-mesh can assess them.",
         "Examples:\n  tm-bench-cgal-mesh3 -i head.nii.gz -o cgal.msh --facet-size-mm 3 --cell-size-mm 5\n"
         "  tm-bench-cgal-mesh3 -i head.nii.gz -o cgal.msh --threads 2 --json cgal.json"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Label image (any format of tm-info)")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "Tet mesh: .msh, .mesh, .node, .inp")->required();
            app.add_option("--facet-angle-deg", options.facet_angle_deg, "Lower bound on surface angles")
                ->capture_default_str();
            app.add_option("--facet-size-mm", options.facet_size_mm, "Surface Delaunay ball radius bound")
                ->capture_default_str();
            app.add_option("--facet-distance-mm", options.facet_distance_mm, "Surface approximation bound")
                ->capture_default_str();
            app.add_option("--radius-edge", options.cell_radius_edge_ratio, "Tet circumradius / shortest edge bound")
                ->capture_default_str();
            app.add_option("--cell-size-mm", options.cell_size_mm, "Tet circumradius bound")->capture_default_str();
            app.add_option("--threads", options.threads, "1: sequential; more: TBB-parallel")->capture_default_str();
            app.add_flag("!--no-perturb", options.perturb, "Skip sliver perturbation");
            app.add_flag("--exude", options.exude, "Run sliver exudation (slow)");
            app.add_option("--perturb-time-s", options.perturb_time_s, "Perturber time limit (0: none)")
                ->capture_default_str();
            app.add_option("--exude-time-s", options.exude_time_s, "Exuder time limit (0: none)")->capture_default_str();
        },
        [&](tools::ToolContext& context) {
            if (options.threads < 1) throw InputError("--threads must be at least 1");
            const LabelImage image = io::read_label_image(input);
            const auto start = std::chrono::steady_clock::now();
            TetMesh mesh;
            if (options.threads == 1) {
                mesh = run_mesh3<CGAL::Sequential_tag>(image, options);
            } else {
                const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                                static_cast<std::size_t>(options.threads));
                mesh = run_mesh3<CGAL::Parallel_tag>(image, options);
            }
            const double mesh_seconds = tools::seconds_since(start);
            if (mesh.tets.empty())
                throw AlgorithmError(concat(input, ": CGAL made no tet; lower --cell-size-mm or --facet-size-mm"));
            io::write_tet_mesh(mesh, output);
            context.log(
                concat(mesh.tets.size(), " tets, ", mesh.vertices.size(), " nodes (", mesh_seconds, " s meshing)"));
            context.summary = {{"tets", mesh.tets.size()},
                               {"nodes", mesh.vertices.size()},
                               {"faces", mesh.faces.size()},
                               {"mesh_seconds", mesh_seconds},
                               {"threads", options.threads},
                               {"facet_size_mm", options.facet_size_mm},
                               {"facet_distance_mm", options.facet_distance_mm},
                               {"cell_size_mm", options.cell_size_mm},
                               {"radius_edge", options.cell_radius_edge_ratio},
                               {"perturb", options.perturb},
                               {"exude", options.exude}};
        });
}
