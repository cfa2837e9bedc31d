#include "image/label_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "core/error.h"
#include "image/connected_components.h"

namespace tissuemesh::image {

std::string orientation_code(const Mat3& direction)
{
    std::string code;
    for (int column = 0; column < 3; ++column) {
        int axis = 0;
        for (int row = 1; row < 3; ++row)
            if (std::abs(direction[3 * row + column]) > std::abs(direction[3 * axis + column])) axis = row;
        const bool positive = direction[3 * axis + column] > 0;
        code += "RAS"[axis] == 'R' ? (positive ? 'R' : 'L')
                : axis == 1        ? (positive ? 'A' : 'P')
                                   : (positive ? 'S' : 'I');
    }
    return code;
}

namespace {

/// Per-voxel pass: counts, bounding boxes, border voxels, face contacts and thin voxels.
void scan_voxels(const LabelImage& image, std::vector<LabelSummary>& summaries, const std::vector<int>& slot,
                 std::set<std::pair<Label, Label>>& contacts, const Progress& progress)
{
    const Dims& d = image.dims();
    const auto& labels = image.labels();
    const std::size_t stride[3] = {1, d[0], d[0] * d[1]};
    ProgressTicker ticker(progress, "labels", d[2]);
    std::pair<Label, Label> last_contact{0, 0};
    for (std::size_t k = 0; k < d[2]; ++k, ticker.step()) {
        for (std::size_t j = 0; j < d[1]; ++j) {
            for (std::size_t i = 0; i < d[0]; ++i) {
                const std::size_t v = image.linear_index(i, j, k);
                const Label label = labels[v];
                LabelSummary& s = summaries[static_cast<std::size_t>(slot[label])];
                const std::size_t index[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) {
                    s.index_min[a] = std::min(s.index_min[a], index[a]);
                    s.index_max[a] = std::max(s.index_max[a], index[a]);
                }
                ++s.voxels;
                bool border = false, thin = false;
                for (int a = 0; a < 3; ++a) {
                    const bool first = index[a] == 0, end = index[a] + 1 == d[a];
                    border |= first || end;
                    if (!end && labels[v + stride[a]] != label) {
                        const Label other = labels[v + stride[a]];
                        const std::pair<Label, Label> pair{std::min(label, other), std::max(label, other)};
                        if (pair != last_contact) contacts.insert(last_contact = pair);
                    }
                    if (!first && !end && labels[v - stride[a]] != label && labels[v + stride[a]] != label) thin = true;
                }
                s.border_voxels += border;
                s.thin_voxels += thin;
            }
        }
    }
}

/// World axis-aligned box of the voxel cells between two index corners (inclusive).
std::array<Vec3, 2> cell_bounds_mm(const LabelImage& image, const std::array<std::size_t, 3>& lo,
                                   const std::array<std::size_t, 3>& hi)
{
    std::array<Vec3, 2> box{Vec3{INFINITY, INFINITY, INFINITY}, Vec3{-INFINITY, -INFINITY, -INFINITY}};
    for (int corner = 0; corner < 8; ++corner) {
        Vec3 index;
        for (int a = 0; a < 3; ++a)
            index[a] = (corner >> a & 1) ? static_cast<double>(hi[a]) + 0.5 : static_cast<double>(lo[a]) - 0.5;
        const Vec3 p = image.index_to_world(index);
        for (int a = 0; a < 3; ++a) box[0][a] = std::min(box[0][a], p[a]), box[1][a] = std::max(box[1][a], p[a]);
    }
    return box;
}

void add_warnings(LabelSummary& s, const LabelStatisticsOptions& options)
{
    if (s.label == options.background) return;
    if (s.border_voxels > 0)
        s.warnings.push_back(concat(s.name, ": ", s.border_voxels,
                                    " voxels on the image border; the mesh would "
                                    "be cut open there. Pad the image: tm-prep --crop-pad 2"));
    if (s.thin_voxels > 0)
        s.warnings.push_back(concat(s.name, ": ", s.thin_voxels,
                                    " voxels are one voxel thin (other tissues on "
                                    "both sides along an axis); surfaces may touch there. Resample finer "
                                    "(tm-prep --spacing-mm) or accept the contact"));
    if (s.islands > 0)
        s.warnings.push_back(concat(s.name, ": ", s.islands, " islands under ", options.island_voxels, " voxels (",
                                    s.island_voxels, " voxels in all); remove them: tm-prep --remove-islands ",
                                    options.island_voxels));
}

} // namespace

LabelStatistics analyze_labels(const LabelImage& image, const LabelStatisticsOptions& options, const Progress& progress)
{
    if (image.empty()) throw InputError("label image is empty; nothing to analyse");
    LabelStatistics stats;
    stats.dims = image.dims();
    stats.spacing_mm = image.spacing_mm();
    stats.origin_mm = image.origin_mm();
    stats.direction = image.direction();
    stats.orientation = orientation_code(image.direction());
    stats.bounds_mm = image.world_bounds_mm();
    stats.voxel_count = image.voxel_count();

    std::vector<int> slot(std::size_t{std::numeric_limits<Label>::max()} + 1, -1);
    for (const auto& [label, count] : count_labels(image)) {
        slot[label] = static_cast<int>(stats.labels.size());
        LabelSummary s;
        s.label = label;
        s.name = image.name_of(label);
        s.index_min = {image.dims()[0], image.dims()[1], image.dims()[2]};
        stats.labels.push_back(s);
    }
    std::set<std::pair<Label, Label>> contacts;
    scan_voxels(image, stats.labels, slot, contacts, progress);
    for (const auto& [a, b] : contacts) {
        stats.labels[static_cast<std::size_t>(slot[a])].touches.push_back(b);
        stats.labels[static_cast<std::size_t>(slot[b])].touches.push_back(a);
    }

    progress.info("labels", "connected components (6- and 26-neighbours)");
    const Components faces = find_components(image, Connectivity::faces6);
    for (std::size_t c = 0; c < faces.count(); ++c) {
        LabelSummary& s = stats.labels[static_cast<std::size_t>(slot[faces.label[c]])];
        ++s.components6;
    }
    // Islands are pieces isolated even through edges and corners: a thin layer whose voxels touch only
    // diagonally (the CSF of a 2 mm sphere head) is one piece, and removing its 6-connected bits would cut it.
    const Components full = find_components(image, Connectivity::full26);
    for (std::size_t c = 0; c < full.count(); ++c) {
        LabelSummary& s = stats.labels[static_cast<std::size_t>(slot[full.label[c]])];
        ++s.components26;
        if (full.size[c] < options.island_voxels) ++s.islands, s.island_voxels += full.size[c];
    }

    for (LabelSummary& s : stats.labels) {
        std::sort(s.touches.begin(), s.touches.end());
        s.volume_mm3 = static_cast<double>(s.voxels) * image.voxel_volume_mm3();
        s.bounds_mm = cell_bounds_mm(image, s.index_min, s.index_max);
        add_warnings(s, options);
    }
    return stats;
}

} // namespace tissuemesh::image
