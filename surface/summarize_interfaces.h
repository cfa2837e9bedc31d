// Counts of an interface complex per tissue: what tm-extract reports.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "core/interface_complex.h"
#include "core/interface_sink.h"

namespace tissuemesh::surface {

/// Counts for one tissue.
struct TissueCounts {
    std::size_t triangles = 0;      ///< triangles with this tissue on one side
    std::size_t junction_edges = 0; ///< edges of its surface where 3 or more tissues meet
};

/// Counts for a whole complex.
struct InterfaceSummary {
    std::size_t vertices = 0;              ///< of the whole complex
    std::size_t triangles = 0;             ///< of the whole complex
    std::map<Label, TissueCounts> tissues; ///< by label, background included
    std::size_t patches = 0;               ///< distinct unordered tissue pairs
    std::size_t junction_edges = 0;        ///< edges where 3 or more tissues meet
};

/// Counts triangles per tissue and junction edges (an edge whose incident triangles name 3 or more
/// distinct tissues). Near-linear: edge uses bucketed by lower vertex, 8 bytes per triangle corner.
InterfaceSummary summarize_interfaces(const InterfaceComplex& complex);

/// The same counts taken from a complex streamed piece by piece (e.g. by extract_interfaces()), holding
/// only the edges of the last two pieces: summary() equals summarize_interfaces() of the whole complex.
/// @pre every triangle of a piece uses only vertices of that piece and the one before (then every edge's
///      triangles arrive within two consecutive pieces, as extract_interfaces() guarantees)
/// @throws InputError from add() when a triangle breaks the precondition
class InterfaceSummarizer final : public InterfaceSink {
public:
    void start(const TissueNames& names, Label background) override;
    void add(const InterfacePiece& piece) override;
    /// The counts of everything added so far (the last piece's edges included).
    InterfaceSummary summary() const;

    /// Up to 4 distinct labels seen around an edge (4 is enough to know "3 or more"), in order of use.
    struct EdgeLabels {
        std::array<Label, 4> labels{};
        int count = 0;
        void add(Label label)
        {
            for (int l = 0; l < count; ++l)
                if (labels[static_cast<std::size_t>(l)] == label) return;
            if (count < 4) labels[static_cast<std::size_t>(count++)] = label;
        }
    };

private:
    using Edge = std::pair<std::uint64_t, EdgeLabels>; ///< (lower vertex << 32 | upper vertex, labels)
    /// Sorts this piece's edge uses (bucketed by lower vertex) into edges_ with their labels.
    void collect_edges(const InterfacePiece& piece);

    InterfaceSummary done_; ///< counts of finished edges
    std::vector<std::size_t> triangles_per_tissue_ = std::vector<std::size_t>(std::size_t{1} << 16, 0);
    std::set<std::pair<Label, Label>> pairs_;
    std::vector<Edge> pending_;                                 ///< the previous piece's edges, sorted by key
    std::vector<Edge> edges_;                                   ///< this piece's edges, sorted by key
    std::vector<std::size_t> bucket_start_;                     ///< scratch: uses bucketed by lower vertex
    std::vector<std::pair<std::uint32_t, std::uint32_t>> uses_; ///< scratch: (upper vertex, triangle)
    std::size_t previous_first_vertex_ = 0;
};

} // namespace tissuemesh::surface
