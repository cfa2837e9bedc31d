// tm-assess: every tet measured against the voxels (tissue histogram, majority, error volume, quality key).
#include <chrono>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_label_image.h"
#include "io/tet_mesh_io.h"
#include "tools/mesh_format_options.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"
#include "tools/extract_priority.h"
#include "tools/tissue_arguments.h"
#include "volume/assess.h"
#include "volume/mark_interfaces.h"
#include "io/write_vtu.h"

using namespace tissuemesh;

namespace {

/// Parses "scalp=2,4=1.5" (tissue by name or label = positive weight) into options.priority; the tissues are
/// those of the mesh and of the image.
void parse_priority(const std::string& text, const tools::TissueTable& tissues, volume::AssessOptions& options)
{
    std::stringstream items(text);
    for (std::string item; std::getline(items, item, ',');) {
        const auto equals = item.find('=');
        const std::string number = equals == std::string::npos ? "" : item.substr(equals + 1);
        char* end = nullptr;
        const double weight = std::strtod(number.c_str(), &end);
        if (number.empty() || *end != '\0' || !(weight > 0))
            throw InputError(concat("priority \"", item, "\" is not tissue=positive number; write e.g. scalp=2,4=1.5"));
        options.priority[tools::parse_tissue_setting(item, tissues, "--priority", "scalp=2,4=1.5").tissue] = weight;
    }
}

/// The tissues --priority may name: the mesh's and the image's (the mesh's name first where both name a label).
tools::TissueTable mesh_and_image_tissues(const TetMesh& mesh, const LabelImage& image, const std::string& mesh_path,
                                          const std::string& image_path)
{
    tools::TissueTable tissues = tools::tissue_table(mesh, mesh_path);
    const tools::TissueTable voxels = tools::tissue_table(image, image_path);
    tissues.names.insert(voxels.names.begin(), voxels.names.end());
    tissues.present.insert(voxels.present.begin(), voxels.present.end());
    tissues.source = concat(mesh_path, " and ", image_path);
    return tissues;
}

nlohmann::json summarize(const TetMesh& mesh, const volume::Assessment& a, std::size_t relabelled)
{
    nlohmann::json tissues = nlohmann::json::object(), worst = nlohmann::json::array();
    for (const auto& [label, t] : a.tissues) {
        nlohmann::json& tissue = tissues[std::to_string(label)] = t;
        tissue["name"] = mesh.names.count(label) ? mesh.names.at(label) : std::to_string(label);
    }
    for (std::size_t r = 0; r < std::min<std::size_t>(10, a.worst_first.size()); ++r) {
        const std::uint32_t t = a.worst_first[r];
        worst.push_back({{"tet", t},
                         {"quality_key", a.quality_key[t]},
                         {"error_volume_mm3", a.error_volume_mm3[t]},
                         {"radius_edge_ratio", a.radius_edge_ratio[t]}});
    }
    return {{"tets", mesh.tets.size()},
            {"nodes", mesh.vertices.size()},
            {"voxels_inside", a.voxels_inside},
            {"sampled_tets", a.sampled_tets},
            {"total_error_volume_mm3", a.total_error_volume_mm3},
            {"total_majority_error_volume_mm3", a.total_majority_error_volume_mm3},
            {"sampled_error_volume_mm3", a.sampled_error_volume_mm3},
            {"relabelled_tets", relabelled},
            {"tissues", tissues},
            {"worst", worst}};
}

/// The assessment's per-tet fields as .vtu cell arrays (after "tissue").
std::vector<io::VtuArray> assessment_arrays(const volume::Assessment& a)
{
    return {io::make_vtu_array("majority", a.majority, true),
            io::make_vtu_array("error_volume_mm3", a.error_volume_mm3),
            io::make_vtu_array("majority_error_volume_mm3", a.majority_error_volume_mm3),
            io::make_vtu_array("quality_key", a.quality_key),
            io::make_vtu_array("voxel_count", a.voxel_count, true),
            io::make_vtu_array("sampled", a.sampled, true),
            io::make_vtu_array("volume_mm3", a.volume_mm3),
            io::make_vtu_array("min_dihedral_deg", a.min_dihedral_deg),
            io::make_vtu_array("radius_edge_ratio", a.radius_edge_ratio),
            io::make_vtu_array("aspect_ratio", a.aspect_ratio)};
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, image_path, output, priority;
    std::vector<std::string> extract_priority;
    bool relabel = false;
    volume::AssessOptions options;
    tools::MeshFormatFlags format_flags;
    return tools::run_tool(
        argc, argv,
        {"tm-assess",
         "Assesses every tet of a labelled mesh against a label image (Mueller & Sachse): the voxel centres in each "
         "tet "
         "(tissue histogram), its majority tissue (with --priority weights), its error volume (mm^3 of voxels not of "
         "its "
         "tissue), its shape, and a quality key (larger = worse: misclassified voxels + shape weight x (radius-edge / "
         "regular - 1)). OUT .vtu gets every field as cell data; OUT .msh/.mesh gets the mesh itself (with --relabel: "
         "each tet set to its majority tissue and the interface faces rebuilt). The summary has per-tissue Dice, "
         "volume "
         "error and error volume.",
         "Examples:\n  tm-assess -i head.msh --image head.nii.gz -o head-assessed.vtu --json assess.json\n"
         "  tm-assess -i head.msh --image head.nii.gz -o relabelled.msh --relabel --priority skull=2,csf=1.5\n"
         "  tm-assess -i head.msh --image head.nii.gz -o head-assessed.vtu --extract-priority auto\n"
         "  tm-assess -i head.msh --image head.nii.gz -o head-assessed.vtu --extract-priority csf=1"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Tet mesh (.msh 2.2 or .mesh)")->required();
            app.add_option("--image", image_path, "Label image the mesh should match")->required();
            app.add_option("-o,--output", output, "Output: .vtu (assessment fields) or .msh/.mesh (mesh)")->required();
            app.add_flag("--relabel", relabel, "Set each tet's tissue to its majority (interfaces rebuilt)");
            app.add_option("--priority", priority, "Majority weights: tissue=weight,... (name or label; default 1)");
            app.add_option("--extract-priority", extract_priority,
                           "The --priority the surfaces were extracted with (tm-extract --priority: TISSUE=N, name or "
                           "label, or auto), so that a tet holding no voxel centre is sampled with the tissues the "
                           "priority rule's split cubes put there")
                ->delimiter(',');
            app.add_option("--error-weight", options.error_weight, "Quality key weight of misclassified voxels")
                ->capture_default_str();
            app.add_option("--shape-weight", options.shape_weight, "Quality key weight of the shape term")
                ->capture_default_str();
            format_flags.add_to(app);
        },
        [&](tools::ToolContext& context) {
            const std::string extension = full_extension(output);
            if (extension != ".vtu" && extension != ".msh" && extension != ".mesh")
                throw InputError(
                    concat(output, ": unknown output format \"", extension, "\"; use .vtu, .msh or .mesh"));
            format_flags.check();
            TetMesh mesh = io::read_tet_mesh(input);
            const LabelImage image = io::read_label_image(image_path);
            if (!priority.empty() || !extract_priority.empty()) { // the tissue table costs a pass over the voxels
                const tools::TissueTable tissues = mesh_and_image_tissues(mesh, image, input, image_path);
                if (!priority.empty()) parse_priority(priority, tissues, options);
                options.extract_priority = tools::parse_extract_priority(extract_priority, image, options.background,
                                                                         tissues, "--extract-priority");
            }
            const auto start = std::chrono::steady_clock::now();
            volume::Assessment assessment = volume::assess_elements(mesh, image, options, context.progress);
            const double assess_seconds = tools::seconds_since(start);
            std::size_t relabelled = 0;
            if (relabel) {
                for (std::size_t t = 0; t < mesh.tets.size(); ++t)
                    relabelled += mesh.tet_labels[t] != assessment.majority[t];
                volume::relabel_by_majority(mesh, assessment);
                volume::mark_interfaces(mesh);
                assessment =
                    volume::assess_elements(mesh, image, options, context.progress); // fields of the new labels
            }
            if (extension == ".vtu")
                io::write_vtu(mesh, output, {}, assessment_arrays(assessment),
                              format_flags.vtu_ascii ? io::VtuEncoding::ascii : io::VtuEncoding::compressed);
            else io::write_tet_mesh(mesh, output, format_flags.to_write_options(mesh));
            if (assessment.voxels_inside == 0)
                context.progress.warn("assess",
                                      "no voxel centre lies inside the mesh; are mesh and image in the same mm frame?");
            context.summary = summarize(mesh, assessment, relabelled);
            context.summary["assess_seconds"] = assess_seconds;
            context.summary["image_voxels"] = image.voxel_count();
            context.summary["extract_priority"] = tools::priority_summary(options.extract_priority);
            std::printf(
                "%s: %zu tets, %zu voxel centres inside, %zu tets sampled, error volume %.1f mm^3 (majority %.1f)\n",
                input.c_str(), mesh.tets.size(), assessment.voxels_inside, assessment.sampled_tets,
                assessment.total_error_volume_mm3, assessment.total_majority_error_volume_mm3);
            std::printf("%-20s %8s %14s %14s %14s\n", "tissue", "Dice", "mesh mm^3", "voxels mm^3", "error mm^3");
            for (const auto& [label, t] : assessment.tissues)
                std::printf("%-20s %8.4f %14.1f %14.1f %14.1f\n",
                            (mesh.names.count(label) ? mesh.names.at(label) : image.name_of(label)).c_str(), t.dice,
                            t.mesh_volume_mm3, t.voxel_volume_mm3, t.error_volume_mm3);
        });
}
