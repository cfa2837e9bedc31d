#include "surface/extract_interfaces.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <set>
#include <unordered_map>

#include "core/error.h"
#include "surface/detail/extraction_labels.h"
#include "surface/detail/priority_cube.h"

namespace tissuemesh::surface {
namespace {

constexpr std::uint32_t no_vertex = std::numeric_limits<std::uint32_t>::max();
constexpr std::size_t max_priority_side = 80'000; // (side + 2) * 24 fits 21 bits
constexpr std::uint64_t coordinate_mask = (std::uint64_t{1} << 21) - 1;

/// Positions inside one cube in 24ths of a voxel, so that every dual point is exact (down to the
/// centroids of split-cube tetrahedra, at odd multiples of 3) and orientation tests are exact integer
/// determinants.
using Local = std::array<int, 3>;
/// Labels of a cube's vertices: corners 0-7 (bit 0: +x, bit 1: +y, bit 2: +z) and the centre, 8 (used by
/// split cubes only).
using Labels9 = std::array<Label, 9>;

/// Slot of a triangle of the triangulation with corners base, base + a, base + b (a subset of b, as axis
/// bit sets): 12 triangle kinds per grid point.
constexpr std::array<std::int8_t, 64> face_slots = [] {
    std::array<std::int8_t, 64> slots{};
    std::int8_t next = 0;
    for (int b = 1; b < 8; ++b)
        for (int a = 1; a < 8; ++a) slots[static_cast<std::size_t>(8 * a + b)] = ((a & b) == a && a != b) ? next++ : -1;
    return slots;
}();

long long orientation(const Local& p, const Local& q, const Local& r, const Local& s)
{
    const long long a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const long long b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const long long c[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

struct DualPoint {
    std::uint32_t id = no_vertex;
    Local local{};
};

/// Walks the padded cube grid one slab (cube layer) at a time. Padded grid point (i, j, k) is voxel
/// (i - 1, j - 1, k - 1); vertex ids of grid edges and triangles are kept for the two grid layers of
/// the current slab only.
class SlabExtractor {
public:
    SlabExtractor(const LabelImage& image, std::vector<Label> label_map, Label background,
                  const std::map<Label, int>& priority)
        : image_(image), map_(std::move(label_map)), background_(background), rule_(priority), px_(image.dims()[0] + 2),
          py_(image.dims()[1] + 2), flip_(determinant(image.direction()) < 0)
    {
        for (int layer = 0; layer < 2; ++layer) {
            labels_[layer].assign(px_ * py_, background_);
            edges_[layer].assign(px_ * py_ * 8, no_vertex);
            faces_[layer].assign(px_ * py_ * 12, no_vertex);
        }
    }

    /// Hands the complex to `sink` one slab (piece) at a time.
    void run(InterfaceSink& sink, const Progress& progress)
    {
        const std::size_t slabs = image_.dims()[2] + 1;
        ProgressTicker ticker(progress, "extract", slabs);
        sink.start(image_.names(), background_);
        load_layer(1, 0);
        for (std::size_t k = 0; k < slabs; ++k) {
            std::swap(labels_[0], labels_[1]);
            std::swap(edges_[0], edges_[1]);
            std::swap(faces_[0], faces_[1]);
            std::fill(edges_[1].begin(), edges_[1].end(), no_vertex);
            std::fill(faces_[1].begin(), faces_[1].end(), no_vertex);
            load_layer(1, k + 1);
            k_ = k;
            // Split-cube points on the plane z = k stay shared with this slab; older ones are done.
            std::erase_if(shared_, [k](const auto& entry) { return (entry.first & coordinate_mask) < 24 * k; });
            extract_slab();
            for (const LabelPair& pair : sides_) seen_[pair.from] = seen_[pair.to] = true;
            sink.add({first_vertex_, vertices_, triangles_, sides_});
            first_vertex_ += vertices_.size();
            triangle_count_ += triangles_.size();
            vertices_.clear();
            triangles_.clear();
            sides_.clear();
            ticker.step();
        }
    }

    std::size_t vertex_count() const { return first_vertex_; }
    std::size_t triangle_count() const { return triangle_count_; }
    /// Whether some triangle has `label` on one of its sides.
    bool produced(Label label) const { return seen_[label]; }

private:
    /// Fills labels_[slot] with padded grid layer `k` (all background outside the image).
    void load_layer(int slot, std::size_t k)
    {
        std::vector<Label>& layer = labels_[slot];
        std::fill(layer.begin(), layer.end(), background_);
        if (k == 0 || k > image_.dims()[2]) return;
        const Dims& dims = image_.dims();
        for (std::size_t j = 0; j < dims[1]; ++j) {
            const Label* row = &image_.labels()[image_.linear_index(0, j, k - 1)];
            Label* target = &layer[(j + 1) * px_ + 1];
            for (std::size_t i = 0; i < dims[0]; ++i) target[i] = map_[row[i]];
        }
    }

    void extract_slab()
    {
        const Label* bottom = labels_[0].data();
        const Label* top = labels_[1].data();
        for (std::size_t j = 0; j + 1 < py_; ++j) {
            for (std::size_t i = 0; i + 1 < px_; ++i) {
                const std::size_t at = j * px_ + i;
                const std::array<Label, 8> corners{bottom[at], bottom[at + 1], bottom[at + px_], bottom[at + px_ + 1],
                                                   top[at],    top[at + 1],    top[at + px_],    top[at + px_ + 1]};
                bool uniform = true;
                for (int c = 1; c < 8; ++c) uniform = uniform && corners[c] == corners[0];
                if (uniform) continue;
                i_ = i, j_ = j;
                const detail::CubePlan plan = rule_.active() ? rule_.plan(corners) : detail::CubePlan{};
                Labels9 labels{};
                std::copy(corners.begin(), corners.end(), labels.begin());
                labels[8] = plan.split ? plan.centre : Label{0};
                const detail::CubeTets tets = detail::cube_tetrahedra(plan);
                for (std::size_t t = 0; t < tets.count; ++t) extract_tet(tets.tets[t], labels);
            }
        }
    }

    LabelPair sides_of(Label a, Label b) const
    {
        if (a == background_) return {b, a};
        if (b == background_) return {a, b};
        return a > b ? LabelPair{a, b} : LabelPair{b, a};
    }

    std::size_t grid_index(int corner) const
    {
        return (j_ + static_cast<std::size_t>(corner >> 1 & 1)) * px_ + i_ + static_cast<std::size_t>(corner & 1);
    }

    /// Position of cube vertex v (corner 0-7 or centre 8).
    static Local vertex_local(int v)
    {
        return v == 8 ? Local{12, 12, 12} : Local{24 * (v & 1), 24 * (v >> 1 & 1), 24 * (v >> 2 & 1)};
    }

    /// The barycentric-dual surface in tetrahedron `tet` (cube vertices; a Kuhn tetrahedron lists them
    /// in chain order).
    void extract_tet(const std::array<int, 4>& tet, const Labels9& all)
    {
        std::array<Label, 4> labels{};
        for (int v = 0; v < 4; ++v) labels[v] = all[tet[v]];
        std::array<Label, 4> distinct = labels;
        std::sort(distinct.begin(), distinct.end());
        const auto count = std::unique(distinct.begin(), distinct.end()) - distinct.begin();
        if (count == 1) return;
        if (count == 2) return extract_two_label_tet(tet, labels);
        DualPoint centroid;
        for (int v = 0; v < 4; ++v)
            for (int axis = 0; axis < 3; ++axis) centroid.local[axis] += vertex_local(tet[v])[axis] / 4;
        centroid.id = new_vertex(centroid.local);
        for (int omitted = 3; omitted >= 0; --omitted) {
            std::array<int, 3> face{};
            for (int v = 0, n = 0; v < 4; ++v)
                if (v != omitted) face[n++] = tet[v];
            cone_face(face, all, centroid);
        }
    }

    /// Marching tetrahedra: one triangle around a lone vertex, or the planar quad between two pairs (split
    /// along the diagonal from the midpoint of the edge between the first vertices of each side).
    void extract_two_label_tet(const std::array<int, 4>& tet, const std::array<Label, 4>& labels)
    {
        std::array<int, 4> side_a{}, side_b{};
        int na = 0, nb = 0;
        for (int v = 0; v < 4; ++v) (labels[v] == labels[0] ? side_a[na++] : side_b[nb++]) = tet[v];
        const Label la = labels[0];
        Label other = la;
        for (const Label label : labels)
            if (label != la) other = label;
        if (na == 1 || nb == 1) {
            const bool a_lone = na == 1;
            const std::array<int, 4>& lone = a_lone ? side_a : side_b;
            const std::array<int, 4>& rest = a_lone ? side_b : side_a;
            const int w = lone[0];
            emit(edge_point(w, rest[0]), edge_point(w, rest[1]), edge_point(w, rest[2]), w, a_lone ? la : other,
                 a_lone ? other : la);
            return;
        }
        const int a = side_a[0], b = side_a[1], c = side_b[0], d = side_b[1];
        const DualPoint ac = edge_point(a, c), bd = edge_point(b, d);
        emit(ac, edge_point(a, d), bd, a, la, other);
        emit(ac, bd, edge_point(b, c), a, la, other);
    }

    /// The triangles from the tetrahedron's centroid to the separating curve on one face.
    void cone_face(const std::array<int, 3>& face, const Labels9& all, const DualPoint& centroid)
    {
        const Label l0 = all[face[0]], l1 = all[face[1]], l2 = all[face[2]];
        if (l0 == l1 && l1 == l2) return;
        if (l0 != l1 && l1 != l2 && l0 != l2) {
            const DualPoint middle = face_point(face);
            for (int e = 0; e < 3; ++e) {
                const int x = face[e], y = face[(e + 1) % 3];
                emit(edge_point(x, y), middle, centroid, x, all[x], all[y]);
            }
            return;
        }
        const int w = l1 == l2 ? face[0] : (l0 == l2 ? face[1] : face[2]);
        std::array<int, 2> pair{};
        for (int v = 0, n = 0; v < 3; ++v)
            if (face[v] != w) pair[n++] = face[v];
        emit(edge_point(w, pair[0]), edge_point(w, pair[1]), centroid, w, all[w], all[pair[0]]);
    }

    /// Appends triangle (p, q, r) separating `reference_label` (the label of cube vertex `reference`, which
    /// lies strictly on one side of the triangle's plane) from `other`, oriented from `from` into `to`.
    void emit(const DualPoint& p, DualPoint q, DualPoint r, int reference, Label reference_label, Label other)
    {
        const LabelPair pair = sides_of(reference_label, other);
        const long long side = orientation(p.local, q.local, r.local, vertex_local(reference));
        if (side == 0)
            throw AlgorithmError("extract_interfaces: degenerate dual triangle; this is a bug, please report it");
        // side > 0: the reference vertex is in front of the triangle; `from` must be behind it.
        if ((side > 0) == (reference_label == pair.from)) std::swap(q, r);
        if (flip_) std::swap(q, r);
        triangles_.push_back({p.id, q.id, r.id});
        sides_.push_back(pair);
    }

    /// Midpoint of the edge between cube vertices x and y. A grid edge of the Kuhn kind (one corner a
    /// subset of the other: it starts at the lower one in a non-negative grid direction) has a slot per
    /// grid point; any other edge (a split face's other diagonal, a centre edge) is keyed by position.
    DualPoint edge_point(int x, int y)
    {
        DualPoint point;
        for (int axis = 0; axis < 3; ++axis) point.local[axis] = (vertex_local(x)[axis] + vertex_local(y)[axis]) / 2;
        const int low = std::min(x, y), high = std::max(x, y);
        if (high < 8 && (low & high) == low) {
            std::uint32_t& slot = edges_[low >> 2][grid_index(low) * 8 + static_cast<std::size_t>(high & ~low)];
            if (slot == no_vertex) slot = new_vertex(point.local);
            point.id = slot;
        } else {
            point.id = shared_vertex(point.local);
        }
        return point;
    }

    /// Centroid of a triangle of cube vertices: a Kuhn triangle (corners a chain of subsets) has a slot per
    /// grid point; any other is keyed by position.
    DualPoint face_point(std::array<int, 3> face)
    {
        DualPoint point;
        for (int axis = 0; axis < 3; ++axis)
            point.local[axis] =
                (vertex_local(face[0])[axis] + vertex_local(face[1])[axis] + vertex_local(face[2])[axis]) / 3;
        std::sort(face.begin(), face.end());
        const int c0 = face[0], c1 = face[1], c2 = face[2];
        if (c2 < 8 && (c0 & c1) == c0 && (c1 & c2) == c1) {
            const auto kind = face_slots[static_cast<std::size_t>(8 * (c1 & ~c0) + (c2 & ~c0))];
            std::uint32_t& slot = faces_[c0 >> 2][grid_index(c0) * 12 + static_cast<std::size_t>(kind)];
            if (slot == no_vertex) slot = new_vertex(point.local);
            point.id = slot;
        } else {
            point.id = shared_vertex(point.local);
        }
        return point;
    }

    /// The vertex at `local` in the current cube, created on first use (see shared_).
    std::uint32_t shared_vertex(const Local& local)
    {
        const auto global = [&](int axis, std::size_t base) {
            return static_cast<std::uint64_t>(24 * base) +
                   static_cast<std::uint64_t>(local[static_cast<std::size_t>(axis)]);
        };
        const std::uint64_t key = global(0, i_) << 42 | global(1, j_) << 21 | global(2, k_);
        const auto [it, inserted] = shared_.try_emplace(key, no_vertex);
        if (inserted) it->second = new_vertex(local);
        return it->second;
    }

    std::uint32_t new_vertex(const Local& local)
    {
        const std::size_t id = first_vertex_ + vertices_.size();
        if (id >= no_vertex)
            throw InputError("extract_interfaces: more than 4 294 967 294 vertices; crop or coarsen the image");
        const Vec3 index{static_cast<double>(i_) - 1 + local[0] / 24.0, static_cast<double>(j_) - 1 + local[1] / 24.0,
                         static_cast<double>(k_) - 1 + local[2] / 24.0};
        vertices_.push_back(image_.index_to_world(index));
        return static_cast<std::uint32_t>(id);
    }

    const LabelImage& image_;
    std::vector<Label> map_;
    Label background_;
    detail::PriorityRule rule_;
    /// Vertex ids of split-cube dual points that no grid slot holds, keyed by their padded-grid position
    /// in 24ths of a voxel (21 bits per axis): a dual point is the barycentre of one simplex, and distinct
    /// simplices of a triangulation have distinct barycentres, so the key names the simplex exactly.
    std::unordered_map<std::uint64_t, std::uint32_t> shared_;
    std::size_t px_, py_;
    bool flip_;
    std::size_t i_ = 0, j_ = 0, k_ = 0;
    std::array<std::vector<Label>, 2> labels_;
    std::array<std::vector<std::uint32_t>, 2> edges_;
    std::array<std::vector<std::uint32_t>, 2> faces_;
    /// The current slab's new vertices and triangles, handed to the sink when the slab is done.
    std::vector<Vec3> vertices_;
    std::vector<Triangle> triangles_;
    std::vector<LabelPair> sides_;
    std::size_t first_vertex_ = 0, triangle_count_ = 0;
    std::vector<bool> seen_ = std::vector<bool>(std::size_t{1} << 16, false);
};

} // namespace

void extract_interfaces(const LabelImage& image, const ExtractOptions& options, InterfaceSink& sink,
                        const Progress& progress)
{
    detail::ExtractionLabels labels = detail::prepare_extraction(
        image, options.tissues, options.background, options.priority, max_priority_side, "extract_interfaces");
    const std::set<Label>& tissues = labels.tissues;
    std::vector<Label> map = std::move(labels.map);
    SlabExtractor extractor(image, std::move(map), options.background, options.priority);
    extractor.run(sink, progress);
    // No tissue may be lost: padding gives every tissue a boundary, so this is a guard against bugs.
    for (const Label tissue : tissues)
        if (!extractor.produced(tissue))
            throw AlgorithmError(concat("extract_interfaces: tissue ", tissue,
                                        " produced no triangles; this is "
                                        "a bug, please report it with the image"));
    progress.info("extract", concat(extractor.triangle_count(), " triangles, ", extractor.vertex_count(), " vertices, ",
                                    tissues.size(), " tissues"));
}

InterfaceComplex extract_interfaces(const LabelImage& image, const ExtractOptions& options, const Progress& progress)
{
    CollectingSink collect;
    extract_interfaces(image, options, collect, progress);
    return std::move(collect.complex());
}

} // namespace tissuemesh::surface
