// tm-check-surface: says whether an interface complex is fit for tetrahedralization, and if not, what
// is wrong where: per tissue closedness, orientation, components and volume; every kind of defect with
// its count and located examples. Exit 0 when fit, 1 when defects were found, 2 when unreadable.
#include <algorithm>
#include <array>
#include <cstdio>

#include "core/error.h"
#include "io/surface_io.h"
#include "surface/check_complex.h"
#include "tools/report_json.h"
#include "tools/run_tool.h"

using namespace tissuemesh;
using surface::CheckReport;
using surface::Defect;
using surface::DefectKind;

namespace {

std::string tissue_name(const InterfaceComplex& complex, Label label)
{
    const auto found = complex.names.find(label);
    return found != complex.names.end() && !found->second.empty() ? found->second : std::to_string(label);
}

/// At most `limit` stored defects, taken in turn from each kind so that every kind found is shown.
std::vector<const Defect*> defects_to_show(const CheckReport& report, std::size_t limit)
{
    std::array<std::vector<const Defect*>, surface::defect_kind_count> by_kind;
    for (const Defect& defect : report.defects) by_kind[static_cast<std::size_t>(defect.kind)].push_back(&defect);
    std::vector<const Defect*> shown;
    for (std::size_t round = 0; shown.size() < limit && shown.size() < report.defects.size(); ++round)
        for (const auto& list : by_kind)
            if (round < list.size() && shown.size() < limit) shown.push_back(list[round]);
    std::stable_sort(shown.begin(), shown.end(), [](const Defect* a, const Defect* b) { return a->kind < b->kind; });
    return shown;
}

void print_report(const std::string& path, const InterfaceComplex& complex, const CheckReport& report,
                  std::size_t max_report)
{
    std::printf("%s: %zu triangles, %zu vertices, %zu edges (%zu on junction curves), %zu tissues\n\n", path.c_str(),
                report.triangles, report.vertices, report.edges, report.junction_edges, report.tissues.size());
    std::printf("%5s  %-16s %10s  %-6s  %-8s  %10s  %15s\n", "label", "tissue", "triangles", "closed", "oriented",
                "components", "volume_mm3");
    for (const auto& [label, t] : report.tissues)
        std::printf("%5u  %-16s %10zu  %-6s  %-8s  %10zu  %15.3f%s\n", static_cast<unsigned>(label),
                    tissue_name(complex, label).c_str(), t.triangles, t.closed ? "yes" : "NO",
                    t.oriented ? "yes" : "NO", t.components, t.volume_mm3,
                    label == complex.background ? "  (background: minus the enclosed volume)" : "");
    std::printf("\n%zu errors, %zu warnings%s\n", report.error_count(), report.warning_count(),
                report.intersections_checked ? "" : " (intersections not checked)");
    for (std::size_t k = 0; k < surface::defect_kind_count; ++k)
        if (report.counts[k] > 0)
            std::printf("  %-22s %zu%s\n", std::string(surface::to_string(DefectKind(k))).c_str(), report.counts[k],
                        surface::is_error(DefectKind(k)) ? "" : " (warning)");
    const std::vector<const Defect*> shown = defects_to_show(report, max_report);
    if (!shown.empty()) std::printf("\n");
    for (const Defect* defect : shown)
        std::printf("  %s: %s\n", std::string(surface::to_string(defect->kind)).c_str(), defect->description.c_str());
    if (shown.size() < report.error_count() + report.warning_count())
        std::printf("  ... %zu more (--max-report N shows more)\n",
                    report.error_count() + report.warning_count() - shown.size());
    std::printf("\n%s\n", !report.ok()                   ? "NOT fit for tetrahedralization"
                          : report.intersections_checked ? "fit for tetrahedralization"
                                                         : "fit for tetrahedralization unless it self-intersects "
                                                           "(intersections not checked)");
}

nlohmann::json to_json(const InterfaceComplex& complex, const CheckReport& report, std::size_t max_report)
{
    nlohmann::json tissues = nlohmann::json::array();
    for (const auto& [label, t] : report.tissues) {
        nlohmann::json tissue = t;
        tissue.update({{"label", label}, {"name", tissue_name(complex, label)}});
        tissues.push_back(tissue);
    }
    nlohmann::json counts = nlohmann::json::object();
    for (std::size_t k = 0; k < surface::defect_kind_count; ++k)
        counts[std::string(surface::to_string(DefectKind(k)))] = report.counts[k];
    nlohmann::json defects = nlohmann::json::array();
    for (const Defect* d : defects_to_show(report, max_report))
        defects.push_back({{"kind", surface::to_string(d->kind)},
                           {"description", d->description},
                           {"location_mm", d->location_mm},
                           {"tissues", d->tissues},
                           {"triangles", d->triangles}});
    return {{"fit_for_tetrahedralization", report.ok()},
            {"triangles", report.triangles},
            {"vertices", report.vertices},
            {"edges", report.edges},
            {"junction_edges", report.junction_edges},
            {"intersections_checked", report.intersections_checked},
            {"errors", report.error_count()},
            {"warnings", report.warning_count()},
            {"defect_counts", counts},
            {"tissues", tissues},
            {"defects", defects}};
}

/// "2 patch-intersection, 6 open-edge"
std::string error_summary(const CheckReport& report)
{
    std::string text;
    for (std::size_t k = 0; k < surface::defect_kind_count; ++k)
        if (report.counts[k] > 0 && surface::is_error(DefectKind(k)))
            text += concat(text.empty() ? "" : ", ", report.counts[k], ' ', surface::to_string(DefectKind(k)));
    return text;
}

} // namespace

int main(int argc, char** argv)
{
    std::string input;
    std::size_t max_report = 20;
    bool skip_intersections = false;
    surface::CheckOptions options;
    return tools::run_tool(
        argc, argv,
        {"tm-check-surface",
         "Checks that an interface complex is fit for tetrahedralization: every tissue's surface closed and "
         "consistently oriented, no tissue touching itself along an edge, no degenerate or duplicate triangle or "
         "vertex, and no intersection (exact predicates). Prints per tissue its volume and components, and each "
         "defect with the tissues and a location in mm. Exit 0: fit; 1: defects found; 2: unreadable input.",
         "Examples:\n  tm-check-surface head.ply\n  tm-check-surface -i head.ply --max-report 100 --json check.json\n"},
        [&](CLI::App& app) {
            app.add_option("-i,--input,surface", input, "Interface complex (.ply with label pairs)")
                ->required()
                ->type_name("SURFACE");
            app.add_option("--max-report", max_report, "Print at most N defects")
                ->check(CLI::NonNegativeNumber)
                ->capture_default_str();
            app.add_option("--needle-angle-deg", options.needle_angle_deg, "Warn about angles below this")
                ->capture_default_str();
            app.add_flag("--skip-intersections", skip_intersections, "Skip the intersection test (faster)");
        },
        [&](tools::ToolContext& ctx) {
            const InterfaceComplex complex = io::read_surface(input);
            options.max_defects_per_kind = std::max<std::size_t>(max_report, 1);
            options.check_intersections = !skip_intersections;
            const CheckReport report = surface::check_complex(complex, options, ctx.progress);
            print_report(input, complex, report, max_report);
            ctx.summary = to_json(complex, report, max_report);
            ctx.summary["input"] = input;
            const double sector = surface::smallest_tissue_sector_deg(complex);
            ctx.summary["min_tissue_sector_deg"] = sector;
            if (!report.ok())
                throw AlgorithmError(concat(input, ": not fit for tetrahedralization: ", error_summary(report),
                                            "; first: ", report.first_error()->description, "; ",
                                            surface::repair_hint(report)));
            ctx.log(concat(input, ": fit for tetrahedralization (", report.triangles, " triangles, ",
                           report.warning_count(), " warnings); smallest angle a tissue fills about an edge ",
                           format_mm(sector, 2), " deg (no tet there can have all its dihedral angles above it)"));
        });
}
