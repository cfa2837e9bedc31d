#include "surface/snake.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.h"
#include "surface/check_complex.h"
#include "surface/detail/complex_editor.h"
#include "surface/detail/mesh_measures.h"
#include "surface/detail/snake_resolution.h"

namespace tissuemesh::surface {
namespace {

using detail::ComplexEditor;

void validate(const SnakeOptions& o, const std::vector<SnakeTarget>& targets)
{
    if (targets.empty()) throw InputError("snake: no target; give at least one tissue or grey level");
    const auto positive = [](double x) { return x > 0 && std::isfinite(x); };
    const auto fraction = [](double x) { return x >= 0 && x <= 1; };
    if (!fraction(o.image_weight) || !fraction(o.tension) || !(o.rigidity >= 0 && o.rigidity <= 0.5))
        throw InputError(concat("snake: weights image ", o.image_weight, ", tension ", o.tension, ", rigidity ",
                                o.rigidity, " must lie in [0, 1] ([0, 0.5] for rigidity); try 0.8, 0.2, 0.05"));
    if (!positive(o.max_step_voxels) || o.max_step_voxels > 2)
        throw InputError(concat("snake: max step ", o.max_step_voxels, " voxels must lie in (0, 2]"));
    if (!std::isfinite(o.balloon_voxels) || std::abs(o.balloon_voxels) > o.max_step_voxels)
        throw InputError(
            concat("snake: balloon ", o.balloon_voxels, " voxels exceeds the max step ", o.max_step_voxels, " voxels"));
    if (!(o.target_edge_mm >= 0) || !(o.max_chord_error_mm >= 0) || !(o.min_separation_voxels >= 0) ||
        !positive(o.tolerance_voxels))
        throw InputError("snake: target edge, chord error and separation must be >= 0, the tolerance > 0");
    if (o.max_iterations == 0) throw InputError("snake: the iteration cap must be at least 1");
    for (std::size_t a = 0; a < targets.size(); ++a)
        for (std::size_t b = a + 1; b < targets.size(); ++b) {
            const LabelPair p = targets[a].pair, q = targets[b].pair;
            if ((p.from == q.from && p.to == q.to) || (p.from == q.to && p.to == q.from))
                throw InputError(concat("snake: two snakes share the tissue pair ", p.from, "|", p.to,
                                        "; give each snake its own pair of tissues"));
        }
}

/// Index of the target whose pair is `side` in either orientation, and whether it is reversed.
struct TargetOf {
    std::size_t index = 0;
    bool reversed = false;
};

std::vector<TargetOf> classify_triangles(const InterfaceComplex& complex, const std::vector<SnakeTarget>& targets)
{
    std::vector<TargetOf> out(complex.triangle_count());
    for (std::size_t t = 0; t < complex.triangle_count(); ++t) {
        const LabelPair s = complex.sides[t];
        bool found = false;
        for (std::size_t k = 0; k < targets.size() && !found; ++k) {
            const LabelPair p = targets[k].pair;
            if (s == p || (s.from == p.to && s.to == p.from)) {
                out[t] = {k, !(s == p)};
                found = true;
            }
        }
        if (!found)
            throw InputError(concat("snake: triangle ", t, " separates tissues ", s.from, "|", s.to,
                                    ", which no snake stands for; relabel the initial surface"));
    }
    return out;
}

/// The state of one iteration: per vertex its snake, outward normal and umbrella vector.
class SnakeStepper {
public:
    SnakeStepper(ComplexEditor& editor, const std::vector<SnakeTarget>& targets, const SnakeOptions& options,
                 double voxel_mm)
        : editor_(editor), targets_(targets), options_(options), voxel_mm_(voxel_mm)
    {
    }

    /// Moves every vertex once; returns the largest motion made across the surface (along the vertex
    /// normal, mm): tangential motion only redistributes vertices over the same surface.
    double iterate(SnakeReport& report)
    {
        refresh();
        const std::size_t n = editor_.vertex_slots();
        const double max_step = options_.max_step_voxels * voxel_mm_;
        last_shift_.resize(n, Vec3{0, 0, 0});
        damping_.resize(n, 1.0);
        std::vector<Vec3> shift(n, Vec3{0, 0, 0});
        for (std::uint32_t v = 0; v < n; ++v) {
            if (!editor_.vertex_alive(v)) continue;
            Vec3 ring_l2{0, 0, 0};
            const std::vector<std::uint32_t> ring = editor_.neighbours(v);
            for (const std::uint32_t u : ring) ring_l2 = ring_l2 + laplacian_[u];
            ring_l2 = (1.0 / static_cast<double>(ring.size())) * ring_l2 - laplacian_[v];
            const double d = std::clamp(field_distance(v), -max_step, max_step);
            Vec3 s = (options_.image_weight * d + options_.balloon_voxels * voxel_mm_) * normal_[v] +
                     options_.tension * laplacian_[v] - options_.rigidity * ring_l2;
            const double length = norm(s);
            if (length > max_step) s = (max_step / length) * s;
            // A vertex that reverses its motion is overshooting (across a thin ridge of the field, or where
            // explicit steps of the internal forces are too long): its own step is halved, and grows back while
            // it keeps its direction.
            if (dot(s, last_shift_[v]) < 0) damping_[v] *= 0.5;
            else damping_[v] = std::min(1.0, 1.25 * damping_[v]);
            shift[v] = damping_[v] * s;
        }
        last_shift_ = shift;
        double largest = 0;
        const double negligible = 0.1 * options_.tolerance_voxels * voxel_mm_;
        for (std::uint32_t v = 0; v < n; ++v) {
            if (!editor_.vertex_alive(v) || norm(shift[v]) < negligible) continue;
            const Vec3 start = editor_.position(v);
            bool moved = false;
            for (int attempt = 0; attempt < 3 && !moved; ++attempt) {
                moved = editor_.try_move(v, start + (1.0 / static_cast<double>(1 << attempt)) * shift[v]);
                if (moved && attempt > 0) ++report.shortened_moves;
            }
            if (!moved) {
                ++report.refused_moves;
                continue;
            }
            ++report.moves;
            const double across = std::abs(dot(editor_.position(v) - start, normal_[v]));
            if (across > largest) {
                largest = across;
                largest_at_ = start;
            }
        }
        return largest;
    }

    /// Edge length sought at v (mm): the target, shortened where the surface is curved.
    double target_edge(std::uint32_t v) const
    {
        const double target = options_.target_edge_mm > 0 ? options_.target_edge_mm : 2 * voxel_mm_;
        if (options_.max_chord_error_mm <= 0 || v >= curvature_.size()) return target;
        // A chord of length e on a circle of curvature k leaves it by about k e^2 / 8.
        const double k = curvature_[v];
        if (k <= 0) return target;
        return std::clamp(std::sqrt(8 * options_.max_chord_error_mm / k), 0.25 * target, target);
    }

    /// Recomputes normals, Laplacians and curvatures from the current positions.
    void refresh()
    {
        const std::size_t n = editor_.vertex_slots();
        normal_.assign(n, Vec3{0, 0, 0});
        laplacian_.assign(n, Vec3{0, 0, 0});
        curvature_.assign(n, 0);
        snake_.assign(n, 0);
        for (std::uint32_t v = 0; v < n; ++v) {
            if (!editor_.vertex_alive(v)) continue;
            for (const std::uint32_t t : editor_.star(v)) {
                const detail::TriangleCorners c = editor_.corners(t);
                const TargetOf of = target_of(editor_.side(t));
                snake_[v] = of.index;
                const Vec3 area_normal = cross(c[1] - c[0], c[2] - c[0]);
                normal_[v] = normal_[v] + (of.reversed ? -1.0 : 1.0) * area_normal;
            }
            const double length = norm(normal_[v]);
            if (length > 0) normal_[v] = (1.0 / length) * normal_[v];
            const std::vector<std::uint32_t> ring = editor_.neighbours(v);
            Vec3 mean{0, 0, 0};
            double ring_length = 0;
            for (const std::uint32_t u : ring) {
                mean = mean + editor_.position(u);
                ring_length += distance(editor_.position(u), editor_.position(v));
            }
            const double count = static_cast<double>(ring.size());
            laplacian_[v] = (1.0 / count) * mean - editor_.position(v);
            ring_length /= count;
            // The umbrella vector's normal part is about k * e^2 / 2 on a surface of curvature k.
            curvature_[v] = 2 * std::abs(dot(laplacian_[v], normal_[v])) / (ring_length * ring_length);
        }
    }

    /// First-order signed distance of v to its field's zero level, mm (positive: inside, move outwards).
    double field_distance(std::uint32_t v) const
    {
        const PotentialField& field = targets_[snake_[v]].field;
        const Vec3& p = editor_.position(v);
        const double phi = field.value(p);
        const double g = norm(field.gradient(p));
        if (g > 1e-12) return phi / g;
        return phi > 0 ? 1e300 : phi < 0 ? -1e300 : 0;
    }

    /// Where the largest motion of the last iteration started (mm), for the log.
    const Vec3& largest_at() const { return largest_at_; }

    TargetOf target_of(const LabelPair& side) const
    {
        for (std::size_t k = 0; k < targets_.size(); ++k) {
            const LabelPair p = targets_[k].pair;
            if (side == p) return {k, false};
            if (side.from == p.to && side.to == p.from) return {k, true};
        }
        return {};
    }

private:
    ComplexEditor& editor_;
    const std::vector<SnakeTarget>& targets_;
    const SnakeOptions& options_;
    double voxel_mm_;
    std::vector<Vec3> normal_, laplacian_;
    Vec3 largest_at_{0, 0, 0};     ///< where the largest motion of the last iteration started
    std::vector<Vec3> last_shift_; ///< per vertex slot: its shift of the previous iteration
    std::vector<double> damping_;  ///< per vertex slot: factor of its step, halved on each reversal
    std::vector<double> curvature_;
    std::vector<std::size_t> snake_;
};

/// Mean |phi / |grad phi|| over the alive vertices (mm).
double mean_field_distance(const ComplexEditor& editor, const SnakeStepper& stepper)
{
    double sum = 0;
    std::size_t count = 0;
    for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v) {
        if (!editor.vertex_alive(v)) continue;
        sum += std::min(std::abs(stepper.field_distance(v)), 1e6);
        ++count;
    }
    return count > 0 ? sum / static_cast<double>(count) : 0;
}

} // namespace

SnakeReport evolve_snakes(InterfaceComplex& complex, const std::vector<SnakeTarget>& targets,
                          const SnakeOptions& options, const Progress& progress)
{
    validate(options, targets);
    validate_indices(complex, "snake start");
    classify_triangles(complex, targets);
    require_fit_for_tetrahedralization(complex, "snake start surface");
    const double voxel_mm = targets.front().field.smallest_spacing_mm();
    SnakeReport report;
    ComplexEditor editor(std::move(complex),
                         {.min_angle_deg = options.min_angle_deg,
                          .max_normal_change_deg = options.max_normal_change_deg,
                          .min_gap_mm = options.min_separation_voxels * voxel_mm},
                         2 * voxel_mm);
    editor.rebuild_grid(2 * std::max(editor.mean_edge_length(), voxel_mm));
    SnakeStepper stepper(editor, targets, options, voxel_mm);
    const double tolerance_mm = options.tolerance_voxels * voxel_mm;
    bool edited = true; // resolution edits since the last converged check
    for (std::size_t i = 0; i < options.max_iterations; ++i) {
        report.last_max_motion_mm = stepper.iterate(report);
        ++report.iterations;
        const Vec3& at = stepper.largest_at();
        progress.debug("snake", concat("iteration ", i + 1, ": largest motion ",
                                       format_mm(report.last_max_motion_mm, 4), " mm near (", format_mm(at[0], 1), ", ",
                                       format_mm(at[1], 1), ", ", format_mm(at[2], 1), ") mm"));
        progress.update("snake", static_cast<double>(i + 1) / static_cast<double>(options.max_iterations));
        if (report.last_max_motion_mm < tolerance_mm && !edited) {
            report.converged = true;
            break;
        }
        edited = false;
        if (options.resolution_every > 0 && (i + 1) % options.resolution_every == 0) {
            stepper.refresh();
            const detail::ResolutionCounts counts =
                detail::adapt_resolution(editor, [&](std::uint32_t v) { return stepper.target_edge(v); });
            report.splits += counts.splits;
            report.collapses += counts.collapses;
            report.flips += counts.flips;
            edited = counts.total() > 0;
            if (edited) editor.rebuild_grid(2 * std::max(editor.mean_edge_length(), voxel_mm));
        }
    }
    stepper.refresh();
    report.mean_abs_field_distance_mm = mean_field_distance(editor, stepper);
    complex = editor.result();
    // The editor orients patches canonically; give every snake its own orientation back.
    const std::vector<TargetOf> of = classify_triangles(complex, targets);
    for (std::size_t t = 0; t < complex.triangle_count(); ++t)
        if (of[t].reversed) {
            std::swap(complex.triangles[t][1], complex.triangles[t][2]);
            complex.sides[t] = targets[of[t].index].pair;
        }
    report.triangles = complex.triangle_count();
    progress.info("snake", concat(report.iterations, " iterations, ", report.converged ? "converged" : "not converged",
                                  " (last largest motion ", format_mm(report.last_max_motion_mm, 4), " mm); ",
                                  report.splits, " splits, ", report.collapses, " collapses, ", report.flips,
                                  " flips; ", report.refused_moves, " moves refused"));
    return report;
}

} // namespace tissuemesh::surface
