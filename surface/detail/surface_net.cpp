#include "surface/detail/surface_net.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "surface/detail/priority_cube.h"

namespace tissuemesh::surface::detail {
namespace {

/// A point of the padded grid in half-voxel units: grid point p at 2p, a cube's centre at 2p + 1.
using Half = std::array<std::int64_t, 3>;

constexpr std::uint32_t no_surface = std::numeric_limits<std::uint32_t>::max();
constexpr std::uint32_t fallback_flag = 0x80000000u;

constexpr int centre_vertex = 8;

/// Corners joined by the cube's edges (bit masks).
constexpr std::array<std::uint8_t, 8> edge_neighbours = [] {
    std::array<std::uint8_t, 8> masks{};
    for (int c = 0; c < 8; ++c) masks[c] = static_cast<std::uint8_t>(1 << (c ^ 1) | 1 << (c ^ 2) | 1 << (c ^ 4));
    return masks;
}();

/// Whether the corners in `set` are connected through `neighbours` (the empty set is).
bool connected(std::uint8_t set, const std::array<std::uint8_t, 8>& neighbours)
{
    if (set == 0) return true;
    std::uint8_t reached = static_cast<std::uint8_t>(set & -set);
    for (std::uint8_t before = 0; before != reached;) {
        before = reached;
        for (int c = 0; c < 8; ++c)
            if (reached >> c & 1) reached = static_cast<std::uint8_t>(reached | (neighbours[c] & set));
    }
    return reached == set;
}

/// The chosen diagonal of face f (cube_faces order).
std::array<int, 2> face_diagonal(const CubePlan& plan, std::size_t f)
{
    const auto& c = cube_faces[f];
    return plan.anti[f] ? std::array<int, 2>{c[1], c[3]} : std::array<int, 2>{c[0], c[2]};
}

/// Whether a cube's tetrahedra vertices may merge into one (see surface_net.h).
bool mergeable(const std::array<Label, 8>& corners, const CubePlan& plan)
{
    std::array<std::uint8_t, 8> neighbours = edge_neighbours;
    for (std::size_t f = 0; f < cube_faces.size(); ++f) {
        const auto& c = cube_faces[f];
        const auto [x, y] = face_diagonal(plan, f);
        neighbours[x] = static_cast<std::uint8_t>(neighbours[x] | 1 << y);
        neighbours[y] = static_cast<std::uint8_t>(neighbours[y] | 1 << x);
        const bool four_mixed = corners[c[0]] != corners[c[1]] && corners[c[1]] != corners[c[2]] &&
                                corners[c[2]] != corners[c[3]] && corners[c[3]] != corners[c[0]];
        // Four mixed edges meet at one point of the face unless two curves cross it separately; either way
        // a label on both ends of a diagonal would touch that point twice. Only four distinct labels pass.
        if (four_mixed && (corners[c[0]] == corners[c[2]] || corners[c[1]] == corners[c[3]])) return false;
    }
    std::uint8_t done = 0;
    for (int c = 0; c < 8; ++c) {
        if (done >> c & 1) continue;
        std::uint8_t set = 0;
        for (int d = 0; d < 8; ++d)
            if (corners[d] == corners[c]) set = static_cast<std::uint8_t>(set | 1 << d);
        done = static_cast<std::uint8_t>(done | set);
        if (!connected(set, neighbours) || !connected(static_cast<std::uint8_t>(~set), neighbours)) return false;
    }
    return true;
}

/// A mixed cube kept as its tetrahedra.
struct Fallback {
    std::array<std::size_t, 3> cube{};
    CubePlan plan;
    std::uint32_t first_vertex = 0; ///< vertex of its first mixed tetrahedron; the others follow in order
    std::uint16_t mixed = 0;        ///< bit t: tetrahedron t is mixed
};

/// A vertex around an edge, with a point inside its wedge around the edge (half-voxel units) to order it by.
struct Unit {
    std::uint32_t vertex;
    Vec3 point;
    bool cube;
};

class NetBuilder {
public:
    NetBuilder(const LabelImage& image, const std::vector<Label>& map, Label background,
               const std::map<Label, int>& priority)
        : rule_(priority),
          background_(background), padded_{image.dims()[0] + 2, image.dims()[1] + 2, image.dims()[2] + 2}
    {
        net_.cube_grid = {padded_[0] - 1, padded_[1] - 1, padded_[2] - 1};
        const double cubes = static_cast<double>(net_.cube_grid[0]) * static_cast<double>(net_.cube_grid[1]) *
                             static_cast<double>(net_.cube_grid[2]);
        if (cubes >= 4294967295.0)
            throw InputError("surface nets: the image has 2^32 grid cubes or more; crop or coarsen it");
        labels_.assign(padded_[0] * padded_[1] * padded_[2], background);
        const Dims& d = image.dims();
        for (std::size_t k = 0; k < d[2]; ++k)
            for (std::size_t j = 0; j < d[1]; ++j) {
                const Label* row = &image.labels()[image.linear_index(0, j, k)];
                Label* target = &labels_[padded(1, j + 1, k + 1)];
                for (std::size_t i = 0; i < d[0]; ++i) target[i] = map[row[i]];
            }
        state_.assign(static_cast<std::size_t>(cubes), no_surface);
    }

    SurfaceNet run()
    {
        classify_cubes();
        for (std::size_t k = 0; k + 1 < padded_[2]; ++k)
            for (std::size_t j = 0; j + 1 < padded_[1]; ++j)
                for (std::size_t i = 0; i + 1 < padded_[0]; ++i)
                    for (int axis = 0; axis < 3; ++axis) grid_edge({i, j, k}, axis);
        // Grid edges on the last layers have both ends in the padding (background): nothing to do there.
        for (std::size_t f = 0; f < fallbacks_.size(); ++f) fallback_edges(f);
        return std::move(net_);
    }

private:
    std::size_t padded(std::size_t i, std::size_t j, std::size_t k) const
    {
        return i + padded_[0] * (j + padded_[1] * k);
    }
    std::uint32_t cube(const std::array<std::size_t, 3>& c) const
    {
        return cube_index(net_.cube_grid, c[0], c[1], c[2]);
    }

    std::array<Label, 8> corners(const std::array<std::size_t, 3>& c) const
    {
        std::array<Label, 8> labels{};
        for (int v = 0; v < 8; ++v)
            labels[v] = labels_[padded(c[0] + (v & 1), c[1] + (v >> 1 & 1), c[2] + (v >> 2 & 1))];
        return labels;
    }

    static Half half_point(const std::array<std::size_t, 3>& c, int v)
    {
        if (v == centre_vertex)
            return {2 * static_cast<std::int64_t>(c[0]) + 1, 2 * static_cast<std::int64_t>(c[1]) + 1,
                    2 * static_cast<std::int64_t>(c[2]) + 1};
        return {2 * static_cast<std::int64_t>(c[0] + (v & 1)), 2 * static_cast<std::int64_t>(c[1] + (v >> 1 & 1)),
                2 * static_cast<std::int64_t>(c[2] + (v >> 2 & 1))};
    }

    /// Image index of a point given in half-voxel units of the padded grid (half / 2 - 1).
    static Vec3 to_index(const Vec3& half) { return {half[0] / 2 - 1, half[1] / 2 - 1, half[2] / 2 - 1}; }

    std::uint32_t add_vertex(const Vec3& half, NetVertexKind kind, std::uint32_t cell, const VertexBox* box = nullptr)
    {
        if (net_.positions.size() >= fallback_flag)
            throw InputError("surface nets: 2^31 vertices or more; crop or coarsen the image");
        const Vec3 index = to_index(half);
        net_.positions.push_back(index);
        net_.boxes.push_back(box ? *box : VertexBox{index, index});
        net_.kinds.push_back(kind);
        net_.cells.push_back(cell);
        return static_cast<std::uint32_t>(net_.positions.size() - 1);
    }

    void classify_cubes()
    {
        const auto& g = net_.cube_grid;
        for (std::size_t k = 0; k < g[2]; ++k)
            for (std::size_t j = 0; j < g[1]; ++j)
                for (std::size_t i = 0; i < g[0]; ++i) {
                    const std::array<std::size_t, 3> c{i, j, k};
                    const std::array<Label, 8> labels = corners(c);
                    if (std::all_of(labels.begin() + 1, labels.end(), [&](Label l) { return l == labels[0]; }))
                        continue;
                    ++net_.mixed_cubes;
                    const CubePlan plan = rule_.active() ? rule_.plan(labels) : CubePlan{};
                    const std::uint32_t cell = cube(c);
                    if (mergeable(labels, plan)) {
                        const Vec3 low{static_cast<double>(i) - 1, static_cast<double>(j) - 1,
                                       static_cast<double>(k) - 1};
                        const VertexBox box{low, {low[0] + 1, low[1] + 1, low[2] + 1}};
                        const Half centre = half_point(c, centre_vertex);
                        state_[cell] = add_vertex({static_cast<double>(centre[0]), static_cast<double>(centre[1]),
                                                   static_cast<double>(centre[2])},
                                                  NetVertexKind::cube, cell, &box);
                        continue;
                    }
                    Fallback fallback{c, plan, static_cast<std::uint32_t>(net_.positions.size()), 0};
                    const CubeTets tets = cube_tetrahedra(plan);
                    for (std::size_t t = 0; t < tets.count; ++t) {
                        Vec3 sum{0, 0, 0};
                        bool mixed = false;
                        for (const int v : tets.tets[t]) {
                            const Half h = half_point(c, v);
                            sum = sum +
                                  Vec3{static_cast<double>(h[0]), static_cast<double>(h[1]), static_cast<double>(h[2])};
                            mixed = mixed || label_of(labels, plan, v) != label_of(labels, plan, tets.tets[t][0]);
                        }
                        if (!mixed) continue;
                        fallback.mixed = static_cast<std::uint16_t>(fallback.mixed | 1 << t);
                        add_vertex(0.25 * sum, NetVertexKind::tetrahedron, cell);
                    }
                    state_[cell] = fallback_flag | static_cast<std::uint32_t>(fallbacks_.size());
                    fallbacks_.push_back(fallback);
                }
        net_.fallback_cubes = fallbacks_.size();
    }

    static Label label_of(const std::array<Label, 8>& corners, const CubePlan& plan, int v)
    {
        return v == centre_vertex ? plan.centre : corners[v];
    }

    /// Appends the vertices of cube `c` around the edge a-b (half units): the cube's own vertex, or the
    /// vertices of its mixed tetrahedra that contain the edge.
    void add_units(const std::array<std::size_t, 3>& c, const Half& a, const Half& b)
    {
        const std::uint32_t state = state_[cube(c)];
        if (state == no_surface) return;
        if (!(state & fallback_flag)) {
            const Half centre = half_point(c, centre_vertex);
            units_.push_back({state, {double(centre[0]), double(centre[1]), double(centre[2])}, true});
            return;
        }
        const Fallback& fallback = fallbacks_[state & ~fallback_flag];
        const CubeTets tets = cube_tetrahedra(fallback.plan);
        std::uint32_t vertex = fallback.first_vertex;
        for (std::size_t t = 0; t < tets.count; ++t) {
            if (!(fallback.mixed >> t & 1)) continue;
            const std::uint32_t id = vertex++;
            bool has_a = false, has_b = false;
            Vec3 sum{0, 0, 0};
            for (const int v : tets.tets[t]) {
                const Half h = half_point(c, v);
                has_a = has_a || h == a;
                has_b = has_b || h == b;
                sum = sum + Vec3{double(h[0]), double(h[1]), double(h[2])};
            }
            if (has_a && has_b) units_.push_back({id, 0.25 * sum, false});
        }
    }

    /// The polygon of the units around edge a-b, whose ends carry labels la and lb.
    void emit_polygon(const Half& a, const Half& b, Label la, Label lb)
    {
        if (units_.size() < 3) return; // the tetrahedra around the edge all merged into one or two vertices
        const Vec3 d{double(b[0] - a[0]), double(b[1] - a[1]), double(b[2] - a[2])};
        int least = 0;
        for (int axis = 1; axis < 3; ++axis)
            if (std::abs(d[axis]) < std::abs(d[least])) least = axis;
        Vec3 e{0, 0, 0};
        e[least] = 1;
        const Vec3 u = cross(d, e), w = cross(d, u);
        const Vec3 origin{double(a[0]), double(a[1]), double(a[2])};
        for (Unit& unit : units_) {
            const Vec3 r = unit.point - origin;
            unit.point[0] = std::atan2(dot(r, w), dot(r, u)); // the angle around the edge, counterclockwise about d
        }
        std::sort(units_.begin(), units_.end(), [](const Unit& x, const Unit& y) { return x.point[0] < y.point[0]; });
        // Counterclockwise about a -> b, the polygon's normal points from a's label into b's.
        const LabelPair pair = sides_of(la, lb);
        const bool reverse = pair.from != la;
        const auto emit = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
            net_.triangles.push_back(reverse ? Triangle{p, r, q} : Triangle{p, q, r});
            net_.sides.push_back(pair);
        };
        const std::size_t n = units_.size();
        const bool all_cubes = std::all_of(units_.begin(), units_.end(), [](const Unit& x) { return x.cube; });
        if (n == 3) {
            emit(units_[0].vertex, units_[1].vertex, units_[2].vertex);
        } else if (n == 4 && all_cubes) {
            emit(units_[0].vertex, units_[1].vertex, units_[2].vertex);
            emit(units_[0].vertex, units_[2].vertex, units_[3].vertex);
        } else {
            const Vec3 middle{double(a[0] + b[0]) / 2, double(a[1] + b[1]) / 2, double(a[2] + b[2]) / 2};
            const std::uint32_t centre = add_vertex(middle, NetVertexKind::edge, net_.cells[units_[0].vertex]);
            for (std::size_t i = 0; i < n; ++i) emit(centre, units_[i].vertex, units_[(i + 1) % n].vertex);
        }
    }

    LabelPair sides_of(Label a, Label b) const
    {
        if (a == background_) return {b, a};
        if (b == background_) return {a, b};
        return a > b ? LabelPair{a, b} : LabelPair{b, a};
    }

    /// The polygon around the grid edge from grid point p along `axis`, when its labels differ.
    void grid_edge(const std::array<std::size_t, 3>& p, int axis)
    {
        std::array<std::size_t, 3> q = p;
        ++q[axis];
        if (q[axis] >= padded_[axis]) return;
        const Label la = labels_[padded(p[0], p[1], p[2])], lb = labels_[padded(q[0], q[1], q[2])];
        if (la == lb) return;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        const Half a{2 * std::int64_t(p[0]), 2 * std::int64_t(p[1]), 2 * std::int64_t(p[2])};
        const Half b{2 * std::int64_t(q[0]), 2 * std::int64_t(q[1]), 2 * std::int64_t(q[2])};
        units_.clear();
        // A mixed edge never lies on the padding's outer layer, so its four cubes exist.
        for (int du = 0; du < 2; ++du)
            for (int dw = 0; dw < 2; ++dw) {
                std::array<std::size_t, 3> c = p;
                c[u] -= static_cast<std::size_t>(du);
                c[w] -= static_cast<std::size_t>(dw);
                add_units(c, a, b);
            }
        emit_polygon(a, b, la, lb);
    }

    /// The polygons around a kept cube's inner edges and its faces' mixed diagonals (a diagonal shared
    /// with another kept cube is done by the one listed first).
    void fallback_edges(std::size_t f)
    {
        const Fallback& fallback = fallbacks_[f];
        const auto& c = fallback.cube;
        const std::array<Label, 8> labels = corners(c);
        const auto inner = [&](int x, int y) {
            const Label lx = label_of(labels, fallback.plan, x), ly = label_of(labels, fallback.plan, y);
            if (lx == ly) return;
            const Half a = half_point(c, x), b = half_point(c, y);
            units_.clear();
            add_units(c, a, b);
            emit_polygon(a, b, lx, ly);
        };
        if (fallback.plan.split) {
            for (int v = 0; v < 8; ++v) inner(centre_vertex, v);
        } else {
            inner(0, 7);
        }
        for (std::size_t face = 0; face < cube_faces.size(); ++face) {
            const auto [x, y] = face_diagonal(fallback.plan, face);
            if (labels[x] == labels[y]) continue;
            const int axis = static_cast<int>(face / 2);
            std::array<std::size_t, 3> other = c;
            if (face % 2 == 1) {
                if (++other[axis] >= net_.cube_grid[axis]) continue;
            } else {
                if (other[axis]-- == 0) continue;
            }
            const std::uint32_t state = state_[cube(other)];
            if ((state & fallback_flag) && state != no_surface && (state & ~fallback_flag) < f) continue;
            const Half a = half_point(c, x), b = half_point(c, y);
            units_.clear();
            add_units(c, a, b);
            add_units(other, a, b);
            emit_polygon(a, b, labels[x], labels[y]);
        }
    }

    PriorityRule rule_;
    Label background_;
    std::array<std::size_t, 3> padded_;
    std::vector<Label> labels_;        ///< the padded grid's labels (mapped)
    std::vector<std::uint32_t> state_; ///< per cube: no_surface, its vertex, or fallback_flag | fallback index
    std::vector<Fallback> fallbacks_;
    std::vector<Unit> units_; ///< scratch: the vertices around the current edge
    SurfaceNet net_;
};

} // namespace

SurfaceNet build_surface_net(const LabelImage& image, const std::vector<Label>& label_map, Label background,
                             const std::map<Label, int>& priority)
{
    return NetBuilder(image, label_map, background, priority).run();
}

} // namespace tissuemesh::surface::detail
