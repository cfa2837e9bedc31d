#include "tests/surface/complex_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <set>
#include <sstream>

#include "core/error.h"

namespace tissuemesh::testing {

LabelImage make_image(const Dims& dims, const std::function<Label(int, int, int)>& label_of)
{
    LabelImage image(dims, {1, 1, 1});
    for (std::size_t k = 0; k < dims[2]; ++k)
        for (std::size_t j = 0; j < dims[1]; ++j)
            for (std::size_t i = 0; i < dims[0]; ++i)
                image.at(i, j, k) = label_of(static_cast<int>(i), static_cast<int>(j), static_cast<int>(k));
    return image;
}

LabelImage random_image(const Dims& dims, std::mt19937& random, Label max_label)
{
    std::uniform_int_distribution<int> pick(0, max_label);
    return make_image(dims, [&](int, int, int) { return static_cast<Label>(pick(random)); });
}

namespace {

using Edge = std::pair<std::uint32_t, std::uint32_t>;

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t x)
{
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

/// Integer points (24ths of a mm) and exact predicates for the intersection test.
using IPoint = std::array<long long, 3>;

long long orient3(const IPoint& p, const IPoint& q, const IPoint& r, const IPoint& s)
{
    const long long a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const long long b[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const long long c[3] = {s[0] - p[0], s[1] - p[1], s[2] - p[2]};
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

int sign(long long v) { return (v > 0) - (v < 0); }

/// 2D orientation after dropping axis `drop`.
long long orient2(const IPoint& p, const IPoint& q, const IPoint& r, int drop)
{
    const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
    return (q[u] - p[u]) * (r[v] - p[v]) - (q[v] - p[v]) * (r[u] - p[u]);
}

bool on_segment2(const IPoint& p, const IPoint& a, const IPoint& b)
{
    for (int axis = 0; axis < 3; ++axis)
        if (p[axis] < std::min(a[axis], b[axis]) || p[axis] > std::max(a[axis], b[axis])) return false;
    return true;
}

bool segments_meet2(const IPoint& a, const IPoint& b, const IPoint& c, const IPoint& d, int drop)
{
    const int o1 = sign(orient2(a, b, c, drop)), o2 = sign(orient2(a, b, d, drop));
    const int o3 = sign(orient2(c, d, a, drop)), o4 = sign(orient2(c, d, b, drop));
    if (o1 * o2 < 0 && o3 * o4 < 0) return true;
    return (o1 == 0 && on_segment2(c, a, b)) || (o2 == 0 && on_segment2(d, a, b)) ||
           (o3 == 0 && on_segment2(a, c, d)) || (o4 == 0 && on_segment2(b, c, d));
}

/// Closed segment [a, b] against closed triangle t, exactly.
bool segment_meets_triangle(const IPoint& a, const IPoint& b, const std::array<IPoint, 3>& t)
{
    const int sa = sign(orient3(t[0], t[1], t[2], a)), sb = sign(orient3(t[0], t[1], t[2], b));
    if (sa * sb > 0) return false;
    if (sa == 0 && sb == 0) {
        // Coplanar: drop the axis along which the triangle's normal is largest.
        const IPoint e1{t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]};
        const IPoint e2{t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]};
        const std::array<long long, 3> n{std::llabs(e1[1] * e2[2] - e1[2] * e2[1]),
                                         std::llabs(e1[2] * e2[0] - e1[0] * e2[2]),
                                         std::llabs(e1[0] * e2[1] - e1[1] * e2[0])};
        const int drop = static_cast<int>(std::max_element(n.begin(), n.end()) - n.begin());
        const int s = sign(orient2(t[0], t[1], t[2], drop));
        const auto inside = [&](const IPoint& p) {
            return sign(orient2(t[0], t[1], p, drop)) * s >= 0 && sign(orient2(t[1], t[2], p, drop)) * s >= 0 &&
                   sign(orient2(t[2], t[0], p, drop)) * s >= 0;
        };
        if (inside(a) || inside(b)) return true;
        for (int e = 0; e < 3; ++e)
            if (segments_meet2(a, b, t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)], drop))
                return true;
        return false;
    }
    const int o0 = sign(orient3(a, b, t[0], t[1])), o1 = sign(orient3(a, b, t[1], t[2]));
    const int o2 = sign(orient3(a, b, t[2], t[0]));
    return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
}

bool triangles_meet(const std::array<IPoint, 3>& s, const std::array<IPoint, 3>& t)
{
    for (int e = 0; e < 3; ++e) {
        if (segment_meets_triangle(s[static_cast<std::size_t>(e)], s[static_cast<std::size_t>((e + 1) % 3)], t))
            return true;
        if (segment_meets_triangle(t[static_cast<std::size_t>(e)], t[static_cast<std::size_t>((e + 1) % 3)], s))
            return true;
    }
    return false;
}

/// 24ths, not 12ths: the priority rule's split cubes put tetrahedron centroids on the 1/24 lattice.
IPoint twenty_fourths(const Vec3& p)
{
    IPoint q{};
    for (int axis = 0; axis < 3; ++axis) {
        q[axis] = std::llround(p[axis] * 24.0);
        if (std::abs(p[axis] * 24.0 - static_cast<double>(q[axis])) > 1e-6)
            throw InputError("intersecting_pairs: vertex not on the 1/24 mm lattice");
    }
    return q;
}

IPoint minus(const IPoint& a, const IPoint& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

/// Triangles s and t share exactly one vertex, s[0] == t[0] after rotation: they may meet only there.
bool meet_beyond_shared_vertex(const std::array<IPoint, 3>& s, const std::array<IPoint, 3>& t)
{
    if (segment_meets_triangle(s[1], s[2], t) || segment_meets_triangle(t[1], t[2], s)) return true;
    // An edge from the shared vertex lying in the other's plane and inside its angle at that vertex.
    const auto edge_enters = [](const std::array<IPoint, 3>& a, const std::array<IPoint, 3>& b) {
        for (int e = 1; e < 3; ++e) {
            const IPoint& w = a[static_cast<std::size_t>(e)];
            if (orient3(b[0], b[1], b[2], w) != 0) continue;
            const IPoint x = minus(b[1], b[0]), y = minus(b[2], b[0]), d = minus(w, b[0]);
            const IPoint n{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
            const auto dot_cross = [&](const IPoint& u, const IPoint& v) {
                return n[0] * (u[1] * v[2] - u[2] * v[1]) + n[1] * (u[2] * v[0] - u[0] * v[2]) +
                       n[2] * (u[0] * v[1] - u[1] * v[0]);
            };
            if (dot_cross(x, d) >= 0 && dot_cross(d, y) >= 0) return true;
        }
        return false;
    };
    return edge_enters(s, t) || edge_enters(t, s);
}

/// Triangles sharing edge (a, b) with third vertices p and q overlap only when coplanar on one side.
bool overlap_across_shared_edge(const IPoint& a, const IPoint& b, const IPoint& p, const IPoint& q)
{
    if (orient3(a, b, p, q) != 0) return false;
    const IPoint e = minus(b, a), u = minus(p, a), v = minus(q, a);
    const IPoint cu{e[1] * u[2] - e[2] * u[1], e[2] * u[0] - e[0] * u[2], e[0] * u[1] - e[1] * u[0]};
    const IPoint cv{e[1] * v[2] - e[2] * v[1], e[2] * v[0] - e[0] * v[2], e[0] * v[1] - e[1] * v[0]};
    return cu[0] * cv[0] + cu[1] * cv[1] + cu[2] * cv[2] > 0;
}

bool pair_intersects(const Triangle& s_ids, const Triangle& t_ids, std::array<IPoint, 3> s, std::array<IPoint, 3> t)
{
    int shared = 0;
    std::array<int, 3> where{-1, -1, -1};
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            if (s_ids[static_cast<std::size_t>(a)] == t_ids[static_cast<std::size_t>(b)]) where[a] = b, ++shared;
    if (shared == 0) return triangles_meet(s, t);
    if (shared == 3) return true;
    // Rotate so that shared vertices come first in both.
    std::array<IPoint, 3> s2{}, t2{};
    int n = 0;
    for (int a = 0; a < 3; ++a)
        if (where[a] >= 0) s2[n] = s[a], t2[n++] = t[where[a]];
    const int shared_count = n;
    for (int a = 0; a < 3; ++a)
        if (where[a] < 0) s2[n++] = s[a];
    n = shared_count;
    for (int b = 0; b < 3; ++b)
        if (std::find(where.begin(), where.end(), b) == where.end()) t2[n++] = t[b];
    if (shared == 1) return meet_beyond_shared_vertex(s2, t2);
    return overlap_across_shared_edge(s2[0], s2[1], s2[2], t2[2]);
}

} // namespace

TissueSurfaceFacts tissue_facts(const InterfaceComplex& complex, Label tissue)
{
    TissueSurfaceFacts facts;
    std::map<Edge, int> directed;
    std::vector<std::size_t> mine;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair side = complex.sides[t];
        if (side.from != tissue && side.to != tissue) continue;
        Triangle tri = complex.triangles[t];
        if (side.to == tissue) std::swap(tri[1], tri[2]);
        mine.push_back(t);
        const Vec3 &a = complex.vertices[tri[0]], &b = complex.vertices[tri[1]], &c = complex.vertices[tri[2]];
        facts.volume_mm3 += dot(a, cross(b, c)) / 6.0;
        for (int e = 0; e < 3; ++e)
            ++directed[{tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)]}];
    }
    facts.triangles = mine.size();
    for (const auto& [edge, count] : directed) {
        const auto reverse = directed.find({edge.second, edge.first});
        if (count != 1 || reverse == directed.end() || reverse->second != 1) ++facts.bad_edges;
    }
    // Edge-connected components by union-find over triangles.
    std::vector<std::uint32_t> parent(mine.size());
    std::iota(parent.begin(), parent.end(), 0u);
    std::map<Edge, std::uint32_t> first_user;
    for (std::uint32_t m = 0; m < mine.size(); ++m)
        for (int e = 0; e < 3; ++e) {
            const Triangle& tri = complex.triangles[mine[m]];
            const std::uint32_t a = tri[static_cast<std::size_t>(e)], b = tri[static_cast<std::size_t>((e + 1) % 3)];
            const auto [it, fresh] = first_user.try_emplace(std::minmax(a, b), m);
            if (!fresh) parent[find_root(parent, m)] = find_root(parent, it->second);
        }
    for (std::uint32_t m = 0; m < mine.size(); ++m) facts.components += find_root(parent, m) == m ? 1 : 0;
    return facts;
}

std::size_t duplicate_triangles(const InterfaceComplex& complex)
{
    std::set<Triangle> seen;
    std::size_t duplicates = 0;
    for (Triangle tri : complex.triangles) {
        std::sort(tri.begin(), tri.end());
        if (!seen.insert(tri).second) ++duplicates;
    }
    return duplicates;
}

std::size_t degenerate_triangles(const InterfaceComplex& complex, double min_area_mm2)
{
    std::size_t count = 0;
    for (const Triangle& tri : complex.triangles) {
        const Vec3 &a = complex.vertices[tri[0]], &b = complex.vertices[tri[1]], &c = complex.vertices[tri[2]];
        if (0.5 * norm(cross(b - a, c - a)) < min_area_mm2) ++count;
    }
    return count;
}

std::size_t intersecting_pairs(const InterfaceComplex& complex)
{
    std::vector<IPoint> points;
    for (const Vec3& v : complex.vertices) points.push_back(twenty_fourths(v));
    const std::size_t n = complex.triangles.size();
    std::vector<std::array<IPoint, 3>> tris(n);
    std::vector<std::array<long long, 6>> boxes(n);
    for (std::size_t t = 0; t < n; ++t) {
        for (int c = 0; c < 3; ++c)
            tris[t][static_cast<std::size_t>(c)] = points[complex.triangles[t][static_cast<std::size_t>(c)]];
        for (int axis = 0; axis < 3; ++axis) {
            boxes[t][axis] = std::min({tris[t][0][axis], tris[t][1][axis], tris[t][2][axis]});
            boxes[t][axis + 3] = std::max({tris[t][0][axis], tris[t][1][axis], tris[t][2][axis]});
        }
    }
    std::size_t count = 0;
    for (std::size_t s = 0; s < n; ++s)
        for (std::size_t t = s + 1; t < n; ++t) {
            bool apart = false;
            for (int axis = 0; axis < 3; ++axis)
                apart = apart || boxes[s][axis] > boxes[t][axis + 3] || boxes[t][axis] > boxes[s][axis + 3];
            if (!apart && pair_intersects(complex.triangles[s], complex.triangles[t], tris[s], tris[t])) ++count;
        }
    return count;
}

namespace {

/// The image padded by one voxel of `background`, as a flat array over (nx+2, ny+2, nz+2).
struct Padded {
    std::array<long long, 3> dims{};
    std::vector<Label> labels;
    Label at(long long i, long long j, long long k) const
    {
        return labels[static_cast<std::size_t>(i + dims[0] * (j + dims[1] * k))];
    }
};

Padded pad(const LabelImage& image, Label background)
{
    Padded padded;
    for (int axis = 0; axis < 3; ++axis) padded.dims[axis] = static_cast<long long>(image.dims()[axis]) + 2;
    padded.labels.assign(static_cast<std::size_t>(padded.dims[0] * padded.dims[1] * padded.dims[2]), background);
    for (std::size_t k = 0; k < image.dims()[2]; ++k)
        for (std::size_t j = 0; j < image.dims()[1]; ++j)
            for (std::size_t i = 0; i < image.dims()[0]; ++i)
                padded.labels[(i + 1) + static_cast<std::size_t>(padded.dims[0]) *
                                            ((j + 1) + static_cast<std::size_t>(padded.dims[1]) * (k + 1))] =
                    image.at(i, j, k);
    return padded;
}

} // namespace

std::size_t voxel_components(const LabelImage& image, Label label, Label background, bool complement)
{
    const Padded padded = pad(image, background);
    // The Freudenthal 14-neighbourhood: the edges of the Kuhn tetrahedra.
    static const std::array<std::array<int, 3>, 7> steps{
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}}};
    const auto member = [&](std::size_t at) { return (padded.labels[at] == label) != complement; };
    std::vector<char> seen(padded.labels.size(), 0);
    std::size_t components = 0;
    const long long nx = padded.dims[0], ny = padded.dims[1], nz = padded.dims[2];
    for (std::size_t start = 0; start < padded.labels.size(); ++start) {
        if (seen[start] || !member(start)) continue;
        ++components;
        std::vector<std::size_t> stack{start};
        seen[start] = 1;
        while (!stack.empty()) {
            const auto at = static_cast<long long>(stack.back());
            stack.pop_back();
            const long long i = at % nx, j = at / nx % ny, k = at / (nx * ny);
            for (const auto& step : steps)
                for (const int s : {1, -1}) {
                    const long long a = i + s * step[0], b = j + s * step[1], c = k + s * step[2];
                    if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
                    const auto next = static_cast<std::size_t>(a + nx * (b + ny * c));
                    if (seen[next] || !member(next)) continue;
                    seen[next] = 1;
                    stack.push_back(next);
                }
        }
    }
    return components;
}

std::size_t boundary_cubes(const LabelImage& image, Label label, Label background)
{
    const Padded padded = pad(image, background);
    std::size_t count = 0;
    for (long long k = 0; k + 1 < padded.dims[2]; ++k)
        for (long long j = 0; j + 1 < padded.dims[1]; ++j)
            for (long long i = 0; i + 1 < padded.dims[0]; ++i) {
                bool has = false, other = false;
                for (int c = 0; c < 8; ++c) {
                    const bool is = padded.at(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1)) == label;
                    has = has || is;
                    other = other || !is;
                }
                count += has && other ? 1 : 0;
            }
    return count;
}

std::string invariant_failures(const LabelImage& image, const InterfaceComplex& complex, Label background,
                               bool exact_intersections, const std::map<Label, int>& priority)
{
    std::ostringstream failures;
    const double voxel = image.voxel_volume_mm3();
    std::map<Label, std::size_t> counts = count_labels(image);
    counts.try_emplace(background, 0);
    double tissue_volume = 0;
    for (const auto& [label, voxels] : counts) {
        const TissueSurfaceFacts facts = tissue_facts(complex, label);
        if (facts.triangles == 0) failures << "tissue " << label << " lost\n";
        if (facts.bad_edges != 0) failures << "tissue " << label << ": " << facts.bad_edges << " bad edges\n";
        const std::size_t expected = priority.empty()
                                         ? voxel_components(image, label, background, false) +
                                               voxel_components(image, label, background, true) - 1
                                         : priority_components(image, label, background, false, priority) +
                                               priority_components(image, label, background, true, priority) - 1;
        if (facts.components != expected)
            failures << "tissue " << label << ": " << facts.components << " surface components, expected " << expected
                     << "\n";
        if (label == background) continue;
        tissue_volume += facts.volume_mm3;
        // The dual surface differs from the voxel-cube boundary only inside non-uniform cubes.
        const double bound = static_cast<double>(boundary_cubes(image, label, background)) * voxel;
        if (std::abs(facts.volume_mm3 - static_cast<double>(voxels) * voxel) > bound)
            failures << "tissue " << label << ": volume " << facts.volume_mm3 << " vs voxels "
                     << static_cast<double>(voxels) * voxel << "\n";
    }
    // The background's outward surface is every tissue's surface turned inside out.
    const double background_volume = tissue_facts(complex, background).volume_mm3;
    if (std::abs(background_volume + tissue_volume) > 1e-9 * std::max(1.0, tissue_volume))
        failures << "background volume " << background_volume << " != -" << tissue_volume << "\n";
    if (const std::size_t d = duplicate_triangles(complex)) failures << d << " duplicate triangles\n";
    // Dual triangles have areas of at least 1/144 of a voxel face: anything far below is degenerate.
    const double min_area = 1e-6 * std::min({image.spacing_mm()[0], image.spacing_mm()[1], image.spacing_mm()[2]});
    if (const std::size_t d = degenerate_triangles(complex, min_area * min_area)) failures << d << " degenerate\n";
    if (exact_intersections)
        if (const std::size_t d = intersecting_pairs(complex)) failures << d << " intersecting pairs\n";
    return failures.str();
}

} // namespace tissuemesh::testing
