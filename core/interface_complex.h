// InterfaceComplex: the triangles that separate tissues, each knowing the two tissues it separates.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/label_image.h"
#include "core/vec3.h"

namespace tissuemesh {

using Triangle = std::array<std::uint32_t, 3>;

/// The two tissues a triangle separates. The triangle's normal (right-hand rule over its vertex order)
/// points from `from` into `to`, i.e. `from` lies behind the triangle and `to` in front of it.
struct LabelPair {
    Label from = 0;
    Label to = 0;
    friend bool operator==(const LabelPair&, const LabelPair&) = default;
};

/// A set of triangles in world mm, each separating two tissues (#triangles == #sides).
/// Intended invariants (checked by the surface checker, not by this type):
///  - the region of every tissue is bounded by a closed, consistently oriented surface;
///  - patches (triangles of one tissue pair) meet other patches only along junction curves, where
///    three or more tissues meet, and share those curves' vertices exactly;
///  - no two triangles intersect except at shared vertices and edges.
struct InterfaceComplex {
    std::vector<Vec3> vertices;      ///< #V positions, mm
    std::vector<Triangle> triangles; ///< #T vertex indices
    std::vector<LabelPair> sides;    ///< #T tissue pairs, one per triangle
    TissueNames names;               ///< tissue names by label, carried from the image
    Label background = 0;            ///< the label standing for everything outside the image

    std::size_t vertex_count() const { return vertices.size(); }
    std::size_t triangle_count() const { return triangles.size(); }
    /// Appends a triangle separating `from` (behind) and `to` (in front).
    void add_triangle(const Triangle& triangle, LabelPair pair)
    {
        triangles.push_back(triangle);
        sides.push_back(pair);
    }
};

/// Throws InputError when index arrays are out of range, sizes disagree, or a coordinate is not finite;
/// `what` names the source in the message. Cheap (linear); geometric checks live in surface/.
void validate_indices(const InterfaceComplex& complex, const std::string& what);

} // namespace tissuemesh
