#include "surface/detail/net_smoother.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "surface/detail/edge_fan.h"
#include "surface/detail/local_geometry.h"
#include "surface/detail/rows.h"
#include "surface/detail/star_check.h"
#include "surface/detail/triangle_distance.h"

namespace tissuemesh::surface::detail {

void validate(const NetSmoothOptions& o)
{
    const auto require = [](bool ok, const char* what) {
        if (!ok) throw InputError(concat("surface nets smoothing: ", what));
    };
    require(o.iterations <= 10000, "iterations must be at most 10 000");
    require(o.pairs_per_check >= 1 && o.pairs_per_check <= 100, "pairs per check must lie in [1, 100]");
    require(o.lambda > 0 && o.lambda <= 1, "lambda must lie in (0, 1]");
    require(o.mu < -o.lambda && o.mu >= -1, "mu must lie in [-1, -lambda) (Taubin: |mu| > lambda)");
    require(o.margin_voxels >= 0.01 && o.margin_voxels <= 0.4, "the margin must lie in [0.01, 0.4] voxels");
    require(o.max_depth_voxels > 0 && o.max_depth_voxels <= 1, "the depth bound must lie in (0, 1] voxels");
    require(o.min_angle_deg >= 0 && o.min_angle_deg < 60, "the smallest angle must lie in [0, 60) degrees");
    require(o.max_normal_change_deg > 0 && o.max_normal_change_deg <= 90, "the tilt limit must lie in (0, 90] degrees");
}

namespace {

constexpr double pi = 3.14159265358979323846;

struct Box {
    Vec3 low, high;
};

bool overlap(const Box& a, const Box& b)
{
    for (int axis = 0; axis < 3; ++axis)
        if (a.high[axis] < b.low[axis] || b.high[axis] < a.low[axis]) return false;
    return true;
}

class NetSmoother {
public:
    NetSmoother(SurfaceNet& net, const LabelImage& image, const std::vector<Label>& label_map, Label background,
                const NetSmoothOptions& options)
        : net_(net), options_(options), cos_tilt_(std::cos(options.max_normal_change_deg * pi / 180)),
          cos_min_angle_(std::cos(options.min_angle_deg * pi / 180))
    {
        for (int row = 0; row < 3; ++row)
            for (int col = 0; col < 3; ++col)
                to_world_[3 * row + col] = image.direction()[3 * row + col] * image.spacing_mm()[col];
        build_topology();
        build_evidence(image, label_map, background);
        build_candidates();
    }

    void run(const Progress& progress, SurfaceNetsReport& report)
    {
        ProgressTicker ticker(progress, "smooth", options_.iterations);
        for (std::size_t i = 0; i < options_.iterations;) {
            // The net move of a run of pairs is judged at once: its triangles may tilt by the limit per pair.
            start_ = net_.positions;
            const std::size_t run = std::min(options_.pairs_per_check, options_.iterations - i);
            cos_tilt_ = std::cos(std::min(90.0, options_.max_normal_change_deg * static_cast<double>(run)) * pi / 180);
            for (std::size_t r = 0; r < run; ++r, ++i) {
                step(options_.lambda);
                step(options_.mu);
                ++report.iterations;
                ticker.step();
            }
            report.refused_by_checks += put_back_offenders();
        }
        report.refused_by_image = refused_by_image_;
        report.moves = moves_;
        progress.info("smooth", concat(report.iterations, " Taubin pairs over ", movable_count_, " movable vertices; ",
                                       candidate_pairs_, " neighbouring pairs watched, ", report.refused_by_checks,
                                       " moves put back, ", refused_by_image_, " refused by the image"));
    }

private:
    Vec3 world(const Vec3& index) const { return multiply(to_world_, index); }

    TriangleCorners world_corners(const Triangle& t, const std::vector<Vec3>& positions) const
    {
        return {world(positions[t[0]]), world(positions[t[1]]), world(positions[t[2]])};
    }

    void build_topology()
    {
        const std::size_t vertex_count = net_.positions.size();
        stars_ = star_rows(net_.triangles, vertex_count);
        sheets_ = build_star_sheets(net_.triangles, stars_);
        movable_.assign(vertex_count, 0);
        tissues_.assign(vertex_count, {});
        // Blocks of vertices side by side, each with its rows of links and junction neighbours; joined in order.
        constexpr std::size_t block = 16384;
        const std::size_t blocks = (vertex_count + block - 1) / block;
        std::vector<std::vector<std::uint32_t>> block_links(blocks), block_junctions(blocks);
        std::vector<std::uint32_t> link_count(vertex_count, 0), junction_count(vertex_count, 0);
        std::size_t movable_count = 0;
#pragma omp parallel reduction(+ : movable_count)
        {
            std::vector<std::pair<std::uint32_t, int>> around; // neighbour, triangles on the edge
#pragma omp for schedule(dynamic, 1)
            for (std::size_t b = 0; b < blocks; ++b)
                for (auto v = static_cast<std::uint32_t>(b * block); v < std::min(vertex_count, (b + 1) * block); ++v)
                    movable_count +=
                        sort_links(v, around, block_links[b], link_count[v], block_junctions[b], junction_count[v]);
        }
        movable_count_ = movable_count;
        links_ = join_rows(link_count, block_links);
        junction_links_ = join_rows(junction_count, block_junctions);
    }

    /// Vertex v's tissues and kind, and its rows: the neighbours it is smoothed towards (appended to `links`,
    /// `link_count` of them) and its neighbours of larger index across junction edges. Returns whether it moves.
    bool sort_links(std::uint32_t v, std::vector<std::pair<std::uint32_t, int>>& around,
                    std::vector<std::uint32_t>& links, std::uint32_t& link_count, std::vector<std::uint32_t>& junctions,
                    std::uint32_t& junction_count)
    {
        around.clear();
        auto& tissues = tissues_[v];
        for (const std::uint32_t t : stars_[v]) {
            for (const std::uint32_t w : net_.triangles[t]) {
                if (w == v) continue;
                auto it = std::find_if(around.begin(), around.end(), [&](const auto& x) { return x.first == w; });
                if (it == around.end()) around.emplace_back(w, 1);
                else ++it->second;
            }
            for (const Label label : {net_.sides[t].from, net_.sides[t].to})
                if (std::find(tissues.labels.begin(), tissues.labels.begin() + tissues.count, label) ==
                        tissues.labels.begin() + tissues.count &&
                    tissues.count < tissues.labels.size())
                    tissues.labels[tissues.count++] = label;
        }
        std::sort(around.begin(), around.end());
        std::size_t junction = 0;
        for (const auto& [w, count] : around)
            if (count >= 3) {
                ++junction;
                if (w > v) junctions.push_back(w), ++junction_count;
            }
        if (net_.kinds[v] != NetVertexKind::cube || (junction != 0 && junction != 2)) return false;
        movable_[v] = 1;
        for (const auto& [w, count] : around)
            if (junction == 0 || count >= 3) links.push_back(w), ++link_count;
        return true;
    }

    /// Per movable vertex and tissue of its star, the corners of its cube (voxels) holding that tissue.
    void build_evidence(const LabelImage& image, const std::vector<Label>& label_map, Label background)
    {
        masks_.assign(net_.positions.size(), {});
        const auto& g = net_.cube_grid;
        for (std::size_t v = 0; v < net_.positions.size(); ++v) {
            if (!movable_[v]) continue;
            const std::size_t cell = net_.cells[v];
            const Index3 low{static_cast<std::int64_t>(cell % g[0]) - 1,
                             static_cast<std::int64_t>(cell / g[0] % g[1]) - 1,
                             static_cast<std::int64_t>(cell / g[0] / g[1]) - 1};
            std::array<Label, 8> corners{};
            for (int c = 0; c < 8; ++c) {
                const Index3 at{low[0] + (c & 1), low[1] + (c >> 1 & 1), low[2] + (c >> 2 & 1)};
                corners[c] = image.contains(at) ? label_map[image.at_or(at, background)] : background;
            }
            for (std::size_t n = 0; n < tissues_[v].count; ++n)
                for (int c = 0; c < 8; ++c)
                    if (corners[c] == tissues_[v].labels[n])
                        masks_[v][n] = static_cast<std::uint8_t>(masks_[v][n] | 1 << c);
        }
    }

    /// Whether the image allows vertex v at `x` (index space): within the depth bound of the voxels of each
    /// of its tissues (three where more meet). Only the 8 voxels of its cube can be that near.
    bool allowed(std::uint32_t v, const Vec3& x) const
    {
        const Vec3& low = net_.boxes[v].low;
        const double depth2 = options_.max_depth_voxels * options_.max_depth_voxels;
        // Squared distance along each axis to the cells of the low and the high corner voxels.
        std::array<double, 3> to_low{}, to_high{};
        for (int axis = 0; axis < 3; ++axis) {
            const double t = x[axis] - low[axis];
            to_low[axis] = t > 0.5 ? (t - 0.5) * (t - 0.5) : 0;
            to_high[axis] = t < 0.5 ? (0.5 - t) * (0.5 - t) : 0;
        }
        std::uint8_t near = 0;
        for (int c = 0; c < 8; ++c) {
            const double d2 =
                (c & 1 ? to_high[0] : to_low[0]) + (c & 2 ? to_high[1] : to_low[1]) + (c & 4 ? to_high[2] : to_low[2]);
            if (d2 < depth2) near = static_cast<std::uint8_t>(near | 1 << c);
        }
        const std::size_t count = tissues_[v].count;
        std::size_t own = 0;
        for (std::size_t n = 0; n < count; ++n) own += (near & masks_[v][n]) != 0;
        return own >= std::min<std::size_t>(count, 3);
    }

    Box reach(std::uint32_t v) const
    {
        if (!movable_[v]) return {net_.positions[v], net_.positions[v]};
        const double m = options_.margin_voxels;
        const VertexBox& b = net_.boxes[v];
        return {{b.low[0] + m, b.low[1] + m, b.low[2] + m}, {b.high[0] - m, b.high[1] - m, b.high[2] - m}};
    }

    Box reach(const Triangle& t) const
    {
        constexpr double slack = 1e-9; // so that points on a cube's boundary are filed in every cube they touch
        Box box = reach(t[0]);
        for (int k = 1; k < 3; ++k) {
            const Box b = reach(t[k]);
            for (int axis = 0; axis < 3; ++axis) {
                box.low[axis] = std::min(box.low[axis], b.low[axis]);
                box.high[axis] = std::max(box.high[axis], b.high[axis]);
            }
        }
        for (int axis = 0; axis < 3; ++axis) box.low[axis] -= slack, box.high[axis] += slack;
        return box;
    }

    std::size_t cell_of(double x, int axis) const
    {
        const double c = std::floor(x) + 1;
        return static_cast<std::size_t>(std::clamp(c, 0.0, static_cast<double>(net_.cube_grid[axis] - 1)));
    }

    /// The pairs of triangles sharing no vertex whose reach boxes (the boxes of their vertices' cubes,
    /// shrunk by the margin) overlap: the only pairs without a common vertex that can ever meet.
    void build_candidates()
    {
        const auto& g = net_.cube_grid;
        const std::size_t triangle_count = net_.triangles.size();
        std::vector<Box> boxes(triangle_count);
        const auto cells_of = [&](std::size_t t) {
            std::array<std::size_t, 6> r{};
            for (int a = 0; a < 3; ++a) r[a] = cell_of(boxes[t].low[a], a), r[3 + a] = cell_of(boxes[t].high[a], a);
            return r;
        };
        // File every triangle in each cube its reach box overlaps (counting sort by cube).
        std::vector<std::uint32_t> start(g[0] * g[1] * g[2] + 1, 0);
#pragma omp parallel for schedule(static)
        for (std::size_t t = 0; t < triangle_count; ++t) boxes[t] = reach(net_.triangles[t]);
        for (std::size_t t = 0; t < triangle_count; ++t) {
            const auto r = cells_of(t);
            for (std::size_t k = r[2]; k <= r[5]; ++k)
                for (std::size_t j = r[1]; j <= r[4]; ++j)
                    for (std::size_t i = r[0]; i <= r[3]; ++i) ++start[cube_index(g, i, j, k) + 1];
        }
        for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
        std::vector<std::uint32_t> filed(start.back()), next(start.begin(), start.end() - 1);
        for (std::size_t t = 0; t < triangle_count; ++t) {
            const auto r = cells_of(t);
            for (std::size_t k = r[2]; k <= r[5]; ++k)
                for (std::size_t j = r[1]; j <= r[4]; ++j)
                    for (std::size_t i = r[0]; i <= r[3]; ++i)
                        filed[next[cube_index(g, i, j, k)]++] = static_cast<std::uint32_t>(t);
        }
        next.clear();
        next.shrink_to_fit();
        // The pairs, each once, cube after cube: blocks of cubes side by side, joined in order (the same rows
        // whatever the threads).
        const std::size_t cube_count = start.size() - 1;
        constexpr std::size_t block = 4096;
        const std::size_t blocks = (cube_count + block - 1) / block;
        std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> found(blocks);
#pragma omp parallel for schedule(dynamic, 1)
        for (std::size_t b = 0; b < blocks; ++b)
            for (std::size_t cell = b * block; cell < std::min(cube_count, (b + 1) * block); ++cell) {
                const std::size_t begin = start[cell], end = start[cell + 1];
                for (std::size_t x = begin; x < end; ++x)
                    for (std::size_t y = x + 1; y < end; ++y) {
                        const std::uint32_t t = filed[x], u = filed[y];
                        if (share_vertex(net_.triangles[t], net_.triangles[u]) || !overlap(boxes[t], boxes[u]))
                            continue;
                        // File the pair once: in the cell of the low corner of the two boxes' overlap.
                        std::array<std::size_t, 3> c{};
                        for (int a = 0; a < 3; ++a) c[a] = cell_of(std::max(boxes[t].low[a], boxes[u].low[a]), a);
                        if (cube_index(g, c[0], c[1], c[2]) != cell) continue;
                        found[b].emplace_back(t, u);
                    }
            }
        // Per triangle its partners, in the order the pairs were found, both ways.
        partners_.offsets.assign(triangle_count + 1, 0);
        for (const auto& pairs : found)
            for (const auto& [t, u] : pairs) ++partners_.offsets[t + 1], ++partners_.offsets[u + 1];
        for (std::size_t t = 0; t < triangle_count; ++t) partners_.offsets[t + 1] += partners_.offsets[t];
        partners_.items.resize(partners_.offsets.back());
        std::vector<std::uint32_t> fill(partners_.offsets.begin(), partners_.offsets.end() - 1);
        for (const auto& pairs : found) {
            candidate_pairs_ += pairs.size();
            for (const auto& [t, u] : pairs) partners_.items[fill[t]++] = u, partners_.items[fill[u]++] = t;
        }
    }

    /// One Jacobi step of factor f: each movable vertex towards the mean of its links, inside its box and
    /// as far as the image allows.
    void step(double f)
    {
        const std::vector<Vec3>& now = net_.positions;
        std::vector<Vec3>& next = spare_;
        next.resize(now.size());
        const double m = options_.margin_voxels;
        std::size_t refused = 0, moved = 0;
#pragma omp parallel for schedule(static) reduction(+ : refused, moved)
        for (std::size_t v = 0; v < now.size(); ++v) {
            next[v] = now[v];
            if (!movable_[v]) continue;
            const auto links = links_[v];
            if (links.empty()) continue;
            Vec3 mean{0, 0, 0};
            for (const std::uint32_t w : links) mean = mean + now[w];
            mean = (1.0 / static_cast<double>(links.size())) * mean;
            Vec3 target = now[v] + f * (mean - now[v]);
            const VertexBox& box = net_.boxes[v];
            for (int a = 0; a < 3; ++a) target[a] = std::clamp(target[a], box.low[a] + m, box.high[a] - m);
            if (!allowed(static_cast<std::uint32_t>(v), target)) {
                target = 0.5 * (now[v] + target);
                if (!allowed(static_cast<std::uint32_t>(v), target)) {
                    ++refused;
                    continue;
                }
            }
            next[v] = target;
            ++moved;
        }
        refused_by_image_ += refused;
        moves_ += moved;
        net_.positions.swap(next);
    }

    /// Whether moved triangle t breaks a rule of its own (in world space): degenerate, a new angle below the
    /// limit, or a tilt beyond it since the start of the pair.
    bool shape_breaks(std::uint32_t t) const
    {
        const Triangle& tri = net_.triangles[t];
        const TriangleCorners now = world_corners(tri, net_.positions), before = world_corners(tri, start_);
        const Vec3 n1 = cross(now[1] - now[0], now[2] - now[0]),
                   n0 = cross(before[1] - before[0], before[2] - before[0]);
        if (dot(n1, n0) < cos_tilt_ * norm(n1) * norm(n0)) return true;
        const double cosine = smallest_angle_cosine(now);
        return cosine > cos_min_angle_ && cosine > smallest_angle_cosine(before);
    }

    bool meet(std::uint32_t t, std::uint32_t u) const
    {
        return triangles_meet(net_.positions, net_.triangles[t], net_.triangles[u]);
    }

    /// Whether the triangles on the junction edges from v (to neighbours of larger index) still turn about
    /// each edge in the order their tissues demand (edge_fan.h).
    bool junctions_in_order(std::uint32_t v) const
    {
        std::vector<FanBlade> blades;
        for (const std::uint32_t w : junction_links_[v]) {
            blades.clear();
            for (const std::uint32_t t : stars_[v]) {
                const Triangle& tri = net_.triangles[t];
                if (tri[0] == w || tri[1] == w || tri[2] == w)
                    blades.push_back(blade_on(tri, v, w, net_.positions, net_.sides[t]));
            }
            if (fan_order(net_.positions[v], net_.positions[w], blades) != FanOrder::in_order) return false;
        }
        return true;
    }

    /// Judges every triangle the pair moved and puts back the vertices of offenders (and of the triangles
    /// they meet) to where the pair found them, until none offends. Returns the vertices put back.
    std::size_t put_back_offenders()
    {
        const std::size_t vertex_count = net_.positions.size();
        std::vector<char> moved(vertex_count, 0), dirty(vertex_count, 0), seen(net_.triangles.size(), 0);
        std::vector<std::uint32_t> changed; // vertices whose surroundings are to be judged
        for (std::uint32_t v = 0; v < vertex_count; ++v)
            if (net_.positions[v] != start_[v]) moved[v] = 1, changed.push_back(v);
        std::size_t put_back = 0;
        while (!changed.empty()) {
            // The triangles around changed vertices, and every vertex of theirs (its star changed).
            std::vector<std::uint32_t> triangles, vertices;
            for (const std::uint32_t v : changed)
                for (const std::uint32_t t : stars_[v]) {
                    if (seen[t]) continue;
                    seen[t] = 1;
                    triangles.push_back(t);
                    for (const std::uint32_t w : net_.triangles[t])
                        if (!dirty[w]) dirty[w] = 1, vertices.push_back(w);
                }
            for (const std::uint32_t w : vertices) dirty[w] = 0;
            // (Any order: what offends depends on the positions only, and offenders are sorted below.)
            std::vector<std::uint32_t> offenders;
#pragma omp parallel
            {
                std::vector<std::uint32_t> local;
#pragma omp for schedule(dynamic, 256) nowait
                for (std::size_t n = 0; n < triangles.size(); ++n) {
                    const std::uint32_t t = triangles[n];
                    const Triangle& tri = net_.triangles[t];
                    bool offends = (moved[tri[0]] || moved[tri[1]] || moved[tri[2]]) && shape_breaks(t);
                    for (const std::uint32_t u : partners_[t])
                        // A pair of two judged triangles once, from its lower one.
                        if (!(seen[u] && u < t) && meet(t, u)) {
                            offends = true;
                            local.push_back(u);
                        }
                    if (offends) local.push_back(t);
                }
#pragma omp for schedule(dynamic, 256) nowait
                for (std::size_t n = 0; n < vertices.size(); ++n) {
                    const std::uint32_t v = vertices[n];
                    star_offenders(v, sheets_, net_.positions, net_.triangles, local);
                    if (!junctions_in_order(v))
                        for (const std::uint32_t t : stars_[v]) local.push_back(t);
                }
#pragma omp critical
                offenders.insert(offenders.end(), local.begin(), local.end());
            }
            for (const std::uint32_t t : triangles) seen[t] = 0;
            changed.clear();
            std::sort(offenders.begin(), offenders.end());
            offenders.erase(std::unique(offenders.begin(), offenders.end()), offenders.end());
            for (const std::uint32_t t : offenders)
                for (const std::uint32_t v : net_.triangles[t])
                    if (moved[v]) {
                        net_.positions[v] = start_[v];
                        moved[v] = 0;
                        changed.push_back(v);
                        ++put_back;
                    }
            if (changed.empty() && !offenders.empty())
                throw AlgorithmError(
                    "surface nets smoothing: an offending triangle has no moved vertex; this is a bug, "
                    "please report it with the image");
        }
        return put_back;
    }

    SurfaceNet& net_;
    NetSmoothOptions options_;
    double cos_tilt_, cos_min_angle_;
    Mat3 to_world_{};
    Rows stars_; ///< triangles per vertex
    StarSheets sheets_;
    Rows links_;    ///< the vertices each movable vertex is smoothed towards
    Rows partners_; ///< per triangle: the triangles sharing no vertex it could meet
    std::vector<char> movable_;
    Rows junction_links_; ///< per vertex: its neighbours of larger index across junction edges
    struct Tissues {
        std::array<Label, 4> labels{};
        std::size_t count = 0;
    };
    std::vector<Tissues> tissues_;
    std::vector<std::array<std::uint8_t, 4>> masks_; ///< see build_evidence()
    std::vector<Vec3> start_;                        ///< positions at the start of the current run of pairs
    std::vector<Vec3> spare_;                        ///< the other buffer of the Jacobi steps
    std::size_t movable_count_ = 0, candidate_pairs_ = 0, refused_by_image_ = 0, moves_ = 0;
};

} // namespace

std::size_t vertices_outside_boxes(const SurfaceNet& net, double margin_voxels)
{
    constexpr double slack = 1e-9; // rounding of the clamp
    std::size_t outside = 0;
    for (std::size_t v = 0; v < net.positions.size(); ++v) {
        const VertexBox& box = net.boxes[v];
        const bool fixed = box.low == box.high;
        const double m = fixed ? 0 : margin_voxels;
        for (int a = 0; a < 3; ++a)
            if (net.positions[v][a] < box.low[a] + m - slack || net.positions[v][a] > box.high[a] - m + slack) {
                ++outside;
                break;
            }
    }
    return outside;
}

void smooth_net(SurfaceNet& net, const LabelImage& image, const std::vector<Label>& label_map, Label background,
                const NetSmoothOptions& options, const Progress& progress, SurfaceNetsReport& report)
{
    validate(options);
    NetSmoother(net, image, label_map, background, options).run(progress, report);
    if (const std::size_t outside = vertices_outside_boxes(net, options.margin_voxels))
        throw AlgorithmError(
            concat("surface nets smoothing: ", outside,
                   " vertices left their cubes, where the local "
                   "checks cannot see what they meet; this is a bug, please report it with the image"));
}

} // namespace tissuemesh::surface::detail
