// tm-prep: cleans a label image before meshing: relabel/merge, resample, keep the largest pieces,
// remove islands, fill holes, crop and pad, in that fixed order; each step logs what it changed.
#include <charconv>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/prepare_image.h"
#include "io/read_label_image.h"
#include "io/write_label_image.h"
#include "tools/run_tool.h"
#include "tools/tissue_arguments.h"

using namespace tissuemesh;

namespace {

std::vector<std::string> split(const std::string& text, char separator)
{
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t end; (end = text.find(separator, start)) != std::string::npos; start = end + 1)
        parts.push_back(text.substr(start, end - start));
    parts.push_back(text.substr(start));
    return parts;
}

template <typename Number>
Number parse_number(const std::string& text, const std::string& option)
{
    Number value{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || text.empty())
        throw InputError(concat(option, ": '", text, "' is not a valid number"));
    return value;
}

/// The command-line strings that need no image (--spacing-mm) into `options`; bad values throw InputError naming
/// the option.
void parse_spacing(const std::string& spacing, image::PrepOptions& options)
{
    if (spacing.empty()) return;
    const auto parts = split(spacing, ',');
    if (parts.size() != 1 && parts.size() != 3)
        throw InputError(concat("--spacing-mm: '", spacing, "' must be X or X,Y,Z in mm"));
    Vec3 s;
    for (int a = 0; a < 3; ++a) s[a] = parse_number<double>(parts[parts.size() == 1 ? 0 : a], "--spacing-mm");
    options.spacing_mm = s;
}

/// The tissue arguments, by name or number (tools/tissue_arguments.h), against the tissues of the input image:
/// --relabel's FROM must be one of them, its TO may be any label (a new one too), and the later steps may name
/// the TO labels as well.
void parse_tissue_options(const std::string& relabel, const std::vector<std::string>& merges,
                          const std::string& keep_largest, const std::string& fill_holes_in, tools::TissueTable tissues,
                          image::PrepOptions& options)
{
    const tools::TissueTable any_label{tissues.names, {}, tissues.source};
    if (!relabel.empty())
        for (const std::string& pair : split(relabel, ',')) {
            const auto ends = split(pair, ':');
            if (ends.size() != 2) throw InputError(concat("--relabel: '", pair, "' is not FROM:TO (e.g. 5:4,6:0)"));
            const Label to = tools::parse_tissue(ends[1], any_label, "--relabel");
            options.relabel[tools::parse_tissue(ends[0], tissues, "--relabel")] = to;
        }
    for (const auto& [from, to] : options.relabel) tissues.present.insert(to);
    for (const std::string& group : merges)
        options.merge.push_back(tools::parse_tissue_list(group, tissues, "--merge"));
    if (!keep_largest.empty()) options.keep_largest = tools::parse_tissue_list(keep_largest, tissues, "--keep-largest");
    if (!fill_holes_in.empty())
        options.fill_holes = true,
        options.fill_holes_tissues = tools::parse_tissue_list(fill_holes_in, tissues, "--fill-holes-in");
}

/// OUT.labels.json for OUT.nii.gz: the tissue names after relabelling, readable by --labels.
std::filesystem::path names_path(const std::filesystem::path& out)
{
    const std::string name = out.filename().string();
    return out.parent_path() / (name.substr(0, name.size() - full_extension(out).size()) + ".labels.json");
}

nlohmann::json to_json(const image::PrepReport& report)
{
    const auto counts = [](const std::map<Label, std::size_t>& voxels) {
        nlohmann::json object = nlohmann::json::object();
        for (const auto& [label, count] : voxels) object[std::to_string(label)] = count;
        return object;
    };
    return {{"step", report.step},
            {"detail", report.detail},
            {"dims_before", report.dims_before},
            {"dims_after", report.dims_after},
            {"voxels_before", counts(report.voxels_before)},
            {"voxels_after", counts(report.voxels_after)},
            {"changed_voxels", report.changed_voxels}};
}

// Bytes per voxel besides the file's own, measured on spheres4 at 1 and 2 mm and the 1 mm usc19-5 head
// (docs/robustness.md): the labels; the clean-ups (--keep-largest, --remove-islands, --fill-holes: component maps
// and queues) on the grid they run on, which is the output's when resampling; a resampled output's labels and
// the writer's buffer.
constexpr double bytes_per_label = 2;
constexpr double bytes_per_cleaned_voxel = 12;
constexpr double bytes_per_resampled_voxel = 4;

/// Refuses an image, or a resampling of it, that would need more memory than --max-memory allows: checked
/// when the header is read, before the voxels are.
/// `cleans`: --keep-largest, --remove-islands or --fill-holes(-in) is given.
tools::ImageSizeCheck memory_check(const tools::MemoryLimit& limit, const std::string& input,
                                   const image::PrepOptions& options, bool cleans)
{
    return [=](const Dims& dims, const Vec3& spacing_mm, std::size_t file_bytes_per_voxel) {
        const double voxels =
            static_cast<double>(dims[0]) * static_cast<double>(dims[1]) * static_cast<double>(dims[2]);
        // A bad --spacing-mm (0, negative, not finite) is left to prepare_image() and its message.
        double scale = 1;
        if (options.spacing_mm)
            for (int axis = 0; axis < 3; ++axis) scale *= spacing_mm[axis] / (*options.spacing_mm)[axis];
        if (!std::isfinite(scale) || !(scale > 0)) return;
        const double in = static_cast<double>(file_bytes_per_voxel) +
                          (cleans && !options.spacing_mm ? bytes_per_cleaned_voxel : bytes_per_label);
        const double out = options.spacing_mm ? (cleans ? bytes_per_cleaned_voxel : bytes_per_resampled_voxel) : 0;
        tools::require_memory(limit, input, voxels * in + voxels * scale * out,
                              concat(tools::format_count(voxels), " voxels x ", tools::format_bytes(in),
                                     options.spacing_mm ? concat(", resampled to ", tools::format_count(voxels * scale),
                                                                 " voxels x ", tools::format_bytes(out))
                                                        : std::string()),
                              options.spacing_mm ? "choose a coarser --spacing-mm, or crop first (--crop-pad)"
                                                 : "crop or resample it with another program first");
    };
}

} // namespace

int main(int argc, char** argv)
{
    std::string input, output, names, relabel, spacing, keep_largest, fill_holes_in;
    std::vector<std::string> merges;
    std::size_t crop_pad = 0;
    bool nearest = false;
    CLI::Option* crop_option = nullptr;
    image::PrepOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-prep",
         "Cleans a label image before meshing. Operations run in this fixed order, whatever the order of the "
         "flags: 1 --relabel, 2 --merge, 3 --spacing-mm (resample), 4 --keep-largest, 5 --remove-islands, "
         "6 --fill-holes, 7 --crop-pad. Each logs what it changed; --json has the counts per label. Tissues are "
         "label numbers or names (from the image or --labels, in any case). Tissue names, renamed by --relabel and "
         "--merge, go to OUT.labels.json.",
         "Examples:\n  tm-prep -i head.nii.gz -o clean.nii.gz --relabel 6:0 --remove-islands 20 --crop-pad 2\n"
         "  tm-prep -i liver.inr.gz -o liver.nii.gz --merge 127,85 --spacing-mm 1 --fill-holes\n"
         "  tm-prep -i liver.inr.gz -o clean.nii.gz --fill-holes-under 8 --crop-pad 2\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input", input, "Input label image")->required()->type_name("IMAGE");
            app.add_option("-o,--output", output, "Output label image")->required()->type_name("IMAGE");
            app.add_option("--labels", names,
                           "Tissue names for the input: JSON, FreeSurfer LUT, ITK-SNAP labels or BIDS dseg.tsv")
                ->type_name("FILE");
            app.add_option("--relabel", relabel, "FROM:TO pairs of tissues, applied at once (5:4,6:0; names or labels)")
                ->type_name("MAP");
            app.add_option("--merge", merges, "Merge tissues into the first (4,5 or names); repeatable")
                ->type_name("LABELS");
            app.add_option("--spacing-mm", spacing, "Resample to X or X,Y,Z mm (majority of the overlap)")
                ->type_name("MM");
            app.add_flag("--nearest", nearest, "Resample by nearest neighbour instead of majority");
            app.add_option("--keep-largest", keep_largest,
                           "Keep only the largest piece of these tissues (1,2 or names)")
                ->type_name("LABELS");
            app.add_option("--remove-islands", options.remove_islands_voxels,
                           "Give pieces under N voxels to their surrounding tissue")
                ->check(CLI::NonNegativeNumber)
                ->type_name("N");
            app.add_flag("--fill-holes", options.fill_holes, "Fill background cavities enclosed in tissue");
            app.add_option("--fill-holes-in", fill_holes_in,
                           "Fill only cavities enclosed by these tissues (labels or names)")
                ->type_name("LABELS");
            app.add_option("--fill-holes-under", options.fill_holes_under_voxels,
                           "Fill only cavities under N voxels (specks of segmentation noise, too small to mesh "
                           "well; the default workflow gives 8)")
                ->check(CLI::Range(1, 1000000000))
                ->type_name("N");
            crop_option = app.add_option("--crop-pad", crop_pad, "Crop to the tissue and pad with N background voxels")
                              ->check(CLI::NonNegativeNumber)
                              ->type_name("N");
            app.add_option("--background", options.background, "The label outside the tissues")
                ->check(CLI::Range(0, 65535))
                ->capture_default_str();
        },
        [&](tools::ToolContext& ctx) {
            parse_spacing(spacing, options);
            if (nearest) options.resample_method = image::ResampleMethod::nearest;
            if (crop_option->count() > 0) options.crop_pad_voxels = crop_pad;
            if (options.fill_holes_under_voxels > 0) options.fill_holes = true;
            const bool cleans = !keep_largest.empty() || options.remove_islands_voxels > 0 || options.fill_holes ||
                                !fill_holes_in.empty();
            LabelImage image = io::read_label_image(
                input, {.names_json = names, .before_voxels = memory_check(ctx.memory, input, options, cleans)});
            parse_tissue_options(relabel, merges, keep_largest, fill_holes_in, tools::tissue_table(image, input),
                                 options);
            const auto reports = image::prepare_image(image, options, ctx.progress);
            io::write_label_image(image, output);
            if (!image.names().empty()) {
                nlohmann::json table = nlohmann::json::object();
                for (const auto& [label, tissue] : image.names()) table[std::to_string(label)] = tissue;
                write_text_atomically(names_path(output), table.dump(2) + "\n");
            }
            nlohmann::json steps = nlohmann::json::array();
            for (const auto& report : reports) steps.push_back(to_json(report));
            ctx.summary = {{"input", input}, {"output", output}, {"dims", image.dims()}, {"steps", steps}};
            ctx.log(concat(reports.size(), " steps; wrote ", output));
        });
}
