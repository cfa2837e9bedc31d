#include "volume/detail/improver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <queue>

#include "core/error.h"
#include "surface/detail/voxel_sides.h"
#include "volume/detail/flips.h"
#include "volume/detail/insert_node.h"
#include "volume/detail/interface_flip.h"
#include "volume/detail/outer_boundary.h"
#include "volume/detail/smooth_node.h"
#include "volume/detail/work_mesh.h"

namespace tissuemesh::volume::detail {
namespace {

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
/// For a tet under rescue_fraction of the target that no edit lifts in the last round's last pass (rescue_pass()), the
/// edits are tried again with the interface faces they make allowed this many times ImproveOptions::max_face_deviation
/// from the reference, one factor after the other. Nodes stay on the reference whatever the factor. 8 since the
/// twenty-fourth session: the usc19-5 head resampled to 0.7 mm (the long group's test) kept a grey-matter sliver
/// of 7.78 degrees at a CSF|grey|white junction that 4 does not lift (11.41 with 8; its faces 0.27 mm off the surface,
/// 0.38 voxel; every Dice the same to the sixth decimal).
constexpr std::array<double, 3> rescue_face_factors{2, 4, 8};

/// What improved a tet.
enum class Change { none, edge_removal, face_removal, interface_flip, move, insertion };

/// The schedule: passes over the tets below the target, worst first, each tet trying flips, then smoothing of
/// its nodes, then (from the second pass on, for the tets below the insertion bar) node insertion. The first
/// change that raises the local minimum is kept; tets it makes or reshapes below the target join the queue.
class Improver {
public:
    /// Nodes flagged in `frozen` never change (WorkMesh); with `seeds` (per node), only tets at a flagged node
    /// are queued at the start of a pass (tets the edits make or reshape join as always).
    /// `allowance` and `last`: as improve_in_place()'s volume_allowance_mm3 and last.
    Improver(TetMesh& mesh, const SurfaceReference& reference, const surface::detail::VoxelSides* sides,
             const ImproveOptions& options, ImproveReport& report, std::vector<char> frozen, std::vector<char> seeds,
             const std::map<Label, double>& allowance, bool last)
        : mesh_(mesh), work_(mesh, std::move(frozen)), outer_(work_), seeds_(std::move(seeds)), reference_(reference),
          sides_(sides), last_(last), options_(options), report_(report),
          target_(sine_of_deg(options.target_dihedral_deg)),
          insert_bar_(sine_of_deg(std::min(options.insert_below_deg, options.target_dihedral_deg))),
          // Never quite zero: a node moving in a flat patch leaves its faces there up to rounding.
          face_tolerance_mm_((options.max_face_deviation + 1e-9) * reference.mean_edge_mm()),
          start_volumes_(work_.tissue_volumes())
    {
        for (const auto& [label, volume] : start_volumes_) {
            const auto it = allowance.find(label);
            allowed_drift_[label] = it != allowance.end() ? it->second : options.max_volume_change * std::abs(volume);
        }
    }

    void run(const Progress& progress)
    {
        for (std::size_t pass = 0; pass < options_.max_passes; ++pass) {
            const auto start = std::chrono::steady_clock::now();
            const bool insert = pass > 0 && options_.insert;
            const std::size_t changes = run_pass(insert);
            ++report_.passes;
            progress.update("improve", static_cast<double>(pass + 1) / static_cast<double>(options_.max_passes));
            std::size_t below = 0;
            for (std::uint32_t t = 0; t < work_.tet_slots(); ++t) below += work_.alive(t) && work_.quality(t) < target_;
            progress.debug("improve",
                           concat("pass ", pass + 1, ": ", changes, " changes, ", below, " tets below the target, ",
                                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                                  " s"));
            if (changes == 0 && (insert || !options_.insert)) break;
        }
        if (sides_ != nullptr || last_) rescue_pass(progress);
        mesh_ = work_.result();
    }

private:
    /// With the voxels judging interface edits (sides_), or in the last round (last_), one more pass over the tets left
    /// under a bar, every memory of earlier failures dropped (they may have been the voxels' refusals):
    /// - for the tets under waiver_fraction of the target the voxels are not asked. The floor is 10 degrees,
    ///   and a few edits cost the Dice and the surface little. A safety net: the 1 mm usc19-5 head's tm-tetra mesh
    ///   kept one of 8.37 degrees when the voxels were judged only after the tet's first edit.
    /// - in the last round the bar is rescue_fraction of the target, and a tet under it that no edit lifts gets its
    ///   edits again with the faces allowed further from the reference (rescue_face_factors; the voxels still asked
    ///   above the waiver). The head resampled to 0.7 mm kept a sliver of 8.92 degrees between two junction curves 0.9
    ///   mm apart whose interface flip moves the faces 3.6 times max_face_deviation (0.165 mm, a quarter voxel; it is
    ///   lifted to 11.04 degrees, no Dice changed). Until the twenty-third session the bar was half the target, and
    ///   tets of 11-17 degrees that the factors lift were left (improver.h, rescue_fraction).
    void rescue_pass(const Progress& progress)
    {
        const double target = options_.target_dihedral_deg, waiver = sine_of_deg(waiver_fraction * target);
        const double high = sine_of_deg(rescue_fraction * target);
        std::size_t under_high = 0, under_waiver = 0;
        for (std::uint32_t t = 0; t < work_.tet_slots(); ++t)
            if (work_.alive(t)) under_high += work_.quality(t) < high, under_waiver += work_.quality(t) < waiver;
        const double bar = last_ ? sine_of_deg(last_round_bar_deg(under_high, work_.tet_count(), target)) : waiver;
        if ((bar > waiver ? under_high : under_waiver) == 0) return;
        failed_.clear(), insertion_tried_.clear();
        std::fill(node_tried_.begin(), node_tried_.end(), -1);
        waived_below_ = waiver, rescued_below_ = bar;
        const std::size_t changes = run_pass(options_.insert, bar);
        waived_below_ = 0, rescued_below_ = 0;
        progress.debug("improve", concat("pass for the tets under ", bar, " (sine), the voxels not asked under ",
                                         waiver, ": ", changes, " changes"));
    }

    /// One pass over the tets below `below` (the target by default), worst first; the number of changes kept.
    std::size_t run_pass(bool insert, double below = -1)
    {
        if (below < 0) below = target_;
        Queue queue;
        for (std::uint32_t t = 0; t < work_.tet_slots(); ++t)
            if (work_.alive(t) && work_.quality(t) < below && seeded(t))
                queue.push({work_.quality(t), t, work_.stamp(t)});
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
            improving_ = work_.quality(w.tet);
            Change change = improve(w.tet, insert, local_failed);
            // A tet the last pass takes on that no edit lifts gets them again with the faces allowed further from the
            // reference (rescue_face_factors).
            for (std::size_t k = 0;
                 last_ && change == Change::none && improving_ < rescued_below_ && k < rescue_face_factors.size();
                 ++k) {
                work_.rollback(0);
                // Every edit again: the failed moves and the insertion tried are remembered.
                for (const std::uint32_t v : work_.tet(w.tet))
                    if (v < node_tried_.size()) node_tried_[v] = -1;
                if (w.tet < insertion_tried_.size()) insertion_tried_[w.tet] = never;
                face_factor_ = rescue_face_factors[k];
                change = improve(w.tet, insert, false);
                face_factor_ = 1;
            }
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

    /// Whether t has a frozen node. No node is inserted for such a tet: many of its edits are barred, insertion
    /// costs a dozen trials, and the bands around the faces between mesh parts, where none of its nodes is frozen,
    /// take it on with every edit (improve_mesh.cpp).
    bool at_frozen(std::uint32_t t) const
    {
        const Tet& tet = work_.tet(t);
        return std::any_of(tet.begin(), tet.end(), [&](std::uint32_t v) { return work_.frozen(v); });
    }

    bool seeded(std::uint32_t t) const
    {
        if (seeds_.empty()) return true;
        const Tet& tet = work_.tet(t);
        return std::any_of(tet.begin(), tet.end(), [&](std::uint32_t v) { return v < seeds_.size() && seeds_[v]; });
    }

    Change improve(std::uint32_t t, bool insert, bool only_insert)
    {
        const Tet tet = work_.tet(t);
        if (options_.flip && !only_insert) {
            // Edge and face removal change no interface face; an interface flip the voxels refuse is undone and the
            // next edit tried.
            for (const auto& e : edge_corners)
                if (remove_edge(work_, tet[e[0]], tet[e[1]])) return Change::edge_removal;
            if (options_.move_interface_nodes)
                for (const auto& e : edge_corners) {
                    const std::size_t mark = work_.mark();
                    if (flip_interface_edge(work_, tet[e[0]], tet[e[1]], reference_,
                                            face_factor_ * face_tolerance_mm_) &&
                        kept_at_interfaces(mark))
                        return Change::interface_flip;
                }
            for (int i = 0; i < 4; ++i)
                if (remove_faces(work_, t, i)) return Change::face_removal;
        }
        if (options_.smooth && !only_insert) {
            node_changed_.resize(work_.node_count(), 0), node_tried_.resize(work_.node_count(), -1);
            // Inner nodes first, then nodes on patches, then on junction curves: the order of how often a move
            // succeeds, and of its freedom (1 mm usc19-5 head: 81%, 39% and 10% of the trials; the improver 5.0 ->
            // 4.8 s with fewer tets left under 20 degrees, 283 -> 216).
            Tet order = tet;
            std::stable_sort(order.begin(), order.end(),
                             [&](std::uint32_t a, std::uint32_t b) { return work_.kind(a) < work_.kind(b); });
            for (const std::uint32_t v : order) {
                if (!options_.move_interface_nodes && work_.kind(v) != NodeKind::interior) continue;
                // A node that could not be moved stays so until something around it changes.
                if (node_tried_[v] >= node_changed_[v]) continue;
                const std::size_t mark = work_.mark();
                if (smooth_node(work_, v, reference_, face_factor_ * face_tolerance_mm_) && kept_at_interfaces(mark))
                    return Change::move;
                node_tried_[v] = clock_;
            }
        }
        if (insert && work_.quality(t) < insert_bar_ && !at_frozen(t) && !insertion_tried(t)) {
            // Each candidate is judged as it is tried: one the voxels refuse leaves the others their chance (judged
            // once, after the best was chosen, a refused best failed the tet: the liver's worst tet with
            // tm-tetra --layer-points).
            if (insert_for_tet(work_, t, reference_, options_.insert_on_interfaces, face_factor_ * face_tolerance_mm_,
                               [&](std::size_t mark) { return kept_at_interfaces(mark); }))
                return Change::insertion;
        }
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
                ++(work_.kind(v) == NodeKind::interior ? report_.nodes_inserted : report_.nodes_inserted_on_interfaces);
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

    /// Whether the edit since `mark` keeps the outer boundary from crossing itself and, judged by the voxels, the
    /// interfaces from carrying a voxel centre across; if not, it is undone.
    bool kept_at_interfaces(std::size_t mark)
    {
        if (!outer_.clear_since(work_, mark)) {
            ++report_.refused_crossing_boundary;
            work_.rollback(mark);
            return false;
        }
        return kept_by_voxels(mark);
    }

    /// Whether the interface faces the edit since `mark` changed sweep no voxel centre next to another label (when
    /// judged by voxels): such a centre would change sides, and the Dice against the voxels fall. If one does, the
    /// edit is undone, so that the tet's next edit may be tried (judged only once the first edit that worked was
    /// chosen, a refused move of one node left the tet's other nodes and edits untried: the liver's smallest angle
    /// 10.72 degrees, now 14.58).
    bool kept_by_voxels(std::size_t mark)
    {
        if (sides_ == nullptr || improving_ < waived_below_) return true;
        work_.swept_faces(mark, swept_before_, swept_after_);
        if (swept_before_.empty() && swept_after_.empty()) return true;
        if (!sides_->carries_a_centre(swept_before_, swept_after_)) return true;
        ++report_.refused_by_voxels;
        work_.rollback(mark);
        return false;
    }

    /// Whether every tissue's volume is within the allowed change of its start, or no further from it than at the
    /// last commit (interface moves and splits on curved patches change volumes a little; flips never do).
    bool volumes_kept()
    {
        bool kept = true;
        for (const auto& [label, volume] : work_.tissue_volumes()) {
            const double from = start_volumes_.count(label) ? start_volumes_.at(label) : 0;
            const double drift = std::abs(volume - from),
                         allowed = allowed_drift_.count(label) ? allowed_drift_.at(label) : 0;
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
    OuterBoundary outer_; ///< the outer boundary's faces, so that no edit makes it cross itself
    std::vector<char> seeds_;
    const SurfaceReference& reference_;
    const surface::detail::VoxelSides* sides_;
    bool last_; ///< no round follows this one (improve_in_place())
    std::vector<surface::detail::TriangleCorners> swept_before_, swept_after_;
    double face_factor_ = 1;   ///< ImproveOptions::max_face_deviation times this bounds the faces an edit makes
    double improving_ = 0;     ///< the quality of the tet being improved
    double waived_below_ = 0;  ///< the voxels are not asked for tets below this quality (rescue_pass())
    double rescued_below_ = 0; ///< a tet below this quality that no edit lifts gets rescue_face_factors (last_)
    const ImproveOptions& options_;
    ImproveReport& report_;
    double target_, insert_bar_, face_tolerance_mm_;
    std::map<Label, double> start_volumes_, committed_drift_;
    std::map<Label, double> allowed_drift_;  ///< per tissue, how far its volume may drift from start_volumes_ (mm^3)
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

} // namespace

void improve_in_place(TetMesh& mesh, const SurfaceReference& reference, const surface::detail::VoxelSides* sides,
                      const ImproveOptions& options, ImproveReport& report, std::vector<char> frozen,
                      std::vector<char> seeds, const std::map<Label, double>& volume_allowance_mm3, bool last,
                      const Progress& progress)
{
    Improver(mesh, reference, sides, options, report, std::move(frozen), std::move(seeds), volume_allowance_mm3, last)
        .run(progress);
}

} // namespace tissuemesh::volume::detail
