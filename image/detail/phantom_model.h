// The analytic models behind make_phantom(). Internal to image/: nlohmann::json appears here only.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/interface_complex.h"
#include "core/label_image.h"

namespace tissuemesh::image::detail {

/// One phantom's exact geometry. Pairs passed to the virtual functions are normalised (from < to)
/// and are among interfaces().
class PhantomModel {
public:
    virtual ~PhantomModel() = default;

    virtual Label label_at(const Vec3& p) const = 0;
    virtual double distance_to_interface(const Vec3& p, LabelPair pair) const = 0;
    virtual std::vector<Vec3> sample_interface(LabelPair pair, double spacing_mm) const = 0;
    virtual std::vector<LabelPair> interfaces() const = 0;
    /// Exact volume of a tissue (not the background); 0 for unknown labels.
    virtual double tissue_volume_mm3(Label label) const = 0;
    /// The primitives and their parameters, for the JSON sidecar.
    virtual nlohmann::json primitives() const = 0;

    std::string name;
    TissueNames names;                  ///< the background included
    double domain_volume_mm3 = 0;       ///< volume of the image's voxel cells, for the background's volume
    std::vector<LabelPair> known_pairs; ///< interfaces(), computed once: distance queries check against it
};

/// A model and the (all-background) grid that samples it.
struct PhantomSetup {
    std::shared_ptr<PhantomModel> model;
    LabelImage grid;
};

/// A grid of `dims` voxels of `spacing_mm` whose centre (the middle of the index range) is at `centre_mm`.
LabelImage centred_grid(const Dims& dims, const Vec3& spacing_mm, const Vec3& centre_mm,
                        const Mat3& direction = identity_matrix());

/// An even number of voxels holding [-half_extent_mm, half_extent_mm] (centred) with at least 2 voxel
/// centres of margin beyond it on each side; voxel centres then sit at half-integer multiples of the spacing.
std::size_t voxels_for(double half_extent_mm, double spacing_mm);

PhantomSetup make_spheres4(double voxel_mm);
PhantomSetup make_thin(double voxel_mm);
PhantomSetup make_junction(double voxel_mm);
PhantomSetup make_boxes(double voxel_mm);
PhantomSetup make_ellipsoids(double voxel_mm);

/// Normalised copy of a pair: from <= to.
inline LabelPair ordered(LabelPair pair) { return pair.from <= pair.to ? pair : LabelPair{pair.to, pair.from}; }

inline nlohmann::json to_json(const Vec3& v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

} // namespace tissuemesh::image::detail
