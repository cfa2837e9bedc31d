#include "surface/detail/label_field.h"

#include <array>
#include <cmath>

#include "core/error.h"

namespace tissuemesh::surface::detail {

LabelField::LabelField(const LabelImage& image, Label background, double sigma_voxels)
    : image_(image), background_(background), sigma_(sigma_voxels)
{
    // sample_field() holds its taps on the stack: 2 ceil(3 sigma) + 1 of them, at most 7.
    if (!(sigma_voxels > 0 && sigma_voxels <= 1))
        throw InputError(concat("label field: blur ", sigma_voxels, " voxels is outside (0, 1]"));
}

namespace {

/// The field and its gradient at one point, index space.
struct FieldSample {
    double value = 0;
    Vec3 gradient{0, 0, 0};
    double other_weight = 0; ///< share of the kernel's weight on tissues other than a and b
};

int radius_for(double sigma) { return static_cast<int>(std::ceil(3 * sigma)); }

/// In index space x, with voxel weights w(n) = prod_axes g(x_a - n_a), g the Gaussian: the field is
/// f = sum_n w(n) s(n) / sum_n w(n), s = +1 in tissue a, -1 in b, 0 elsewhere (normalised, so that a
/// truncated kernel stays unbiased), and its gradient follows from dg/dx = -(x - n) g / sigma^2.
FieldSample sample_field(const LabelImage& image, Label background, const Vec3& x, Label a, Label b, double sigma)
{
    constexpr int max_taps = 7; // 2 * radius + 1 for sigma <= 1
    const int radius = radius_for(sigma);
    const int taps = 2 * radius + 1;
    std::array<std::int64_t, 3> low{};
    std::array<std::array<double, max_taps>, 3> g{}, dg{};
    for (int axis = 0; axis < 3; ++axis) {
        low[axis] = static_cast<std::int64_t>(std::lround(x[axis])) - radius;
        for (int t = 0; t < taps; ++t) {
            const double d = x[axis] - static_cast<double>(low[axis] + t);
            g[axis][t] = std::exp(-0.5 * d * d / (sigma * sigma));
            dg[axis][t] = -d / (sigma * sigma) * g[axis][t];
        }
    }
    double sum = 0, signed_sum = 0, other = 0;
    Vec3 grad_sum{0, 0, 0}, grad_signed{0, 0, 0};
    for (int k = 0; k < taps; ++k)
        for (int j = 0; j < taps; ++j)
            for (int i = 0; i < taps; ++i) {
                const double w = g[0][i] * g[1][j] * g[2][k];
                const Vec3 dw{dg[0][i] * g[1][j] * g[2][k], g[0][i] * dg[1][j] * g[2][k], g[0][i] * g[1][j] * dg[2][k]};
                const Label label = image.at_or({low[0] + i, low[1] + j, low[2] + k}, background);
                sum += w;
                grad_sum = grad_sum + dw;
                if (label == a) signed_sum += w, grad_signed = grad_signed + dw;
                else if (label == b) signed_sum -= w, grad_signed = grad_signed - dw;
                else other += w;
            }
    FieldSample sample;
    sample.value = signed_sum / sum;
    sample.gradient = (1.0 / sum) * grad_signed - (sample.value / sum) * grad_sum;
    sample.other_weight = other / sum;
    return sample;
}

} // namespace

/// Where a third tissue lies within the blur (a thin layer, a junction nearby), it counts for neither side
/// and pulls the level: the narrow blur is used there instead, and where even that one reaches a third
/// tissue (a layer one voxel thick) the field has no answer.
std::optional<Vec3> LabelField::step_to_interface(const Vec3& position_mm, Label a, Label b,
                                                  double max_step_voxels) const
{
    const Vec3 x = image_.world_to_index(position_mm);
    FieldSample sample = sample_field(image_, background_, x, a, b, sigma_);
    if (sample.other_weight > third_tissue_share) sample = sample_field(image_, background_, x, a, b, narrow_sigma);
    if (sample.other_weight > third_tissue_share) return std::nullopt;
    const double g2 = dot(sample.gradient, sample.gradient);
    if (!(g2 > 1e-6)) return std::nullopt;
    Vec3 step = (-sample.value / g2) * sample.gradient; // index space
    const double length = norm(step);
    if (length > max_step_voxels) step = (max_step_voxels / length) * step;
    return image_.index_to_world(x + step) - position_mm;
}

} // namespace tissuemesh::surface::detail
