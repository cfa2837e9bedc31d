#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/write_vtu.h"
#include "tests/support/cli.h"

namespace tissuemesh::io {
namespace {

TetMesh one_tet()
{
    TetMesh mesh;
    mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    mesh.tets = {{0, 1, 2, 3}};
    mesh.tet_labels = {7};
    return mesh;
}

std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(WriteVtu, WritesTissueAndNamedArrays)
{
    testing::TempDir dir;
    const TetMesh mesh = one_tet();
    write_vtu(mesh, dir / "a.vtu", {make_vtu_array("potential_V", std::vector<double>{1, 2, 3, 4})},
              {make_vtu_vectors("E_V_per_m", {{1, 2, 3}}), make_vtu_array("key", std::vector<double>{INFINITY})});
    const std::string text = slurp(dir / "a.vtu");
    EXPECT_NE(text.find("Name=\"tissue\""), std::string::npos);
    EXPECT_NE(text.find("<PointData Scalars=\"potential_V\">"), std::string::npos);
    EXPECT_NE(text.find("Name=\"E_V_per_m\" NumberOfComponents=\"3\""), std::string::npos);
    EXPECT_NE(text.find("\n1 2 3\n"), std::string::npos) << "one vector per line";
    EXPECT_NE(text.find("1e+30"), std::string::npos) << "infinity is written as a large number";
    EXPECT_EQ(dir.files(), std::vector<std::string>{"a.vtu"});
}

TEST(WriteVtu, RejectsArraysOfTheWrongSizeAndWritesNothing)
{
    testing::TempDir dir;
    EXPECT_THROW(write_vtu(one_tet(), dir / "a.vtu", {make_vtu_array("potential_V", std::vector<double>{1, 2})}),
                 InputError);
    EXPECT_THROW(write_vtu(one_tet(), dir / "a.vtu", {}, {make_vtu_vectors("E", {{1, 2, 3}, {4, 5, 6}})}), InputError);
    EXPECT_TRUE(dir.files().empty());
}

} // namespace
} // namespace tissuemesh::io
