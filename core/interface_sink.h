// InterfaceSink: an interface complex handed over piece by piece, so that its producer (extract_interfaces)
// and its consumer (a file writer, a counter) never need the whole complex in memory at once.
#pragma once

#include <cstddef>
#include <span>

#include "core/interface_complex.h"

namespace tissuemesh {

/// The next part of a complex: vertices numbered on from those of earlier pieces, and triangles whose
/// indices refer to vertices of this piece or of earlier ones.
struct InterfacePiece {
    std::size_t first_vertex = 0;        ///< global index of vertices[0] (the count of earlier vertices)
    std::span<const Vec3> vertices;      ///< new vertices, mm
    std::span<const Triangle> triangles; ///< new triangles (global vertex indices)
    std::span<const LabelPair> sides;    ///< one pair per triangle
};

/// Receives a complex in order: start() once, then add() for each piece. The concatenation of the pieces
/// (vertices, triangles and sides in order) is the complex. The spans are valid during add() only.
class InterfaceSink {
public:
    virtual ~InterfaceSink() = default;
    /// The complex's tissue names and background label, before any piece.
    virtual void start(const TissueNames& names, Label background) = 0;
    virtual void add(const InterfacePiece& piece) = 0;
};

/// Collects the pieces into one InterfaceComplex (what an in-memory caller wants).
class CollectingSink final : public InterfaceSink {
public:
    void start(const TissueNames& names, Label background) override
    {
        complex_.names = names;
        complex_.background = background;
    }
    void add(const InterfacePiece& piece) override
    {
        complex_.vertices.insert(complex_.vertices.end(), piece.vertices.begin(), piece.vertices.end());
        complex_.triangles.insert(complex_.triangles.end(), piece.triangles.begin(), piece.triangles.end());
        complex_.sides.insert(complex_.sides.end(), piece.sides.begin(), piece.sides.end());
    }
    InterfaceComplex& complex() { return complex_; }

private:
    InterfaceComplex complex_;
};

/// Hands every call on to two sinks, `first` before `second`.
class TeeSink final : public InterfaceSink {
public:
    TeeSink(InterfaceSink& first, InterfaceSink& second) : first_(first), second_(second) {}
    void start(const TissueNames& names, Label background) override
    {
        first_.start(names, background);
        second_.start(names, background);
    }
    void add(const InterfacePiece& piece) override
    {
        first_.add(piece);
        second_.add(piece);
    }

private:
    InterfaceSink& first_;
    InterfaceSink& second_;
};

} // namespace tissuemesh
