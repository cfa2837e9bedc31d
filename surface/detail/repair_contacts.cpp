#include "surface/detail/repair_contacts.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>
#include <set>

#include "core/error.h"
#include "surface/detail/cgal_intersections.h"
#include "surface/detail/surface_contacts.h"
#include "surface/detail/triangle_grid.h"
#include "surface/detail/voxel_evidence.h"

namespace tissuemesh::surface::detail {
namespace {

/// How far a vertex should go and where: the sum of the unit directions asked for, and the largest distance.
struct Push {
    Vec3 direction{0, 0, 0};
    double distance_mm = 0;
};

class Separator {
public:
    Separator(ComplexEditor& editor, const SeparateOptions& options, RepairLog& log)
        : editor_(editor), options_(options), log_(log), edge_mm_(editor.mean_edge_length())
    {
        if (options.image) evidence_.emplace(*options.image, Label{0}, options.max_depth_voxels);
    }

    /// Rounds of moves until no contact of the phase's kind is left; returns those left.
    std::vector<Contact> run(bool crossings, const Progress& progress)
    {
        std::vector<Contact> contacts = of_kind(find_contacts(editor_, crossings ? 0 : options_.gap_mm), crossings);
        const std::vector<Contact> first = contacts;
        std::size_t ring = 0, best = contacts.size(), stalled = 0;
        for (std::size_t round = 0; round < options_.max_rounds && !contacts.empty(); ++round) {
            ++log_.report().rounds;
            // Against terraced (voxel) surfaces a point just past the other side is not enough: the margin
            // doubles each round, up to an edge length.
            margin_mm_ =
                std::min(0.55 * options_.gap_mm +
                             0.02 * edge_mm_ * std::pow(2.0, static_cast<double>(std::min<std::size_t>(round, 6))),
                         std::max(edge_mm_, 0.55 * options_.gap_mm));
            move_apart(contacts, crossings, ring);
            contacts = of_kind(find_contacts(editor_, crossings ? 0 : options_.gap_mm), crossings);
            if (contacts.size() < best) best = contacts.size(), stalled = 0;
            else if (++stalled >= 2) ring = std::min<std::size_t>(ring + 1, 4), stalled = 0;
            const EditCounters& n = editor_.counters();
            progress.debug("repair",
                           concat(crossings ? "intersections" : "near-contacts", " left after round ", round + 1, ": ",
                                  contacts.size(), " (edits made ", n.accepted, ", refused: shape ", n.shape, ", tilt ",
                                  n.normal, ", intersection ", n.intersection, ", gap ", n.gap, ")"));
        }
        log_resolved(first, contacts, crossings);
        return contacts;
    }

private:
    static std::vector<Contact> of_kind(std::vector<Contact> contacts, bool crossings)
    {
        std::erase_if(contacts, [&](const Contact& c) { return c.crossing != crossings; });
        return contacts;
    }

    /// Pushes for the vertices of t1 away from t2, or marks them for smoothing (a patch through itself).
    void ask(std::uint32_t t1, std::uint32_t t2, bool crossing, std::map<std::uint32_t, Push>& pushes,
             std::set<std::uint32_t>& smooth) const
    {
        const LabelPair s1 = editor_.side(t1), s2 = editor_.side(t2);
        std::vector<Label> shared;
        for (const Label x : {s1.from, s1.to})
            if (x == s2.from || x == s2.to) shared.push_back(x);
        const Vec3 n = unit_normal(editor_.corners(t1));
        const TriangleCorners other = editor_.corners(t2);
        const double margin = crossing ? margin_mm_ : 0.55 * options_.gap_mm;
        for (const std::uint32_t v : editor_.triangle(t1)) {
            if (editor_.kind(v) == VertexKind::corner) continue;
            if (crossing && shared.size() == 2) {
                smooth.insert(v);
                continue;
            }
            const Vec3& p = editor_.position(v);
            const Vec3 q = closest_point_on_triangle(p, other);
            // Grow the tissue both patches bound (the layer between them); otherwise leave the other side.
            const Vec3 away =
                shared.size() == 1 ? (s1.from == shared[0] ? n : -1.0 * n) : (dot(p - q, n) >= 0 ? n : -1.0 * n);
            Push& push = pushes[v];
            push.direction = push.direction + away;
            push.distance_mm = std::max(push.distance_mm, std::max(margin - dot(p - q, away), 0.25 * margin));
        }
    }

    /// With the image: for a vertex where the image allows no such interface, the first place along `away`
    /// (up to three voxels) where it does; the image says where the surface belongs.
    std::optional<Vec3> where_image_allows(std::uint32_t v, const Vec3& away) const
    {
        if (!evidence_) return std::nullopt;
        const std::vector<Label> tissues = tissues_around(editor_, v);
        const Vec3& p = editor_.position(v);
        if (evidence_->allows(p, tissues)) return std::nullopt;
        const Vec3& spacing = options_.image->spacing_mm();
        const double voxel = std::min({spacing[0], spacing[1], spacing[2]});
        for (double t = 0.1; t <= 3.0; t += 0.1)
            if (const Vec3 q = p + t * voxel * away; evidence_->allows(q, tissues)) return q + 0.1 * voxel * away;
        return std::nullopt;
    }

    bool allowed(std::uint32_t v, const Vec3& target) const
    {
        if (!evidence_) return true;
        const std::vector<Label> tissues = tissues_around(editor_, v);
        return evidence_->allows(target, tissues) || !evidence_->allows(editor_.position(v), tissues);
    }

    /// Moves v towards target, halving the step up to three times when the image or the editor refuses.
    bool move_towards(std::uint32_t v, const Vec3& target)
    {
        const Vec3 start = editor_.position(v);
        for (double f = 1.0; f > 0.1; f *= 0.5) {
            const Vec3 p = start + f * (target - start);
            if (allowed(v, p) && editor_.try_move(v, p)) return true;
        }
        return false;
    }

    bool smooth_vertex(std::uint32_t v)
    {
        const bool curve = editor_.kind(v) == VertexKind::curve;
        const std::vector<std::uint32_t> ring = curve ? editor_.curve_neighbours(v) : editor_.neighbours(v);
        if (ring.empty() || editor_.kind(v) == VertexKind::corner) return false;
        Vec3 mean{0, 0, 0};
        for (const std::uint32_t u : ring) mean = mean + editor_.position(u);
        mean = (1.0 / static_cast<double>(ring.size())) * mean;
        return move_towards(v, editor_.position(v) + 0.5 * (mean - editor_.position(v)));
    }

    /// Unit normal at v over its triangles of `patch` (the editor's orientation of that patch).
    Vec3 patch_normal(std::uint32_t v, const LabelPair& patch) const
    {
        Vec3 n{0, 0, 0};
        for (const std::uint32_t t : editor_.star(v))
            if (editor_.side(t) == patch) {
                const TriangleCorners c = editor_.corners(t);
                n = n + cross(c[1] - c[0], c[2] - c[0]);
            }
        const double length = norm(n);
        return length > 0 ? (1.0 / length) * n : n;
    }

    /// The nearest point to p on a triangle of `patch` within `reach` of p, if any.
    /// Also gives that triangle's unit normal.
    std::optional<std::pair<Vec3, Vec3>> nearest_on(const Vec3& p, const LabelPair& patch, double reach)
    {
        grid_.query(Box3{p - Vec3{reach, reach, reach}, p + Vec3{reach, reach, reach}}, nearby_);
        std::optional<std::pair<Vec3, Vec3>> best;
        double nearest = reach;
        for (const std::uint32_t t : nearby_) {
            if (!editor_.triangle_alive(t) || !(editor_.side(t) == patch)) continue;
            const TriangleCorners c = editor_.corners(t);
            const Vec3 q = closest_point_on_triangle(p, c);
            if (const double d = distance(p, q); d < nearest) nearest = d, best = {q, unit_normal(c)};
        }
        return best;
    }

    void rebuild_grid()
    {
        Box3 bounds{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
        for (std::uint32_t t = 0; t < editor_.triangle_slots(); ++t) {
            if (!editor_.triangle_alive(t)) continue;
            const Box3 box = bounding_box(editor_.corners(t));
            for (int i = 0; i < 3; ++i)
                bounds.low[i] = std::min(bounds.low[i], box.low[i]),
                bounds.high[i] = std::max(bounds.high[i], box.high[i]);
        }
        grid_ = TriangleGrid(bounds, 2 * edge_mm_, editor_.triangle_slots());
        for (std::uint32_t t = 0; t < editor_.triangle_slots(); ++t)
            if (editor_.triangle_alive(t)) grid_.insert(t, bounding_box(editor_.corners(t)));
    }

    /// Where a patch has gone through another (a bulge through a layer), the vertices on the wrong side are
    /// many, and most belong to no crossing triangle: from the crossing triangles' vertices, the region of
    /// the patch on the wrong side of the other patch (towards the tissue they share) is flooded and moved
    /// back past it in one edit. Returns whether any region moved.
    bool move_regions(const std::vector<Contact>& contacts)
    {
        rebuild_grid();
        std::map<std::tuple<Label, Label, Label, Label, Label>, std::set<std::uint32_t>> seeds;
        for (const Contact& c : contacts)
            for (const auto& [t1, t2] : {std::pair{c.a, c.b}, std::pair{c.b, c.a}}) {
                const LabelPair s1 = editor_.side(t1), s2 = editor_.side(t2);
                std::vector<Label> shared;
                for (const Label x : {s1.from, s1.to})
                    if (x == s2.from || x == s2.to) shared.push_back(x);
                if (shared.size() != 1) continue;
                for (const std::uint32_t v : editor_.triangle(t1))
                    if (editor_.kind(v) != VertexKind::corner)
                        seeds[{s1.from, s1.to, s2.from, s2.to, shared[0]}].insert(v);
            }
        const double margin = margin_mm_, reach = 4 * edge_mm_;
        bool moved = false;
        for (const auto& [key, start] : seeds) {
            const auto [from, to, other_from, other_to, shared] = key;
            const LabelPair mine{from, to}, other{other_from, other_to};
            std::vector<std::uint32_t> queue(start.begin(), start.end()), group;
            std::set<std::uint32_t> seen(start.begin(), start.end());
            std::vector<Vec3> targets;
            for (std::size_t i = 0; i < queue.size() && group.size() < 5000; ++i) {
                const std::uint32_t u = queue[i];
                const Vec3& p = editor_.position(u);
                const Vec3 away = (from == shared ? 1.0 : -1.0) * patch_normal(u, mine);
                // Beyond the other patch: behind its nearest triangle, not beside it (where patches meet).
                const auto q = nearest_on(p, other, reach);
                const double d = q ? dot(p - q->first, away) : margin;
                const bool beyond = q && d < 0 && std::abs(dot(p - q->first, q->second)) > 0.5 * distance(p, q->first);
                const std::optional<Vec3> by_image = where_image_allows(u, away);
                if (!beyond && !by_image && !start.contains(u)) continue; // on the right side: the region ends here
                const Vec3 target = by_image ? *by_image : p + std::max(margin - d, 0.25 * margin) * away;
                if (!allowed(u, target)) continue;
                group.push_back(u);
                targets.push_back(target);
                for (const std::uint32_t w : editor_.neighbours(u))
                    if (editor_.kind(w) != VertexKind::corner && seen.insert(w).second) queue.push_back(w);
            }
            if (!group.empty() && editor_.try_move_group(group, targets)) moved = true;
        }
        return moved;
    }

    void move_apart(const std::vector<Contact>& contacts, bool crossings, std::size_t ring)
    {
        if (crossings && move_regions(contacts)) return;
        std::map<std::uint32_t, Push> pushes;
        std::set<std::uint32_t> smooth;
        for (const Contact& c : contacts) {
            ask(c.a, c.b, c.crossing, pushes, smooth);
            ask(c.b, c.a, c.crossing, pushes, smooth);
        }
        for (const auto& [v, push] : pushes) {
            const double length = norm(push.direction);
            const double step = std::min(push.distance_mm, 0.5 * edge_mm_);
            if (length == 0 || !move_towards(v, editor_.position(v) + (step / length) * push.direction))
                smooth.insert(v);
        }
        // A region that resists grows by rings of neighbours, smoothed so that the pushed vertices can follow.
        std::set<std::uint32_t> region = smooth;
        for (const auto& [v, push] : pushes) region.insert(v);
        for (std::size_t r = 0; r < ring; ++r) {
            std::set<std::uint32_t> grown = region;
            for (const std::uint32_t v : region)
                for (const std::uint32_t u : editor_.neighbours(v)) grown.insert(u);
            region = std::move(grown);
        }
        for (const std::uint32_t v : region)
            if (smooth.contains(v) || !pushes.contains(v)) smooth_vertex(v);
    }

    void log_resolved(const std::vector<Contact>& first, const std::vector<Contact>& left, bool crossings)
    {
        std::vector<Vec3> logged;
        for (const Contact& c : first) {
            if (std::binary_search(left.begin(), left.end(), c)) continue;
            const TriangleCorners a = editor_.corners(c.a), b = editor_.corners(c.b);
            const Vec3 where = 0.5 * ((1.0 / 3.0) * (a[0] + a[1] + a[2]) + (1.0 / 3.0) * (b[0] + b[1] + b[2]));
            // One action per place: pairs within two edge lengths of a logged one are the same region.
            if (std::any_of(logged.begin(), logged.end(),
                            [&](const Vec3& p) { return distance(p, where) < 2 * edge_mm_; }))
                continue;
            logged.push_back(where);
            const LabelPair sa = editor_.side(c.a), sb = editor_.side(c.b);
            log_.add(crossings ? RepairKind::intersection : RepairKind::near_contact, where,
                     {sa.from, sa.to, sb.from, sb.to},
                     concat(crossings ? "moved apart crossing " : "moved apart touching ", log_.patch(sa), " and ",
                            log_.patch(sb), " triangles"));
        }
    }

    ComplexEditor& editor_;
    const SeparateOptions& options_;
    RepairLog& log_;
    double edge_mm_;
    double margin_mm_ = 0; ///< how far past the other patch a crossing vertex goes, this round
    std::optional<VoxelEvidence> evidence_;
    TriangleGrid grid_;                 ///< all triangles, rebuilt each round of region moves
    std::vector<std::uint32_t> nearby_; ///< scratch for grid queries
};

} // namespace

void collapse_degenerate_triangles(ComplexEditor& editor, RepairLog& log)
{
    for (std::uint32_t t = 0; t < editor.triangle_slots(); ++t) {
        if (!editor.triangle_alive(t) || !degenerate(editor, t)) continue;
        const Triangle tri = editor.triangle(t);
        const TriangleCorners c = editor.corners(t);
        const LabelPair side = editor.side(t);
        // The vertex opposite the longest edge lies on it: collapsing it into an end changes no shape. Then
        // the other collapses, shortest edge first (a needle of two nearly coincident vertices).
        int middle = 0;
        for (int k = 1; k < 3; ++k)
            if (distance(c[(k + 1) % 3], c[(k + 2) % 3]) > distance(c[(middle + 1) % 3], c[(middle + 2) % 3]))
                middle = k;
        std::vector<std::tuple<bool, double, std::pair<std::uint32_t, std::uint32_t>>> edges;
        for (int k = 0; k < 3; ++k) {
            const double length = distance(c[k], c[(k + 1) % 3]);
            edges.emplace_back(k != middle, length, std::pair{tri[k], tri[(k + 1) % 3]});
            edges.emplace_back((k + 1) % 3 != middle, length, std::pair{tri[(k + 1) % 3], tri[k]});
        }
        std::sort(edges.begin(), edges.end());
        for (const auto& [other, length, edge] : edges) {
            if (!editor.try_collapse(edge.first, edge.second)) continue;
            ++log.report().collapsed_degenerate;
            log.add(RepairKind::collapsed_degenerate, (1.0 / 3.0) * (c[0] + c[1] + c[2]), {side.from, side.to},
                    concat("collapsed zero-area ", log.patch(side), " triangle (vertex ", edge.first, " into ",
                           edge.second, ")"));
            break;
        }
    }
}

void separate_surfaces(ComplexEditor& editor, const SeparateOptions& options, RepairLog& log, const Progress& progress)
{
    const std::vector<Vec3> start = editor.positions();
    Separator separator(editor, options, log);
    RepairReport& report = log.report();
    std::vector<Contact> all = find_contacts(editor, options.gap_mm);
    for (const Contact& c : all) {
        if (!c.crossing) ++report.near_contacts_before;
        else if (same_patch(editor.side(c.a), editor.side(c.b))) ++report.self_intersections_before;
        else ++report.patch_intersections_before;
    }
    const std::vector<Contact> crossing = separator.run(true, progress);
    if (!crossing.empty()) {
        const TriangleCorners a = editor.corners(crossing.front().a), b = editor.corners(crossing.front().b);
        throw AlgorithmError(concat(
            "repair: ", crossing.size(), " intersecting triangle pair", crossing.size() == 1 ? "" : "s",
            " remain after ", options.max_rounds, " rounds of local moves, first between ",
            log.patch(editor.side(crossing.front().a)), " and ", log.patch(editor.side(crossing.front().b)), " near ",
            concat('(', format_mm(intersection_point(a, b)[0]), ", ", format_mm(intersection_point(a, b)[1]), ", ",
                   format_mm(intersection_point(a, b)[2]), ") mm"),
            "; the surfaces cross over more than local moves can undo: re-extract the "
            "interfaces from the label image with tm-extract"));
    }
    if (options.gap_mm > 0) {
        EditLimits limits = editor.limits();
        limits.min_gap_mm = options.gap_mm;
        editor.set_limits(limits);
        report.near_contacts_after = separator.run(false, progress).size();
    }
    for (std::uint32_t v = 0; v < start.size(); ++v) {
        if (!editor.vertex_alive(v)) continue;
        const double moved = distance(start[v], editor.position(v));
        if (moved == 0) continue;
        ++report.moved_vertices;
        report.max_move_mm = std::max(report.max_move_mm, moved);
    }
}

} // namespace tissuemesh::surface::detail
