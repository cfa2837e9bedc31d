// The gmsh program opens every .msh variant we write (re-saving it, which it does only for elements in
// physical groups), and we read the meshes gmsh makes itself.
#include <fstream>
#include <gtest/gtest.h>

#include "io/tet_mesh_io.h"
#include "tests/io_clients/clients.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

const TetMesh& sample() { return testing::client_sample(); }
using testing::tets_per_label;

std::map<std::pair<Label, Label>, std::size_t> faces_per_pair(const TetMesh& mesh)
{
    std::map<std::pair<Label, Label>, std::size_t> counts;
    for (const LabelPair& pair : mesh.face_sides) ++counts[{pair.from, pair.to}];
    return counts;
}

TEST(GmshOpensOurFiles, EveryMshVariantResavesWithTheSameTissuesAndInterfaces)
{
    testing::TempDir dir;
    const std::vector<std::pair<std::string, TetMeshWriteOptions>> variants{{"a.msh", {}},
                                                                            {"b.msh", {MshVersion::v2_2, true}},
                                                                            {"c.msh", {MshVersion::v4_1, false}},
                                                                            {"d.msh", {MshVersion::v4_1, true}}};
    for (const auto& [name, options] : variants) {
        write_tet_mesh(sample(), dir / name, options);
        for (const std::string format : {"msh22", "msh41"}) {
            SCOPED_TRACE(name + " re-saved by gmsh as " + format);
            const std::string resaved = format + "_" + name;
            if (!testing::run_gmsh({name, "-0", "-format", format, "-o", resaved}, dir.path())) continue;
            const TetMesh back = read_tet_mesh(dir / resaved);
            EXPECT_EQ(back.vertices.size(), sample().vertices.size());
            EXPECT_EQ(tets_per_label(back), tets_per_label(sample()));
            EXPECT_EQ(faces_per_pair(back), faces_per_pair(sample()))
                << "physical 1000 + from, elementary 1000 * from + to";
            EXPECT_EQ(back.names, sample().names) << "$PhysicalNames";
            const auto volumes = testing::tissue_volumes(back);
            EXPECT_NEAR(volumes.at(1), 56.0, 1e-9);
            EXPECT_NEAR(volumes.at(2), 8.0, 1e-9);
        }
    }
}

TEST(WeReadGmshFiles, TwoBoxesMeshedByGmshInEveryVariant)
{
    testing::TempDir dir;
    std::ofstream(dir / "two.geo")
        << "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\nBox(2) = {1, 0, 0, 1, 1, 1};\n"
           "BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }\n"
           "Physical Volume(\"left\", 1) = {1};\nPhysical Volume(\"right\", 2) = {2};\n"
           "Mesh.MeshSizeMax = 0.4;\n";
    std::map<Label, std::size_t> first_counts;
    for (const auto& [name, args] :
         std::vector<std::pair<std::string, std::vector<std::string>>>{{"a.msh", {"-format", "msh22"}},
                                                                       {"b.msh", {"-format", "msh22", "-bin"}},
                                                                       {"c.msh", {"-format", "msh41"}},
                                                                       {"d.msh", {"-format", "msh41", "-bin"}}}) {
        SCOPED_TRACE(name);
        std::vector<std::string> command{"-3", "two.geo", "-o", name};
        command.insert(command.end(), args.begin(), args.end());
        if (!testing::run_gmsh(command, dir.path())) continue;
        const TetMesh mesh = read_tet_mesh(dir / name);
        EXPECT_EQ(mesh.names, (TissueNames{{1, "left"}, {2, "right"}}));
        const auto volumes = testing::tissue_volumes(mesh);
        ASSERT_EQ(volumes.size(), 2u);
        EXPECT_NEAR(volumes.at(1), 1.0, 1e-12) << "the boxes are exact in any tetrahedralization";
        EXPECT_NEAR(volumes.at(2), 1.0, 1e-12);
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) ASSERT_GT(signed_volume(mesh, t), 0) << "tet " << t;
        // The same file through meshio: the same counts.
        const testing::MeshioView view = testing::meshio_read(dir / name);
        if (view.ok) {
            EXPECT_EQ(view.points, mesh.vertices.size());
            EXPECT_EQ(view.tets_per_label, tets_per_label(mesh));
        }
        if (first_counts.empty()) first_counts = tets_per_label(mesh);
        EXPECT_EQ(tets_per_label(mesh), first_counts) << "gmsh meshes alike whatever the output format";
    }
}

} // namespace
} // namespace tissuemesh::io
