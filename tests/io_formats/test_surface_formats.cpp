// The new surface formats: .obj keeps label pairs and names; ASCII STL reads like binary STL.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/surface_io.h"
#include "tests/io/expect_error.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"

namespace tissuemesh::io {
namespace {

InterfaceComplex two_boxes()
{
    InterfaceComplex complex;
    testing::add_box(complex, {0, 0, 0}, {4, 4, 4}, 1, 0);
    testing::add_box(complex, {1, 1, 1}, {2, 2, 2}, 2, 1);
    complex.names = {{1, "outer"}, {2, "inner tissue"}};
    return complex;
}

/// Signed volume enclosed by the triangles of `complex` with `from` == tissue, minus those with `to` ==
/// tissue (divergence theorem): the tissue's volume for a closed complex.
double tissue_volume(const InterfaceComplex& complex, Label tissue)
{
    double volume = 0;
    for (std::size_t t = 0; t < complex.triangles.size(); ++t) {
        const Vec3 &a = complex.vertices[complex.triangles[t][0]], &b = complex.vertices[complex.triangles[t][1]],
                   &c = complex.vertices[complex.triangles[t][2]];
        const double v = dot(a, cross(b, c)) / 6.0;
        if (complex.sides[t].from == tissue) volume += v;
        if (complex.sides[t].to == tissue) volume -= v;
    }
    return volume;
}

TEST(SurfaceFormats, ObjKeepsGeometryPairsAndNames)
{
    testing::TempDir dir;
    const InterfaceComplex complex = two_boxes();
    write_surface(complex, dir / "a.obj");
    const InterfaceComplex back = read_surface(dir / "a.obj");
    EXPECT_EQ(back.vertices, complex.vertices);
    EXPECT_EQ(back.triangles, complex.triangles);
    EXPECT_EQ(back.sides, complex.sides);
    EXPECT_EQ(back.names, complex.names);
    EXPECT_NEAR(tissue_volume(back, 1), 63.0, 1e-12);
    EXPECT_NEAR(tissue_volume(back, 2), 1.0, 1e-12);
}

TEST(SurfaceFormats, ObjFromOtherToolsSlashesNegativeIndicesAndNoGroups)
{
    testing::TempDir dir;
    std::ofstream(dir / "a.obj") << "# other tool\nmtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nv 0 0 1\n"
                                    "usemtl red\nf 1/1/1 3/1/1 2/1/1\nf -4//1 -3//1 -1//1\ns off\nf 2 3 4\nf 1 4 3\n";
    const InterfaceComplex complex = read_surface(dir / "a.obj");
    ASSERT_EQ(complex.triangles.size(), 4u);
    EXPECT_EQ(complex.triangles[1], (Triangle{0, 1, 3}));
    EXPECT_EQ(complex.sides[0], (LabelPair{1, 0}));
    EXPECT_NEAR(tissue_volume(complex, 1), 1.0 / 6.0, 1e-12) << "the unit corner tet, outward";
}

TEST(SurfaceFormats, BadObjFilesAreRefused)
{
    testing::TempDir dir;
    std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    testing::expect_error<IoError>([&] { read_surface(dir / "quad.obj"); }, {"quad.obj", "4 corners", "triangulate"});
    std::ofstream(dir / "dangling.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 9\n";
    testing::expect_error<InputError>([&] { read_surface(dir / "dangling.obj"); }, {"dangling.obj", "face corner 9"});
    std::ofstream(dir / "word.obj") << "v 0 0 zero\n";
    testing::expect_error<IoError>([&] { read_surface(dir / "word.obj"); }, {"word.obj", "\"zero\""});
    std::ofstream(dir / "nan.obj") << "v 0 0 nan\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
    testing::expect_error<InputError>([&] { read_surface(dir / "nan.obj"); }, {"nan.obj", "non-finite"});
}

TEST(SurfaceFormats, AsciiStlReadsWithSharedCorners)
{
    testing::TempDir dir;
    std::ofstream(dir / "a.stl")
        << "solid tet\n"
           "facet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n  vertex 1 0 0\n endloop\nendfacet\n"
           "facet normal 0 -1 0\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 0 1\n endloop\nendfacet\n"
           "facet normal -1 0 0\n outer loop\n  vertex 0 0 0\n  vertex 0 0 1\n  vertex 0 1 0\n endloop\nendfacet\n"
           "facet normal 1 1 1\n outer loop\n  vertex 1 0 0\n  vertex 0 1 0\n  vertex 0 0 1\n endloop\nendfacet\n"
           "endsolid tet\n";
    const InterfaceComplex complex = read_surface(dir / "a.stl");
    EXPECT_EQ(complex.vertices.size(), 4u);
    EXPECT_EQ(complex.triangles.size(), 4u);
    EXPECT_NEAR(tissue_volume(complex, 1), 1.0 / 6.0, 1e-12);
    std::ofstream(dir / "cut.stl") << "solid tet\nfacet normal 0 0 -1\n outer loop\n  vertex 0 0 0\n  vertex 0 1 0\n";
    testing::expect_error<IoError>([&] { read_surface(dir / "cut.stl"); }, {"cut.stl", "truncated"});
}

} // namespace
} // namespace tissuemesh::io
