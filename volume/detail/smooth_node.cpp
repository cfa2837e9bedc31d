#include "volume/detail/smooth_node.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surface/detail/triangle_distance.h"

namespace tissuemesh::volume::detail {
namespace {

constexpr double active_band = 1e-4; ///< sines this close to the minimum count as active
constexpr std::size_t max_active = 6;
constexpr double model_band = 0.25; ///< sines this close to the minimum enter the step's linear model
constexpr int max_halvings = 10;
constexpr double max_step_fraction = 0.4; ///< of the shortest edge at the node, per step
constexpr double min_gain = 1e-2;         ///< a move is kept when it raises the smallest sine by this much
constexpr std::uint32_t no_hint = ~0u;

/// The six sines of each of v's tets with v at some point (6 per tet, in tet order), and their minimum.
struct Evaluation {
    double minimum = std::numeric_limits<double>::infinity();
    std::vector<double> values;
};

/// The directions v may move in: all of space, a plane (normal), or a line (tangent).
struct Freedom {
    NodeKind kind = NodeKind::interior;
    Vec3 axis{0, 0, 0};
    Vec3 restrict(const Vec3& g) const
    {
        if (kind == NodeKind::surface) return g - dot(g, axis) * axis;
        if (kind == NodeKind::curve) return dot(g, axis) * axis;
        return g;
    }
};

class NodeSmoother {
public:
    NodeSmoother(WorkMesh& mesh, std::uint32_t v, const SurfaceReference& reference, double face_tolerance_mm)
        : mesh_(mesh), v_(v), reference_(reference), face_tolerance_mm_(face_tolerance_mm)
    {
        for (const std::uint32_t t : mesh.tets_of(v)) {
            const Tet& tet = mesh.tet(t);
            tets_.push_back(tet);
            corners_.push_back(mesh.corners(tet));
            corner_.push_back(static_cast<int>(std::find(tet.begin(), tet.end(), v) - tet.begin()));
        }
        shortest_edge_ = std::numeric_limits<double>::infinity();
        for (const Tet& tet : tets_)
            for (const std::uint32_t w : tet)
                if (w != v) shortest_edge_ = std::min(shortest_edge_, distance(mesh.point(w), mesh.point(v)));
        for (const std::uint32_t f : mesh.faces_of(v)) {
            const ConstraintFace& face = mesh.face(f);
            faces_.push_back(face.corners), face_sides_.push_back(face.sides);
            for (const std::uint32_t w : face.corners) {
                if (w == v) continue;
                const auto same = [&](const auto& s) {
                    return s.first == w &&
                           std::minmax(s.second.from, s.second.to) == std::minmax(face.sides.from, face.sides.to);
                };
                if (std::none_of(spokes_.begin(), spokes_.end(), same)) spokes_.push_back({w, face.sides});
            }
        }
        face_hints_.assign(faces_.size(), no_hint), spoke_hints_.assign(spokes_.size(), no_hint);
    }

    bool set_freedom()
    {
        freedom_.kind = mesh_.kind(v_);
        if (freedom_.kind == NodeKind::corner) return false;
        if (freedom_.kind == NodeKind::surface) {
            Vec3 sum{0, 0, 0};
            for (const std::uint32_t f : mesh_.faces_of(v_)) {
                const ConstraintFace& face = mesh_.face(f);
                Vec3 n = face_normal(face.corners, v_, mesh_.point(v_));
                if (face.sides.from > face.sides.to) n = -1.0 * n; // all faces of one pair turned alike
                sum = sum + n;
            }
            if (norm(sum) == 0) return false;
            freedom_.axis = (1.0 / norm(sum)) * sum;
            pair_ = {mesh_.face(mesh_.faces_of(v_).front()).sides.from,
                     mesh_.face(mesh_.faces_of(v_).front()).sides.to};
        } else if (freedom_.kind == NodeKind::curve) {
            const std::vector<std::uint32_t> ends = mesh_.curve_neighbours(v_);
            if (ends.size() != 2) return false;
            const Vec3 along = mesh_.point(ends[1]) - mesh_.point(ends[0]);
            if (norm(along) == 0) return false;
            freedom_.axis = (1.0 / norm(along)) * along;
            tissues_ = mesh_.tissues_at(v_);
        }
        return true;
    }

    bool run(int max_steps)
    {
        Vec3 p = mesh_.point(v_);
        Evaluation now = evaluate(p);
        const double start = now.minimum;
        std::vector<Vec3> gradients(now.values.size());
        std::vector<std::size_t> modelled; // sines in the linear model (their tets' gradients computed)
        std::vector<Vec3> active;
        Evaluation trial;
        for (int step = 0; step < max_steps; ++step) {
            // Gradients only for the tets near the minimum: the others cannot become the minimum within a step
            // the model trusts, and halving catches those that do.
            modelled.clear(), active.clear();
            for (std::size_t i = 0; i < tets_.size(); ++i) {
                const double* six = &now.values[6 * i];
                if (*std::min_element(six, six + 6) > now.minimum + model_band) continue;
                TetCorners c = corners_[i];
                c[static_cast<std::size_t>(corner_[i])] = p;
                const std::array<Vec3, 6> g =
                    dihedral_sine_gradients(c, corner_[i], {six[0], six[1], six[2], six[3], six[4], six[5]});
                for (int e = 0; e < 6; ++e)
                    gradients[6 * i + e] = freedom_.restrict(g[e]), modelled.push_back(6 * i + e);
            }
            for (const std::size_t i : modelled)
                if (now.values[i] <= now.minimum + active_band && active.size() < max_active)
                    active.push_back(gradients[i]);
            const Vec3 d = min_norm_point(active);
            const double rate = dot(d, d);
            if (!(rate * shortest_edge_ * shortest_edge_ > 1e-18)) break;
            // Where the linear model of each other sine meets the rising minimum.
            double alpha = max_step_fraction * shortest_edge_ / std::sqrt(rate);
            for (const std::size_t i : modelled) {
                const double slope = dot(gradients[i], d);
                if (now.values[i] > now.minimum + active_band && slope < rate)
                    alpha = std::min(alpha, (now.values[i] - now.minimum) / (rate - slope));
            }
            bool moved = false;
            for (int h = 0; h < max_halvings && !moved; ++h, alpha *= 0.5) {
                // A move is kept only when it gains min_gain in all. Once even this step's model gain, repeated in
                // every step left, could not bring the move there, smaller steps are not tried: most moves that
                // fail end in a step whose every halving fails, and that step cost 36-54% of the trial points (1 mm
                // usc19-5 head, nodes on patches and on junction curves).
                if (h > 0 && now.minimum - start + alpha * rate * (max_steps - step) < min_gain) break;
                const std::optional<Vec3> q = place(p + alpha * d, alpha * std::sqrt(rate));
                // Cheap tests first: the faces' distance to the reference (of the trial points on the 1 mm
                // usc19-5 head, 39% fail there and 17% on the sines; none on the orientations), then the sines in
                // doubles, then the exact orientations only for a point that gains.
                if (!q || !stays_on_reference(*q) || !rises_above(*q, now.minimum + 1e-12, trial) || !positive_at(*q))
                    continue;
                p = *q, std::swap(now, trial), moved = true;
            }
            if (!moved) break;
        }
        if (!(now.minimum >= start + min_gain)) return false;
        mesh_.move_node(v_, p);
        return true;
    }

private:
    Vec3 face_normal(const Triangle& c, std::uint32_t moved, const Vec3& at) const
    {
        auto point = [&](std::uint32_t w) { return w == moved ? at : mesh_.point(w); };
        return cross(point(c[1]) - point(c[0]), point(c[2]) - point(c[0]));
    }

    /// The point p brought back onto v's patch or curve (within a few step lengths); none when it cannot be.
    std::optional<Vec3> place(const Vec3& p, double step) const
    {
        const double reach = 2 * step + 1e-9 * shortest_edge_;
        if (freedom_.kind == NodeKind::surface)
            return reference_.onto_patch(p, pair_.from, pair_.to, reach, &patch_hint_);
        if (freedom_.kind == NodeKind::curve) return reference_.onto_curve(p, tissues_, reach);
        return p;
    }

    /// Whether every tet of v is positively oriented with v at q (exact predicates).
    bool positive_at(const Vec3& q) const
    {
        for (std::size_t i = 0; i < tets_.size(); ++i) {
            TetCorners c = corners_[i];
            c[static_cast<std::size_t>(corner_[i])] = q;
            if (!positive(c[0], c[1], c[2], c[3])) return false;
        }
        return true;
    }

    bool stays_on_reference(const Vec3& q) const
    {
        // A face at v must not turn over (for faces of the outer boundary the tets alone do not ensure it), and
        // must stay on its patch: as SurfaceReference::holds_triangle, less the midpoint of the edge opposite v,
        // which stays where it was. The centroids first (the farthest from the patch), then the midpoint of each
        // edge at v once for each tissue pair (two faces share it).
        for (std::size_t i = 0; i < faces_.size(); ++i) {
            const Triangle& f = faces_[i];
            if (dot(face_normal(f, v_, q), face_normal(f, v_, mesh_.point(v_))) <= 0) return false;
            const std::uint32_t w1 = f[0] == v_ ? f[1] : f[0], w2 = f[2] == v_ ? f[1] : f[2];
            if (!reference_.within((1.0 / 3) * (q + mesh_.point(w1) + mesh_.point(w2)), face_sides_[i].from,
                                   face_sides_[i].to, face_tolerance_mm_, &face_hints_[i]))
                return false;
        }
        for (std::size_t i = 0; i < spokes_.size(); ++i) {
            const auto& [w, sides] = spokes_[i];
            if (!reference_.within(0.5 * (q + mesh_.point(w)), sides.from, sides.to, face_tolerance_mm_,
                                   &spoke_hints_[i]))
                return false;
        }
        return true;
    }

    /// Whether every sine of v's tets with v at q exceeds `bar` (stops at the first that does not); the sines
    /// and their minimum in `e` when they do.
    bool rises_above(const Vec3& q, double bar, Evaluation& e) const
    {
        e.values.clear();
        e.minimum = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < tets_.size(); ++i) {
            TetCorners c = corners_[i];
            c[static_cast<std::size_t>(corner_[i])] = q;
            const std::array<double, 6> sines = dihedral_sines(c);
            const double least = *std::min_element(sines.begin(), sines.end());
            if (!(least > bar)) return false;
            e.values.insert(e.values.end(), sines.begin(), sines.end());
            e.minimum = std::min(e.minimum, least);
        }
        return true;
    }

    Evaluation evaluate(const Vec3& q) const
    {
        Evaluation e;
        e.values.reserve(6 * tets_.size());
        for (std::size_t i = 0; i < tets_.size(); ++i) {
            TetCorners c = corners_[i];
            c[static_cast<std::size_t>(corner_[i])] = q;
            const std::array<double, 6> sines = dihedral_sines(c);
            e.values.insert(e.values.end(), sines.begin(), sines.end());
            for (const double s : sines) e.minimum = std::min(e.minimum, s);
        }
        return e;
    }

    WorkMesh& mesh_;
    std::uint32_t v_;
    const SurfaceReference& reference_;
    double face_tolerance_mm_;
    std::vector<Tet> tets_;
    std::vector<TetCorners> corners_; ///< per tet of v: its corners' points (v's own replaced at each trial)
    std::vector<int> corner_;
    std::vector<Triangle> faces_;
    std::vector<LabelPair> face_sides_;
    /// The edges at v on its faces: the other end and a tissue pair of a face holding it, once per pair.
    std::vector<std::pair<std::uint32_t, LabelPair>> spokes_;
    /// Per face and spoke: the reference triangle its last check found near (SurfaceReference::within).
    mutable std::vector<std::uint32_t> face_hints_, spoke_hints_;
    mutable std::uint32_t patch_hint_ = no_hint; ///< the reference triangle v was last projected onto
    double shortest_edge_ = 0;
    Freedom freedom_;
    LabelPair pair_;
    std::vector<Label> tissues_;
};

} // namespace

Vec3 min_norm_point(const std::vector<Vec3>& points)
{
    if (points.empty()) return {0, 0, 0};
    Vec3 best = points[0];
    auto consider = [&](const Vec3& q) {
        if (dot(q, q) < dot(best, best)) best = q;
    };
    const Vec3 origin{0, 0, 0};
    const std::size_t n = points.size();
    for (std::size_t i = 0; i < n; ++i) {
        consider(points[i]);
        for (std::size_t j = i + 1; j < n; ++j) {
            consider(surface::detail::closest_point_on_segment(origin, points[i], points[j]));
            for (std::size_t k = j + 1; k < n; ++k)
                consider(surface::detail::closest_point_on_triangle(origin, {points[i], points[j], points[k]}));
        }
    }
    // The nearest point of the hull d satisfies g . d >= d . d for every point g; when the origin lies inside
    // the hull the nearest point of its faces does not.
    const double squared = dot(best, best);
    for (const Vec3& g : points)
        if (dot(g, best) < squared * (1 - 1e-9)) return {0, 0, 0};
    return best;
}

bool smooth_node(WorkMesh& mesh, std::uint32_t v, const SurfaceReference& reference, double face_tolerance_mm,
                 int max_steps)
{
    if (mesh.tets_of(v).empty()) return false;
    NodeSmoother smoother(mesh, v, reference, face_tolerance_mm);
    if (!smoother.set_freedom()) return false;
    return smoother.run(max_steps);
}

} // namespace tissuemesh::volume::detail
