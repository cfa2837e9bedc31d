#include "surface/snake_field.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "core/error.h"

namespace tissuemesh::surface {
namespace {

std::size_t voxel_count(const Dims& dims) { return dims[0] * dims[1] * dims[2]; }

/// Normalised samples of a Gaussian of `sigma` voxels at offsets -r..r, r = ceil(3 sigma).
std::vector<double> gaussian_kernel(double sigma)
{
    const int radius = static_cast<int>(std::ceil(3 * sigma));
    std::vector<double> kernel(static_cast<std::size_t>(2 * radius + 1));
    double sum = 0;
    for (int d = -radius; d <= radius; ++d) {
        const double w = std::exp(-0.5 * d * d / (sigma * sigma));
        kernel[static_cast<std::size_t>(d + radius)] = w;
        sum += w;
    }
    for (double& w : kernel) w /= sum;
    return kernel;
}

/// Convolves every line of the volume along `axis` with `kernel` (edge voxels replicated).
void smooth_axis(std::vector<float>& values, const Dims& dims, int axis, const std::vector<double>& kernel)
{
    const std::int64_t radius = static_cast<std::int64_t>(kernel.size() / 2);
    const std::size_t n = dims[static_cast<std::size_t>(axis)];
    const std::size_t stride = axis == 0 ? 1 : axis == 1 ? dims[0] : dims[0] * dims[1];
    std::vector<double> line(n);
    for (std::size_t start = 0; start < values.size(); ++start) {
        // `start` is the first voxel of a line when its coordinate along `axis` is 0.
        if ((start / stride) % n != 0) continue;
        for (std::size_t a = 0; a < n; ++a) line[a] = values[start + a * stride];
        for (std::size_t a = 0; a < n; ++a) {
            double sum = 0;
            for (std::int64_t d = -radius; d <= radius; ++d) {
                const std::int64_t b =
                    std::clamp<std::int64_t>(static_cast<std::int64_t>(a) + d, 0, static_cast<std::int64_t>(n) - 1);
                sum += kernel[static_cast<std::size_t>(d + radius)] * line[static_cast<std::size_t>(b)];
            }
            values[start + a * stride] = static_cast<float>(sum);
        }
    }
}

} // namespace

PotentialField::PotentialField(const LabelImage& geometry, std::vector<float> values)
    : dims_(geometry.dims()), spacing_mm_(geometry.spacing_mm()), origin_mm_(geometry.origin_mm()),
      direction_(geometry.direction()), values_(std::move(values))
{
    if (values_.size() != voxel_count(dims_))
        throw InputError(concat("potential field: ", values_.size(), " values for ", voxel_count(dims_),
                                " voxels; give one value per voxel of the image"));
}

double PotentialField::smallest_spacing_mm() const
{
    return std::min({spacing_mm_[0], spacing_mm_[1], spacing_mm_[2]});
}

Vec3 PotentialField::world_to_index(const Vec3& world_mm) const
{
    // world = origin + D * diag(s) * index, D orthonormal: index = diag(1/s) * D^T * (world - origin).
    const Vec3 local = multiply(transpose(direction_), world_mm - origin_mm_);
    return {local[0] / spacing_mm_[0], local[1] / spacing_mm_[1], local[2] / spacing_mm_[2]};
}

Vec3 PotentialField::index_to_world(const Vec3& index) const
{
    return origin_mm_ +
           multiply(direction_, Vec3{index[0] * spacing_mm_[0], index[1] * spacing_mm_[1], index[2] * spacing_mm_[2]});
}

double PotentialField::at(std::int64_t i, std::int64_t j, std::int64_t k) const
{
    const auto clamp = [](std::int64_t v, std::size_t n) {
        return static_cast<std::size_t>(std::clamp<std::int64_t>(v, 0, static_cast<std::int64_t>(n) - 1));
    };
    return values_[clamp(i, dims_[0]) + dims_[0] * (clamp(j, dims_[1]) + dims_[1] * clamp(k, dims_[2]))];
}

namespace {

/// The cell of a continuous index (clamped to the grid) and the fractions within it.
struct Cell {
    std::array<std::int64_t, 3> base{};
    Vec3 t{0, 0, 0};
};

Cell cell_of(const Vec3& index, const Dims& dims)
{
    Cell cell;
    for (std::size_t a = 0; a < 3; ++a) {
        const double top = static_cast<double>(dims[a]) - 1;
        const double x = std::clamp(index[a], 0.0, top);
        const double floor = std::min(std::floor(x), std::max(top - 1, 0.0));
        cell.base[a] = static_cast<std::int64_t>(floor);
        cell.t[a] = x - floor;
    }
    return cell;
}

} // namespace

double PotentialField::value(const Vec3& world_mm) const
{
    const Cell c = cell_of(world_to_index(world_mm), dims_);
    double sum = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const int di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
        const double w = (di ? c.t[0] : 1 - c.t[0]) * (dj ? c.t[1] : 1 - c.t[1]) * (dk ? c.t[2] : 1 - c.t[2]);
        sum += w * at(c.base[0] + di, c.base[1] + dj, c.base[2] + dk);
    }
    return sum;
}

Vec3 PotentialField::gradient(const Vec3& world_mm) const
{
    const Vec3 index = world_to_index(world_mm);
    const Cell c = cell_of(index, dims_);
    Vec3 g_index{0, 0, 0};
    for (int corner = 0; corner < 8; ++corner) {
        const int d[3] = {corner & 1, (corner >> 1) & 1, (corner >> 2) & 1};
        const double f = at(c.base[0] + d[0], c.base[1] + d[1], c.base[2] + d[2]);
        for (std::size_t a = 0; a < 3; ++a) {
            double w = d[a] ? 1 : -1; // derivative of the weight along axis a
            for (std::size_t b = 0; b < 3; ++b)
                if (b != a) w *= d[b] ? c.t[b] : 1 - c.t[b];
            g_index[a] += w * f;
        }
    }
    // Outside the grid along an axis the field is constant there.
    for (std::size_t a = 0; a < 3; ++a)
        if (index[a] < 0 || index[a] > static_cast<double>(dims_[a]) - 1) g_index[a] = 0;
    // d(index)/d(world) = diag(1/s) D^T, so grad_world = D diag(1/s) grad_index.
    const Vec3 scaled{g_index[0] / spacing_mm_[0], g_index[1] / spacing_mm_[1], g_index[2] / spacing_mm_[2]};
    return multiply(direction_, scaled);
}

std::optional<std::array<Vec3, 2>> PotentialField::positive_bounds_mm() const
{
    Vec3 low{1e300, 1e300, 1e300}, high{-1e300, -1e300, -1e300};
    bool found = false;
    for (std::size_t k = 0; k < dims_[2]; ++k)
        for (std::size_t j = 0; j < dims_[1]; ++j)
            for (std::size_t i = 0; i < dims_[0]; ++i) {
                if (!(values_[i + dims_[0] * (j + dims_[1] * k)] > 0)) continue;
                const Vec3 p = index_to_world({static_cast<double>(i), static_cast<double>(j), static_cast<double>(k)});
                for (std::size_t a = 0; a < 3; ++a) {
                    low[a] = std::min(low[a], p[a]);
                    high[a] = std::max(high[a], p[a]);
                }
                found = true;
            }
    if (!found) return std::nullopt;
    return std::array<Vec3, 2>{low, high};
}

void gaussian_smooth(std::vector<float>& values, const Dims& dims, const Vec3& sigma_voxels)
{
    for (int axis = 0; axis < 3; ++axis) {
        const double sigma = sigma_voxels[static_cast<std::size_t>(axis)];
        if (sigma > 0 && dims[static_cast<std::size_t>(axis)] > 1)
            smooth_axis(values, dims, axis, gaussian_kernel(sigma));
    }
}

std::vector<char> enclosed_region(const LabelImage& image, Label tissue)
{
    const Dims& dims = image.dims();
    const std::vector<Label>& labels = image.labels();
    if (std::find(labels.begin(), labels.end(), tissue) == labels.end())
        throw InputError(concat("snake: the image has no voxel of tissue ", image.name_of(tissue), " (label ", tissue,
                                "); choose a tissue it holds (tm-info lists them)"));
    // Flood the outside from the border voxels through voxels of other labels (6-connected).
    std::vector<char> outside(labels.size(), 0);
    std::deque<std::size_t> queue;
    const auto visit = [&](std::size_t v) {
        if (!outside[v] && labels[v] != tissue) {
            outside[v] = 1;
            queue.push_back(v);
        }
    };
    for (std::size_t k = 0; k < dims[2]; ++k)
        for (std::size_t j = 0; j < dims[1]; ++j)
            for (std::size_t i = 0; i < dims[0]; ++i)
                if (i == 0 || j == 0 || k == 0 || i + 1 == dims[0] || j + 1 == dims[1] || k + 1 == dims[2])
                    visit(image.linear_index(i, j, k));
    const std::size_t sj = dims[0], sk = dims[0] * dims[1];
    while (!queue.empty()) {
        const std::size_t v = queue.front();
        queue.pop_front();
        const std::size_t i = v % dims[0], j = (v / sj) % dims[1], k = v / sk;
        if (i > 0) visit(v - 1);
        if (i + 1 < dims[0]) visit(v + 1);
        if (j > 0) visit(v - sj);
        if (j + 1 < dims[1]) visit(v + sj);
        if (k > 0) visit(v - sk);
        if (k + 1 < dims[2]) visit(v + sk);
    }
    for (char& c : outside) c = static_cast<char>(!c);
    return outside;
}

PotentialField label_potential(const LabelImage& image, const std::vector<char>& region, double sigma_mm)
{
    if (region.size() != image.voxel_count())
        throw InputError(concat("snake: the region has ", region.size(), " voxels, the image ", image.voxel_count()));
    if (!(sigma_mm >= 0) || !std::isfinite(sigma_mm))
        throw InputError(concat("snake: Gaussian sigma ", sigma_mm, " mm must be zero or positive; try 1 voxel"));
    std::vector<float> values(region.size());
    for (std::size_t v = 0; v < region.size(); ++v) values[v] = region[v] ? 1.0f : 0.0f;
    const Vec3& s = image.spacing_mm();
    gaussian_smooth(values, image.dims(), {sigma_mm / s[0], sigma_mm / s[1], sigma_mm / s[2]});
    for (float& f : values) f -= 0.5f;
    return PotentialField(image, std::move(values));
}

PotentialField grey_potential(const LabelImage& geometry, const std::vector<float>& values, double iso, double sigma_mm,
                              bool bright_inside)
{
    if (values.size() != geometry.voxel_count())
        throw InputError(concat("snake: ", values.size(), " grey values for ", geometry.voxel_count(), " voxels"));
    if (!(sigma_mm >= 0) || !std::isfinite(sigma_mm))
        throw InputError(concat("snake: Gaussian sigma ", sigma_mm, " mm must be zero or positive"));
    if (!std::isfinite(iso)) throw InputError("snake: the iso value must be a finite number");
    std::vector<float> field = values;
    const Vec3& s = geometry.spacing_mm();
    gaussian_smooth(field, geometry.dims(), {sigma_mm / s[0], sigma_mm / s[1], sigma_mm / s[2]});
    const double sign = bright_inside ? 1 : -1;
    for (float& f : field) f = static_cast<float>(sign * (f - iso));
    return PotentialField(geometry, std::move(field));
}

} // namespace tissuemesh::surface
