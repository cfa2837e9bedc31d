// The streaming form of extract_interfaces() (slab by slab into an InterfaceSink) and the streamed counts
// (InterfaceSummarizer): the pieces add up to exactly the returned complex, they are local as the header
// promises, and the streamed counts equal both summarize_interfaces() and a direct count.
#include <algorithm>
#include <gtest/gtest.h>
#include <map>

#include "core/error.h"
#include "image/phantom.h"
#include "surface/extract_interfaces.h"
#include "surface/summarize_interfaces.h"

namespace tissuemesh {
namespace {

/// The phantoms of the streaming tests: a triple junction, a one-voxel shell under a priority (split
/// cubes, position-keyed vertices), and the four-shell head at 2 mm.
struct StreamCase {
    const char* phantom;
    double voxel_mm;
    std::map<Label, int> priority;
};

const StreamCase stream_cases[] = {{"junction", 2.0, {}}, {"thin", 2.0, {{1, 1}}}, {"spheres4", 2.0, {}}};

/// Keeps each piece's ranges and the concatenation, checking the piece contract as it goes.
class RecordingSink final : public InterfaceSink {
public:
    void start(const TissueNames& names, Label background) override
    {
        ++starts;
        collected.start(names, background);
    }
    void add(const InterfacePiece& piece) override
    {
        EXPECT_EQ(starts, 1) << "start() comes once, before the pieces";
        EXPECT_EQ(piece.first_vertex, collected.complex().vertices.size()) << "piece " << pieces;
        EXPECT_EQ(piece.sides.size(), piece.triangles.size()) << "piece " << pieces;
        const std::size_t end = piece.first_vertex + piece.vertices.size();
        for (const Triangle& tri : piece.triangles)
            for (const std::uint32_t v : tri) {
                EXPECT_GE(v, previous_first) << "piece " << pieces << " uses a vertex older than the piece before";
                EXPECT_LT(v, end) << "piece " << pieces << " uses a vertex not yet handed over";
            }
        previous_first = piece.first_vertex;
        collected.add(piece);
        ++pieces;
    }
    CollectingSink collected;
    int starts = 0;
    std::size_t pieces = 0;
    std::size_t previous_first = 0;
};

/// Junction edges counted the plain way: every (edge, tissue) incidence, sorted and made unique; an edge
/// listed with 3 or more tissues is a junction edge.
surface::InterfaceSummary direct_count(const InterfaceComplex& complex)
{
    std::vector<std::pair<std::uint64_t, Label>> incidences;
    surface::InterfaceSummary summary;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const LabelPair side = complex.sides[t];
        ++summary.tissues[side.from].triangles;
        ++summary.tissues[side.to].triangles;
        for (int e = 0; e < 3; ++e) {
            const auto [a, b] = std::minmax(complex.triangles[t][e], complex.triangles[t][(e + 1) % 3]);
            for (const Label label : {side.from, side.to}) incidences.emplace_back(std::uint64_t{a} << 32 | b, label);
        }
    }
    std::sort(incidences.begin(), incidences.end());
    incidences.erase(std::unique(incidences.begin(), incidences.end()), incidences.end());
    for (std::size_t first = 0, last = 0; first < incidences.size(); first = last) {
        while (last < incidences.size() && incidences[last].first == incidences[first].first) ++last;
        if (last - first < 3) continue;
        ++summary.junction_edges;
        for (std::size_t i = first; i < last; ++i) ++summary.tissues[incidences[i].second].junction_edges;
    }
    return summary;
}

void expect_same_counts(const surface::InterfaceSummary& a, const surface::InterfaceSummary& b, const std::string& what)
{
    EXPECT_EQ(a.junction_edges, b.junction_edges) << what;
    ASSERT_EQ(a.tissues.size(), b.tissues.size()) << what;
    for (const auto& [label, counts] : a.tissues) {
        ASSERT_TRUE(b.tissues.contains(label)) << what << ": tissue " << label;
        EXPECT_EQ(counts.triangles, b.tissues.at(label).triangles) << what << ": tissue " << label;
        EXPECT_EQ(counts.junction_edges, b.tissues.at(label).junction_edges) << what << ": tissue " << label;
    }
}

TEST(ExtractStreamed, PiecesAreTheSlabsAndAddUpToTheReturnedComplex)
{
    for (const StreamCase& c : stream_cases) {
        const image::Phantom phantom = image::make_phantom(c.phantom, {.voxel_mm = c.voxel_mm});
        const surface::ExtractOptions options{.priority = c.priority};
        const InterfaceComplex whole = surface::extract_interfaces(phantom.image, options);
        RecordingSink sink;
        surface::extract_interfaces(phantom.image, options, sink);
        const InterfaceComplex& streamed = sink.collected.complex();
        EXPECT_EQ(sink.pieces, phantom.image.dims()[2] + 1) << c.phantom << ": one piece per slab";
        ASSERT_GT(whole.triangle_count(), 0u) << c.phantom;
        EXPECT_EQ(streamed.vertices, whole.vertices) << c.phantom;
        EXPECT_EQ(streamed.triangles, whole.triangles) << c.phantom;
        EXPECT_EQ(streamed.sides, whole.sides) << c.phantom;
        EXPECT_EQ(streamed.names, whole.names) << c.phantom;
        EXPECT_FALSE(streamed.names.empty()) << c.phantom << ": phantoms name their tissues";
        EXPECT_EQ(streamed.background, whole.background) << c.phantom;
    }
}

TEST(ExtractStreamed, StreamedCountsEqualTheWholeComplexCounts)
{
    for (const StreamCase& c : stream_cases) {
        const image::Phantom phantom = image::make_phantom(c.phantom, {.voxel_mm = c.voxel_mm});
        const surface::ExtractOptions options{.priority = c.priority};
        surface::InterfaceSummarizer summarizer;
        surface::extract_interfaces(phantom.image, options, summarizer);
        const surface::InterfaceSummary streamed = summarizer.summary();
        const InterfaceComplex whole = surface::extract_interfaces(phantom.image, options);
        const surface::InterfaceSummary reference = surface::summarize_interfaces(whole);
        EXPECT_EQ(streamed.vertices, whole.vertex_count()) << c.phantom;
        EXPECT_EQ(streamed.triangles, whole.triangle_count()) << c.phantom;
        EXPECT_EQ(streamed.patches, reference.patches) << c.phantom;
        expect_same_counts(streamed, reference, c.phantom);
        expect_same_counts(streamed, direct_count(whole), c.phantom);
        if (std::string(c.phantom) == "junction") {
            EXPECT_GT(streamed.junction_edges, 0u) << "three tissues meet on a circle";
        }
    }
}

TEST(ExtractStreamed, SummarizerJoinsEdgesSplitBetweenPieces)
{
    // Extraction never splits a junction edge between slabs (its triangles share one tetrahedron), so
    // the joining of the two pieces' edge lists is tested on hand-made pieces (combinatorics only):
    // edge (0,1) is a junction in each piece alone and must count once; edge (2,3) becomes one only when
    // both pieces' tissues are joined. Hand count: junction edges (0,1) {0,1,2,3}, (0,2) {0,1,5},
    // (0,3) {0,1,2,5}, (2,3) {0,4,5}.
    const std::vector<Vec3> points(4, Vec3{0, 0, 0});
    const std::vector<Triangle> first{{0, 1, 2}, {1, 0, 3}, {2, 3, 0}}, second{{0, 1, 4}, {1, 0, 5}, {2, 3, 4}};
    const std::vector<LabelPair> first_sides{{1, 0}, {2, 1}, {5, 0}}, second_sides{{2, 0}, {3, 2}, {4, 0}};
    surface::InterfaceSummarizer summarizer;
    summarizer.start({}, 0);
    summarizer.add({0, points, first, first_sides});
    summarizer.add({4, std::span(points).first(2), second, second_sides});
    const surface::InterfaceSummary summary = summarizer.summary();
    EXPECT_EQ(summary.junction_edges, 4u);
    const std::map<Label, std::size_t> expected{{0, 4}, {1, 3}, {2, 2}, {3, 1}, {4, 1}, {5, 3}};
    for (const auto& [label, count] : expected) EXPECT_EQ(summary.tissues.at(label).junction_edges, count) << label;
    EXPECT_EQ(summary.vertices, 6u);
    EXPECT_EQ(summary.triangles, 6u);
    CollectingSink whole;
    whole.add({0, points, first, first_sides});
    whole.add({4, std::span(points).first(2), second, second_sides});
    expect_same_counts(summary, surface::summarize_interfaces(whole.complex()), "hand-made pieces");
}

TEST(ExtractStreamed, SummarizerRefusesPiecesThatAreNotLocal)
{
    // Three pieces; the third reuses vertex 0 of the first, so one of its edges could have been counted
    // already: the streamed counts would be wrong, and the summarizer says so.
    const std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const std::vector<Triangle> first{{0, 1, 2}}, third{{0, 7, 8}};
    const std::vector<Triangle> second{{1, 3, 4}};
    const std::vector<LabelPair> sides{{1, 0}};
    surface::InterfaceSummarizer summarizer;
    summarizer.start({}, 0);
    summarizer.add({0, points, first, sides});
    summarizer.add({3, points, second, sides});
    try {
        summarizer.add({6, points, third, sides});
        FAIL() << "a non-local piece was accepted";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("uses vertex 0, outside its piece and the one before"),
                  std::string::npos)
            << error.what();
    }
}

} // namespace
} // namespace tissuemesh
