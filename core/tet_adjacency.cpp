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

template <typename TetList>
void TetAdjacency::build(const TetList& tets, std::size_t vertex_count)
{
    // Every tet face goes into the bucket of its smallest vertex (a counting sort), then each small bucket is
    // sorted by the other two vertices, so the holders of a face are neighbours: passes over the faces, no
    // search through other tets per face. The buckets are filled in parallel with atomic cursors, so the order
    // inside a bucket varies from run to run; sorting by (middle, largest, slot) makes it unique again.
    const auto count = static_cast<std::int64_t>(tets.size());
    const auto sorted_face = [&](std::size_t t, int k) {
        std::array<std::uint32_t, 3> v{static_cast<std::uint32_t>(tets[t][tet_faces[k][0]]),
                                       static_cast<std::uint32_t>(tets[t][tet_faces[k][1]]),
                                       static_cast<std::uint32_t>(tets[t][tet_faces[k][2]])};
        std::sort(v.begin(), v.end());
        return v;
    };
    start_.assign(vertex_count + 1, 0);
#pragma omp parallel for schedule(static)
    for (std::int64_t t = 0; t < count; ++t)
        for (int k = 0; k < 4; ++k) {
            const std::uint32_t smallest = sorted_face(static_cast<std::size_t>(t), k)[0];
#pragma omp atomic
            ++start_[smallest + 1];
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
        std::sort(begin, end, [](const Entry& a, const Entry& b) {
            return a.middle != b.middle     ? a.middle < b.middle
                   : a.largest != b.largest ? a.largest < b.largest
                                            : a.slot < b.slot;
        });
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
    Face face{{v, head.middle, head.largest}, 0, {no_tet, no_tet}};
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
    for (std::uint32_t v = 0; v + 1 < start_.size(); ++v)
        for (std::size_t e = start_[v]; e < start_[v + 1]; e += out.back().holders) out.push_back(face_at(v, e));
    return out;
}

TetAdjacency::Face TetAdjacency::find(std::uint32_t a, std::uint32_t b, std::uint32_t c) const
{
    std::array<std::uint32_t, 3> v{a, b, c};
    std::sort(v.begin(), v.end());
    if (v[0] + std::size_t{1} >= start_.size()) return {v, 0, {no_tet, no_tet}};
    const auto begin = entries_.begin() + static_cast<std::ptrdiff_t>(start_[v[0]]);
    const auto end = entries_.begin() + static_cast<std::ptrdiff_t>(start_[v[0] + 1]);
    const auto found = std::lower_bound(begin, end, v, [](const Entry& e, const std::array<std::uint32_t, 3>& key) {
        return e.middle != key[1] ? e.middle < key[1] : e.largest < key[2];
    });
    if (found == end || found->middle != v[1] || found->largest != v[2]) return {v, 0, {no_tet, no_tet}};
    return face_at(v[0], static_cast<std::size_t>(found - entries_.begin()));
}

} // namespace tissuemesh
