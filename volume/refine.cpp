#include "volume/refine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/node_tets.h"
#include "surface/detail/triangle_grid.h"
#include "volume/check_mesh.h"
#include "volume/detail/refine_mesh.h"
#include "volume/detail/refine_placement.h"
#include "volume/mark_interfaces.h"

namespace tissuemesh::volume {
namespace {

/// What refine() keeps of a tet's assessment between rounds.
struct TetState {
    double error_mm3 = 0; ///< error volume for the tet's tissue (an estimate when sampled)
    double key = 0;       ///< quality key, larger = worse
    bool sampled = false; ///< holds no voxel centre: error_mm3 is not in the totals
};

/// Four numbers as a hash key (a grid cell in a Tet).
struct TetKeyHash {
    std::size_t operator()(const Tet& tet) const
    {
        std::uint64_t h = 0;
        for (const std::uint32_t v : tet) h = (h ^ v) * 0x9E3779B97F4A7C15ull;
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

/// Whether `tet` has every node of `nodes` (four distinct nodes: the same tet), to recognise the tets a rebuild
/// left unchanged.
bool holds_all(const Tet& tet, const Tet& nodes)
{
    return std::all_of(nodes.begin(), nodes.end(),
                       [&](std::uint32_t v) { return std::find(tet.begin(), tet.end(), v) != tet.end(); });
}

struct Refinement {
    const LabelImage& image;
    const RefineOptions& options;
    bool constrained;
    TetMesh mesh;
    std::vector<TetState> state; ///< #T, like mesh.tets
};

/// Constrained mode: the interface faces of `mesh` (they never change, nor do their nodes), to keep new nodes
/// off them; reads `mesh` (kept by reference) on every query.
/// A node placed closer to an interface than the node spacing adds nothing the interface does not already
/// give, makes slivers against the face, and can make TetGen's -Y boundary recovery fail: on the demo's
/// sphere head, nodes within 1e-3 mm of faces crashed TetGen 1.5 (suppresssteinerpoints) in the third round.
class InterfaceClearance {
public:
    InterfaceClearance(const TetMesh& mesh, double clearance_mm) : mesh_(mesh), clearance_mm_(clearance_mm)
    {
        if (mesh.faces.empty() || clearance_mm <= 0) return;
        surface::detail::Box3 bounds{mesh.vertices[mesh.faces[0][0]], mesh.vertices[mesh.faces[0][0]]};
        for (const Triangle& face : mesh.faces) {
            const surface::detail::Box3 box = surface::detail::bounding_box(corners(face));
            for (int a = 0; a < 3; ++a)
                bounds.low[a] = std::min(bounds.low[a], box.low[a]),
                bounds.high[a] = std::max(bounds.high[a], box.high[a]);
        }
        grid_ = surface::detail::TriangleGrid(bounds, 2 * clearance_mm, mesh.faces.size());
        for (std::size_t f = 0; f < mesh.faces.size(); ++f)
            grid_.insert(static_cast<std::uint32_t>(f), surface::detail::bounding_box(corners(mesh.faces[f])));
    }

    /// True when `p` is at least the clearance away from every interface face.
    bool clear(const Vec3& p)
    {
        if (mesh_.faces.empty() || clearance_mm_ <= 0) return true;
        const Vec3 margin{clearance_mm_, clearance_mm_, clearance_mm_};
        grid_.query({p - margin, p + margin}, found_);
        return std::all_of(found_.begin(), found_.end(), [&](std::uint32_t f) {
            return distance(p, surface::detail::closest_point_on_triangle(p, corners(mesh_.faces[f]))) >= clearance_mm_;
        });
    }

private:
    surface::detail::TriangleCorners corners(const Triangle& face) const
    {
        return {mesh_.vertices[face[0]], mesh_.vertices[face[1]], mesh_.vertices[face[2]]};
    }

    const TetMesh& mesh_;
    double clearance_mm_;
    surface::detail::TriangleGrid grid_;
    std::vector<std::uint32_t> found_;
};

/// Assesses the tets listed in `which` (all nodes kept, so rasterization's tie rule sees the same faces as
/// in the whole mesh). Delaunay-only: each takes its majority tissue.
void assess_tets(Refinement& r, const std::vector<std::uint32_t>& which)
{
    if (which.empty()) return;
    TetMesh part;
    part.vertices = r.mesh.vertices;
    for (const std::uint32_t t : which)
        part.tets.push_back(r.mesh.tets[t]), part.tet_labels.push_back(r.mesh.tet_labels[t]);
    const Assessment a = assess_elements(part, r.image, r.options.assess);
    const double per_voxel = r.options.assess.error_weight / r.image.voxel_volume_mm3();
    for (std::size_t k = 0; k < which.size(); ++k) {
        TetState& s = r.state[which[k]];
        s.sampled = a.sampled[k] != 0;
        s.error_mm3 = a.error_volume_mm3[k];
        s.key = a.quality_key[k];
        if (!r.constrained) {
            // The key's error term, moved from the placeholder tissue to the majority.
            r.mesh.tet_labels[which[k]] = a.majority[k];
            s.key -= per_voxel * (a.error_volume_mm3[k] - a.majority_error_volume_mm3[k]);
            s.error_mm3 = a.majority_error_volume_mm3[k];
        }
    }
}

/// Carries the state of unchanged tets over from `old` and assesses the new ones; returns how many.
std::size_t reassess(Refinement& r, const TetMesh& old, const std::vector<TetState>& old_state)
{
    // A new tet with an old one's nodes (old nodes keep their numbers) is that tet: found among the old tets at its
    // smallest node, the first of them in order, side by side.
    const NodeTets around = node_tets(old);
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> match(r.mesh.tets.size(), none);
    const auto count = static_cast<std::int64_t>(r.mesh.tets.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t) {
        const Tet& tet = r.mesh.tets[static_cast<std::size_t>(t)];
        const std::uint32_t lowest = *std::min_element(tet.begin(), tet.end());
        if (lowest >= old.vertices.size()) continue;
        for (std::size_t k = around.offsets[lowest]; k < around.offsets[lowest + 1]; ++k)
            if (holds_all(old.tets[around.tets[k]], tet)) {
                match[static_cast<std::size_t>(t)] = around.tets[k];
                break;
            }
    }
    r.state.assign(r.mesh.tets.size(), {});
    std::vector<std::uint32_t> changed;
    for (std::size_t t = 0; t < r.mesh.tets.size(); ++t) {
        if (match[t] == none) {
            changed.push_back(static_cast<std::uint32_t>(t));
            continue;
        }
        r.state[t] = old_state[match[t]];
        r.mesh.tet_labels[t] = old.tet_labels[match[t]];
    }
    assess_tets(r, changed);
    return changed.size();
}

RefineIteration summarize(const Refinement& r, std::size_t iteration)
{
    RefineIteration it;
    it.iteration = iteration, it.nodes = r.mesh.vertices.size(), it.tets = r.mesh.tets.size();
    for (const TetState& s : r.state) {
        if (!s.sampled) it.total_error_volume_mm3 += s.error_mm3;
        it.worst_quality_key = std::max(it.worst_quality_key, s.key);
    }
    return it;
}

/// The tets to refine this round: worst keys first (Delaunay-only: only tets with an error).
std::vector<std::uint32_t> select_batch(const Refinement& r, std::size_t budget)
{
    std::vector<std::uint32_t> candidates;
    for (std::size_t t = 0; t < r.state.size(); ++t)
        if (r.constrained || r.state[t].error_mm3 > 0) candidates.push_back(static_cast<std::uint32_t>(t));
    const auto wanted =
        std::max(r.options.min_batch,
                 static_cast<std::size_t>(std::ceil(r.options.batch_fraction * static_cast<double>(r.state.size()))));
    const std::size_t count = std::min({wanted, budget, candidates.size()});
    std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(count), candidates.end(),
                      [&](std::uint32_t a, std::uint32_t b) {
                          return r.state[a].key > r.state[b].key || (r.state[a].key == r.state[b].key && a < b);
                      });
    candidates.resize(count);
    return candidates;
}

/// New nodes spaced at least `min_distance` apart (and from their tet's corners), with their source tets.
struct NewNodes {
    std::vector<Vec3> points;
    std::vector<std::uint32_t> sources;
};

NewNodes place_batch(const Refinement& r, const std::vector<std::uint32_t>& batch, double min_distance, bool fallback,
                     InterfaceClearance* clearance)
{
    NewNodes nodes;
    std::unordered_map<Tet, std::vector<std::uint32_t>, TetKeyHash> grid; // cell (x, y, z, 0) -> node numbers
    auto cell = [&](const Vec3& p, int dx, int dy, int dz) {
        return Tet{static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(p[0] / min_distance)) + dx),
                   static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(p[1] / min_distance)) + dy),
                   static_cast<std::uint32_t>(static_cast<std::int64_t>(std::floor(p[2] / min_distance)) + dz), 0};
    };
    // Each tet's node by the placement side by side (the tissue-change search is the cost); then in order, each
    // kept where it is free.
    const auto corners_of = [&](std::uint32_t t) {
        std::array<Vec3, 4> corners;
        for (int c = 0; c < 4; ++c) corners[c] = r.mesh.vertices[r.mesh.tets[t][c]];
        return corners;
    };
    std::vector<Vec3> placed(batch.size());
    const auto count = static_cast<std::int64_t>(batch.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t i = 0; i < count; ++i) {
        const auto k = static_cast<std::size_t>(i);
        placed[k] = detail::place_node(r.image, corners_of(batch[k]), r.options.placement, r.options.assess.background,
                                       r.constrained);
    }
    for (std::size_t k = 0; k < batch.size(); ++k) {
        const std::uint32_t t = batch[k];
        const std::array<Vec3, 4> corners = corners_of(t);
        auto is_free = [&](const Vec3& p) {
            bool free = std::all_of(corners.begin(), corners.end(),
                                    [&](const Vec3& c) { return distance(c, p) >= min_distance; });
            for (int d = 0; d < 27 && free; ++d) {
                const auto found = grid.find(cell(p, d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1));
                if (found == grid.end()) continue;
                for (const std::uint32_t other : found->second)
                    free = free && distance(nodes.points[other], p) >= min_distance;
            }
            return free && (clearance == nullptr || clearance->clear(p));
        };
        Vec3 p = placed[k];
        // A tissue change too close to a node: the centroid instead, so that such tets still get refined.
        if (!is_free(p) && fallback)
            p = detail::place_node(r.image, corners, Placement::centroid, r.options.assess.background, r.constrained);
        if (!is_free(p)) continue;
        grid[cell(p, 0, 0, 0)].push_back(static_cast<std::uint32_t>(nodes.points.size()));
        nodes.points.push_back(p);
        nodes.sources.push_back(t);
    }
    return nodes;
}

/// The Delaunay mesh of a lattice over the image's world box (corners included), tissues by majority.
void start_delaunay(Refinement& r)
{
    const auto [low, high] = r.image.world_bounds_mm();
    const double extent = std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2]});
    const double spacing = r.options.initial_spacing_mm > 0 ? r.options.initial_spacing_mm : extent / 4;
    std::array<int, 3> steps;
    for (int a = 0; a < 3; ++a)
        steps[a] = std::max(1, static_cast<int>(std::ceil((high[a] - low[a]) / spacing - 1e-9)));
    for (int k = 0; k <= steps[2]; ++k)
        for (int j = 0; j <= steps[1]; ++j)
            for (int i = 0; i <= steps[0]; ++i) {
                const std::array<int, 3> n{i, j, k};
                Vec3 p;
                for (int a = 0; a < 3; ++a) p[a] = low[a] + (high[a] - low[a]) * n[a] / steps[a];
                r.mesh.vertices.push_back(p);
            }
    r.mesh.names = r.image.names();
    r.mesh.tets = detail::delaunay_tets(r.mesh.vertices);
    r.mesh.tet_labels.assign(r.mesh.tets.size(), r.options.assess.background);
}

void validate(const LabelImage& image, const TetMesh* constrained, const RefineOptions& o)
{
    if (image.empty()) throw InputError("label image is empty; give the image to refine against");
    if (!(o.batch_fraction >= 0 && o.batch_fraction <= 1))
        throw InputError(
            concat("batch fraction ", o.batch_fraction, " is outside 0..1; 0.05 refines the worst 5% per round"));
    for (const double value :
         {o.target_error_mm3, o.target_error_percent, o.initial_spacing_mm, o.min_node_distance_mm})
        if (!(value >= 0) || !std::isfinite(value))
            throw InputError(concat("refinement option value ", value, " is not a finite number >= 0"));
    if (constrained != nullptr) {
        validate_indices(*constrained, "mesh");
        if (constrained->tets.empty()) throw InputError("mesh has no tetrahedra; give a mesh from tm-tetra");
    }
}

std::string stop_reason(const Refinement& r, const RefineReport& report, double mesh_volume, bool* target_reached)
{
    const RefineOptions& o = r.options;
    const RefineIteration& it = report.iterations.back();
    *target_reached =
        (o.target_error_mm3 > 0 && it.total_error_volume_mm3 <= o.target_error_mm3) ||
        (o.target_error_percent > 0 && it.total_error_volume_mm3 <= o.target_error_percent / 100 * mesh_volume);
    if (*target_reached) return "target reached";
    if (it.iteration >= o.max_iterations) return "iteration cap";
    if (o.max_nodes > 0 && it.nodes >= o.max_nodes) return "node budget";
    // Constrained: the error volume is fixed by the interfaces, so only Delaunay-only refinement can stall.
    const std::size_t n = o.max_stalled_rounds;
    if (!r.constrained && n > 0 && report.iterations.size() > n &&
        it.total_error_volume_mm3 >= report.iterations[report.iterations.size() - 1 - n].total_error_volume_mm3)
        return "stalled";
    return "";
}

/// Defects that make a mesh unfit for FEM (tissues across unmarked faces, flat or inverted tets, ...); the
/// quality figures and unused nodes (dropped at the end) do not count.
std::size_t fem_defects(const TetMesh& mesh) { return check_mesh(mesh).tet_defects(); }

enum class RoundResult { refined, no_nodes, rebuild_unfit, rebuild_failed };

/// The constrained rebuild with `nodes` added, retried twice with the first half of the nodes left when TetGen
/// fails (it can crash on a point set: caught in its child process, volume/detail/isolated_call.h; measured on
/// the liver sample, whose first round crashed TetGen 1.6). None, and `failure` said, when every try failed.
std::optional<TetMesh> rebuild(const TetMesh& mesh, NewNodes& nodes, std::string& failure)
{
    for (int attempt = 0; attempt < 3 && !nodes.points.empty(); ++attempt) {
        try {
            return detail::insert_constrained(mesh, nodes.points, nodes.sources);
        } catch (const AlgorithmError& error) {
            failure = error.what();
            nodes.points.resize(nodes.points.size() / 2), nodes.sources.resize(nodes.sources.size() / 2);
        }
    }
    return std::nullopt;
}

/// One round: place nodes in the batch, put them into the mesh (cavities, or a rebuild), reassess. A constrained
/// round whose mesh has more defects than the mesh before (TetGen's rebuild: tets between close interfaces disagreeing
/// on their tissue, the 1 mm usc19-5 head's third round) is undone, and refinement stops there: its output is never
/// less fit for FEM than its input. Cavities cannot make such a defect (they never cross a constraint face and keep
/// every tet positive, exactly); the check stays as the safety net.
RoundResult refine_round(Refinement& r, std::size_t budget, double min_distance, InterfaceClearance* clearance,
                         RefineIteration& it, std::size_t& defects, std::string& failure)
{
    const std::vector<std::uint32_t> batch = select_batch(r, budget);
    // Tissue changes first; only when fewer than a tenth of the batch found a free one, centroids for the rest
    // (measured on spheres4: centroids mixed in from the start cost 10-20% more nodes for the same error).
    NewNodes nodes = place_batch(r, batch, min_distance, false, clearance);
    if (nodes.points.size() * 10 < batch.size()) nodes = place_batch(r, batch, min_distance, true, clearance);
    if (nodes.points.empty()) return RoundResult::no_nodes;
    TetMesh old = r.mesh;
    const std::vector<TetState> old_state = r.state;
    std::size_t added = 0; // the nodes that went in
    if (r.constrained) {
        if (r.options.tetgen_rebuild) {
            std::optional<TetMesh> rebuilt = rebuild(old, nodes, failure);
            if (!rebuilt) return RoundResult::rebuild_failed;
            r.mesh = std::move(*rebuilt);
            added = nodes.points.size(); // a retry keeps the first half
        } else {
            r.mesh = detail::insert_in_cavities(old, nodes.points, nodes.sources, [&](const Vec3& p) {
                return clearance == nullptr || clearance->clear(p);
            });
            added = r.mesh.vertices.size() - old.vertices.size(); // the points a cavity took
            if (added == 0) {
                r.mesh = std::move(old);
                return RoundResult::no_nodes;
            }
        }
        const std::size_t now = fem_defects(r.mesh);
        if (now > defects) {
            r.mesh = std::move(old);
            return RoundResult::rebuild_unfit;
        }
        defects = now;
    } else {
        added = nodes.points.size();
        r.mesh.vertices.insert(r.mesh.vertices.end(), nodes.points.begin(), nodes.points.end());
        r.mesh.tets = detail::delaunay_tets(r.mesh.vertices);
        r.mesh.tet_labels.assign(r.mesh.tets.size(), r.options.assess.background);
    }
    const std::size_t reassessed = reassess(r, old, old_state);
    it = summarize(r, it.iteration + 1);
    it.added_nodes = added, it.reassessed_tets = reassessed;
    return RoundResult::refined;
}

} // namespace

TetMesh refine(const LabelImage& image, const TetMesh* constrained, const RefineOptions& options,
               const Progress& progress, RefineReport* report)
{
    const auto start = std::chrono::steady_clock::now();
    validate(image, constrained, options);
    Refinement r{image, options, constrained != nullptr, constrained ? *constrained : TetMesh{}, {}};
    if (!r.constrained) start_delaunay(r);
    r.state.assign(r.mesh.tets.size(), {});
    std::vector<std::uint32_t> all(r.mesh.tets.size());
    std::iota(all.begin(), all.end(), 0u);
    assess_tets(r, all);
    RefineReport local;
    RefineReport& rep = report != nullptr ? *report : local;
    rep = {};
    for (std::size_t t = 0; t < r.mesh.tets.size(); ++t) rep.mesh_volume_mm3 += signed_volume(r.mesh, t);
    const Vec3& spacing = image.spacing_mm();
    const double min_distance = options.min_node_distance_mm > 0 ? options.min_node_distance_mm
                                                                 : 0.5 * std::min({spacing[0], spacing[1], spacing[2]});
    // The interface faces and their nodes are the same in every round (insert_constrained keeps both), so the
    // grid built from r.mesh now stays right while r.mesh is rebuilt.
    InterfaceClearance clearance(r.mesh, r.constrained ? min_distance : 0);
    RefineIteration it = summarize(r, 0);
    it.reassessed_tets = r.mesh.tets.size();
    std::size_t defects = r.constrained ? fem_defects(r.mesh) : 0;
    for (;;) {
        it.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        rep.iterations.push_back(it);
        progress.info("refine", concat("round ", it.iteration, ": ", it.nodes, " nodes, ", it.tets,
                                       " tets, error volume ", format_mm(it.total_error_volume_mm3, 1),
                                       " mm^3, worst key ", format_mm(it.worst_quality_key, 2)));
        rep.stop_reason = stop_reason(r, rep, rep.mesh_volume_mm3, &rep.target_reached);
        if (!rep.stop_reason.empty()) break;
        const std::size_t budget = options.max_nodes > 0 ? options.max_nodes - it.nodes : r.mesh.tets.size();
        if (!r.constrained && it.total_error_volume_mm3 == 0 &&
            std::none_of(r.state.begin(), r.state.end(), [](const TetState& s) { return s.error_mm3 > 0; })) {
            rep.stop_reason = "no error left";
            break;
        }
        std::string failure;
        const RoundResult round = refine_round(r, budget, min_distance, &clearance, it, defects, failure);
        if (round == RoundResult::no_nodes) {
            rep.stop_reason = "no node could be placed";
            break;
        }
        if (round == RoundResult::rebuild_failed) {
            rep.stop_reason = "the next round's rebuild failed (TetGen)";
            progress.warn("refine", concat("TetGen could not rebuild the next round, with half and a quarter of its "
                                           "nodes too (",
                                           failure, "); the mesh of the round before is the result"));
            break;
        }
        if (round == RoundResult::rebuild_unfit) {
            rep.stop_reason = "the next round's rebuild was not fit for FEM (undone)";
            progress.warn("refine", options.tetgen_rebuild
                                        ? "TetGen's rebuild of the next round left tets disagreeing on their tissue "
                                          "between close interfaces; that round is undone and the mesh of the round "
                                          "before is the result"
                                        : "the next round's mesh was less fit for FEM than the one before (a fault "
                                          "of tm-refine's node insertion: please report it); that round is undone "
                                          "and the mesh of the round before is the result");
            break;
        }
    }
    detail::drop_unused_nodes(r.mesh);
    if (!r.constrained) mark_interfaces(r.mesh, options.assess.background);
    if (options.improve) {
        ImproveOptions improvement = options.improvement;
        if (options.max_nodes > 0) improvement.insert = improvement.insert_on_interfaces = false; // the budget holds
        // Delaunay-only: the interfaces are the labels' staircase faces, no surface worth sliding on; a box mesh of
        // majority tissues would also take nodes by the thousand. Flips and inner moves only.
        if (!r.constrained)
            improvement.insert = improvement.insert_on_interfaces = improvement.move_interface_nodes = false;
        rep.improvement = improve_mesh(r.mesh, improvement, progress);
        rep.improved = true;
        if (improvement.move_interface_nodes || improvement.insert || improvement.insert_on_interfaces)
            rep.improved_error_volume_mm3 =
                assess_elements(r.mesh, image, options.assess, progress).total_error_volume_mm3;
    }
    return std::move(r.mesh);
}

std::string placement_name(Placement placement)
{
    switch (placement) {
    case Placement::centroid: return "centroid";
    case Placement::incentre: return "incentre";
    case Placement::longest_edge: return "longest-edge";
    case Placement::material_half_edges: return "material-half-edges";
    case Placement::material_centroid: return "material-centroid";
    }
    return "centroid";
}

Placement parse_placement(const std::string& name)
{
    for (const Placement p : {Placement::centroid, Placement::incentre, Placement::longest_edge,
                              Placement::material_half_edges, Placement::material_centroid})
        if (placement_name(p) == name) return p;
    throw InputError(concat("unknown placement \"", name,
                            "\"; use centroid, incentre, longest-edge, material-half-edges or "
                            "material-centroid"));
}

} // namespace tissuemesh::volume
