// tm-phantom: writes a phantom label image with exactly known geometry, plus its geometry and tissue
// names as JSON sidecars (OUT.geometry.json, OUT.labels.json).
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/phantom.h"
#include "io/write_label_image.h"
#include "tools/run_tool.h"

namespace fs = std::filesystem;
using namespace tissuemesh;

namespace {

/// OUT with its (possibly compound) extension replaced: head.nii.gz -> head<suffix>.
fs::path sidecar(const fs::path& out, const std::string& suffix)
{
    const std::string name = out.filename().string();
    const std::string stem = name.substr(0, name.size() - full_extension(out).size());
    return out.parent_path() / (stem + suffix);
}

std::string names_json(const TissueNames& names)
{
    nlohmann::json document = nlohmann::json::object();
    for (const auto& [label, name] : names) document[std::to_string(label)] = name;
    return document.dump(2) + "\n";
}

} // namespace

int main(int argc, char** argv)
{
    std::string name, output;
    image::PhantomOptions options;
    bool list = false;
    return tools::run_tool(
        argc, argv,
        {"tm-phantom",
         "Writes a phantom label image whose tissues have an exactly known geometry, with that geometry in "
         "OUT.geometry.json and the tissue names in OUT.labels.json (OUT without its image extension).",
         "Examples:\n  tm-phantom --list\n  tm-phantom spheres4 --voxel-mm 2 -o spheres4.nii.gz --json phantom.json\n"},
        [&](CLI::App& app) {
            app.add_option("name", name, "Phantom name (see --list)");
            app.add_option("-o,--output", output, "Output label image (.nii.gz, .nrrd, .mha, ...)")->type_name("FILE");
            app.add_option("--voxel-mm", options.voxel_mm, "Voxel size in mm (z is 1.5x for ellipsoids)")
                ->capture_default_str();
            app.add_flag("--list", list, "List the phantoms and exit");
        },
        [&](tools::ToolContext& ctx) {
            if (list) {
                for (const auto& [phantom, description] : image::phantom_names())
                    std::printf("%-11s %s\n", phantom.c_str(), description.c_str());
                return;
            }
            if (name.empty() || output.empty())
                throw InputError("tm-phantom needs a phantom name and -o OUT; see tm-phantom --list");
            const image::Phantom phantom = image::make_phantom(name, options);
            const fs::path geometry_path = sidecar(output, ".geometry.json");
            const fs::path labels_path = sidecar(output, ".labels.json");
            io::write_label_image(phantom.image, output);
            write_text_atomically(geometry_path, phantom.geometry.to_json());
            write_text_atomically(labels_path, names_json(phantom.image.names()));

            const auto counts = count_labels(phantom.image);
            nlohmann::json tissues = nlohmann::json::object();
            for (const auto& [label, tissue] : phantom.image.names()) {
                const auto found = counts.find(label);
                const std::size_t voxels = found == counts.end() ? 0 : found->second;
                tissues[std::to_string(label)] = {
                    {"name", tissue},
                    {"voxels", voxels},
                    {"volume_exact_mm3", phantom.geometry.volume_mm3(label)},
                    {"volume_voxels_mm3", static_cast<double>(voxels) * phantom.image.voxel_volume_mm3()}};
            }
            const auto& dims = phantom.image.dims();
            ctx.summary = {{"phantom", name},
                           {"voxel_mm", options.voxel_mm},
                           {"dims", dims},
                           {"spacing_mm", phantom.image.spacing_mm()},
                           {"output", output},
                           {"geometry", geometry_path.string()},
                           {"labels", labels_path.string()},
                           {"tissues", tissues}};
            ctx.log(concat(name, ": ", dims[0], " x ", dims[1], " x ", dims[2], " voxels of ",
                           format_mm(options.voxel_mm), " mm -> ", output));
        });
}
