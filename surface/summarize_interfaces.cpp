#include "surface/summarize_interfaces.h"

#include <algorithm>
#include <utility>

#include "core/error.h"

namespace tissuemesh::surface {
namespace {

using EdgeLabels = InterfaceSummarizer::EdgeLabels;

/// Counts an edge once all its triangles are known: a junction edge when 3 or more tissues meet there.
void count_edge(const EdgeLabels& labels, InterfaceSummary& summary)
{
    if (labels.count < 3) return;
    ++summary.junction_edges;
    for (int l = 0; l < labels.count; ++l) ++summary.tissues[labels.labels[static_cast<std::size_t>(l)]].junction_edges;
}

std::pair<std::uint32_t, std::uint32_t> edge_of(const Triangle& tri, int e)
{
    return std::minmax(tri[static_cast<std::size_t>(e)], tri[static_cast<std::size_t>((e + 1) % 3)]);
}

} // namespace

InterfaceSummary summarize_interfaces(const InterfaceComplex& complex)
{
    InterfaceSummary summary;
    summary.vertices = complex.vertices.size();
    summary.triangles = complex.triangles.size();
    std::set<std::pair<Label, Label>> pairs;
    // Edges bucketed by their lower vertex (compressed rows): (other vertex, triangle) per use.
    const std::size_t n = complex.vertices.size();
    std::vector<std::size_t> start(n + 1, 0);
    for (const Triangle& tri : complex.triangles)
        for (int e = 0; e < 3; ++e) ++start[edge_of(tri, e).first + 1];
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::pair<std::uint32_t, std::uint32_t>> uses(start[n]);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair side = complex.sides[t];
        ++summary.tissues[side.from].triangles;
        ++summary.tissues[side.to].triangles;
        pairs.insert(std::minmax(side.from, side.to));
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = edge_of(complex.triangles[t], e);
            uses[fill[a]++] = {b, static_cast<std::uint32_t>(t)};
        }
    }
    summary.patches = pairs.size();
    for (std::size_t v = 0; v < n; ++v) {
        const auto first = uses.begin() + static_cast<std::ptrdiff_t>(start[v]);
        const auto last = uses.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
        std::sort(first, last);
        for (auto run = first; run != last;) {
            EdgeLabels labels;
            auto next = run;
            for (; next != last && next->first == run->first; ++next) {
                labels.add(complex.sides[next->second].from);
                labels.add(complex.sides[next->second].to);
            }
            run = next;
            count_edge(labels, summary);
        }
    }
    return summary;
}

void InterfaceSummarizer::start(const TissueNames&, Label) {}

void InterfaceSummarizer::add(const InterfacePiece& piece)
{
    LabelPair last{0, 0};
    for (std::size_t t = 0; t < piece.triangles.size(); ++t) {
        const LabelPair side = piece.sides[t];
        ++triangles_per_tissue_[side.from];
        ++triangles_per_tissue_[side.to];
        if (t == 0 || side != last) pairs_.insert(std::minmax(side.from, side.to));
        last = side;
    }
    collect_edges(piece);
    done_.vertices += piece.vertices.size();
    done_.triangles += piece.triangles.size();
    // An edge of the previous piece is complete now: its later triangles, if any, are in this piece. Both
    // lists are sorted by key; an edge found in both is counted once, with its earlier labels first.
    auto match = edges_.begin();
    for (auto& [key, labels] : pending_) {
        while (match != edges_.end() && match->first < key) ++match;
        if (match != edges_.end() && match->first == key) {
            for (int l = 0; l < match->second.count; ++l) labels.add(match->second.labels[static_cast<std::size_t>(l)]);
            match->second.count = -1;
        }
        count_edge(labels, done_);
    }
    std::erase_if(edges_, [](const Edge& edge) { return edge.second.count < 0; });
    std::swap(pending_, edges_);
    previous_first_vertex_ = piece.first_vertex;
}

void InterfaceSummarizer::collect_edges(const InterfacePiece& piece)
{
    // Vertices of this piece and the one before (the precondition) number the buckets.
    const std::size_t end_vertex = piece.first_vertex + piece.vertices.size();
    const std::size_t window = end_vertex - std::min(previous_first_vertex_, end_vertex);
    bucket_start_.assign(window + 1, 0);
    for (std::size_t t = 0; t < piece.triangles.size(); ++t)
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = edge_of(piece.triangles[t], e);
            if (a < previous_first_vertex_ || b >= end_vertex)
                throw InputError(concat("summarize_interfaces: triangle ", done_.triangles + t, " uses vertex ",
                                        a < previous_first_vertex_ ? a : b,
                                        ", outside its piece and the one before "
                                        "(vertices ",
                                        previous_first_vertex_, "..", end_vertex - 1,
                                        "); the streamed "
                                        "summary needs local pieces, use summarize_interfaces() on the whole complex"));
            ++bucket_start_[a - previous_first_vertex_ + 1];
        }
    for (std::size_t v = 0; v < window; ++v) bucket_start_[v + 1] += bucket_start_[v];
    uses_.resize(bucket_start_[window]);
    for (std::size_t t = 0; t < piece.triangles.size(); ++t)
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = edge_of(piece.triangles[t], e);
            uses_[bucket_start_[a - previous_first_vertex_]++] = {b, static_cast<std::uint32_t>(t)};
        }
    // bucket_start_[v] is now the end of bucket v: sort each bucket by (upper vertex, triangle) and group.
    edges_.clear();
    for (std::size_t v = 0, begin = 0; v < window; begin = bucket_start_[v++]) {
        const auto first = uses_.begin() + static_cast<std::ptrdiff_t>(begin);
        const auto last = uses_.begin() + static_cast<std::ptrdiff_t>(bucket_start_[v]);
        // Buckets hold about 6 uses: insertion sort.
        for (auto i = first; i != last; ++i)
            for (auto j = i; j != first && *j < *(j - 1); --j) std::iter_swap(j, j - 1);
        for (auto run = first; run != last;) {
            EdgeLabels labels;
            auto next = run;
            for (; next != last && next->first == run->first; ++next) {
                labels.add(piece.sides[next->second].from);
                labels.add(piece.sides[next->second].to);
            }
            edges_.emplace_back(std::uint64_t{previous_first_vertex_ + v} << 32 | run->first, labels);
            run = next;
        }
    }
}

InterfaceSummary InterfaceSummarizer::summary() const
{
    InterfaceSummary summary = done_;
    for (const auto& [key, labels] : pending_) count_edge(labels, summary);
    for (std::size_t label = 0; label < triangles_per_tissue_.size(); ++label)
        if (triangles_per_tissue_[label] > 0)
            summary.tissues[static_cast<Label>(label)].triangles = triangles_per_tissue_[label];
    summary.patches = pairs_.size();
    return summary;
}

} // namespace tissuemesh::surface
