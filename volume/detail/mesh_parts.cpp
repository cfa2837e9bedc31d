#include "volume/detail/mesh_parts.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_set>

#include "volume/detail/face_map.h"

namespace tissuemesh::volume::detail {

PartCutter::PartCutter(const TetMesh& whole)
    : whole_(whole), row_start_(whole.vertices.size() + 1, 0), tets_at_(whole.vertices.size(), 0)
{
    on_face_.assign(whole.vertices.size(), 0);
    for (const Triangle& face : whole.faces) {
        ++row_start_[std::min({face[0], face[1], face[2]}) + 1];
        for (const std::uint32_t v : face) on_face_[v] = 1;
    }
    for (std::size_t v = 0; v + 1 < row_start_.size(); ++v) row_start_[v + 1] += row_start_[v];
    by_low_.resize(whole.faces.size());
    std::vector<std::uint32_t> fill(row_start_.begin(), row_start_.end() - 1);
    for (std::uint32_t f = 0; f < whole.faces.size(); ++f) {
        const FaceKey key = face_key(whole.faces[f][0], whole.faces[f][1], whole.faces[f][2]);
        by_low_[fill[key.v[0]]++] = {key.v[1], key.v[2], f};
    }
    for (const Tet& tet : whole.tets)
        for (const std::uint32_t v : tet) ++tets_at_[v];
}

std::optional<std::uint32_t> PartCutter::listed(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
{
    const FaceKey key = face_key(a, b, c);
    for (std::uint32_t i = row_start_[key.v[0]]; i < row_start_[key.v[0] + 1]; ++i)
        if (by_low_[i].middle == key.v[1] && by_low_[i].high == key.v[2]) return by_low_[i].face;
    return std::nullopt;
}

MeshPart PartCutter::part(const std::vector<std::uint32_t>& tets) const
{
    MeshPart part;
    part.mesh.names = whole_.names;
    // The part's nodes in ascending order, each with how many of its tets hold it: frozen when the whole has more.
    std::vector<std::uint32_t> count(whole_.vertices.size(), 0);
    for (const std::uint32_t t : tets)
        for (const std::uint32_t v : whole_.tets[t]) ++count[v];
    std::vector<std::uint32_t>& local = count; // reused: the part's index of each node it holds
    for (std::uint32_t v = 0; v < count.size(); ++v) {
        if (count[v] == 0) continue;
        part.frozen.push_back(count[v] < tets_at_[v]);
        local[v] = static_cast<std::uint32_t>(part.from_node.size());
        part.from_node.push_back(v);
    }
    part.mesh.vertices.reserve(part.from_node.size());
    for (const std::uint32_t v : part.from_node) part.mesh.vertices.push_back(whole_.vertices[v]);
    std::vector<std::uint32_t> faces;
    part.mesh.tets.reserve(tets.size());
    part.mesh.tet_labels.reserve(tets.size());
    for (const std::uint32_t t : tets) {
        const Tet& tet = whole_.tets[t];
        part.mesh.tets.push_back({local[tet[0]], local[tet[1]], local[tet[2]], local[tet[3]]});
        part.mesh.tet_labels.push_back(whole_.tet_labels[t]);
        for (int i = 0; i < 4; ++i) {
            const std::uint32_t a = tet[(i + 1) % 4], b = tet[(i + 2) % 4], c = tet[(i + 3) % 4];
            if (!on_face_[a] || !on_face_[b] || !on_face_[c]) continue; // most faces: no lookup
            if (const std::optional<std::uint32_t> found = listed(a, b, c)) faces.push_back(*found);
        }
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    part.listed = faces;
    for (const std::uint32_t f : faces) {
        const Triangle& c = whole_.faces[f];
        part.mesh.faces.push_back({local[c[0]], local[c[1]], local[c[2]]});
        part.mesh.face_sides.push_back(whole_.face_sides[f]);
    }
    return part;
}

namespace {

double axis_key(const TetMesh& mesh, std::uint32_t t, int axis)
{
    double sum = 0;
    for (const std::uint32_t v : mesh.tets[t]) sum += mesh.vertices[v][axis];
    return sum;
}

} // namespace

std::uint32_t Cut::nearest(const TetMesh& mesh, std::uint32_t t) const
{
    const double key = axis_key(mesh, t, axis);
    std::uint32_t best = 0;
    for (std::uint32_t j = 1; j < between.size(); ++j)
        if (std::abs(key - between[j]) < std::abs(key - between[best])) best = j;
    return best;
}

Cut cut_across(const TetMesh& mesh, std::size_t count)
{
    Vec3 low = mesh.vertices.front(), high = low;
    for (const Vec3& p : mesh.vertices)
        for (int a = 0; a < 3; ++a) low[a] = std::min(low[a], p[a]), high[a] = std::max(high[a], p[a]);
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (high[a] - low[a] > high[axis] - low[axis]) axis = a;
    std::vector<double> key(mesh.tets.size());
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) key[t] = axis_key(mesh, t, axis);
    std::vector<std::uint32_t> order(mesh.tets.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto before = [&](std::uint32_t a, std::uint32_t b) {
        return key[a] < key[b] || (key[a] == key[b] && a < b);
    };
    // Rank r goes to part r * count / n: only the ranks where that changes need their tets, not a full sort.
    Cut cut{std::vector<std::uint32_t>(mesh.tets.size()), axis, {}};
    const std::size_t n = order.size();
    std::size_t from = 0;
    for (std::size_t k = 1; k < count; ++k) {
        const std::size_t r = (k * n + count - 1) / count; // the first rank of part k
        if (r <= from || r >= n) continue;
        const auto at = order.begin() + static_cast<std::ptrdiff_t>(r);
        std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(from), at, order.end(), before);
        const std::uint32_t last = *std::max_element(order.begin() + static_cast<std::ptrdiff_t>(from), at, before);
        cut.between.push_back((key[last] + key[*at]) / 2);
        from = r;
    }
    for (std::size_t r = 0; r < n; ++r) cut.part_of[order[r]] = static_cast<std::uint32_t>(r * count / n);
    return cut;
}

std::vector<char> TetsAtNodes::around(const std::vector<char>& seeds, std::size_t rings) const
{
    std::vector<char> marked(mesh_.vertices.size(), 0), in(mesh_.tets.size(), 0);
    for (std::size_t t = 0; t < std::min(seeds.size(), in.size()); ++t) in[t] = seeds[t];
    for (std::size_t ring = 0; ring < rings; ++ring) {
        for (std::size_t t = 0; t < mesh_.tets.size(); ++t)
            if (in[t])
                for (const std::uint32_t v : mesh_.tets[t]) marked[v] = 1;
        for (std::uint32_t v = 0; v < mesh_.vertices.size(); ++v)
            if (marked[v])
                for (std::size_t i = at_.offsets[v]; i < at_.offsets[v + 1]; ++i) in[at_.tets[i]] = 1;
    }
    return in;
}

std::vector<char> tets_around(const TetMesh& mesh, const std::vector<char>& seeds, std::size_t rings)
{
    return TetsAtNodes(mesh).around(seeds, rings);
}

std::vector<std::uint32_t> groups_of(const TetMesh& mesh, const std::vector<char>& in, const std::vector<char>& through)
{
    std::vector<std::uint32_t> root(mesh.tets.size(), no_part);
    const auto find = [&](std::uint32_t t) {
        while (root[t] != t) t = root[t] = root[root[t]];
        return t;
    };
    std::vector<std::uint32_t> first(mesh.vertices.size(), no_part); // per node: the first flagged tet at it
    for (std::uint32_t t = 0; t < mesh.tets.size(); ++t) {
        if (t >= in.size() || !in[t]) continue;
        root[t] = t;
        for (const std::uint32_t v : mesh.tets[t]) {
            if (!through.empty() && !through[v]) continue;
            if (first[v] == no_part) {
                first[v] = t;
                continue;
            }
            const std::uint32_t a = find(first[v]), b = find(t);
            if (a != b) root[std::max(a, b)] = std::min(a, b); // the lower index stays the root
        }
    }
    for (std::uint32_t t = 0; t < root.size(); ++t)
        if (root[t] != no_part) root[t] = find(t);
    return root;
}

TetMesh merge_parts(const TetMesh& whole, const std::vector<std::uint32_t>& part_of, const std::vector<MeshPart>& parts,
                    const std::vector<TetMesh>& edited)
{
    TetMesh out;
    out.names = whole.names;
    out.vertices = whole.vertices;
    for (std::size_t t = 0; t < whole.tets.size(); ++t)
        if (part_of[t] == no_part) out.tets.push_back(whole.tets[t]), out.tet_labels.push_back(whole.tet_labels[t]);
    std::vector<std::vector<std::uint32_t>> to_whole(parts.size());
    std::vector<char> covered(whole.faces.size(), 0);
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const MeshPart& part = parts[k];
        const TetMesh& mesh = edited[k];
        std::vector<std::uint32_t>& map = to_whole[k];
        map.resize(mesh.vertices.size());
        for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
            if (v < part.from_node.size()) {
                map[v] = part.from_node[v];
                out.vertices[map[v]] = mesh.vertices[v];
            } else {
                map[v] = static_cast<std::uint32_t>(out.vertices.size());
                out.vertices.push_back(mesh.vertices[v]);
            }
        }
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
            const Tet& tet = mesh.tets[t];
            out.tets.push_back({map[tet[0]], map[tet[1]], map[tet[2]], map[tet[3]]});
            out.tet_labels.push_back(mesh.tet_labels[t]);
        }
        for (const std::uint32_t f : part.listed) covered[f] = 1;
    }
    for (std::size_t f = 0; f < whole.faces.size(); ++f)
        if (!covered[f]) out.faces.push_back(whole.faces[f]), out.face_sides.push_back(whole.face_sides[f]);
    // A face two parts hold lies between them: its nodes are frozen in both.
    std::unordered_set<FaceKey, FaceKeyHash> seen;
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const std::vector<std::uint32_t>& map = to_whole[k];
        const auto frozen = [&](std::uint32_t v) { return v < parts[k].frozen.size() && parts[k].frozen[v]; };
        for (std::size_t f = 0; f < edited[k].faces.size(); ++f) {
            const Triangle& c = edited[k].faces[f];
            const Triangle g{map[c[0]], map[c[1]], map[c[2]]};
            if (frozen(c[0]) && frozen(c[1]) && frozen(c[2]) && !seen.insert(face_key(g[0], g[1], g[2])).second)
                continue;
            out.faces.push_back(g), out.face_sides.push_back(edited[k].face_sides[f]);
        }
    }
    return out;
}

} // namespace tissuemesh::volume::detail
