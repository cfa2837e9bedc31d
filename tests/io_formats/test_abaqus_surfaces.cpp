// Abaqus interface faces: element-face surfaces per tissue pair, named for boundary conditions, read back with
// their pairs and orientation; surfaces of other tools read as faces out of their elements.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/tet_mesh_io.h"
#include "tests/io/expect_error.h"
#include "tests/io_formats/mesh_compare.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

using testing::nested_cubes_mesh;

std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(AbaqusSurfaces, OneElementFaceSurfacePerTissuePairWithS1ToS4Sets)
{
    testing::TempDir dir;
    write_tet_mesh(nested_cubes_mesh(), dir / "a.inp");
    const std::string text = slurp(dir / "a.inp");
    std::map<std::pair<Label, Label>, std::size_t> pairs;
    for (const LabelPair& p : nested_cubes_mesh().face_sides) ++pairs[{p.from, p.to}];
    ASSERT_GE(pairs.size(), 2u) << "the inner cube's interface and the outer boundary";
    for (const auto& [pair, count] : pairs) {
        const std::string name = concat("IF_", pair.first, "_", pair.second);
        SCOPED_TRACE(name);
        EXPECT_NE(text.find("*SURFACE, TYPE=ELEMENT, NAME=" + name + "\n"), std::string::npos);
        // The face ids of the surface's lines: each names an element set defined before it.
        std::size_t listed = 0;
        for (int k = 1; k <= 4; ++k) {
            const std::string set = concat(name, "_S", k, "_ELEMS");
            if (text.find(concat(set, ", S", k, "\n")) == std::string::npos) continue;
            const std::size_t header = text.find("*ELSET, ELSET=" + set + "\n");
            ASSERT_NE(header, std::string::npos);
            const std::size_t start = header + set.size() + 15, end = text.find('*', start);
            std::string numbers = text.substr(start, end - start);
            std::replace(numbers.begin(), numbers.end(), ',', ' ');
            std::istringstream in(numbers);
            for (long long element = 0; in >> element;) ++listed;
        }
        EXPECT_EQ(listed, count) << "one element face per interface face";
    }
}

TEST(AbaqusSurfaces, FacesReadBackWithTheirPairsAndOrientationAndTheTissuesStay)
{
    testing::TempDir dir;
    write_tet_mesh(nested_cubes_mesh(), dir / "a.inp");
    const TetMesh back = read_tet_mesh(dir / "a.inp");
    EXPECT_EQ(testing::face_set(back), testing::face_set(nested_cubes_mesh()))
        << "same vertices in the same rotation: same orientation";
    EXPECT_EQ(testing::tet_set(back), testing::tet_set(nested_cubes_mesh())) << "the face sets did not relabel any tet";
}

TEST(AbaqusSurfaces, ForeignSurfacesAreFacesOutOfTheirElements)
{
    testing::TempDir dir;
    // One positively oriented tet, listed with its last two corners swapped (negative in the file), surfaces by
    // element number and by set, with face ids in either case.
    std::ofstream(dir / "a.inp")
        << "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n*ELEMENT, TYPE=C3D4, ELSET=brain4\n"
           "7, 1, 2, 4, 3\n*ELSET, ELSET=skin\n7\n*Surface, type=ELEMENT, name=Outer\n7, S1\nskin, S3\n";
    const TetMesh mesh = read_tet_mesh(dir / "a.inp");
    ASSERT_EQ(mesh.faces.size(), 2u);
    EXPECT_EQ(mesh.tet_labels, std::vector<Label>{4}) << "the set a surface uses is no tissue";
    const Vec3 centre{0.25, 0.25, 0.25};
    for (std::size_t f = 0; f < 2; ++f) {
        EXPECT_EQ(mesh.face_sides[f], (LabelPair{4, 0}));
        const Triangle& t = mesh.faces[f];
        const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
        EXPECT_LT(dot(cross(b - a, c - a), centre - a), 0) << "face " << f << " points out of the tet";
    }
    std::ofstream(dir / "b.inp")
        << "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n"
           "*SURFACE, NAME=X\nnowhere, S2\n";
    testing::expect_error<IoError>([&] { read_tet_mesh(dir / "b.inp"); },
                                   {"b.inp", "element set nowhere, which is not defined"});
    std::ofstream(dir / "c.inp")
        << "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n"
           "*SURFACE, NAME=X\n1, S5\n";
    testing::expect_error<IoError>([&] { read_tet_mesh(dir / "c.inp"); }, {"c.inp", "face S5", "S1, S2, S3 or S4"});
}

} // namespace
} // namespace tissuemesh::io
