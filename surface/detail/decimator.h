// Decimator: the collapse loop of decimate() over one LocalEditor (the whole complex, or one slab of it
// fenced off from the others), with what it carries along: per vertex a quadric, per triangle the input
// vertices it answers for (the distance bound). Used by decimate.cpp only; the loop is in decimator.cpp.
#pragma once

#include <optional>
#include <vector>

#include <OpenMesh/Core/Utils/vector_traits.hh>
#include <OpenMesh/Core/Geometry/QuadricT.hh>
#include <OpenMesh/Core/Geometry/VectorT.hh>

#include "core/progress.h"
#include "surface/decimate.h"
#include "surface/detail/layer_sizing.h"
#include "surface/detail/local_editor.h"
#include "surface/detail/triangle_distance.h"
#include "surface/detail/slabs.h"
#include "surface/detail/vertex_queue.h"

namespace tissuemesh::surface::detail {

using Quadric = OpenMesh::Geometry::QuadricT<double>;

/// What decimation carries along besides the complex: per vertex the quadric of the planes merged into it,
/// per triangle the input vertices it answers for (the distance bound).
struct Carried {
    std::vector<Quadric> quadrics;
    std::vector<std::vector<std::uint32_t>> samples;
};

/// The quadric of each vertex's triangles (area-weighted planes); each vertex its own sample, held by the
/// first triangle around it.
Carried initial_carried(const InterfaceComplex& complex);

/// A slab's share of a decimation in pieces, numbered as the whole complex.
struct Piece {
    std::vector<Triangle> triangles; ///< the alive triangles the slab owns (slabs.h)
    std::vector<LabelPair> sides;
    std::vector<std::vector<std::uint32_t>> samples;         ///< per owned triangle
    std::vector<std::pair<std::uint32_t, Quadric>> quadrics; ///< per alive vertex the slab owns
    std::vector<std::uint32_t> fenced;                       ///< alive vertices whose collapse the fence refused
    DecimateReport report;                                   ///< counts of the slab's collapses and refusals
};

/// Adds the editor's refusal counts to a report.
void add_counters(DecimateReport& report, const EditCounters& counters);

class Decimator {
public:
    /// `cell_mm`: the editor's grid cell, computed before `complex` is moved in. `carried` is indexed like
    /// `complex`. With `slab`, the editor is fenced in (Slab::fence()) and a collapse is tried only when the
    /// triangles around both its ends lie inside the fence (those around the kept end take samples over).
    /// `sizing`: the bound on edge lengths by layer thickness (DecimateOptions::edge_per_thickness; an empty field
    /// gives max_edge_mm everywhere).
    Decimator(InterfaceComplex&& complex, Carried&& carried, double cell_mm, const DecimateOptions& options,
              const LayerSizing& sizing, DecimateReport& report, std::optional<Slab> slab = std::nullopt);

    /// Collapses cheapest first, starting from every vertex or, when given, from `seeds` only (the others
    /// are tried when a collapse changes their neighbourhood).
    void collapse_all(const Progress& progress, const std::vector<std::uint32_t>* seeds = nullptr);

    /// DecimateOptions::contract_block_mm: the patch vertices of each block (cubes of that edge from `origin`, the
    /// same for every slab) and patch, joined by edges, contracted into the one their quadrics place best, where
    /// the editor's checks, the edge bound and the distance bound allow; in the order of the blocks.
    void contract_blocks(const Vec3& origin);

    void split_long_edges();

    InterfaceComplex result() const { return editor_.result(); }

    /// A fenced decimator's share of the whole (numbered through `from_vertex`: per own vertex, its index
    /// in the whole), into `piece`.
    void hand_over(const std::vector<std::uint32_t>& from_vertex, Piece& piece) const;
    const LocalEditor& editor() const { return editor_; }

private:
    /// Size mode: the target edge length for edge ab, the smallest over the tissue pairs around it.
    double target_edge(std::uint32_t a, std::uint32_t b) const;

    /// The cost of collapsing v into w.
    std::optional<double> cost(std::uint32_t v, std::uint32_t w) const;

    /// Allowed targets of v (curve neighbours for curve vertices), cheapest first.
    std::vector<std::pair<double, std::uint32_t>> targets_of(std::uint32_t v) const;

    /// Calls visit(cost, w) for every allowed target w of v (curve neighbours for curve vertices).
    template <class Visit>
    void for_each_target(std::uint32_t v, Visit visit) const;

    /// Queues v with its cheapest collapse that keeps edges within the bound (ties: the lowest target);
    /// cheaper ones that would not are counted as refused by the length and never tried.
    void enqueue(std::uint32_t v);

    /// Queues u, a neighbour of w after the collapse of v into w (`multiplicity`: triangles on edge uw), as
    /// enqueue(u) would. The collapse changed, of u's collapses, only the one into w (w's quadric grew, and
    /// w may be new to u's ring) and removed the one into v; the others keep their costs (the quadrics and
    /// positions they read are unchanged). So unless u's entry went to v or w, or u changed kind, or u was not
    /// queued, the new entry is the cheaper of the old one and the collapse into w: the same entry at a
    /// fraction of the cost (a ring and a quadric per neighbour, seven neighbours per collapse).
    void requeue_neighbour(std::uint32_t u, std::uint32_t v, std::uint32_t w, std::uint32_t multiplicity);

    /// Tries v's collapses cheapest first; returns the target it collapsed into.
    std::optional<std::uint32_t> collapse_cheapest(std::uint32_t v);

    /// Assigns each sample of the `sources` triangles to the nearest of `shapes`; false as soon as one is
    /// further than `bound` (mm). A shape whose bounding sphere is further than the best so far is skipped
    /// (the answer is the same, most closest-point computations are saved).
    bool assign_samples(const std::vector<std::uint32_t>& sources, const std::vector<TriangleCorners>& shapes,
                        std::vector<std::pair<std::size_t, std::uint32_t>>& assignment, double& worst,
                        double bound) const;

    /// Collapses v into w if the editor and the distance bound allow it. The bound is asked (through the
    /// editor's veto, after its cheap local checks) of the triangles around w after the collapse.
    bool collapse(std::uint32_t v, std::uint32_t w);

    /// Whether the collapse of v into w leaves every new edge at w (from a neighbour of v that is none of w)
    /// no longer than max_edge_mm and 4/3 of the layer sizing at its midpoint, or no longer than the edge to v
    /// it replaces.
    bool keeps_edges_short(std::uint32_t v, std::uint32_t w) const;

    /// keeps_edges_short() with the ring of v already in ring_.
    bool short_enough(std::uint32_t v, std::uint32_t w) const;

    /// Contracts `cluster` into r (LocalEditor::try_contract) if the edge and distance bounds allow it.
    bool contract(const std::vector<std::uint32_t>& cluster, std::uint32_t r);

    /// After a split at m, each sample of the split triangles goes to the nearer half.
    void redistribute_samples(std::uint32_t m);

    const DecimateOptions& options_;
    const LayerSizing& sizing_;
    DecimateReport& report_;
    LocalEditor editor_;
    std::vector<Quadric> quadrics_;
    std::vector<std::vector<std::uint32_t>> samples_;
    std::optional<Slab> slab_;          ///< the slab this decimator works on, if any (its fence is the editor's)
    std::vector<std::uint32_t> fenced_; ///< vertices whose collapse the fence refused (repeats possible)
    VertexQueue queue_;                 ///< per vertex its cheapest collapse
    mutable std::vector<LocalEditor::RingEntry> ring_; ///< scratch of for_each_target()
    std::vector<std::pair<double, std::uint32_t>> enqueue_scratch_;
    std::vector<std::uint32_t> targets_, sources_; ///< scratch of collapse()
    std::vector<std::pair<std::size_t, std::uint32_t>> assignment_;
    std::vector<TriangleCorners> shapes_;
    mutable std::vector<std::pair<Vec3, double>> spheres_; ///< scratch of assign_samples()
    std::vector<LocalEditor::RingEntry> around_;           ///< scratch of collapse_all()
};

} // namespace tissuemesh::surface::detail
