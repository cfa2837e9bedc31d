// AngleLimit: an angle limit of the editor's rules, compared without atan2 where the answer is certain.
#pragma once

#include <cmath>

namespace tissuemesh::surface::detail {

/// An angle limit that compares angles given as atan2(y, x) (y >= 0) without atan2 where the answer is
/// certain: the sign of y cos(limit) - x sin(limit), the sine of the difference, when it exceeds by far
/// the rounding of the few operations behind it. Otherwise unsure, and the caller computes the angle.
/// Editing asks these questions for every changed triangle; nearly all are far from the limits.
class AngleLimit {
public:
    explicit AngleLimit(double deg = 0)
        : deg_(deg), cos_(std::cos(deg * 3.14159265358979323846 / 180)),
          sin_(std::sin(deg * 3.14159265358979323846 / 180))
    {
    }
    double deg() const { return deg_; }
    /// +1 when atan2(y, x) is certainly above the limit, -1 certainly below, 0 unsure.
    int compare(double y, double x) const
    {
        if (!(deg_ > 0 && deg_ < 89)) return 0; // sin(angle - limit) decides the order only for such limits
        const double s = y * cos_ - x * sin_;
        const double margin = 1e-9 * (y + std::abs(x));
        return s > margin ? 1 : s < -margin ? -1 : 0;
    }

private:
    double deg_, cos_, sin_;
};

} // namespace tissuemesh::surface::detail
