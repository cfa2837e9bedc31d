#include "volume/improve_mesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <map>
#include <queue>

#include "core/error.h"
#include "core/tet_shape.h"
#include "volume/check_mesh.h"
#include "volume/detail/flips.h"
#include "volume/detail/insert_node.h"
#include "volume/detail/interface_flip.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/surface_reference.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume {
namespace {

using detail::WorkMesh;

/// A tet waiting to be improved: worst quality first, then lowest slot; `stamp` tells whether it is current.
struct Waiting {
    double quality;
    std::uint32_t tet, stamp;
    bool operator>(const Waiting& other) const
    {
        return quality > other.quality || (quality == other.quality && tet > other.tet);
    }
};
using Queue = std::priority_queue<Waiting, std::vector<Waiting>, std::greater<>>;
constexpr std::uint32_t never = ~0u;

/// What improved a tet.
enum class Change { none, edge_removal, face_removal, interface_flip, move, insertion };

/// The schedule: passes over the tets below the target, worst first, each tet trying flips, then smoothing of
/// its nodes, then (from the second pass on, for the tets below the insertion bar) node insertion. The first
/// change that raises the local minimum is kept; tets it makes or reshapes below the target join the queue.
class Improver {
public:
    Improver(TetMesh& mesh, const detail::SurfaceReference& reference, const ImproveOptions& options,
             ImproveReport& report)
        : mesh_(mesh), work_(mesh), reference_(reference), options_(options), report_(report),
          target_(detail::sine_of_deg(options.target_dihedral_deg)),
          insert_bar_(detail::sine_of_deg(std::min(options.insert_below_deg, options.target_dihedral_deg))),
          // Never quite zero: a node moving in a flat patch leaves its faces there up to rounding.
          face_tolerance_mm_((options.max_face_deviation + 1e-9) * reference.mean_edge_mm()),
          start_volumes_(work_.tissue_volumes())
    {
    }

    void run(const Progress& progress)
    {
        for (std::size_t pass = 0; pass < options_.max_passes; ++pass) {
            const bool insert = pass > 0 && options_.insert;
            const std::size_t changes = run_pass(insert);
            ++report_.passes;
            progress.update("improve", static_cast<double>(pass + 1) / static_cast<double>(options_.max_passes));
            std::size_t below = 0;
            for (std::uint32_t t = 0; t < work_.tet_slots(); ++t) below += work_.alive(t) && work_.quality(t) < target_;
            progress.debug("improve",
                           concat("pass ", pass + 1, ": ", changes, " changes, ", below, " tets below the target"));
            if (changes == 0 && (insert || !options_.insert)) break;
        }
        mesh_ = work_.result();
    }

private:
    std::size_t run_pass(bool insert)
    {
        Queue queue;
        for (std::uint32_t t = 0; t < work_.tet_slots(); ++t)
            if (work_.alive(t) && work_.quality(t) < target_) queue.push({work_.quality(t), t, work_.stamp(t)});
        // Each tet is tried once a pass (a reshaped tet is the same tet; a new one in a reused slot is not).
        std::vector<std::uint32_t> tried(work_.tet_slots(), never);
        std::size_t changes = 0;
        while (!queue.empty()) {
            const Waiting w = queue.top();
            queue.pop();
            if (!work_.alive(w.tet) || work_.stamp(w.tet) != w.stamp) continue;
            if (w.tet >= tried.size()) tried.resize(work_.tet_slots(), never);
            if (tried[w.tet] == work_.birth(w.tet)) continue;
            tried[w.tet] = work_.birth(w.tet);
            if (unchanged_since_failure(w.tet, insert ? 2 : 1)) continue;
            // Flips and smoothing that failed on this tet with nothing changed around it since fail again: only
            // insertion is new to it.
            const bool local_failed = unchanged_since_failure(w.tet, 1);
            const std::size_t nodes = work_.node_count();
            const Change change = improve(w.tet, insert, local_failed);
            if (change == Change::none || !volumes_kept() || !tets_within_bounds()) {
                work_.rollback(0);
                if (failed_.size() < work_.tet_slots()) failed_.resize(work_.tet_slots());
                failed_[w.tet] = {work_.birth(w.tet), clock_, insert ? 2 : 1};
                continue;
            }
            count(change, nodes);
            ++changes;
            work_.commit();
            ++clock_;
            node_changed_.resize(work_.node_count(), 0), node_tried_.resize(work_.node_count(), -1);
            for (const std::uint32_t t : work_.take_touched()) {
                if (!work_.alive(t)) continue;
                for (const std::uint32_t v : work_.tet(t)) node_changed_[v] = clock_;
                if (work_.quality(t) < target_) queue.push({work_.quality(t), t, work_.stamp(t)});
            }
        }
        work_.take_touched();
        return changes;
    }

    Change improve(std::uint32_t t, bool insert, bool only_insert)
    {
        const Tet tet = work_.tet(t);
        if (options_.flip && !only_insert) {
            for (const auto& e : detail::edge_corners)
                if (detail::remove_edge(work_, tet[e[0]], tet[e[1]])) return Change::edge_removal;
            if (options_.move_interface_nodes)
                for (const auto& e : detail::edge_corners)
                    if (detail::flip_interface_edge(work_, tet[e[0]], tet[e[1]], reference_, face_tolerance_mm_))
                        return Change::interface_flip;
            for (int i = 0; i < 4; ++i)
                if (detail::remove_faces(work_, t, i)) return Change::face_removal;
        }
        if (options_.smooth && !only_insert) {
            node_changed_.resize(work_.node_count(), 0), node_tried_.resize(work_.node_count(), -1);
            for (const std::uint32_t v : tet) {
                if (!options_.move_interface_nodes && work_.kind(v) != detail::NodeKind::interior) continue;
                // A node that could not be moved stays so until something around it changes.
                if (node_tried_[v] >= node_changed_[v]) continue;
                if (detail::smooth_node(work_, v, reference_, face_tolerance_mm_)) return Change::move;
                node_tried_[v] = clock_;
            }
        }
        if (insert && work_.quality(t) < insert_bar_ && !insertion_tried(t) &&
            detail::insert_for_tet(work_, t, reference_, options_.insert_on_interfaces, face_tolerance_mm_))
            return Change::insertion;
        return Change::none;
    }

    void count(Change change, std::size_t nodes_before)
    {
        switch (change) {
        case Change::edge_removal: ++report_.edges_removed; break;
        case Change::face_removal: ++report_.faces_removed; break;
        case Change::interface_flip: ++report_.interface_edges_flipped; break;
        case Change::move: ++report_.smoothed_nodes; break;
        case Change::insertion:
            for (auto v = static_cast<std::uint32_t>(nodes_before); v < work_.node_count(); ++v)
                ++(work_.kind(v) == detail::NodeKind::interior ? report_.nodes_inserted
                                                               : report_.nodes_inserted_on_interfaces);
            break;
        case Change::none: break;
        }
    }

    /// Whether the tets the edit made or reshaped keep the volume bounds (ImproveOptions::max_tet_volume_mm3).
    bool tets_within_bounds() const
    {
        if (!(options_.max_tet_volume_mm3 > 0) && options_.max_tet_volume_per_tissue_mm3.empty()) return true;
        const double none = std::numeric_limits<double>::infinity();
        return work_.changed_tets_within(0, [&](Label label) {
            const auto it = options_.max_tet_volume_per_tissue_mm3.find(label);
            if (it != options_.max_tet_volume_per_tissue_mm3.end()) return it->second;
            return options_.max_tet_volume_mm3 > 0 ? options_.max_tet_volume_mm3 : none;
        });
    }

    /// Whether every tissue's volume is within the allowed change of its start, or no further from it than at the
    /// last commit (interface moves and splits on curved patches change volumes a little; flips never do).
    bool volumes_kept()
    {
        bool kept = true;
        for (const auto& [label, volume] : work_.tissue_volumes()) {
            const double from = start_volumes_.count(label) ? start_volumes_.at(label) : 0;
            const double drift = std::abs(volume - from), allowed = options_.max_volume_change * std::abs(from);
            if (drift > allowed && drift > committed_drift_[label] + 1e-12 * std::abs(from)) kept = false;
        }
        if (kept)
            for (const auto& [label, volume] : work_.tissue_volumes())
                committed_drift_[label] =
                    std::abs(volume - (start_volumes_.count(label) ? start_volumes_.at(label) : 0));
        return kept;
    }

    /// Whether insertion was tried for this tet (slot and birth) before; marks it tried. Insertion costs a
    /// dozen trials, so each tet gets one, however its neighbours change.
    bool insertion_tried(std::uint32_t t)
    {
        if (insertion_tried_.size() < work_.tet_slots()) insertion_tried_.resize(work_.tet_slots(), never);
        if (insertion_tried_[t] == work_.birth(t)) return true;
        insertion_tried_[t] = work_.birth(t);
        return false;
    }

    /// Whether every operation of `level` failed on t before and nothing around it changed since.
    bool unchanged_since_failure(std::uint32_t t, int level) const
    {
        if (t >= failed_.size() || failed_[t].birth != work_.birth(t) || failed_[t].level < level) return false;
        const Tet& tet = work_.tet(t);
        return std::all_of(tet.begin(), tet.end(), [&](std::uint32_t v) {
            return v >= node_changed_.size() || node_changed_[v] <= failed_[t].clock;
        });
    }

    TetMesh& mesh_;
    WorkMesh work_;
    const detail::SurfaceReference& reference_;
    const ImproveOptions& options_;
    ImproveReport& report_;
    double target_, insert_bar_, face_tolerance_mm_;
    std::map<Label, double> start_volumes_, committed_drift_;
    std::int64_t clock_ = 0;                 ///< commits so far
    std::vector<std::int64_t> node_changed_; ///< per node: the commit that last changed a tet around it
    std::vector<std::int64_t> node_tried_;   ///< per node: the clock of its last failed smoothing (-1: none)
    /// Per tet slot: the tet (birth) on which every operation of a level (1: flips and smoothing, 2: also
    /// insertion) failed, and when.
    struct Failure {
        std::uint32_t birth = never;
        std::int64_t clock = 0;
        int level = 0;
    };
    std::vector<Failure> failed_;
    std::vector<std::uint32_t> insertion_tried_; ///< per tet slot: the birth insertion was tried for
};

void validate(const TetMesh& mesh, const ImproveOptions& options)
{
    validate_indices(mesh, "mesh");
    if (!(options.target_dihedral_deg > 0 && options.target_dihedral_deg <= 70))
        throw InputError(concat("target dihedral angle ", options.target_dihedral_deg,
                                " deg is outside (0, 70]; a regular "
                                "tetrahedron has 70.5 deg; the default is 22"));
    if (!(options.max_face_deviation >= 0 && options.max_face_deviation <= 1))
        throw InputError(concat("face deviation ", options.max_face_deviation,
                                " is outside [0, 1]; it is a fraction of the "
                                "reference surface's mean edge (0.03 is the default)"));
    if (!(options.max_volume_change >= 0 && options.max_volume_change <= 1))
        throw InputError(concat("volume change ", options.max_volume_change,
                                " is outside [0, 1]; it is a fraction of each "
                                "tissue's volume (2e-4 is the default)"));
    if (!(options.max_tet_volume_mm3 >= 0 && std::isfinite(options.max_tet_volume_mm3)))
        throw InputError(
            concat("tet volume bound ", options.max_tet_volume_mm3, " mm^3 is not a finite number >= 0 (0: no bound)"));
    for (const auto& [tissue, bound] : options.max_tet_volume_per_tissue_mm3)
        if (!(bound > 0 && std::isfinite(bound)))
            throw InputError(concat("tet volume bound ", bound, " mm^3 for tissue ", tissue,
                                    " is not a finite "
                                    "positive number"));
}

/// Builds the reference with `make_reference` and improves `mesh` against it, timing both.
template <class MakeReference>
ImproveReport run(TetMesh& mesh, MakeReference make_reference, const ImproveOptions& options, const Progress& progress)
{
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    const detail::SurfaceReference reference = make_reference();
    ImproveReport report;
    report.before = shape_figures(mesh);
    Improver(mesh, reference, options, report).run(progress);
    report.after = shape_figures(mesh);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    return report;
}

} // namespace

ShapeFigures shape_figures(const TetMesh& mesh)
{
    ShapeFigures figures;
    figures.tets = mesh.tets.size();
    if (mesh.tets.empty()) return figures;
    std::vector<double> smallest(mesh.tets.size());
    figures.min_dihedral_deg = 180;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
        const TetShape shape = tet_shape(mesh, t);
        smallest[t] = shape.min_dihedral_deg;
        figures.min_dihedral_deg = std::min(figures.min_dihedral_deg, shape.min_dihedral_deg);
        figures.max_dihedral_deg = std::max(figures.max_dihedral_deg, shape.max_dihedral_deg);
        figures.tets_under_10_deg += shape.min_dihedral_deg < 10;
        figures.tets_under_20_deg += shape.min_dihedral_deg < 20;
    }
    const auto nth = smallest.begin() + static_cast<std::ptrdiff_t>(smallest.size() / 100);
    std::nth_element(smallest.begin(), nth, smallest.end());
    figures.p1_min_dihedral_deg = *nth;
    return figures;
}

ImproveReport improve_mesh(TetMesh& mesh, const InterfaceComplex& surface, const ImproveOptions& options,
                           const Progress& progress)
{
    validate(mesh, options);
    return run(
        mesh, [&] { return detail::SurfaceReference(surface); }, options, progress);
}

ImproveReport improve_mesh(TetMesh& mesh, const ImproveOptions& options, const Progress& progress)
{
    validate(mesh, options);
    return run(
        mesh, [&] { return detail::SurfaceReference(mesh.vertices, mesh.faces, mesh.face_sides); }, options, progress);
}

} // namespace tissuemesh::volume
