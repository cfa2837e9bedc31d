#include "surface/smooth.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/edit_rules.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/label_field.h"
#include "surface/detail/voxel_evidence.h"

namespace tissuemesh::surface {
namespace {

using detail::ComplexEditor;
using detail::VertexKind;

void validate(const SmoothOptions& options)
{
    if (!(options.lambda > 0 && options.lambda < 1 && options.mu < -options.lambda && options.mu > -1))
        throw InputError(concat("smooth: lambda ", options.lambda, " and mu ", options.mu,
                                " must satisfy 0 < lambda < -mu < 1 (Taubin); try 0.63 and -0.67"));
    if (!(options.max_depth_voxels > 0 && options.max_depth_voxels <= 1))
        throw InputError(concat("smooth: max depth ", options.max_depth_voxels, " voxels is outside (0, 1]"));
    if (!(options.min_gap_voxels >= 0 && options.min_gap_voxels < 1))
        throw InputError(concat("smooth: min gap ", options.min_gap_voxels, " voxels is outside [0, 1)"));
    if (!(options.fit_sigma_voxels > 0 && options.fit_sigma_voxels <= 1))
        throw InputError(concat("smooth: fit sigma ", options.fit_sigma_voxels, " voxels is outside (0, 1]"));
}

/// The vertices each vertex is smoothed towards (its neighbours; its two curve neighbours on a junction
/// curve; none for a corner), listed once: smoothing never changes the connectivity.
struct Rings {
    std::vector<std::size_t> begin{0};
    std::vector<std::uint32_t> items;

    explicit Rings(const ComplexEditor& editor)
    {
        for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
            if (editor.vertex_alive(v) && editor.kind(v) != VertexKind::corner) {
                const std::vector<std::uint32_t> ring =
                    editor.kind(v) == VertexKind::curve ? editor.curve_neighbours(v) : editor.neighbours(v);
                items.insert(items.end(), ring.begin(), ring.end());
            }
            begin.push_back(items.size());
        }
    }
};

/// The umbrella vector at `positions`: mean of the ring minus the vertex. Inside a patch only its
/// component along the vertex normal: the tangential part would only slide vertices over the surface
/// (and the marching-cubes triangles are already well shaped; remeshing is a later step), so flat places
/// do not move at all and cost nothing.
Vec3 umbrella(const ComplexEditor& editor, const Rings& rings, const std::vector<Vec3>& positions, std::uint32_t v)
{
    Vec3 mean{0, 0, 0};
    for (std::size_t i = rings.begin[v]; i < rings.begin[v + 1]; ++i) mean = mean + positions[rings.items[i]];
    const auto count = static_cast<double>(rings.begin[v + 1] - rings.begin[v]);
    const Vec3 shift = (1.0 / count) * mean - positions[v];
    if (editor.kind(v) == VertexKind::curve) return shift;
    Vec3 normal{0, 0, 0};
    for (const std::uint32_t t : editor.star(v)) {
        const Triangle& tri = editor.triangle(t);
        normal = normal + cross(positions[tri[1]] - positions[tri[0]], positions[tri[2]] - positions[tri[0]]);
    }
    const double length = norm(normal);
    if (length == 0) return shift;
    const Vec3 n = (1.0 / length) * normal;
    return dot(shift, n) * n;
}

/// `positions` after one Jacobi step of factor `factor` (unchecked).
std::vector<Vec3> jacobi_step(const ComplexEditor& editor, const Rings& rings, const std::vector<Vec3>& positions,
                              double factor)
{
    std::vector<Vec3> next = positions;
    const auto slots = static_cast<std::int64_t>(editor.vertex_slots());
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < slots; ++i) {
        const auto v = static_cast<std::uint32_t>(i);
        if (rings.begin[v + 1] > rings.begin[v])
            next[v] = positions[v] + factor * umbrella(editor, rings, positions, v);
    }
    return next;
}

/// Where the voxel evidence lets v go by `shift`: the full step, else half of it, else nowhere.
std::optional<Vec3> allowed_target(const Vec3& p, const Vec3& shift, const detail::VoxelEvidence& evidence,
                                   const std::vector<Label>& tissues)
{
    if (evidence.allows(p + shift, tissues)) return p + shift;
    if (evidence.allows(p + 0.5 * shift, tissues)) return p + 0.5 * shift;
    return std::nullopt;
}

/// Moves `vertices` to `targets` all at once; the editor puts back those that would break the complex,
/// which are tried once more at half length (where the image allows). Returns the moves made.
std::size_t move_checked(ComplexEditor& editor, const detail::VoxelEvidence& evidence,
                         const std::vector<std::vector<Label>>& tissues, const std::vector<std::uint32_t>& vertices,
                         const std::vector<Vec3>& targets, SmoothReport& report)
{
    const std::vector<char> moved = editor.move_together(vertices, targets);
    std::vector<std::uint32_t> again;
    std::vector<Vec3> halves;
    for (std::size_t i = 0; i < vertices.size(); ++i) {
        if (moved[i]) continue;
        const std::uint32_t v = vertices[i];
        const Vec3 half = editor.position(v) + 0.5 * (targets[i] - editor.position(v));
        if (evidence.allows(half, tissues[v])) again.push_back(v), halves.push_back(half);
        else ++report.refused_by_checks;
    }
    const std::vector<char> moved_again = editor.move_together(again, halves);
    const auto made = [](const std::vector<char>& m) {
        return static_cast<std::size_t>(std::count(m.begin(), m.end(), 1));
    };
    report.refused_by_checks += again.size() - made(moved_again);
    report.moves += made(moved) + made(moved_again);
    return made(moved) + made(moved_again);
}

/// Moves each vertex by its `shift` (none where it has none), held to the image and then checked.
std::size_t move_held(ComplexEditor& editor, const detail::VoxelEvidence& evidence,
                      const std::vector<std::vector<Label>>& tissues, const std::vector<std::optional<Vec3>>& shift,
                      SmoothReport& report)
{
    const auto slots = static_cast<std::int64_t>(editor.vertex_slots());
    std::vector<std::optional<Vec3>> target(editor.vertex_slots());
    std::vector<char> refused(editor.vertex_slots(), 0);
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < slots; ++i) {
        const auto v = static_cast<std::uint32_t>(i);
        if (!shift[v]) continue;
        target[v] = allowed_target(editor.position(v), *shift[v], evidence, tissues[v]);
        refused[v] = target[v] ? 0 : 1;
    }
    report.refused_by_image += static_cast<std::size_t>(std::count(refused.begin(), refused.end(), 1));
    std::vector<std::uint32_t> vertices;
    std::vector<Vec3> targets;
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v)
        if (target[v]) vertices.push_back(v), targets.push_back(*target[v]);
    return move_checked(editor, evidence, tissues, vertices, targets, report);
}

/// Puts back to `before` the moved vertices of every triangle (of `round`, and then of the stars of the
/// vertices put back, which may break in turn) that the move from `before` to `now` makes degenerate, gives
/// an angle below the limit (and below its old one) or tilts beyond the limit: the rules of a single triangle
/// (ComplexEditor's judge), cheap enough for every pair of a run. Returns the vertices put back.
std::vector<std::uint32_t> put_back_misshapen(const ComplexEditor& editor, const std::vector<Vec3>& before,
                                              std::vector<Vec3>& now, std::vector<std::uint32_t> round)
{
    const detail::AngleLimit min_angle(editor.limits().min_angle_deg), max_tilt(editor.limits().max_normal_change_deg);
    const auto breaks = [&](std::uint32_t t) {
        const Triangle& tri = editor.triangle(t);
        const detail::TriangleCorners was{before[tri[0]], before[tri[1]], before[tri[2]]};
        const detail::TriangleCorners is{now[tri[0]], now[tri[1]], now[tri[2]]};
        return !(was == is) && detail::single_triangle_rule(is, was, min_angle, max_tilt) != detail::TriangleRule::none;
    };
    std::vector<std::uint32_t> back;
    std::vector<char> broken, listed(editor.triangle_slots(), 0);
    while (!round.empty()) {
        broken.assign(round.size(), 0);
        const auto count = static_cast<std::int64_t>(round.size());
#pragma omp parallel for schedule(dynamic, 16384) if (count > 16384)
        for (std::int64_t i = 0; i < count; ++i)
            broken[static_cast<std::size_t>(i)] = breaks(round[static_cast<std::size_t>(i)]) ? 1 : 0;
        std::vector<std::uint32_t> next;
        for (std::size_t i = 0; i < round.size(); ++i) {
            if (!broken[i]) continue;
            for (const std::uint32_t v : editor.triangle(round[i])) {
                if (now[v] == before[v]) continue;
                now[v] = before[v];
                back.push_back(v);
                for (const std::uint32_t t : editor.star(v))
                    if (!listed[t]) listed[t] = 1, next.push_back(t);
            }
        }
        for (const std::uint32_t t : next) listed[t] = 0;
        round = std::move(next);
    }
    return back;
}

/// Holds one pair's move from `before` to `now` to the rules of a single triangle as move_checked() holds a
/// batch to all rules: the offenders go back, then try half their move, judged against where the others
/// settled. Returns the moves put back even at half.
std::size_t hold_to_shape(const ComplexEditor& editor, const detail::VoxelEvidence& evidence,
                          const std::vector<std::vector<Label>>& tissues, const std::vector<Vec3>& before,
                          std::vector<Vec3>& now)
{
    const std::vector<Vec3> wanted = now;
    std::vector<std::uint32_t> all;
    for (std::uint32_t t = 0; t < editor.triangle_slots(); ++t)
        if (editor.triangle_alive(t)) all.push_back(t);
    const std::vector<std::uint32_t> back = put_back_misshapen(editor, before, now, std::move(all));
    const std::vector<Vec3> settled = now;
    std::vector<std::uint32_t> round;
    std::size_t refused = 0;
    for (const std::uint32_t v : back) {
        const Vec3 half = before[v] + 0.5 * (wanted[v] - before[v]);
        if (!evidence.allows(half, tissues[v])) {
            ++refused;
            continue;
        }
        now[v] = half;
        round.insert(round.end(), editor.star(v).begin(), editor.star(v).end());
    }
    std::sort(round.begin(), round.end());
    round.erase(std::unique(round.begin(), round.end()), round.end());
    return refused + put_back_misshapen(editor, settled, now, std::move(round)).size();
}

/// `count` Taubin pairs run on a copy of the positions, each pair's net move of each vertex held to the image
/// (full, half or none), and only then the net move of the whole run checked against the complex in one
/// batch (the intermediate surfaces are never kept, so they need not be valid). Checking once for many pairs
/// judges every triangle once instead of once per pair.
void step_pairs(ComplexEditor& editor, const Rings& rings, const detail::VoxelEvidence& evidence,
                const std::vector<std::vector<Label>>& tissues, const SmoothOptions& options, std::size_t count,
                SmoothReport& report)
{
    std::vector<Vec3> now = editor.positions();
    const auto slots = static_cast<std::int64_t>(editor.vertex_slots());
    std::vector<char> refused(editor.vertex_slots(), 0);
    for (std::size_t pair = 0; pair < count; ++pair) {
        const std::vector<Vec3> after =
            jacobi_step(editor, rings, jacobi_step(editor, rings, now, options.lambda), options.mu);
        std::vector<Vec3> next = now;
#pragma omp parallel for schedule(dynamic, 4096)
        for (std::int64_t i = 0; i < slots; ++i) {
            const auto v = static_cast<std::size_t>(i);
            const Vec3 s = after[v] - now[v];
            if (dot(s, s) < 1e-20) continue; // flat here (or a corner): nothing to do
            const std::optional<Vec3> target = allowed_target(now[v], s, evidence, tissues[v]);
            if (target) next[v] = *target;
            else refused[v] = 1;
        }
        if (count > 1) report.refused_by_checks += hold_to_shape(editor, evidence, tissues, now, next);
        now = next;
        report.refused_by_image += static_cast<std::size_t>(std::count(refused.begin(), refused.end(), 1));
        std::fill(refused.begin(), refused.end(), 0);
    }
    std::vector<std::uint32_t> vertices;
    std::vector<Vec3> targets;
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        const Vec3 s = now[v] - editor.position(v);
        if (dot(s, s) >= 1e-20) vertices.push_back(v), targets.push_back(now[v]);
    }
    // Each pair tilted each triangle at most by the limit; the run as a whole may turn it further, but not over.
    const detail::EditLimits limits = editor.limits();
    if (count > 1)
        editor.set_limits(
            {.min_angle_deg = limits.min_angle_deg,
             .max_normal_change_deg = std::min(90.0, static_cast<double>(count) * limits.max_normal_change_deg),
             .min_gap_mm = limits.min_gap_mm,
             .min_wedge_deg = limits.min_wedge_deg});
    move_checked(editor, evidence, tissues, vertices, targets, report);
    editor.set_limits(limits);
}

/// One fit pass: every patch vertex (two tissues around it) steps towards the zero level of the two
/// tissues' blurred indicators, at most half a voxel; steps under 1% of a voxel are not taken.
void fit_pass(ComplexEditor& editor, const detail::LabelField& field, const detail::VoxelEvidence& evidence,
              const std::vector<std::vector<Label>>& tissues, double voxel_mm, SmoothReport& report)
{
    const auto slots = static_cast<std::int64_t>(editor.vertex_slots());
    std::vector<std::optional<Vec3>> shift(editor.vertex_slots());
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t i = 0; i < slots; ++i) {
        const auto v = static_cast<std::uint32_t>(i);
        if (!editor.vertex_alive(v) || editor.kind(v) != VertexKind::patch || tissues[v].size() != 2) continue;
        const std::optional<Vec3> step = field.step_to_interface(editor.position(v), tissues[v][0], tissues[v][1], 0.5);
        if (step && norm(*step) > 0.01 * voxel_mm) shift[v] = step;
    }
    report.fit_moves += move_held(editor, evidence, tissues, shift, report);
}

} // namespace

SmoothReport smooth(InterfaceComplex& complex, const LabelImage& image, const SmoothOptions& options,
                    const Progress& progress)
{
    validate(options);
    validate_indices(complex, "smooth input");
    SmoothReport report;
    const Vec3& spacing = image.spacing_mm();
    const double voxel = std::min({spacing[0], spacing[1], spacing[2]});
    const std::vector<Vec3> start = complex.vertices;
    const double cell_mm = 2 * detail::mean_edge_length(complex);
    const Label background = complex.background;
    ComplexEditor editor(std::move(complex),
                         {.min_angle_deg = options.min_angle_deg,
                          .max_normal_change_deg = options.max_normal_change_deg,
                          .min_gap_mm = options.min_gap_voxels * voxel},
                         cell_mm);
    const detail::VoxelEvidence evidence(image, background, options.max_depth_voxels);
    std::vector<std::vector<Label>> tissues(editor.vertex_slots());
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        tissues[v] = tissues_around(editor, v);
        if (editor.vertex_alive(v) && editor.kind(v) == VertexKind::corner) ++report.fixed_vertices;
    }
    const Rings rings(editor);
    const auto steps = static_cast<double>(options.iterations + options.fit_passes);
    const std::size_t per_check = options.pairs_per_check == 0 ? options.iterations : options.pairs_per_check;
    while (report.iterations < options.iterations) {
        const std::size_t count = std::min(per_check, options.iterations - report.iterations);
        step_pairs(editor, rings, evidence, tissues, options, count, report);
        report.iterations += count;
        progress.update("smooth", static_cast<double>(report.iterations) / steps);
    }
    const detail::LabelField field(image, background, options.fit_sigma_voxels);
    for (std::size_t i = 0; i < options.fit_passes; ++i) {
        fit_pass(editor, field, evidence, tissues, voxel, report);
        progress.update("smooth", static_cast<double>(options.iterations + i + 1) / steps);
    }
    complex = editor.result();
    std::size_t counted = 0;
    for (std::uint32_t v = 0; v < start.size(); ++v) {
        if (!editor.vertex_alive(v)) continue;
        const double d = distance(start[v], editor.position(v));
        report.mean_displacement_mm += d;
        report.max_displacement_mm = std::max(report.max_displacement_mm, d);
        ++counted;
    }
    if (counted > 0) report.mean_displacement_mm /= static_cast<double>(counted);
    progress.info("smooth",
                  concat(report.moves, " moves in ", report.iterations, " iterations; ", report.refused_by_image,
                         " refused by the image, ", report.refused_by_checks, " by the validity checks"));
    return report;
}

} // namespace tissuemesh::surface
