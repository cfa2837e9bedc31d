#include "fem/detail/point_location.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <omp.h>

#include "fem/assemble.h"

namespace tissuemesh::fem::detail {
namespace {

// The points in a uniform grid of cells (about 2 points per cell over their bounding box), cells in
// compressed rows.
class PointGrid {
public:
    explicit PointGrid(const std::vector<Vec3>& points) : points_(points)
    {
        low_ = high_ = points.empty() ? Vec3{0, 0, 0} : points.front();
        for (const Vec3& p : points)
            for (int a = 0; a < 3; ++a) low_[a] = std::min(low_[a], p[a]), high_[a] = std::max(high_[a], p[a]);
        const double cells_wanted = std::max(1.0, static_cast<double>(points.size()) / 2);
        double volume = 1;
        for (int a = 0; a < 3; ++a) volume *= std::max(high_[a] - low_[a], 1e-3);
        cell_ = std::max(std::cbrt(volume / cells_wanted), 1e-3);
        for (int a = 0; a < 3; ++a) size_[a] = std::min(1024, static_cast<int>((high_[a] - low_[a]) / cell_) + 1);
        starts_.assign(static_cast<std::size_t>(size_[0]) * size_[1] * size_[2] + 1, 0);
        for (const Vec3& p : points) ++starts_[cell_of(p) + 1];
        for (std::size_t c = 1; c < starts_.size(); ++c) starts_[c] += starts_[c - 1];
        members_.resize(points.size());
        std::vector<std::uint32_t> fill(starts_.begin(), starts_.end() - 1);
        for (std::size_t k = 0; k < points.size(); ++k)
            members_[fill[cell_of(points[k])]++] = static_cast<std::uint32_t>(k);
    }

    // Calls visit(point index) for every point in the cells the box [low, high] overlaps.
    template <typename Visit>
    void visit_box(const Vec3& low, const Vec3& high, Visit&& visit) const
    {
        int from[3], to[3];
        for (int a = 0; a < 3; ++a) {
            if (high[a] < low_[a] || low[a] > high_[a]) return;
            from[a] = index_along(a, low[a]);
            to[a] = index_along(a, high[a]);
        }
        for (int k = from[2]; k <= to[2]; ++k)
            for (int j = from[1]; j <= to[1]; ++j)
                for (int i = from[0]; i <= to[0]; ++i) {
                    const std::size_t cell = (static_cast<std::size_t>(k) * size_[1] + j) * size_[0] + i;
                    for (std::uint32_t at = starts_[cell]; at < starts_[cell + 1]; ++at) visit(members_[at]);
                }
    }

private:
    int index_along(int axis, double x) const
    {
        const double steps = std::floor((x - low_[axis]) / cell_);
        return static_cast<int>(std::clamp(steps, 0.0, static_cast<double>(size_[axis] - 1)));
    }
    std::size_t cell_of(const Vec3& p) const
    {
        return (static_cast<std::size_t>(index_along(2, p[2])) * size_[1] + index_along(1, p[1])) * size_[0] +
               index_along(0, p[0]);
    }

    const std::vector<Vec3>& points_;
    Vec3 low_{}, high_{};
    double cell_ = 1;
    int size_[3] = {1, 1, 1};
    std::vector<std::uint32_t> starts_, members_;
};

struct Candidate {
    double smallest = -std::numeric_limits<double>::infinity(); // smallest barycentric coordinate
    std::uint32_t tet = outside_mesh;
    bool better_than(const Candidate& other) const
    {
        return smallest > other.smallest || (smallest == other.smallest && tet < other.tet);
    }
};

} // namespace

std::vector<std::uint32_t> locate_points(const TetMesh& mesh, const std::vector<Vec3>& points_mm)
{
    std::vector<std::uint32_t> located(points_mm.size(), outside_mesh);
    if (points_mm.empty()) return located;
    const PointGrid grid(points_mm);
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<std::vector<Candidate>> per_thread(static_cast<std::size_t>(omp_get_max_threads()));
#pragma omp parallel
    {
        std::vector<Candidate>& best = per_thread[static_cast<std::size_t>(omp_get_thread_num())];
        best.assign(points_mm.size(), Candidate{});
#pragma omp for schedule(static)
        for (std::int64_t t = 0; t < count; ++t) {
            const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
            Vec3 low = mesh.vertices[tet[0]], high = low;
            for (int k = 1; k < 4; ++k)
                for (int a = 0; a < 3; ++a)
                    low[a] = std::min(low[a], mesh.vertices[tet[k]][a]),
                    high[a] = std::max(high[a], mesh.vertices[tet[k]][a]);
            const Vec3 slack{1e-9, 1e-9, 1e-9};
            bool element_ready = false;
            P1Element element;
            grid.visit_box(low - slack, high + slack, [&](std::uint32_t p) {
                const Vec3& point = points_mm[p];
                for (int a = 0; a < 3; ++a)
                    if (point[a] < low[a] - 1e-9 || point[a] > high[a] + 1e-9) return;
                if (!element_ready) {
                    if (!(signed_volume(mesh, static_cast<std::size_t>(t)) > 0))
                        return; // no P1 element: not ours to refuse
                    element = p1_element(mesh, static_cast<std::size_t>(t));
                    element_ready = true;
                }
                // Barycentric coordinates from the P1 gradients: lambda_k(x) = 1_{k=0} + grad(phi_k) . (x - v0).
                const Vec3 offset = metres_per_mm * (point - mesh.vertices[tet[0]]);
                double smallest = 1, sum = 0;
                for (int k = 1; k < 4; ++k) {
                    const double lambda = dot(element.gradients[k], offset);
                    smallest = std::min(smallest, lambda);
                    sum += lambda;
                }
                const Candidate candidate{std::min(smallest, 1 - sum), static_cast<std::uint32_t>(t)};
                if (candidate.smallest >= -1e-9 && candidate.better_than(best[p])) best[p] = candidate;
            });
        }
    }
    for (std::size_t p = 0; p < points_mm.size(); ++p) {
        Candidate best;
        for (const std::vector<Candidate>& thread : per_thread)
            if (!thread.empty() && thread[p].tet != outside_mesh && thread[p].better_than(best)) best = thread[p];
        located[p] = best.tet;
    }
    return located;
}

std::vector<std::vector<std::uint32_t>> tets_around(const TetMesh& mesh, const std::vector<std::uint32_t>& nodes)
{
    std::unordered_map<std::uint32_t, std::vector<std::size_t>> wanted; // node -> its places in `nodes`
    for (std::size_t k = 0; k < nodes.size(); ++k) wanted[nodes[k]].push_back(k);
    std::vector<std::vector<std::uint32_t>> around(nodes.size());
    for (std::size_t t = 0; t < mesh.tet_count(); ++t)
        for (const std::uint32_t node : mesh.tets[t]) {
            const auto found = wanted.find(node);
            if (found == wanted.end()) continue;
            for (const std::size_t k : found->second) around[k].push_back(static_cast<std::uint32_t>(t));
        }
    return around;
}

} // namespace tissuemesh::fem::detail
