// tm-render: pictures without a display (PNG): a cut-away surface view, a mesh section over the image slice,
// a section of a solved field, quality histograms, and tm-refine's convergence plot.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_label_image.h"
#include "io/read_vtu.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "render/mesh_charts.h"
#include "render/png.h"
#include "render/render_field.h"
#include "render/render_section.h"
#include "render/render_surface.h"
#include "tools/run_tool.h"
#include "volume/assess.h"

using namespace tissuemesh;

// The JSON form of the render reports, keys the field names (tools/report_json.h has the other libraries'; only
// tm-render compiles against render/).
namespace tissuemesh::render {
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SurfaceViewReport, triangles_drawn, triangles_cut, pixels_covered)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(SectionViewReport, position_mm, tets_cut, tets_highlighted)
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(FieldSectionReport, position_mm, tets_cut, outline_segments, field_min, field_max,
                                   colour_min, colour_max)
} // namespace tissuemesh::render

namespace {

Vec3 parse_point(const std::string& text)
{
    Vec3 p{};
    if (std::sscanf(text.c_str(), "%lf,%lf,%lf", &p[0], &p[1], &p[2]) != 3)
        throw InputError(concat("point \"", text, "\" is not X,Y,Z in mm; write e.g. 0,10,-5"));
    return p;
}

int parse_axis(const std::string& text)
{
    if (text == "x") return 0;
    if (text == "y") return 1;
    if (text == "z") return 2;
    throw InputError(concat("axis \"", text, "\" is not x, y or z"));
}

/// Tissues whose colour the picture shows, for the summary (the legend lists the same ones).
nlohmann::json labels_json(const std::set<Label>& labels)
{
    nlohmann::json list = nlohmann::json::array();
    for (const Label label : labels) list.push_back(label);
    return list;
}

render::Canvas surface_view(const std::string& input, const render::SurfaceViewOptions& options,
                            nlohmann::json& summary)
{
    const InterfaceComplex complex = io::read_surface(input);
    render::SurfaceViewReport report;
    render::Canvas picture = render::render_surface(complex, options, &report);
    std::set<Label> tissues;
    for (const LabelPair& pair : complex.sides)
        for (const Label label : {pair.from, pair.to})
            if (label != complex.background) tissues.insert(label);
    summary.update(nlohmann::json(report));
    summary["tissues_shown"] = labels_json(tissues);
    return picture;
}

/// With an image: its slice under the mesh, and every tet's error volume from assess_elements().
render::Canvas section_view(const std::string& input, const std::string& image_path,
                            const render::SectionViewOptions& options, const Progress& progress,
                            nlohmann::json& summary)
{
    const TetMesh mesh = io::read_tet_mesh(input);
    std::optional<LabelImage> image;
    std::optional<volume::Assessment> assessment;
    if (!image_path.empty()) {
        image = io::read_label_image(image_path);
        assessment = volume::assess_elements(mesh, *image, {}, progress);
        summary["total_error_volume_mm3"] = assessment->total_error_volume_mm3;
    }
    render::SectionViewReport report;
    render::Canvas picture = render::render_section(
        mesh, image ? &*image : nullptr, assessment ? &assessment->error_volume_mm3 : nullptr, options, &report);
    summary.update(nlohmann::json(report));
    return picture;
}

/// The histograms, and per tissue the tets, smallest dihedral and largest radius-edge ratio (for tm-report).
render::Canvas quality_view(const std::string& input, std::size_t width, std::size_t height, const std::string& title,
                            nlohmann::json& summary)
{
    const TetMesh mesh = io::read_tet_mesh(input);
    const render::QualityHistograms histograms = render::quality_histograms(mesh);
    nlohmann::json tissues = nlohmann::json::object();
    for (std::size_t s = 0; s < histograms.tissues.size(); ++s) {
        const Label label = histograms.tissues[s];
        tissues[std::to_string(label)] = {
            {"name", mesh.names.count(label) ? mesh.names.at(label) : std::to_string(label)},
            {"tets", histograms.tets[s]},
            {"min_dihedral_deg", histograms.min_dihedral_deg[s]},
            {"max_radius_edge_ratio", histograms.max_radius_edge_ratio[s]}};
    }
    summary["tissues"] = tissues;
    summary["tets"] = mesh.tets.size();
    return render::render_quality_histograms(mesh, histograms, width, height, title);
}

/// The values to colour by: `name` (or its short form: "potential", "E", "J") as a scalar per node or per tet
/// (vectors by their length), with the quantity and the SI unit its name ends with ("E_V_per_m": |E|, V/m).
struct Field {
    std::string name, quantity, unit;
    std::vector<double> values;
};

Field pick_field(const io::VtuContent& content, const std::string& input, const std::string& wanted)
{
    const std::map<std::string, std::vector<std::string>> aliases{
        {"potential", {"potential_V"}}, {"E", {"E_magnitude_V_per_m", "E_V_per_m"}}, {"J", {"J_A_per_m2"}}};
    const auto found = aliases.find(wanted);
    const std::vector<std::string> names = found != aliases.end() ? found->second : std::vector<std::string>{wanted};
    for (const std::string& name : names) {
        const io::VtuArray* array = content.point_array(name) ? content.point_array(name) : content.cell_array(name);
        if (!array) continue;
        Field field{name, name, "", {}};
        for (const auto& [suffix, unit] :
             std::vector<std::pair<std::string, std::string>>{{"_V_per_m", "V/m"}, {"_A_per_m2", "A/m^2"}, {"_V", "V"}})
            if (name.size() > suffix.size() && name.ends_with(suffix)) {
                field.quantity = name.substr(0, name.size() - suffix.size()), field.unit = unit;
                break;
            }
        if (field.quantity == "E_magnitude") field.quantity = "|E|";
        const auto components = static_cast<std::size_t>(array->components);
        if (components > 1 && field.quantity.find('|') == std::string::npos)
            field.quantity = "|" + field.quantity + "|";
        for (std::size_t i = 0; i < array->values.size() / components; ++i) {
            double sum = 0;
            for (std::size_t c = 0; c < components; ++c)
                sum += array->values[components * i + c] * array->values[components * i + c];
            field.values.push_back(components == 1 ? array->values[i] : std::sqrt(sum));
        }
        return field;
    }
    std::string present;
    for (const auto* arrays : {&content.point_arrays, &content.cell_arrays})
        for (const io::VtuArray& array : *arrays) present += (present.empty() ? "" : ", ") + array.name;
    throw InputError(concat(input, ": no point or cell array \"", names.front(), "\" (the file has ",
                            present.empty() ? "none" : present,
                            "); give --field NAME, or solve first: tm-solve -i mesh.msh -o solution.vtu ..."));
}

render::Canvas field_view(const std::string& input, const std::string& wanted, render::FieldSectionOptions options,
                          nlohmann::json& summary)
{
    if (full_extension(input) != ".vtu")
        throw InputError(concat(input, ": the field view reads a .vtu (tm-solve's output)"));
    const io::VtuContent content = io::read_vtu(input);
    const Field field = pick_field(content, input, wanted);
    options.quantity = field.quantity, options.unit = field.unit;
    render::FieldSectionReport report;
    render::Canvas picture = render::render_field_section(content.mesh, field.values, options, &report);
    summary.update({{"field", field.name},
                    {"quantity", field.quantity},
                    {"unit", field.unit},
                    {"per", field.values.size() == content.mesh.vertices.size() ? "node" : "tet"}});
    summary.update(nlohmann::json(report));
    return picture;
}

} // namespace

int main(int argc, char** argv)
{
    std::string view, input, image_path, output, cut = "wedge", cut_point, axis = "z", title, field_name = "potential";
    std::size_t width = 0, height = 0;
    double position_mm = 0;
    bool no_legend = false;
    CLI::Option* position_option = nullptr;
    render::SurfaceViewOptions surface;
    render::SectionViewOptions section;
    render::FieldSectionOptions field;
    return tools::run_tool(
        argc, argv,
        {"tm-render",
         "Draws a picture as PNG, headless (a software rasteriser with a depth buffer). Views: surface (an interface "
         "complex, shaded, colour per tissue, a half or a wedge cut away to show the nested layers), section (a tet "
         "mesh "
         "cut by an axis plane over the slice of the label image: element edges, tets by tissue, tets with error "
         "volume "
         "in red, computed against --image), field (a section of tm-solve's .vtu coloured by the potential or |E|, "
         "perceptual "
         "colour map, colour bar in the field's unit, tissue outlines in black), quality (histograms of smallest "
         "dihedral angle and radius-edge ratio, bars "
         "split by tissue), convergence (tm-refine's --log CSV: error volume and worst quality key against nodes). "
         "Colours are a fixed table by label (render/tissue_colours.h): 1 skin, 2 bone, 3 blue, 4 pink, ...",
         "Examples:\n  tm-render --view surface -i remeshed.ply -o surface.png --cut wedge --azimuth-deg 45\n"
         "  tm-render --view section -i head.msh --image head.nii.gz -o section.png --axis z --position-mm 30\n"
         "  tm-render --view field -i solution.vtu -o potential.png --field potential --axis z --position-mm 31.5\n"
         "  tm-render --view field -i solution.vtu -o field.png --field E --clip-percent 1\n"
         "  tm-render --view quality -i head.msh -o quality.png\n  tm-render --view convergence -i refine.csv -o "
         "refine.png"},
        [&](CLI::App& app) {
            app.add_option("--view", view, "surface, section, field, quality or convergence")
                ->required()
                ->check(CLI::IsMember({"surface", "section", "field", "quality", "convergence"}));
            app.add_option("-i,--input", input,
                           "Interface complex (surface), tet mesh (section, quality), .vtu (field) or CSV log")
                ->required()
                ->check(CLI::ExistingFile);
            app.add_option("-o,--output", output, "PNG picture")->required();
            app.add_option("--image", image_path, "section: the label image (slice shown, error volume computed)")
                ->check(CLI::ExistingFile);
            app.add_option("--width", width, "Picture width in px (default per view)");
            app.add_option("--height", height, "Picture height in px (default per view)");
            app.add_option("--azimuth-deg", surface.azimuth_deg, "surface: camera direction around +z, from +x")
                ->capture_default_str();
            app.add_option("--elevation-deg", surface.elevation_deg, "surface: camera height above the xy-plane")
                ->capture_default_str();
            app.add_option("--cut", cut, "surface: none, half (x > c) or wedge (x > c and y > c)")
                ->capture_default_str();
            app.add_option("--cut-point-mm", cut_point,
                           "surface: X,Y,Z of the cut (default: centre of the bounding box)");
            app.add_option("--axis", axis, "section, field: plane normal x, y or z")->capture_default_str();
            position_option = app.add_option("--position-mm", position_mm,
                                             "section, field: plane position along the axis (default: mesh centre)");
            app.add_option("--min-error-voxels", section.min_error_voxels,
                           "section: tets with this error volume (voxels) or more in red")
                ->capture_default_str();
            app.add_option("--field", field_name,
                           "field: array of the .vtu: potential (potential_V), E (|E|), J (|J|) or any array name")
                ->capture_default_str();
            app.add_option("--clip-percent", field.clip_percent,
                           "field: percent of the values at each end left out of the colour range")
                ->capture_default_str();
            app.add_option("--title", title, "Caption drawn on the picture");
            app.add_flag("--no-legend", no_legend, "Leave out the tissue legend");
        },
        [&](tools::ToolContext& context) {
            if (full_extension(output) != ".png") throw InputError(concat(output, ": the output must be a .png file"));
            const auto start = std::chrono::steady_clock::now();
            std::optional<render::Canvas> picture;
            nlohmann::json summary = {{"view", view}, {"input", input}, {"output", output}};
            if (view == "surface") {
                surface.width_px = width ? width : 800, surface.height_px = height ? height : 800;
                surface.cut = render::parse_cut_away(cut);
                if (!cut_point.empty()) surface.cut_at_centre = false, surface.cut_point_mm = parse_point(cut_point);
                surface.legend = !no_legend, surface.title = title;
                picture = surface_view(input, surface, summary);
            } else if (view == "section") {
                section.width_px = width ? width : 800, section.height_px = height ? height : 800;
                section.axis = parse_axis(axis);
                section.at_centre = position_option->count() == 0;
                section.position_mm = position_mm, section.legend = !no_legend, section.title = title;
                picture = section_view(input, image_path, section, context.progress, summary);
                summary["axis"] = axis;
            } else if (view == "field") {
                field.width_px = width ? width : 960, field.height_px = height ? height : 800;
                field.axis = parse_axis(axis);
                field.at_centre = position_option->count() == 0;
                field.position_mm = position_mm, field.title = title;
                picture = field_view(input, field_name, field, summary);
                summary["axis"] = axis;
            } else if (view == "quality") {
                picture = quality_view(input, width ? width : 1200, height ? height : 480, title, summary);
            } else {
                const std::vector<render::RefineLogRow> rows = render::read_refine_log(input);
                picture = render::render_convergence(rows, width ? width : 900, height ? height : 640, title);
                summary["rounds"] = rows.size();
            }
            render::write_png(*picture, output);
            summary["width_px"] = picture->width(), summary["height_px"] = picture->height();
            summary["render_seconds"] = tools::seconds_since(start);
            context.summary = summary;
            context.log(concat(view, " view ", picture->width(), " x ", picture->height(), " px -> ", output));
        });
}
