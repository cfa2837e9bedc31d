// "boxes": a cube (1) holding two boxes (2 and 3) that share part of a face: sharp edges, corners, and
// a junction where the shared face meets the cube's tissue.
#include <algorithm>
#include <cmath>
#include <map>

#include "image/detail/geometry_primitives.h"
#include "image/detail/phantom_model.h"

namespace tissuemesh::image::detail {
namespace {

struct Box {
    Vec3 lo, hi;
    bool contains(const Vec3& p) const
    {
        for (int a = 0; a < 3; ++a)
            if (p[a] < lo[a] || p[a] > hi[a]) return false;
        return true;
    }
    double volume() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

/// Box b (3) touches box a (2) with its -x face on a's +x face; b's face lies strictly inside a's.
class Boxes final : public PhantomModel {
public:
    Boxes(Box cube, Box a, Box b) : cube_(cube), a_(a), b_(b)
    {
        const AxisRect a_face = box_faces(a.lo, a.hi)[1]; // +x face of a
        const AxisRect b_face = box_faces(b.lo, b.hi)[0]; // -x face of b
        shared_ = {0,
                   a.hi[0],
                   {std::max(a_face.lo[0], b_face.lo[0]), std::max(a_face.lo[1], b_face.lo[1])},
                   {std::min(a_face.hi[0], b_face.hi[0]), std::min(a_face.hi[1], b_face.hi[1])}};
        patches_[{0, 1}] = box_faces(cube.lo, cube.hi);
        for (const auto& [box, label] : {std::pair{a, Label{2}}, std::pair{b, Label{3}}}) {
            auto& patch = patches_[{1, label}];
            for (const AxisRect& face : box_faces(box.lo, box.hi))
                for (const AxisRect& piece : face.axis == 0 && face.coordinate == shared_.coordinate
                                                 ? subtract_rect(face, shared_)
                                                 : std::vector<AxisRect>{face})
                    patch.push_back(piece);
        }
        patches_[{2, 3}] = {shared_};
    }

    Label label_at(const Vec3& p) const override
    {
        if (b_.contains(p)) return 3;
        if (a_.contains(p)) return 2;
        return cube_.contains(p) ? 1 : 0;
    }
    double distance_to_interface(const Vec3& p, LabelPair pair) const override
    {
        double best = INFINITY;
        for (const AxisRect& rect : patches_.at(key(pair))) best = std::min(best, distance_to_rect(p, rect));
        return best;
    }
    std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const override
    {
        std::vector<Vec3> points;
        for (const AxisRect& rect : patches_.at(key(pair))) sample_rect(rect, spacing_mm, points);
        return points;
    }
    std::vector<LabelPair> interfaces() const override { return {{0, 1}, {1, 2}, {1, 3}, {2, 3}}; }
    double tissue_volume_mm3(Label label) const override
    {
        if (label == 1) return cube_.volume() - a_.volume() - b_.volume();
        if (label == 2) return a_.volume();
        return label == 3 ? b_.volume() : 0;
    }
    nlohmann::json primitives() const override
    {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& [box, label] : {std::pair{cube_, 1}, std::pair{a_, 2}, std::pair{b_, 3}})
            list.push_back({{"type", "box"}, {"min", to_json(box.lo)}, {"max", to_json(box.hi)}, {"label", label}});
        return {{"rule", "a point takes the label of the last box containing it (faces included)"}, {"shapes", list}};
    }

private:
    static std::pair<Label, Label> key(LabelPair pair) { return {pair.from, pair.to}; }

    Box cube_, a_, b_;
    AxisRect shared_;
    std::map<std::pair<Label, Label>, std::vector<AxisRect>> patches_;
};

} // namespace

PhantomSetup make_boxes(double voxel_mm)
{
    // The cube reaches at most 0.8 voxel past 28 mm after snapping.
    const std::size_t n = voxels_for(28 + voxel_mm, voxel_mm);
    LabelImage grid = centred_grid({n, n, n}, {voxel_mm, voxel_mm, voxel_mm}, {0, 0, 0});
    // Faces at nominal millimetres, moved to 0.3 voxel past the nearest voxel centre so that no voxel
    // centre lies on a face and all tissues share the same snapped coordinates.
    const double first_centre = grid.origin_mm()[0];
    const auto snap = [&](double mm) {
        return first_centre + std::round((mm - first_centre) / voxel_mm) * voxel_mm + 0.3 * voxel_mm;
    };
    const auto box = [&](Vec3 lo, Vec3 hi) {
        return Box{{snap(lo[0]), snap(lo[1]), snap(lo[2])}, {snap(hi[0]), snap(hi[1]), snap(hi[2])}};
    };
    auto model = std::make_shared<Boxes>(box({-28, -28, -28}, {28, 28, 28}), box({-20, -15, -12}, {0, 15, 12}),
                                         box({0, -8, -6}, {16, 10, 9}));
    model->names = {{0, "background"}, {1, "cube"}, {2, "box_a"}, {3, "box_b"}};
    return {model, std::move(grid)};
}

} // namespace tissuemesh::image::detail
