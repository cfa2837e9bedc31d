// Phantoms: label images generated from an exactly known analytic geometry, so that every later step
// (interfaces, meshes, potentials) can be checked against the truth rather than against a snapshot.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/vec3.h"

namespace tissuemesh::image {

namespace detail {
class PhantomModel;
}

/// The exact geometry behind a phantom image: which tissue occupies each point of space, and where
/// the interfaces between tissues are. Label 0 is the background (air) outside every tissue.
/// Cheap to copy (shares an immutable model).
class PhantomGeometry {
public:
    explicit PhantomGeometry(std::shared_ptr<const detail::PhantomModel> model);

    /// The phantom's name ("spheres4").
    const std::string& name() const;
    /// Exact tissue at a world point (mm). Points exactly on an interface get one of its two tissues.
    Label label_at(const Vec3& world_mm) const;
    /// Distance (mm, exact up to ~1e-9 mm) from `world_mm` to the interface between the two tissues
    /// of `pair` (order-insensitive).
    /// @throws InputError when the two tissues share no interface (see interfaces())
    double distance_to_interface(const Vec3& world_mm, LabelPair pair) const;
    /// Points on the exact interface between the tissues of `pair`, about `spacing_mm` apart,
    /// covering it (deterministic).
    /// @throws InputError for an unknown pair or spacing_mm <= 0
    std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const;
    /// Every tissue pair that shares an interface of positive area, each with from < to, sorted.
    std::vector<LabelPair> interfaces() const;
    /// Exact volume (mm^3) of a tissue; for the background (0), the part of the image domain
    /// outside every tissue. 0 for labels the phantom does not have.
    double volume_mm3(Label label) const;
    /// Tissue labels (without the background), ascending.
    std::vector<Label> tissues() const;
    /// Tissue names by label, the background included ({0: "background", 1: "scalp", ...}).
    const TissueNames& names() const;
    /// The geometry as a JSON document: name, tissue names, primitives with their parameters (mm),
    /// interfaces and exact volumes. Deterministic.
    std::string to_json() const;

private:
    std::shared_ptr<const detail::PhantomModel> model_;
};

/// Options of make_phantom(). Lengths in mm.
struct PhantomOptions {
    double voxel_mm = 1.0; ///< voxel size (mm) along x and y; along z too except for "ellipsoids" (1.5x)
};

/// A phantom image and the exact geometry it samples: image.at(i,j,k) ==
/// geometry.label_at(image.index_to_world({i,j,k})) for every voxel (point sampling at voxel centres).
struct Phantom {
    LabelImage image;
    PhantomGeometry geometry;
};

/// Builds a phantom by name:
///  - "spheres4":   concentric spheres of radii 92/86/80/78 mm: 1 scalp, 2 skull, 3 CSF, 4 brain;
///  - "junction":   a shell (1, radii 30..40 mm) around a ball split by a tilted plane into halves 2 and 3,
///                  so that three tissues meet along a circle;
///  - "thin":       a ball (2, radius 20 mm) inside a shell (1) exactly one voxel thick;
///  - "boxes":      a cube (1) holding two boxes (2 and 3) that share part of a face; box faces lie
///                  0.3 voxel off voxel centres, so classification is unambiguous;
///  - "ellipsoids": nested ellipsoids (1 outer, 2 inner) rotated about a skew axis, on a grid with
///                  anisotropic spacing (z is 1.5 x voxel_mm), rotated direction and non-zero origin.
/// Every image keeps at least 2 voxels of background around the tissues. Names are set in image.names().
/// @throws InputError for an unknown name (listing phantom_names()) or a voxel size that is not a
///         positive number, or so small that the image would exceed 2^31 voxels
Phantom make_phantom(const std::string& name, const PhantomOptions& options = {});

/// The names make_phantom() accepts, with a one-line description each: {{"spheres4", "..."}, ...}.
std::vector<std::pair<std::string, std::string>> phantom_names();

} // namespace tissuemesh::image
