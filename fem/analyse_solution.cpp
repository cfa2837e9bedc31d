#include "fem/analyse_solution.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <ctime>

#include "core/tet_shape.h"
#include "fem/estimate_error.h"

namespace tissuemesh::fem {
namespace {

/// Times consecutive parts: each lap() returns the time since the last one.
class PartClock {
public:
    PartSeconds lap()
    {
        const auto now = std::chrono::steady_clock::now();
        const std::clock_t cpu_now = std::clock();
        const PartSeconds part{std::chrono::duration<double>(now - last_).count(),
                               static_cast<double>(cpu_now - last_cpu_) / CLOCKS_PER_SEC};
        last_ = now, last_cpu_ = cpu_now;
        return part;
    }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
    std::clock_t last_cpu_ = std::clock();
};

/// Per tissue: tets, volume, and the volume-weighted sums of |E| and |J| turned into means (tets in order, so
/// the sums do not depend on the thread count).
std::map<Label, TissueFieldStatistics> tissue_statistics(const TetMesh& mesh, const TetFields& fields,
                                                         const std::vector<double>& e_magnitude)
{
    struct Sums {
        double e_volume = 0, j_volume = 0;
    };
    std::map<Label, TissueFieldStatistics> tissues;
    std::map<Label, Sums> sums;
    for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
        TissueFieldStatistics& tissue = tissues[mesh.tet_labels[t]];
        Sums& sum = sums[mesh.tet_labels[t]];
        const double volume = signed_volume(mesh, t), e = e_magnitude[t];
        ++tissue.tets;
        tissue.volume_mm3 += volume;
        sum.e_volume += volume * e;
        tissue.max_e_v_per_m = std::max(tissue.max_e_v_per_m, e);
        sum.j_volume += volume * norm(fields.current_a_per_m2[t]);
    }
    for (auto& [label, tissue] : tissues) {
        tissue.mean_e_v_per_m = sums[label].e_volume / tissue.volume_mm3;
        tissue.mean_j_a_per_m2 = sums[label].j_volume / tissue.volume_mm3;
    }
    return tissues;
}

double min_dihedral_deg(const TetMesh& mesh)
{
    double smallest = 180;
    const auto count = static_cast<std::int64_t>(mesh.tet_count());
#pragma omp parallel for schedule(static) reduction(min : smallest)
    for (std::int64_t t = 0; t < count; ++t)
        smallest = std::min(smallest, tet_shape(mesh, static_cast<std::size_t>(t)).min_dihedral_deg);
    return smallest;
}

} // namespace

SolutionAnalysis analyse_solution(const TetMesh& mesh, const Conductivities& conductivities,
                                  const std::vector<double>& potential_v, const AnalysisOptions& options)
{
    SolutionAnalysis out;
    PartClock clock;
    out.fields = compute_fields(mesh, conductivities, potential_v);
    out.e_magnitude_v_per_m.reserve(out.fields.electric_v_per_m.size());
    for (const Vec3& e : out.fields.electric_v_per_m) out.e_magnitude_v_per_m.push_back(norm(e));
    out.fields_time = clock.lap();
    if (options.error_indicator) {
        out.error_indicator = estimate_error(mesh, conductivities, potential_v);
        double sum_of_squares = 0;
        for (const double eta : out.error_indicator) sum_of_squares += eta * eta;
        out.error_indicator_total = std::sqrt(sum_of_squares);
        out.error_indicator_time = clock.lap();
    }
    out.tissues = tissue_statistics(mesh, out.fields, out.e_magnitude_v_per_m);
    out.min_dihedral_deg = min_dihedral_deg(mesh);
    out.statistics_time = clock.lap();
    return out;
}

} // namespace tissuemesh::fem
