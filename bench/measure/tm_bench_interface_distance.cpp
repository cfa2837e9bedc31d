// tm-bench-interface-distance: how far a tet mesh's interface faces lie from a phantom's exact interfaces.
// The same measure for every mesher (our pipeline, CGAL): the faces come from the tet labels.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "image/phantom.h"
#include "io/tet_mesh_io.h"
#include "tools/run_tool.h"
#include "volume/mark_interfaces.h"

using namespace tissuemesh;

namespace {

/// Distance (mm) from `point` to the exact interface of `pair`; when the phantom has no such interface (a
/// one-voxel shell broken by sampling makes two tissues touch), the nearest exact interface of either tissue.
double distance_to_pair(const image::PhantomGeometry& geometry, const std::vector<LabelPair>& interfaces,
                        const Vec3& point, LabelPair pair)
{
    const auto [a, b] = std::minmax(pair.from, pair.to);
    if (std::find(interfaces.begin(), interfaces.end(), LabelPair{a, b}) != interfaces.end())
        return geometry.distance_to_interface(point, {a, b});
    double nearest = INFINITY;
    for (const LabelPair& known : interfaces)
        if (known.from == a || known.to == a || known.from == b || known.to == b)
            nearest = std::min(nearest, geometry.distance_to_interface(point, known));
    return nearest;
}

struct Sample {
    double distance_mm;
    double weight_mm2;
};

/// Each interface face sampled at its centroid (weight: its area) and at its vertices (weight 0: they
/// count for the maximum only), so mean and 95th percentile are area-weighted over the interfaces.
std::vector<Sample> sample_faces(const TetMesh& mesh, const image::PhantomGeometry& geometry)
{
    const std::vector<LabelPair> interfaces = geometry.interfaces();
    std::vector<Sample> samples;
    samples.reserve(mesh.faces.size() * 4);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
        const Vec3& a = mesh.vertices[mesh.faces[f][0]];
        const Vec3& b = mesh.vertices[mesh.faces[f][1]];
        const Vec3& c = mesh.vertices[mesh.faces[f][2]];
        const double area = 0.5 * norm(cross(b - a, c - a));
        samples.push_back(
            {distance_to_pair(geometry, interfaces, (1.0 / 3.0) * (a + b + c), mesh.face_sides[f]), area});
        for (const Vec3* corner : {&a, &b, &c})
            samples.push_back({distance_to_pair(geometry, interfaces, *corner, mesh.face_sides[f]), 0});
    }
    return samples;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, phantom_name;
    image::PhantomOptions phantom_options;
    return tools::run_tool(
        argc, argv,
        {"tm-bench-interface-distance",
         "Distance of a tet mesh's interface and boundary faces (rebuilt from the tet labels) to the exact "
         "interfaces of the phantom it was meshed from: area-weighted mean and 95th percentile over face centroids, "
         "maximum over centroids and vertices, in mm.",
         "Example:\n  tm-bench-interface-distance -i spheres4.msh --phantom spheres4 --voxel-mm 2 --json d.json"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh")->required()->check(CLI::ExistingFile);
            app.add_option("--phantom", phantom_name, "Phantom name (as tm-phantom)")->required();
            app.add_option("--voxel-mm", phantom_options.voxel_mm, "Voxel size the phantom was made with")
                ->capture_default_str();
        },
        [&](tools::ToolContext& context) {
            TetMesh mesh = io::read_tet_mesh(input);
            volume::mark_interfaces(mesh);
            const image::Phantom phantom = image::make_phantom(phantom_name, phantom_options);
            std::vector<Sample> samples = sample_faces(mesh, phantom.geometry);
            double total = 0, weighted = 0, maximum = 0;
            for (const Sample& s : samples)
                total += s.weight_mm2, weighted += s.weight_mm2 * s.distance_mm,
                    maximum = std::max(maximum, s.distance_mm);
            std::sort(samples.begin(), samples.end(),
                      [](const Sample& x, const Sample& y) { return x.distance_mm < y.distance_mm; });
            double below = 0, p95 = 0;
            for (const Sample& s : samples)
                if ((below += s.weight_mm2) >= 0.95 * total) {
                    p95 = s.distance_mm;
                    break;
                }
            const double mean = total > 0 ? weighted / total : 0;
            std::printf("%s: %zu faces, distance to the exact interfaces: mean %.3f mm, p95 %.3f mm, max %.3f mm\n",
                        input.c_str(), mesh.faces.size(), mean, p95, maximum);
            context.summary = {{"faces", mesh.faces.size()},
                               {"area_mm2", total},
                               {"mean_mm", mean},
                               {"p95_mm", p95},
                               {"max_mm", maximum}};
        });
}
