// The best triangulation of the polygon of nodes around an edge (edge removal, Shewchuk 2002): the one that,
// swept to both ends of the edge, gives tets whose smallest dihedral sine is largest (Klincsek's dynamic
// programming over sub-polygons).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {

inline constexpr double invalid = -std::numeric_limits<double>::infinity();

/// The quality of a new tet, or `invalid` when it is not better than `bar` or not positively oriented.
inline double new_tet_quality(const WorkMesh& mesh, const Tet& tet, double bar)
{
    const TetCorners c = mesh.corners(tet);
    const double q = min_sine(c);
    if (!(q > bar)) return invalid;
    return positive(c[0], c[1], c[2], c[3]) ? q : invalid;
}

/// The best triangulation of polygon ring[0..n-1] (its closing edge ring[n-1] ring[0]) swept to a and to b,
/// for a ring that turns counter-clockwise seen from b: tets (a, r_i, r_k, r_j) and (b, r_i, r_j, r_k) for each
/// triangle i < k < j. Quality and split point of every sub-polygon ring[i..j]; `bar`: tets no better are left
/// out (the ring's own worst tet, so only improvements count).
class RingTriangulation {
public:
    RingTriangulation(const WorkMesh& mesh, std::uint32_t a, std::uint32_t b, const std::vector<std::uint32_t>& ring,
                      double bar)
        : n_(ring.size()), best_(n_ * n_, invalid), split_(n_ * n_, 0)
    {
        for (std::size_t i = 0; i + 1 < n_; ++i) best_[i * n_ + i + 1] = std::numeric_limits<double>::infinity();
        for (std::size_t length = 2; length < n_; ++length)
            for (std::size_t i = 0; i + length < n_; ++i) {
                const std::size_t j = i + length;
                for (std::size_t k = i + 1; k < j; ++k) {
                    const double sides = std::min(best_[i * n_ + k], best_[k * n_ + j]);
                    if (!(sides > best_[i * n_ + j])) continue;
                    // The ring turns counter-clockwise seen from b: (a, r_i, r_k, r_j) and (b, r_i, r_j, r_k) are
                    // positive.
                    const double below =
                        new_tet_quality(mesh, {a, ring[i], ring[k], ring[j]}, std::max(bar, best_[i * n_ + j]));
                    if (below == invalid) continue;
                    const double above =
                        new_tet_quality(mesh, {b, ring[i], ring[j], ring[k]}, std::max(bar, best_[i * n_ + j]));
                    const double value = std::min({sides, below, above});
                    if (value > best_[i * n_ + j]) best_[i * n_ + j] = value, split_[i * n_ + j] = k;
                }
            }
    }

    double quality() const { return best_[n_ - 1]; }

    /// The triangles (i, k, j) of the best triangulation of ring[i..j].
    void triangles(std::size_t i, std::size_t j, std::vector<std::array<std::size_t, 3>>& out) const
    {
        if (j < i + 2) return;
        const std::size_t k = split_[i * n_ + j];
        out.push_back({i, k, j});
        triangles(i, k, out);
        triangles(k, j, out);
    }

private:
    std::size_t n_;
    std::vector<double> best_;
    std::vector<std::size_t> split_;
};

} // namespace tissuemesh::volume::detail
