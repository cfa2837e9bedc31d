#include "volume/assess.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/error.h"
#include "core/tet_shape.h"
#include "surface/extracted_tissue.h"
#include "volume/check_mesh.h"
#include "volume/rasterize.h"

namespace tissuemesh::volume {
namespace {

constexpr int sample_count = 5;
const double regular_radius_edge = std::sqrt(6.0) / 4.0;

/// Each tet's voxel labels back to back (counting sort of the owner array): tet t's labels are
/// labels[offsets[t] .. offsets[t + 1]).
struct LabelsByTet {
    std::vector<std::size_t> offsets;
    std::vector<Label> labels;
};

LabelsByTet sort_by_owner(const std::vector<std::int32_t>& owner, const LabelImage& image, std::size_t tets)
{
    LabelsByTet sorted;
    sorted.offsets.assign(tets + 1, 0);
    for (const std::int32_t t : owner)
        if (t >= 0) ++sorted.offsets[static_cast<std::size_t>(t) + 1];
    std::partial_sum(sorted.offsets.begin(), sorted.offsets.end(), sorted.offsets.begin());
    sorted.labels.resize(sorted.offsets.back());
    std::vector<std::size_t> next(sorted.offsets.begin(), sorted.offsets.end() - 1);
    const std::vector<Label>& labels = image.labels();
    for (std::size_t v = 0; v < owner.size(); ++v)
        if (owner[v] >= 0) sorted.labels[next[static_cast<std::size_t>(owner[v])]++] = labels[v];
    return sorted;
}

/// Tissues at the centroid and near each vertex (barycentric 0.7 / 0.1 / 0.1 / 0.1) as the extracted surfaces
/// put them; `index_points` are the mesh vertices in continuous voxel index coordinates (the map is affine).
std::array<Label, sample_count> sample_tet(const TetMesh& mesh, const std::vector<Vec3>& index_points,
                                           const surface::ExtractedTissue& extracted, std::size_t t)
{
    std::array<Vec3, 4> p;
    for (int c = 0; c < 4; ++c) p[c] = index_points[mesh.tets[t][static_cast<std::size_t>(c)]];
    std::array<Label, sample_count> samples{};
    for (int s = 0; s < sample_count; ++s) {
        Vec3 point{0, 0, 0};
        for (int c = 0; c < 4; ++c) point = point + (s == 0 ? 0.25 : (c == s - 1 ? 0.7 : 0.1)) * p[c];
        samples[static_cast<std::size_t>(s)] = extracted.at_index(point);
    }
    return samples;
}

/// Histogram bins (labels ascending) of `labels`, using `scratch` (65536 zeros, left zeroed) as counter.
void append_histogram(const Label* first, const Label* last, std::vector<std::uint32_t>& scratch,
                      std::vector<LabelCount>& histogram)
{
    const std::size_t begin = histogram.size();
    for (const Label* l = first; l != last; ++l)
        if (scratch[*l]++ == 0) histogram.push_back({*l, 0});
    std::sort(histogram.begin() + static_cast<std::ptrdiff_t>(begin), histogram.end(),
              [](const LabelCount& a, const LabelCount& b) { return a.label < b.label; });
    for (std::size_t b = begin; b < histogram.size(); ++b) {
        histogram[b].count = scratch[histogram[b].label];
        scratch[histogram[b].label] = 0;
    }
}

/// argmax priority x count; ties to `current` when tied, else to the smallest label (bins ascending).
Label weighted_majority(const LabelCount* first, const LabelCount* last, Label current, const AssessOptions& options)
{
    auto weight = [&](Label label) {
        const auto found = options.priority.find(label);
        return found == options.priority.end() ? 1.0 : found->second;
    };
    double best = -1;
    Label winner = current;
    for (const LabelCount* bin = first; bin != last; ++bin) {
        const double score = weight(bin->label) * static_cast<double>(bin->count);
        if (score > best || (score == best && bin->label == current)) best = score, winner = bin->label;
    }
    return winner;
}

std::uint32_t count_of(const LabelCount* first, const LabelCount* last, Label label)
{
    for (const LabelCount* bin = first; bin != last; ++bin)
        if (bin->label == label) return bin->count;
    return 0;
}

/// Longest edge over (2 sqrt 6 x inradius), inradius = 3 V / surface area: 1 for the regular tet.
double aspect_ratio(const TetMesh& mesh, std::size_t t, double volume)
{
    std::array<Vec3, 4> p;
    for (int c = 0; c < 4; ++c) p[c] = mesh.vertices[mesh.tets[t][static_cast<std::size_t>(c)]];
    double longest = 0, area = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) longest = std::max(longest, distance(p[i], p[j]));
    const int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (const auto& f : faces) area += 0.5 * norm(cross(p[f[1]] - p[f[0]], p[f[2]] - p[f[0]]));
    if (!(volume > 0) || !(area > 0)) return std::numeric_limits<double>::infinity();
    return longest / (2.0 * std::sqrt(6.0) * (3.0 * volume / area));
}

void validate(const TetMesh& mesh, const LabelImage& image, const AssessOptions& options)
{
    validate_indices(mesh, "mesh");
    if (image.empty()) throw InputError("label image is empty; give the image the mesh was made from");
    for (const auto& [label, weight] : options.priority)
        if (!(weight > 0) || !std::isfinite(weight))
            throw InputError(concat("priority of tissue ", label, " is ", weight, "; give a positive finite weight"));
}

/// Per-tet histogram, majority and error volumes (voxel-based, or sampled when a tet holds no centre).
void assess_tissues(const TetMesh& mesh, const LabelImage& image, const LabelsByTet& sorted,
                    const AssessOptions& options, Assessment& out)
{
    const std::size_t tets = mesh.tets.size();
    const double voxel_mm3 = image.voxel_volume_mm3();
    std::vector<std::uint32_t> scratch(std::size_t{1} << 16, 0);
    out.histogram.reserve(tets * 2);
    std::vector<Vec3> index_points(mesh.vertices.size());
    for (std::size_t v = 0; v < index_points.size(); ++v) index_points[v] = image.world_to_index(mesh.vertices[v]);
    const surface::ExtractedTissue extracted(image,
                                             {.background = options.background, .priority = options.extract_priority});
    for (std::size_t t = 0; t < tets; ++t) {
        const std::size_t held = sorted.offsets[t + 1] - sorted.offsets[t];
        out.voxel_count[t] = static_cast<std::uint32_t>(held);
        std::array<Label, sample_count> samples{};
        const Label* first = sorted.labels.data() + sorted.offsets[t];
        const Label* last = first + held;
        if (held == 0) {
            samples = sample_tet(mesh, index_points, extracted, t);
            first = samples.data(), last = samples.data() + sample_count;
            out.sampled[t] = 1, ++out.sampled_tets;
        }
        const std::size_t begin = out.histogram.size();
        append_histogram(first, last, scratch, out.histogram);
        out.histogram_offsets[t + 1] = out.histogram.size();
        const LabelCount* bins = out.histogram.data() + begin;
        const LabelCount* bins_end = out.histogram.data() + out.histogram.size();
        const Label current = mesh.tet_labels[t];
        out.majority[t] = weighted_majority(bins, bins_end, current, options);
        const auto total = static_cast<double>(last - first);
        const auto wrong = total - count_of(bins, bins_end, current);
        const auto wrong_majority = total - count_of(bins, bins_end, out.majority[t]);
        // Sampled tets: the unmatched fraction of the samples times the tet's volume (an estimate).
        const double unit = held > 0 ? voxel_mm3 : std::max(0.0, out.volume_mm3[t]) / sample_count;
        out.error_volume_mm3[t] = wrong * unit;
        out.majority_error_volume_mm3[t] = wrong_majority * unit;
        if (held > 0) {
            out.total_error_volume_mm3 += wrong * unit;
            out.total_majority_error_volume_mm3 += wrong_majority * unit;
        } else {
            out.sampled_error_volume_mm3 += wrong * unit;
        }
    }
}

void assess_geometry(const TetMesh& mesh, Assessment& out)
{
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        out.volume_mm3[t] = signed_volume(mesh, t);
        const TetShape shape = tet_shape(mesh, t);
        out.min_dihedral_deg[t] = shape.min_dihedral_deg;
        out.radius_edge_ratio[t] = shape.radius_edge_ratio;
        out.aspect_ratio[t] = aspect_ratio(mesh, t, out.volume_mm3[t]);
    }
}

void rank(const LabelImage& image, const AssessOptions& options, Assessment& out)
{
    const std::size_t tets = out.volume_mm3.size();
    for (std::size_t t = 0; t < tets; ++t) {
        const double ratio = std::min(out.radius_edge_ratio[t], 1e6);
        out.quality_key[t] = options.error_weight * out.error_volume_mm3[t] / image.voxel_volume_mm3() +
                             options.shape_weight * (ratio / regular_radius_edge - 1.0);
    }
    out.worst_first.resize(tets);
    std::iota(out.worst_first.begin(), out.worst_first.end(), std::uint32_t{0});
    std::stable_sort(out.worst_first.begin(), out.worst_first.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return out.quality_key[a] > out.quality_key[b]; });
}

/// Dice, volumes and error volume per tissue, with check_mesh()'s counting.
void assess_per_tissue(const TetMesh& mesh, const LabelImage& image, const std::vector<std::int32_t>& owner,
                       Assessment& out)
{
    const double voxel_mm3 = image.voxel_volume_mm3();
    for (const auto& [label, count] : count_labels(image)) out.tissues[label].image_voxels = count;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        TissueAssessment& tissue = out.tissues[mesh.tet_labels[t]];
        tissue.mesh_volume_mm3 += out.volume_mm3[t];
        if (!out.sampled[t]) tissue.error_volume_mm3 += out.error_volume_mm3[t];
    }
    const std::vector<Label>& labels = image.labels();
    for (std::size_t v = 0; v < owner.size(); ++v) {
        if (owner[v] < 0) continue;
        const Label meshed = mesh.tet_labels[static_cast<std::size_t>(owner[v])];
        TissueAssessment& tissue = out.tissues[meshed];
        ++tissue.mesh_voxels;
        if (meshed == labels[v]) ++tissue.agreeing_voxels;
    }
    for (auto& [label, tissue] : out.tissues) {
        const auto both = static_cast<double>(tissue.image_voxels + tissue.mesh_voxels);
        tissue.dice = both > 0 ? 2.0 * static_cast<double>(tissue.agreeing_voxels) / both : 1.0;
        tissue.voxel_volume_mm3 = static_cast<double>(tissue.image_voxels) * voxel_mm3;
        tissue.volume_error_mm3 = tissue.mesh_volume_mm3 - tissue.voxel_volume_mm3;
    }
}

} // namespace

Assessment assess_elements(const TetMesh& mesh, const LabelImage& image, const AssessOptions& options,
                           const Progress& progress)
{
    validate(mesh, image, options);
    const std::size_t tets = mesh.tets.size();
    Assessment out;
    out.histogram_offsets.assign(tets + 1, 0);
    out.voxel_count.assign(tets, 0), out.sampled.assign(tets, 0), out.majority.assign(tets, 0);
    for (auto* field : {&out.error_volume_mm3, &out.majority_error_volume_mm3, &out.volume_mm3, &out.min_dihedral_deg,
                        &out.radius_edge_ratio, &out.aspect_ratio, &out.quality_key})
        field->assign(tets, 0.0);

    const std::vector<std::int32_t> owner = rasterize_tets(mesh, image, progress);
    progress.update("assess", 0.5);
    const LabelsByTet sorted = sort_by_owner(owner, image, tets);
    out.voxels_inside = sorted.labels.size();
    assess_geometry(mesh, out);
    progress.update("assess", 0.7);
    assess_tissues(mesh, image, sorted, options, out);
    rank(image, options, out);
    assess_per_tissue(mesh, image, owner, out);
    progress.update("assess", 1.0);
    return out;
}

void relabel_by_majority(TetMesh& mesh, const Assessment& assessment)
{
    if (assessment.majority.size() != mesh.tets.size())
        throw InputError(concat("assessment has ", assessment.majority.size(), " tets but the mesh has ",
                                mesh.tets.size(), "; assess this mesh before relabelling it"));
    mesh.tet_labels = assessment.majority;
}

} // namespace tissuemesh::volume
