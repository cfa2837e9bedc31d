// SurfaceReference: the interface surface a mesh must keep (the complex tm-tetra got, or the mesh's own
// faces as they were), for projecting moved and new nodes back onto it and for measuring how far a
// mesh's interfaces are from it.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "core/interface_complex.h"
#include "surface/detail/box_index.h"

namespace tissuemesh::volume::detail {

class SurfaceReference {
public:
    /// Triangles with their tissue pairs (orientation unused). Junction segments are the edges three or more
    /// triangles share; each knows the tissues of the triangles around it.
    SurfaceReference(std::vector<Vec3> vertices, std::vector<Triangle> triangles, const std::vector<LabelPair>& sides);
    explicit SurfaceReference(const InterfaceComplex& complex);

    /// The nearest point to p of the triangles separating tissues a and b (either order), when one lies
    /// within `reach` mm; of equally near triangles the first. With `hint`, the search starts from triangle
    /// *hint (nothing outside the cube its distance spans can be nearer) and the triangle found is stored there.
    std::optional<Vec3> onto_patch(const Vec3& p, Label a, Label b, double reach, std::uint32_t* hint = nullptr) const;
    /// The nearest point to p of the junction segments whose tissues are exactly `tissues` (ascending),
    /// within `reach` mm.
    std::optional<Vec3> onto_curve(const Vec3& p, const std::vector<Label>& tissues, double reach) const;
    /// Distance from p to the nearest triangle separating a and b (any pair when `any_pair`), searched
    /// within `reach` mm; infinity when none is that near.
    double distance_to(const Vec3& p, Label a, Label b, bool any_pair, double reach) const;

    /// Whether a triangle separating tissues a and b (either order) lies within `tolerance` mm of p. With
    /// `hint`, the triangle *hint is tried first and the one found is stored there: a caller asking again and
    /// again about points that move a little (a node's faces while it is smoothed) mostly needs no search.
    bool within(const Vec3& p, Label a, Label b, double tolerance, std::uint32_t* hint = nullptr) const;

    /// Whether the triangle (a, b, c) of the tissue pair lies on the patch: its centroid and edge midpoints
    /// within `tolerance_mm` of the triangles separating those tissues. A node sliding on a curved or creased
    /// patch keeps its faces as close to it as this, so volumes change only as much.
    bool holds_triangle(const Vec3& a, const Vec3& b, const Vec3& c, Label from, Label to, double tolerance_mm) const;

    std::size_t triangle_count() const { return triangles_.size(); }
    /// Length of a typical reference edge (the mean), for search radii.
    double mean_edge_mm() const { return mean_edge_mm_; }

private:
    /// Whether triangle t lies within `tolerance` mm of p.
    bool triangle_within(std::uint32_t t, const Vec3& p, double tolerance) const;
    /// The nearest point to p that `closest` gives for an item of `index` (`items` of them), within `reach`; with
    /// `hint`, starting from item *hint and storing the item found there.
    template <class Closest>
    std::optional<Vec3> nearest(const surface::detail::BoxIndex& index, std::size_t items, const Vec3& p, double reach,
                                Closest closest, std::uint32_t* hint = nullptr) const;

    std::vector<Vec3> vertices_;
    std::vector<Triangle> triangles_;
    std::vector<std::uint32_t> pairs_; ///< per triangle: smaller label << 16 | larger label
    std::vector<std::array<std::uint32_t, 2>> segments_;
    std::vector<std::uint32_t> segment_tissues_; ///< per segment: index into tissue_sets_
    std::map<std::vector<Label>, std::uint32_t> tissue_sets_;
    surface::detail::BoxIndex triangle_index_, segment_index_;
    double mean_edge_mm_ = 1;
};

} // namespace tissuemesh::volume::detail
