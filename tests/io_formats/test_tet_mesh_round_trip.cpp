// Every tet mesh format we write reads back: same nodes (bit for bit), same labelled tets and faces,
// same names, same volumes per tissue.
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/tet_mesh_io.h"
#include "tests/io_formats/mesh_compare.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

using testing::face_set;
using testing::nested_cubes_mesh;
using testing::tet_set;

struct Variant {
    std::string file;
    TetMeshWriteOptions options;
    bool faces = true; ///< the format keeps interface faces
    bool names = true; ///< the format keeps tissue names
};

std::vector<Variant> variants()
{
    return {{"a.msh", {}},
            {"b.msh", {MshVersion::v2_2, true}},
            {"c.msh", {MshVersion::v4_1, false}},
            {"d.msh", {MshVersion::v4_1, true}},
            {"e.mesh", {}},
            {"f.node", {}},
            {"g.inp", {}}};
}

TEST(TetMeshRoundTrip, TheSampleHasBothTissuesAndTheirExactVolumes)
{
    const auto volumes = testing::tissue_volumes(nested_cubes_mesh());
    ASSERT_EQ(volumes.size(), 2u);
    EXPECT_NEAR(volumes.at(1), 56.0, 1e-9);
    EXPECT_NEAR(volumes.at(2), 8.0, 1e-9);
    EXPECT_GT(nested_cubes_mesh().tets.size(), 100u);
    EXPECT_EQ(nested_cubes_mesh().names.at(2), "inner");
}

TEST(TetMeshRoundTrip, EveryFormatAndEncodingReadsBackTheSameMesh)
{
    testing::TempDir dir;
    for (const Variant& variant : variants()) {
        SCOPED_TRACE(variant.file + (variant.options.binary ? " binary" : ""));
        write_tet_mesh(nested_cubes_mesh(), dir / variant.file, variant.options);
        const TetMesh back = read_tet_mesh(dir / variant.file);
        EXPECT_EQ(back.vertices, nested_cubes_mesh().vertices) << "17 significant digits or raw doubles: exact";
        EXPECT_EQ(tet_set(back), tet_set(nested_cubes_mesh()));
        if (variant.faces) {
            EXPECT_EQ(face_set(back), face_set(nested_cubes_mesh()));
        } else {
            EXPECT_TRUE(back.faces.empty());
        }
        if (variant.names) {
            EXPECT_EQ(back.names, nested_cubes_mesh().names);
        }
        const auto volumes = testing::tissue_volumes(back);
        EXPECT_NEAR(volumes.at(1), 56.0, 1e-9);
        EXPECT_NEAR(volumes.at(2), 8.0, 1e-9);
    }
}

TEST(TetMeshRoundTrip, MshTwoTwoKeepsElementOrderAndTheDefaultIsAsciiTwoTwo)
{
    testing::TempDir dir;
    write_tet_mesh(nested_cubes_mesh(), dir / "a.msh");
    const TetMesh back = read_tet_mesh(dir / "a.msh");
    EXPECT_EQ(back.tets, nested_cubes_mesh().tets);
    EXPECT_EQ(back.tet_labels, nested_cubes_mesh().tet_labels);
    EXPECT_EQ(back.faces, nested_cubes_mesh().faces);
    const std::string head = testing::run_program("head", {"-c", "32", (dir / "a.msh").string()}).out;
    EXPECT_EQ(head.rfind("$MeshFormat\n2.2 0 8\n", 0), 0u) << head;
}

TEST(TetMeshRoundTrip, TetgenWritesThreeFilesAndReadsFromEither)
{
    testing::TempDir dir;
    write_tet_mesh(nested_cubes_mesh(), dir / "m.ele");
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"m.ele", "m.face", "m.node"}));
    EXPECT_EQ(tet_set(read_tet_mesh(dir / "m.node")), tet_set(nested_cubes_mesh()));
    std::filesystem::remove(dir / "m.face");
    const TetMesh no_faces = read_tet_mesh(dir / "m.ele");
    EXPECT_EQ(tet_set(no_faces), tet_set(nested_cubes_mesh()));
    EXPECT_TRUE(no_faces.faces.empty());
}

TEST(TetMeshRoundTrip, ReadersOrientTetsPositively)
{
    testing::TempDir dir;
    TetMesh flipped = nested_cubes_mesh();
    for (Tet& tet : flipped.tets) std::swap(tet[0], tet[1]);
    for (const char* name : {"a.msh", "b.mesh", "c.node", "d.inp"}) {
        write_tet_mesh(flipped, dir / name, {MshVersion::v4_1, true});
        const TetMesh back = read_tet_mesh(dir / name);
        for (std::size_t t = 0; t < back.tets.size(); ++t) ASSERT_GT(signed_volume(back, t), 0) << name << " tet " << t;
    }
}

// A mesh without tetrahedra is no FE model: refused on writing (nothing written), as a file holding one is on reading.
TEST(TetMeshRoundTrip, EmptyMeshesAreRefused)
{
    testing::TempDir dir;
    for (const Variant& variant : variants()) {
        try {
            write_tet_mesh(TetMesh{}, dir / variant.file, variant.options);
            ADD_FAILURE() << variant.file << ": an empty mesh was written";
        } catch (const tissuemesh::InputError& error) {
            EXPECT_NE(std::string(error.what()).find("holds no tetrahedra"), std::string::npos) << error.what();
        }
    }
    EXPECT_TRUE(dir.files().empty());
}

} // namespace
} // namespace tissuemesh::io
