// meshio (Debian's python3-meshio) opens every tet mesh format we write with the same counts, labels and
// volumes, and we read what meshio writes.
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>

#include "core/error.h"

#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "io/write_vtu.h"
#include "tests/io_clients/clients.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

const TetMesh& sample() { return testing::client_sample(); }
using testing::tets_per_label;

void expect_same_volumes(const std::map<Label, double>& volumes, const std::map<Label, double>& expected)
{
    ASSERT_EQ(volumes.size(), expected.size());
    for (const auto& [label, volume] : expected)
        EXPECT_NEAR(volumes.at(label), volume, 1e-9 * volume) << "tissue " << label;
}

TEST(MeshioOpensOurFiles, EveryTetMeshFormatAndEncoding)
{
    testing::TempDir dir;
    struct Case {
        std::string file;
        TetMeshWriteOptions options;
        bool triangles; ///< meshio sees the interface faces
    };
    const std::vector<Case> cases{{"a.msh", {}, true},
                                  {"b.msh", {MshVersion::v2_2, true}, true},
                                  {"c.msh", {MshVersion::v4_1, false}, true},
                                  {"d.msh", {MshVersion::v4_1, true}, true},
                                  {"e.mesh", {}, true},
                                  {"f.node", {}, false},
                                  {"g.inp", {}, false},
                                  {"h.vtu", {}, false},
                                  {"i.vtu", {MshVersion::v2_2, false, false}, false}};
    for (const Case& c : cases) {
        SCOPED_TRACE(c.file);
        write_tet_mesh(sample(), dir / c.file, c.options);
        const std::string opened = c.file == "f.node" ? "f.ele" : c.file; // meshio's TetGen reader takes the .ele
        const testing::MeshioView view = testing::meshio_read(dir / opened);
        if (!view.ok) continue;
        EXPECT_EQ(view.points, sample().vertices.size());
        EXPECT_EQ(view.cells.at("tetra"), sample().tets.size());
        if (c.triangles) {
            EXPECT_EQ(view.cells.count("triangle") ? view.cells.at("triangle") : 0, sample().faces.size());
        }
        EXPECT_EQ(view.tets_per_label, tets_per_label(sample()));
        expect_same_volumes(view.volume_per_label, testing::tissue_volumes(sample()));
    }
}

TEST(MeshioOpensOurFiles, CompressedVtuKeepsNamedCellArrays)
{
    testing::TempDir dir;
    std::vector<double> index(sample().tets.size());
    for (std::size_t t = 0; t < index.size(); ++t) index[t] = static_cast<double>(t);
    write_vtu(sample(), dir / "a.vtu", {}, {make_vtu_array("tet_index", index, true)}, VtuEncoding::compressed);
    const std::string script = "import sys, meshio\nm = meshio.read(sys.argv[1])\n"
                               "a = m.cell_data['tet_index'][0]\nprint(len(a), int(a.sum()), m.cells[0].type)\n";
    std::ofstream(dir / "arrays.py") << script;
    const testing::CliResult result =
        testing::run_program("/usr/bin/python3", {(dir / "arrays.py").string(), (dir / "a.vtu").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const std::size_t n = index.size();
    EXPECT_EQ(result.out, concat(n, " ", n * (n - 1) / 2, " tetra\n"));
}

TEST(MeshioOpensOurFiles, AbaqusInterfaceSurfacesAreElementSetsOfTheRightSize)
{
    testing::TempDir dir;
    write_tet_mesh(sample(), dir / "a.inp");
    std::ofstream(dir / "sets.py")
        << "import sys, meshio\nm = meshio.read(sys.argv[1])\n"
           "for name, blocks in sorted(m.cell_sets.items()):\n    print(name, sum(len(b) for b in blocks))\n";
    const testing::CliResult result =
        testing::run_program("/usr/bin/python3", {(dir / "sets.py").string(), (dir / "a.inp").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    std::map<std::string, std::size_t> faces; // surface -> element faces meshio sees in its S1..S4 sets
    std::istringstream lines(result.out);
    for (std::string name; lines >> name;) {
        std::size_t count = 0;
        lines >> count;
        if (name.rfind("IF_", 0) == 0 && name.size() > 9 && name.ends_with("_ELEMS"))
            faces[name.substr(0, name.size() - 9)] += count;
    }
    std::map<std::string, std::size_t> expected;
    for (const LabelPair& p : sample().face_sides) ++expected[concat("IF_", p.from, "_", p.to)];
    EXPECT_EQ(faces, expected) << result.out;
}

TEST(WeReadMeshioFiles, EveryTetMeshFormatMeshioWrites)
{
    testing::TempDir dir;
    struct Case {
        std::string file, format;
        bool binary;
    };
    for (const Case& c : std::vector<Case>{{"a.msh", "gmsh22", false},
                                           {"b.msh", "gmsh22", true},
                                           {"c.msh", "gmsh", false},
                                           {"d.msh", "gmsh", true},
                                           {"e.mesh", "medit", false},
                                           {"f.node", "tetgen", false},
                                           {"g.inp", "abaqus", false}}) {
        SCOPED_TRACE(c.file + " by meshio as " + c.format + (c.binary ? " binary" : ""));
        if (!testing::meshio_write_two_cubes(dir / c.file, c.format, c.binary)) continue;
        const TetMesh mesh = read_tet_mesh(dir / c.file);
        EXPECT_EQ(mesh.vertices.size(), 12u);
        EXPECT_EQ(tets_per_label(mesh), (std::map<Label, std::size_t>{{1, 6}, {2, 6}}));
        expect_same_volumes(testing::tissue_volumes(mesh), {{1, 1.0}, {2, 1.0}});
        for (std::size_t t = 0; t < mesh.tets.size(); ++t) EXPECT_GT(signed_volume(mesh, t), 0) << "tet " << t;
    }
}

TEST(WeReadMeshioFiles, VtuInEveryEncodingMeshioWritesWithItsArrays)
{
    testing::TempDir dir;
    for (const std::string format : {"vtu", "vtu-raw", "vtu-ascii"}) {
        SCOPED_TRACE("meshio " + format);
        const auto file = dir / (format + ".vtu");
        if (!testing::meshio_write_two_cubes(file, format, true)) continue;
        const VtuContent content = read_vtu(file);
        EXPECT_EQ(content.mesh.vertices.size(), 12u);
        EXPECT_EQ(content.label_array, "tissue");
        EXPECT_EQ(tets_per_label(content.mesh), (std::map<Label, std::size_t>{{1, 6}, {2, 6}}));
        expect_same_volumes(testing::tissue_volumes(content.mesh), {{1, 1.0}, {2, 1.0}});
        const VtuArray* phi = content.point_array("phi");
        ASSERT_NE(phi, nullptr);
        for (std::size_t p = 0; p < 12; ++p)
            EXPECT_DOUBLE_EQ(phi->values[p], content.mesh.vertices[p][0] + 2 * content.mesh.vertices[p][1])
                << "point " << p;
        const VtuArray* volume = content.cell_array("volume");
        ASSERT_NE(volume, nullptr);
        // meshio writes ASCII with 12 significant digits.
        for (std::size_t t = 0; t < 12; ++t)
            EXPECT_NEAR(volume->values[t], signed_volume(content.mesh, t), 1e-11) << "tet " << t;
    }
    // LZMA is not read; the message says how to save instead.
    if (testing::meshio_write_two_cubes(dir / "lzma.vtu", "vtu-lzma", true)) {
        try {
            read_vtu(dir / "lzma.vtu");
            ADD_FAILURE() << "an LZMA-compressed file was accepted";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("vtkLZMADataCompressor"), std::string::npos) << e.what();
        }
    }
}

TEST(WeReadMeshioFiles, OurVtuReadByMeshioAndBackKeepsThePotential)
{
    // meshio reads our compressed file and writes it again in its own encoding; we read that.
    testing::TempDir dir;
    std::vector<double> phi;
    for (const Vec3& p : sample().vertices) phi.push_back(p[0] - 0.5 * p[2]);
    write_vtu(sample(), dir / "ours.vtu", {make_vtu_array("potential_V", phi)}, {}, VtuEncoding::compressed);
    std::ofstream(dir / "again.py")
        << "import sys, meshio\nmeshio.write(sys.argv[2], meshio.read(sys.argv[1]), binary=True)\n";
    const testing::CliResult result = testing::run_program(
        "/usr/bin/python3", {(dir / "again.py").string(), (dir / "ours.vtu").string(), (dir / "theirs.vtu").string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    const VtuContent back = read_vtu(dir / "theirs.vtu");
    EXPECT_EQ(back.mesh.vertices, sample().vertices);
    EXPECT_EQ(back.mesh.tet_labels, sample().tet_labels);
    ASSERT_NE(back.point_array("potential_V"), nullptr);
    EXPECT_EQ(back.point_array("potential_V")->values, phi);
}

} // namespace
} // namespace tissuemesh::io
