#include "core/tet_adjacency.h"

#include <algorithm>
#include <cstdint>

#include "core/tet_shape.h"

namespace tissuemesh {

TetAdjacency::TetAdjacency(const std::vector<Tet>& tets, std::size_t vertex_count) { build(tets, vertex_count); }

TetAdjacency::TetAdjacency(const std::vector<std::array<int, 4>>& tets, std::size_t vertex_count)
{
    build(tets, vertex_count);
}

namespace {

/// The three vertices of a face in ascending order (a sorting network: no loop, no call).
std::array<std::uint32_t, 3> ascending(std::uint32_t a, std::uint32_t b, std::uint32_t c)
{
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {a, b, c};
}

} // namespace

template <typename TetList>
void TetAdjacency::build(const TetList& tets, std::size_t vertex_count)
{
    // Every tet face goes into the bucket of its smallest vertex (a counting sort), then each small bucket is
    // sorted by the other two vertices, so the holders of a face are neighbours: passes over the faces, no
    // search through other tets per face. The buckets are filled in parallel with atomic cursors, so the order
    // inside a bucket varies from run to run; sorting by (middle, largest, slot) makes it unique again.
    const auto count = static_cast<std::int64_t>(tets.size());
    const auto sorted_face = [&](std::size_t t, int k) {
        return ascending(static_cast<std::uint32_t>(tets[t][tet_faces[k][0]]),
                         static_cast<std::uint32_t>(tets[t][tet_faces[k][1]]),
                         static_cast<std::uint32_t>(tets[t][tet_faces[k][2]]));
    };
    start_.assign(vertex_count + 1, 0);
    // A tet's faces' smallest vertices: its smallest vertex for the three faces holding it, its second smallest
    // for the face opposite it.
    const auto smallest_two = [&](std::size_t t) {
        std::array<std::uint32_t, 4> v{static_cast<std::uint32_t>(tets[t][0]), static_cast<std::uint32_t>(tets[t][1]),
                                       static_cast<std::uint32_t>(tets[t][2]), static_cast<std::uint32_t>(tets[t][3])};
        if (v[0] > v[1]) std::swap(v[0], v[1]);
        if (v[2] > v[3]) std::swap(v[2], v[3]);
        if (v[0] > v[2]) std::swap(v[0], v[2]), std::swap(v[1], v[3]); // the pair with the smallest first
        return std::pair{v[0], std::min(v[1], v[2])};
    };
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t) {
        const auto [first, second] = smallest_two(static_cast<std::size_t>(t));
#pragma omp atomic
        start_[first + 1] += 3;
#pragma omp atomic
        ++start_[second + 1];
    }
    for (std::size_t v = 0; v < vertex_count; ++v) start_[v + 1] += start_[v];
    entries_.resize(start_.back());
    std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t)
        for (int k = 0; k < 4; ++k) {
            const std::array<std::uint32_t, 3> v = sorted_face(static_cast<std::size_t>(t), k);
            std::size_t at = 0;
#pragma omp atomic capture
            at = next[v[0]]++;
            entries_[at] = {v[1], v[2], static_cast<std::uint32_t>(4 * t + k)};
        }
    across_.assign(4 * tets.size(), no_tet);
    holders_.assign(4 * tets.size(), 0);
    const auto vertices = static_cast<std::int64_t>(vertex_count);
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::int64_t v = 0; v < vertices; ++v) {
        const auto begin = entries_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(v)]);
        const auto end = entries_.begin() + static_cast<std::ptrdiff_t>(start_[static_cast<std::size_t>(v) + 1]);
        // Buckets hold a dozen entries or so: an insertion sort on (middle, largest) packed in one key, then slot.
        const auto before = [](const Entry& a, const Entry& b) {
            const std::uint64_t ka = std::uint64_t{a.middle} << 32 | a.largest,
                                kb = std::uint64_t{b.middle} << 32 | b.largest;
            return ka != kb ? ka < kb : a.slot < b.slot;
        };
        for (auto i = begin + (begin != end); i < end; ++i) {
            const Entry e = *i;
            auto j = i;
            for (; j != begin && before(e, *(j - 1)); --j) *j = *(j - 1);
            *j = e;
        }
        for (auto run = begin; run != end;) {
            auto run_end = run + 1;
            while (run_end != end && run_end->middle == run->middle && run_end->largest == run->largest) ++run_end;
            const auto holders = static_cast<std::uint8_t>(std::min<std::ptrdiff_t>(run_end - run, 255));
            for (auto e = run; e != run_end; ++e) holders_[e->slot] = holders;
            if (holders >= 2) {
                across_[run->slot] = (run + 1)->slot / 4;
                across_[(run + 1)->slot] = run->slot / 4;
            }
            run = run_end;
        }
    }
}

TetAdjacency::Face TetAdjacency::face_at(std::uint32_t v, std::size_t first) const
{
    const Entry& head = entries_[first];
    Face face{{v, head.middle, head.largest}, 0, {no_tet, no_tet}, first};
    for (std::size_t e = first;
         e < start_[v + 1] && entries_[e].middle == head.middle && entries_[e].largest == head.largest; ++e) {
        if (face.holders < 2) face.tets[face.holders] = entries_[e].slot / 4;
        ++face.holders;
    }
    return face;
}

std::vector<TetAdjacency::Face> TetAdjacency::faces() const
{
    std::vector<Face> out;
    for (std::uint32_t v = 0; v < vertex_count(); ++v)
        for_each_face_at(v, [&](const Face& face) { out.push_back(face); });
    return out;
}

TetAdjacency::Face TetAdjacency::find(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
{
    const std::array<std::uint32_t, 3> v = ascending(a, b, c);
    if (v[0] + std::size_t{1} >= start_.size()) return {v, 0, {no_tet, no_tet}, 0};
    const auto begin = entries_.begin() + static_cast<std::ptrdiff_t>(start_[v[0]]);
    const auto end = entries_.begin() + static_cast<std::ptrdiff_t>(start_[v[0] + 1]);
    const auto found = std::lower_bound(begin, end, v, [](const Entry& e, const std::array<std::uint32_t, 3>& key) {
        return e.middle != key[1] ? e.middle < key[1] : e.largest < key[2];
    });
    if (found == end || found->middle != v[1] || found->largest != v[2]) return {v, 0, {no_tet, no_tet}, 0};
    return face_at(v[0], static_cast<std::size_t>(found - entries_.begin()));
}

} // namespace tissuemesh
