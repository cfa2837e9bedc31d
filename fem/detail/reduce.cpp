#include "fem/detail/reduce.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "fem/detail/locality_order.h"

namespace tissuemesh::fem::detail {

// The system on the free nodes, K_FF x_F = b_F - K_FD x_D, written straight into compressed rows. The
// free nodes are renumbered in Z-order of their positions (detail/locality_order.h): TetGen's numbering
// scatters neighbours over the whole vector, and the AMG setup and cycles run faster on rows whose columns
// are close (measured in bench/SOLVE.md).
ReducedSystem reduce(const SparseMatrix& stiffness, const Eigen::VectorXd& rhs, const std::vector<double>& fixed,
                     const std::vector<Vec3>& nodes_mm)
{
    std::vector<bool> is_free(fixed.size());
    for (std::size_t i = 0; i < fixed.size(); ++i) is_free[i] = std::isnan(fixed[i]);
    const std::vector<std::uint32_t> order = locality_order(nodes_mm, is_free);
    const auto free_count = static_cast<std::int64_t>(order.size());
    ReducedSystem system;
    system.free_index.assign(fixed.size(), -1);
    for (std::size_t k = 0; k < order.size(); ++k) system.free_index[order[k]] = static_cast<int>(k);
    std::vector<int> row_start(order.size() + 1, 0);
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < free_count; ++k) {
        int kept = 0;
        for (SparseMatrix::InnerIterator entry(stiffness, order[static_cast<std::size_t>(k)]); entry; ++entry)
            kept += system.free_index[static_cast<std::size_t>(entry.col())] >= 0;
        row_start[static_cast<std::size_t>(k) + 1] = kept;
    }
    for (std::size_t k = 0; k < order.size(); ++k) row_start[k + 1] += row_start[k];
    system.matrix.resize(static_cast<Eigen::Index>(free_count), static_cast<Eigen::Index>(free_count));
    system.matrix.resizeNonZeros(row_start.back());
    std::copy(row_start.begin(), row_start.end(), system.matrix.outerIndexPtr());
    system.rhs.resize(static_cast<Eigen::Index>(free_count));
#pragma omp parallel
    {
        std::vector<std::pair<int, double>> row;
#pragma omp for schedule(static)
        for (std::int64_t k = 0; k < free_count; ++k) {
            const auto original = static_cast<Eigen::Index>(order[static_cast<std::size_t>(k)]);
            double value = rhs.size() > 0 ? rhs[original] : 0.0;
            row.clear();
            for (SparseMatrix::InnerIterator entry(stiffness, original); entry; ++entry) {
                const int column = system.free_index[static_cast<std::size_t>(entry.col())];
                if (column >= 0) row.emplace_back(column, entry.value());
                else value -= entry.value() * fixed[static_cast<std::size_t>(entry.col())];
            }
            std::sort(row.begin(), row.end()); // columns are distinct: the values only ride along
            int at = row_start[static_cast<std::size_t>(k)];
            for (const auto& [column, entry_value] : row) {
                system.matrix.innerIndexPtr()[at] = column;
                system.matrix.valuePtr()[at++] = entry_value;
            }
            system.rhs[k] = value;
        }
    }
    return system;
}

} // namespace tissuemesh::fem::detail
