#include "fem/assemble.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <omp.h>

#include "core/error.h"
#include "core/node_tets.h"

namespace tissuemesh::fem {

P1Element p1_element(const TetMesh& mesh, std::size_t t)
{
    const Tet& tet = mesh.tets[t];
    const Vec3 origin = mesh.vertices[tet[0]];
    // Edge vectors in metres; the hat gradients are the rows of the inverse of [e1 e2 e3] (columns),
    // computed from cross products: grad(phi_k) = (e_i x e_j) / det for the cyclic pair (i, j).
    const Vec3 e1 = metres_per_mm * (mesh.vertices[tet[1]] - origin);
    const Vec3 e2 = metres_per_mm * (mesh.vertices[tet[2]] - origin);
    const Vec3 e3 = metres_per_mm * (mesh.vertices[tet[3]] - origin);
    const double det = dot(e1, cross(e2, e3));
    if (!(det > 0))
        throw InputError(concat("tet ", t, " has volume ", det / 6 * 1e9, " mm^3; P1 elements need positively ",
                                "oriented, non-degenerate tets: check the mesh with tm-check-mesh"));
    P1Element element;
    element.gradients[1] = (1 / det) * cross(e2, e3);
    element.gradients[2] = (1 / det) * cross(e3, e1);
    element.gradients[3] = (1 / det) * cross(e1, e2);
    element.gradients[0] = -1.0 * (element.gradients[1] + element.gradients[2] + element.gradients[3]);
    element.volume_m3 = det / 6;
    return element;
}

namespace {

// The upper triangle of a tet's symmetric 4 x 4 element matrix, row by row: (0,0) (0,1) (0,2) (0,3)
// (1,1) (1,2) (1,3) (2,2) (2,3) (3,3). Storing one triangle keeps K exactly symmetric and halves the
// memory of the element pass (80 bytes per tet).
using ElementMatrix = std::array<double, 10>;

constexpr int packed(int i, int j)
{
    const int low = i < j ? i : j, high = i < j ? j : i;
    return low * 4 - low * (low + 1) / 2 + high;
}

ElementMatrix element_matrix(const TetMesh& mesh, const Conductivities& conductivities, std::size_t t)
{
    const Mat3& sigma = conductivities.of(mesh.tet_labels[t], t);
    const P1Element element = p1_element(mesh, t);
    ElementMatrix matrix{};
    for (int i = 0; i < 4; ++i) {
        const Vec3 flux = multiply(sigma, element.gradients[i]);
        for (int j = i; j < 4; ++j) matrix[packed(i, j)] = element.volume_m3 * dot(flux, element.gradients[j]);
    }
    return matrix;
}

// Element matrices of every tet, in parallel. An exception may not leave an OpenMP loop: the loop notes
// the first bad tet, and that one is computed again outside to throw its message.
std::vector<ElementMatrix> element_matrices(const TetMesh& mesh, const Conductivities& conductivities)
{
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
    std::vector<ElementMatrix> matrices(mesh.tet_count());
    std::int64_t first_bad = count;
#pragma omp parallel for schedule(static) reduction(min : first_bad)
    for (std::int64_t t = 0; t < count; ++t) {
        try {
            matrices[static_cast<std::size_t>(t)] = element_matrix(mesh, conductivities, static_cast<std::size_t>(t));
        } catch (...) {
            first_bad = std::min(first_bad, t);
        }
    }
    if (first_bad < count) element_matrix(mesh, conductivities, static_cast<std::size_t>(first_bad));
    return matrices;
}

// Per-thread scratch of the row loop. `slot[v]` is the position of column v in the current row, -1 when
// v is not in it: a mark array instead of sorting the 4 x (tets around the node) repeated nodes of a row
// (about 100 for ~15 distinct columns), which made the row loop the bulk of the assembly time.
struct RowScratch {
    explicit RowScratch(std::size_t nodes) : slot(nodes, -1) {}
    std::vector<int> slot;
    std::vector<std::pair<int, double>> entries; ///< (column, value) of the current row
};

// Row `node` of K into `scratch.entries`, sorted by column: the sum of its tets' element rows, in
// increasing tet order for every entry (so the bytes do not depend on how rows are shared among threads).
void gather_row(const TetMesh& mesh, const NodeTets& incidence, const std::vector<ElementMatrix>& elements,
                std::size_t node, RowScratch& scratch)
{
    scratch.entries.clear();
    for (std::size_t i = incidence.offsets[node]; i < incidence.offsets[node + 1]; ++i) {
        const std::uint32_t t = incidence.tets[i];
        const Tet& tet = mesh.tets[t];
        const int local = static_cast<int>(std::find(tet.begin(), tet.end(), node) - tet.begin());
        for (int j = 0; j < 4; ++j) {
            int& slot = scratch.slot[tet[j]];
            if (slot < 0) {
                slot = static_cast<int>(scratch.entries.size());
                scratch.entries.emplace_back(static_cast<int>(tet[j]), 0.0);
            }
            scratch.entries[static_cast<std::size_t>(slot)].second += elements[t][packed(local, j)];
        }
    }
    for (const auto& entry : scratch.entries) scratch.slot[static_cast<std::size_t>(entry.first)] = -1;
    std::sort(scratch.entries.begin(), scratch.entries.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
}

} // namespace

SparseMatrix assemble_stiffness(const TetMesh& mesh, const Conductivities& conductivities)
{
    validate_indices(mesh, "mesh");
    const std::vector<ElementMatrix> elements = element_matrices(mesh, conductivities);
    const NodeTets incidence = node_tets(mesh);
    const auto n = static_cast<std::int64_t>(mesh.vertex_count());
    SparseMatrix matrix(static_cast<int>(n), static_cast<int>(n));
    std::vector<std::int64_t> row_start(static_cast<std::size_t>(n) + 1, 0);
    bool too_large = false;
    // Each thread sums the rows of one contiguous block once, keeps them until the row offsets are known,
    // then copies them in.
#pragma omp parallel
    {
        const auto threads = static_cast<std::int64_t>(omp_get_num_threads());
        const auto thread = static_cast<std::int64_t>(omp_get_thread_num());
        const std::int64_t first = n * thread / threads, last = n * (thread + 1) / threads;
        RowScratch scratch(static_cast<std::size_t>(n));
        std::vector<int> block_columns;
        std::vector<double> block_values;
        for (std::int64_t v = first; v < last; ++v) {
            gather_row(mesh, incidence, elements, static_cast<std::size_t>(v), scratch);
            for (const auto& [column, value] : scratch.entries) {
                block_columns.push_back(column);
                block_values.push_back(value);
            }
            row_start[static_cast<std::size_t>(v) + 1] = static_cast<std::int64_t>(scratch.entries.size());
        }
#pragma omp barrier
#pragma omp single
        {
            for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v) row_start[v + 1] += row_start[v];
            too_large = row_start.back() > std::numeric_limits<int>::max();
            if (!too_large) {
                matrix.resizeNonZeros(static_cast<Eigen::Index>(row_start.back()));
                for (std::size_t v = 0; v <= static_cast<std::size_t>(n); ++v)
                    matrix.outerIndexPtr()[v] = static_cast<int>(row_start[v]);
            }
        }
        if (!too_large) {
            const std::int64_t at = row_start[static_cast<std::size_t>(first)];
            std::copy(block_columns.begin(), block_columns.end(), matrix.innerIndexPtr() + at);
            std::copy(block_values.begin(), block_values.end(), matrix.valuePtr() + at);
        }
    }
    if (too_large)
        throw InputError(concat("mesh: ", row_start.back(), " matrix entries exceed the 32-bit index range; split the ",
                                "mesh or coarsen it"));
    return matrix;
}

} // namespace tissuemesh::fem
