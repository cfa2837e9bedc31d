// Small closed pieces of a tissue keep a shape TetGen can fill. On the 3 mm torso, decimation shrank a pocket of
// the body between two organs (bounded by two tissue pairs, so the one-pair rule of the time did not see it)
// to a flat tetrahedron: TetGen's tet inside it had a smallest dihedral angle of 0.012 degrees, and no
// improvement can mend a tet whose four faces are all interfaces. The usc19-5 head had the same in a CSF speck.
#include <cmath>
#include <iostream>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "surface/check_complex.h"
#include "surface/detail/local_editor.h"
#include "surface/extract_surface_nets.h"

namespace tissuemesh {
namespace {

using surface::detail::LocalEditor;

/// Tissue 1 above z = 3 voxels and tissue 2 below in a 6 x 6 x 6 block, and two voxels of tissue 3 across their
/// interface: a small piece bounded by the pairs 3|1 and 3|2.
InterfaceComplex straddling_pocket()
{
    LabelImage image({6, 6, 6}, {1, 1, 1});
    for (std::size_t k = 0; k < 6; ++k)
        for (std::size_t j = 0; j < 6; ++j)
            for (std::size_t i = 0; i < 6; ++i) image.at(i, j, k) = k >= 3 ? 1 : 2;
    image.at(2, 2, 2) = image.at(2, 2, 3) = 3;
    return surface::extract_surface_nets(image);
}

struct Shape {
    double volume = 0, area = 0;
    double fatness() const { return std::abs(volume) / std::pow(area, 1.5); }
};

/// Volume (tissue 3 inside positive) and area of tissue 3's triangles, with vertex v at p.
Shape pocket_shape(const LocalEditor& editor, const std::vector<std::uint32_t>& triangles, std::uint32_t v,
                   const Vec3& p)
{
    Shape shape;
    for (const std::uint32_t t : triangles) {
        std::array<Vec3, 3> c;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t x = editor.triangle(t)[k];
            c[k] = x == v ? p : editor.position(x);
        }
        const double sign = editor.side(t).from == 3 ? 1 : -1;
        shape.volume += sign * dot(cross(c[0], c[1]), c[2]) / 6;
        shape.area += norm(cross(c[1] - c[0], c[2] - c[0])) / 2;
    }
    return shape;
}

TEST(SmallPieces, APocketBetweenTwoTissuesIsNotFlattened)
{
    const InterfaceComplex complex = straddling_pocket();
    ASSERT_TRUE(surface::check_complex(complex).ok());
    LocalEditor editor(complex, {.min_angle_deg = 0.5, .max_tilt_deg = 89, .min_gap_mm = 0}, 2.0);
    std::vector<std::uint32_t> pocket;
    for (std::uint32_t t = 0; t < complex.triangles.size(); ++t)
        if (complex.sides[t].from == 3 || complex.sides[t].to == 3) pocket.push_back(t);
    bool two_pairs = false;
    for (const std::uint32_t t : pocket) two_pairs |= !(complex.sides[t] == complex.sides[pocket[0]]);
    ASSERT_TRUE(two_pairs);
    ASSERT_LE(pocket.size(), 24u);
    // Flatten the pocket: every vertex of it in turn towards the pocket's middle plane z = 3, in steps.
    std::size_t accepted = 0, refused_thin = 0;
    for (int step = 1; step <= 8; ++step)
        for (const std::uint32_t t : pocket)
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = editor.triangle(t)[k];
                const Vec3 now = editor.position(v);
                const Vec3 to{now[0], now[1], now[2] + (3 - now[2]) * 0.4};
                const double before = pocket_shape(editor, pocket, v, now).fatness();
                const Shape after = pocket_shape(editor, pocket, v, to);
                const bool thin = after.fatness() < 0.02 && after.fatness() < before;
                if (editor.try_move(v, to)) {
                    ++accepted;
                    EXPECT_FALSE(thin) << "vertex " << v << " step " << step << ": fatness " << before << " -> "
                                       << after.fatness();
                } else {
                    refused_thin += thin;
                }
            }
    EXPECT_GT(accepted, 0u);
    EXPECT_GT(refused_thin, 0u);
    const std::uint32_t any = editor.triangle(pocket[0])[0];
    const Shape final_shape = pocket_shape(editor, pocket, any, editor.position(any));
    EXPECT_GE(final_shape.fatness(), 0.02 - 1e-12);
    EXPECT_GT(final_shape.volume, 0);
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
}

/// Per vertex, the triangles with `tissue` on a side reachable from it through shared vertices (0 for vertices
/// without such a triangle), counted the slow way: a search from each vertex not yet reached.
std::vector<std::size_t> piece_sizes(const LocalEditor& editor, Label tissue)
{
    std::vector<std::size_t> size(editor.vertex_slots(), 0);
    std::vector<char> reached(editor.vertex_slots(), 0);
    for (std::uint32_t start = 0; start < editor.vertex_slots(); ++start) {
        if (reached[start] || !editor.vertex_alive(start)) continue;
        std::set<std::uint32_t> triangles;
        std::vector<std::uint32_t> piece{start}, next{start};
        reached[start] = 1;
        while (!next.empty()) {
            const std::uint32_t x = next.back();
            next.pop_back();
            for (const std::uint32_t t : editor.star(x)) {
                if (editor.side(t).from != tissue && editor.side(t).to != tissue) continue;
                if (!triangles.insert(t).second) continue;
                for (const std::uint32_t y : editor.triangle(t))
                    if (!reached[y]) reached[y] = 1, piece.push_back(y), next.push_back(y);
            }
        }
        for (const std::uint32_t x : piece) size[x] = triangles.size();
    }
    return size;
}

// small_pieces() trusts a count of each piece's triangles above its limit instead of searching; the counts must
// stay at most the true sizes through any accepted edit, or a small piece would be let through unmeasured.
TEST(SmallPieces, CountedPiecesNeverExceedTheirTrianglesThroughEdits)
{
    // A slab of tissue 1 over tissue 2, specks of tissues 3 and 4 in it, two of them across the interface.
    LabelImage image({10, 10, 10}, {1, 1, 1});
    for (std::size_t k = 0; k < 10; ++k)
        for (std::size_t j = 0; j < 10; ++j)
            for (std::size_t i = 0; i < 10; ++i) image.at(i, j, k) = k >= 5 ? 1 : 2;
    image.at(2, 2, 4) = image.at(2, 2, 5) = 3;
    image.at(6, 3, 7) = 3;
    image.at(3, 7, 2) = image.at(4, 7, 2) = 4;
    image.at(7, 7, 4) = image.at(7, 7, 5) = image.at(7, 6, 5) = 4;
    const InterfaceComplex complex = surface::extract_surface_nets(image);
    ASSERT_TRUE(surface::check_complex(complex).ok());
    LocalEditor editor(complex, {.min_angle_deg = 1, .max_tilt_deg = 80, .min_gap_mm = 0}, 2.0);
    std::mt19937 random(7);
    std::size_t accepted = 0, checked_small = 0, checked_big = 0;
    for (int round = 0; round < 1500; ++round) {
        std::vector<std::uint32_t> alive;
        for (std::uint32_t v = 0; v < editor.vertex_slots(); ++v)
            if (editor.vertex_alive(v)) alive.push_back(v);
        const std::uint32_t v = alive[random() % alive.size()];
        const Triangle& first = editor.triangle(editor.star(v)[random() % editor.star(v).size()]);
        const std::uint32_t w = first[0] == v ? first[1] : first[0];
        const Vec3 middle = 0.5 * (editor.position(v) + editor.position(w));
        bool done = false;
        switch (random() % 4) {
        case 0: done = editor.try_collapse(v, w); break;
        case 1: done = editor.try_split(v, w, middle).has_value(); break;
        case 2: done = editor.try_flip(v, w); break;
        default: done = editor.try_move(v, editor.position(v) + 0.3 * (middle - editor.position(v))); break;
        }
        if (!done) continue;
        ++accepted;
        if (round % 10 != 0) continue;
        for (const Label tissue : {Label{1}, Label{2}, Label{3}, Label{4}}) {
            const std::vector<std::size_t> real = piece_sizes(editor, tissue);
            for (std::uint32_t x = 0; x < editor.vertex_slots(); ++x) {
                if (!editor.vertex_alive(x)) continue;
                const std::size_t counted = editor.counted_piece(x, tissue);
                if (counted == 0) continue;
                ASSERT_LE(counted, real[x]) << "vertex " << x << ", tissue " << tissue << ", round " << round;
                ++(real[x] <= 24 ? checked_small : checked_big);
            }
        }
    }
    std::cout << "[ figures  ] " << accepted << " edits accepted; counts checked at " << checked_small
              << " vertices of small pieces and " << checked_big << " of large ones\n";
    EXPECT_GT(accepted, 300u);
    EXPECT_GT(checked_small, 0u);
    EXPECT_GT(checked_big, 0u);
    EXPECT_TRUE(surface::check_complex(editor.result()).ok());
}

} // namespace
} // namespace tissuemesh
