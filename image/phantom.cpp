#include "image/phantom.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "image/detail/phantom_model.h"

namespace tissuemesh::image {

using detail::ordered;

PhantomGeometry::PhantomGeometry(std::shared_ptr<const detail::PhantomModel> model) : model_(std::move(model)) {}

const std::string& PhantomGeometry::name() const { return model_->name; }

Label PhantomGeometry::label_at(const Vec3& world_mm) const { return model_->label_at(world_mm); }

namespace {

void require_interface(const detail::PhantomModel& model, LabelPair pair)
{
    if (std::find(model.known_pairs.begin(), model.known_pairs.end(), pair) == model.known_pairs.end())
        throw InputError(concat("phantom ", model.name, ": tissues ", pair.from, " and ", pair.to,
                                " share no interface; use one of the pairs its interfaces() lists"));
}

} // namespace

double PhantomGeometry::distance_to_interface(const Vec3& world_mm, LabelPair pair) const
{
    pair = ordered(pair);
    require_interface(*model_, pair);
    return model_->distance_to_interface(world_mm, pair);
}

std::vector<Vec3> PhantomGeometry::sample_interface(LabelPair pair, double spacing_mm) const
{
    pair = ordered(pair);
    require_interface(*model_, pair);
    if (!(spacing_mm > 0) || !std::isfinite(spacing_mm))
        throw InputError(concat("phantom ", model_->name, ": sample spacing ", format_mm(spacing_mm),
                                " mm; it must be a positive number"));
    return model_->sample_interface(pair, spacing_mm);
}

std::vector<LabelPair> PhantomGeometry::interfaces() const { return model_->known_pairs; }

double PhantomGeometry::volume_mm3(Label label) const
{
    if (label != 0) return model_->tissue_volume_mm3(label);
    double tissue = 0;
    for (const Label t : tissues()) tissue += model_->tissue_volume_mm3(t);
    return model_->domain_volume_mm3 - tissue;
}

std::vector<Label> PhantomGeometry::tissues() const
{
    std::vector<Label> labels;
    for (const auto& [label, name] : model_->names)
        if (label != 0) labels.push_back(label);
    return labels;
}

const TissueNames& PhantomGeometry::names() const { return model_->names; }

std::string PhantomGeometry::to_json() const
{
    nlohmann::json names = nlohmann::json::object();
    nlohmann::json volumes = nlohmann::json::object();
    for (const auto& [label, name] : model_->names) {
        names[std::to_string(label)] = name;
        volumes[std::to_string(label)] = volume_mm3(label);
    }
    nlohmann::json pairs = nlohmann::json::array();
    for (const LabelPair& pair : interfaces()) pairs.push_back({pair.from, pair.to});
    const nlohmann::json document = {{"phantom", model_->name},
                                     {"units", "mm, RAS world coordinates"},
                                     {"labels", names},
                                     {"geometry", model_->primitives()},
                                     {"interfaces", pairs},
                                     {"volume_mm3", volumes},
                                     {"image_domain_volume_mm3", model_->domain_volume_mm3}};
    return document.dump(2) + "\n";
}

namespace detail {

LabelImage centred_grid(const Dims& dims, const Vec3& spacing_mm, const Vec3& centre_mm, const Mat3& direction)
{
    LabelImage grid(dims, spacing_mm, {0, 0, 0}, direction);
    const Vec3 middle{(static_cast<double>(dims[0]) - 1) / 2, (static_cast<double>(dims[1]) - 1) / 2,
                      (static_cast<double>(dims[2]) - 1) / 2};
    grid.set_origin_mm(centre_mm - grid.index_to_world(middle));
    return grid;
}

std::size_t voxels_for(double half_extent_mm, double spacing_mm)
{
    return 2 * static_cast<std::size_t>(std::ceil(half_extent_mm / spacing_mm)) + 4;
}

} // namespace detail

namespace {

using Factory = detail::PhantomSetup (*)(double voxel_mm);

struct Entry {
    const char* name;
    const char* description;
    Factory make;
};

constexpr Entry catalogue[] = {
    {"spheres4", "concentric spheres 92/86/80/78 mm: scalp, skull, CSF, brain (4-shell EEG head)",
     detail::make_spheres4},
    {"junction", "shell (40 mm) around a ball (30 mm) split by a tilted plane: 3 tissues meet on a circle",
     detail::make_junction},
    {"thin", "ball (20 mm) inside a shell exactly one voxel thick", detail::make_thin},
    {"boxes", "cube holding two boxes that share part of a face: sharp edges and corners", detail::make_boxes},
    {"ellipsoids", "nested ellipsoids rotated about a skew axis, anisotropic and rotated grid",
     detail::make_ellipsoids},
};

/// Largest voxel size: beyond it the boxes' faces would snap onto each other.
constexpr double max_voxel_mm = 8.0;

} // namespace

std::vector<std::pair<std::string, std::string>> phantom_names()
{
    std::vector<std::pair<std::string, std::string>> names;
    for (const Entry& entry : catalogue) names.emplace_back(entry.name, entry.description);
    return names;
}

Phantom make_phantom(const std::string& name, const PhantomOptions& options)
{
    const auto entry =
        std::find_if(std::begin(catalogue), std::end(catalogue), [&](const Entry& e) { return name == e.name; });
    if (entry == std::end(catalogue)) {
        std::string known;
        for (const Entry& e : catalogue) known += std::string(known.empty() ? "" : ", ") + e.name;
        throw InputError(concat("unknown phantom '", name, "'; choose one of: ", known));
    }
    const double h = options.voxel_mm;
    if (!std::isfinite(h) || h <= 0 || h > max_voxel_mm)
        throw InputError(
            concat("phantom ", name, ": voxel size ", format_mm(h), " mm; it must be in (0, ", max_voxel_mm, "] mm"));
    // 92 mm spheres need 2 * 92 / h voxels per axis: refuse grids beyond 2^31 voxels before allocating.
    if (std::pow(2 * 100 / h, 3) > 2147483648.0)
        throw InputError(concat("phantom ", name, ": voxel size ", format_mm(h),
                                " mm makes the image too large (over 2^31 voxels); use 0.2 mm or more"));
    detail::PhantomSetup setup = entry->make(h);
    setup.model->name = name;
    setup.model->known_pairs = setup.model->interfaces();
    setup.model->domain_volume_mm3 = static_cast<double>(setup.grid.voxel_count()) * setup.grid.voxel_volume_mm3();
    const detail::PhantomModel& model = *setup.model;
    LabelImage& image = setup.grid;
    const Dims& dims = image.dims();
    for (std::size_t k = 0; k < dims[2]; ++k)
        for (std::size_t j = 0; j < dims[1]; ++j)
            for (std::size_t i = 0; i < dims[0]; ++i)
                image.at(i, j, k) = model.label_at(
                    image.index_to_world({static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)}));
    image.names() = model.names;
    return {std::move(image), PhantomGeometry(std::move(setup.model))};
}

} // namespace tissuemesh::image
