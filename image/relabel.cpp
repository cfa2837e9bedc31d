#include "image/relabel.h"

#include <array>
#include <limits>
#include <numeric>

#include "core/error.h"

namespace tissuemesh::image {
namespace {

std::string list_labels(const std::map<Label, std::size_t>& counts)
{
    std::string text;
    for (const auto& [label, count] : counts) {
        if (!text.empty()) text += ',';
        text += std::to_string(label);
    }
    return text;
}

} // namespace

PrepReport relabel(LabelImage& image, const std::map<Label, Label>& mapping)
{
    PrepReport report = begin_report("relabel", image);
    for (const auto& [from, to] : mapping)
        if (!report.voxels_before.contains(from))
            throw InputError(concat("relabel ", from, ":", to, ": label ", from, " is not in the image (it has ",
                                    list_labels(report.voxels_before), "); check the map against tm-info"));
    std::vector<Label> table(std::size_t{std::numeric_limits<Label>::max()} + 1);
    std::iota(table.begin(), table.end(), Label{0});
    for (const auto& [from, to] : mapping) table[from] = to;
    for (Label& label : image.labels()) {
        const Label next = table[label];
        report.changed_voxels += next != label;
        label = next;
    }
    TissueNames names;
    for (const auto& [label, name] : image.names())
        if (!mapping.contains(label)) names[label] = name;
    for (const auto& [from, to] : mapping) {
        const auto found = image.names().find(from);
        if (found != image.names().end() && !names.contains(to)) names[to] = found->second;
    }
    image.names() = names;
    std::string detail;
    for (const auto& [from, to] : mapping) detail += concat(detail.empty() ? "" : ", ", from, " -> ", to);
    report.detail = concat(detail, " (", report.changed_voxels, " voxels)");
    finish_report(report, image);
    return report;
}

PrepReport merge_labels(LabelImage& image, const std::vector<Label>& group)
{
    if (group.size() < 2)
        throw InputError(concat("merge needs at least two labels (e.g. 4,5 merges 5 into 4); got ", group.size()));
    if (!count_labels(image).contains(group[0]))
        throw InputError(concat("merge: label ", group[0], " is not in the image; check the labels with tm-info"));
    std::map<Label, Label> mapping;
    for (std::size_t k = 1; k < group.size(); ++k)
        if (group[k] != group[0]) mapping[group[k]] = group[0];
    PrepReport report = relabel(image, mapping);
    report.step = "merge";
    return report;
}

} // namespace tissuemesh::image
