// The usc19-5 head (every 8th voxel, each voxel 6 tets) written for SimNIBS and for DUNEuro, read back as they
// read it: SimNIBS's tissue and surface tags through meshio and gmsh, each surface triangle facing out of the
// tissue of its tag; DUNEuro's files through a parser that follows dune-grid's GmshReader rule by rule and
// DUNEuro's conductivity reader.
#include <cstdio>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/read_label_image.h"
#include "io/simnibs_tags.h"
#include "io/tet_mesh_io.h"
#include "tests/io_clients/clients.h"
#include "tests/support/cli.h"

namespace tissuemesh::io {
namespace {

constexpr std::size_t stride = 8; // usc19-5 at 8 mm: 21 x 27 x 28 voxels, every tissue still present

/// The coarse head: voxel (a, b, c) is usc19-5's voxel (8a + 4, 8b + 4, 8c + 4).
LabelImage coarse_head()
{
    const LabelImage full =
        read_label_image(testing::data_path("samples/usc19-5_head.nii.gz"),
                         {.names_json = testing::data_path("samples/usc19-5_head.json"), .before_voxels = {}});
    const Dims& d = full.dims();
    LabelImage coarse({d[0] / stride, d[1] / stride, d[2] / stride},
                      {8.0 * full.spacing_mm()[0], 8.0 * full.spacing_mm()[1], 8.0 * full.spacing_mm()[2]});
    for (std::size_t c = 0; c < coarse.dims()[2]; ++c)
        for (std::size_t b = 0; b < coarse.dims()[1]; ++b)
            for (std::size_t a = 0; a < coarse.dims()[0]; ++a)
                coarse.at(a, b, c) = full.at(stride * a + 4, stride * b + 4, stride * c + 4);
    coarse.names() = full.names();
    return coarse;
}

/// Every non-background voxel as the 6 Kuhn tets of its cube (conforming across faces), voxel corner (a, b, c) at
/// (a, b, c) * spacing.
TetMesh voxel_tets(const LabelImage& image)
{
    TetMesh mesh;
    const Dims& d = image.dims();
    std::map<std::array<std::size_t, 3>, std::uint32_t> ids;
    auto vertex = [&](std::size_t a, std::size_t b, std::size_t c) {
        const auto [it, added] = ids.try_emplace({a, b, c}, static_cast<std::uint32_t>(mesh.vertices.size()));
        if (added)
            mesh.vertices.push_back({static_cast<double>(a) * image.spacing_mm()[0],
                                     static_cast<double>(b) * image.spacing_mm()[1],
                                     static_cast<double>(c) * image.spacing_mm()[2]});
        return it->second;
    };
    const std::array<std::array<int, 3>, 6> orders{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    for (std::size_t c = 0; c < d[2]; ++c)
        for (std::size_t b = 0; b < d[1]; ++b)
            for (std::size_t a = 0; a < d[0]; ++a) {
                if (image.at(a, b, c) == 0) continue;
                for (const auto& order : orders) {
                    std::array<std::size_t, 3> at{a, b, c};
                    Tet tet{vertex(a, b, c), 0, 0, 0};
                    for (std::size_t step = 0; step < 3; ++step) {
                        ++at[static_cast<std::size_t>(order[step])];
                        tet[step + 1] = vertex(at[0], at[1], at[2]);
                    }
                    mesh.tets.push_back(tet);
                    mesh.tet_labels.push_back(image.at(a, b, c));
                    if (signed_volume(mesh, mesh.tets.size() - 1) < 0)
                        std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
                }
            }
    mesh.names = image.names();
    return mesh;
}

/// SimNIBS's surface rule, restated from its mesher: the tag ranked first in (1, 2, 9, 3, 4, 8, 7, 6, 11, 10, 12, 5),
/// then the others ascending.
int ranked_first(int a, int b)
{
    const std::vector<int> order{1, 2, 9, 3, 4, 8, 7, 6, 11, 10, 12, 5};
    const auto rank = [&](int t) {
        const auto at = std::find(order.begin(), order.end(), t);
        return at != order.end() ? at - order.begin() : 100 + t;
    };
    return rank(a) <= rank(b) ? a : b;
}

/// Per cell type, tag -> count as meshio reads `file` (gmsh:physical), and whether gmsh:geometrical equals it.
nlohmann::json meshio_tags(const std::filesystem::path& file)
{
    std::ofstream(file.parent_path() / "tags.py")
        << "import json, sys, meshio, numpy as np\nm = meshio.read(sys.argv[1])\nout = {'equal': True}\n"
           "for b, block in enumerate(m.cells):\n"
           "    phys = np.asarray(m.cell_data['gmsh:physical'][b]).astype(int)\n"
           "    geo = np.asarray(m.cell_data['gmsh:geometrical'][b]).astype(int)\n"
           "    out['equal'] = out['equal'] and bool((phys == geo).all())\n"
           "    counts = out.setdefault(block.type, {})\n"
           "    for t in phys.tolist(): counts[str(t)] = counts.get(str(t), 0) + 1\n"
           "print(json.dumps(out))\n";
    const testing::CliResult result =
        testing::run_program("/usr/bin/python3", {(file.parent_path() / "tags.py").string(), file.string()});
    EXPECT_EQ(result.exit_code, 0) << result.err.substr(0, 2000);
    return result.exit_code == 0 ? nlohmann::json::parse(result.out) : nlohmann::json::object();
}

TEST(SimnibsNumbering, UscHeadCarriesSimnibsTissueAndSurfaceTags)
{
    testing::TempDir dir;
    const LabelImage head = coarse_head();
    const TetMesh mesh = voxel_tets(head);
    TetMeshWriteOptions options;
    options.numbering = TissueNumbering::simnibs;
    try {
        write_tet_mesh(mesh, dir / "refused.msh", options);
        ADD_FAILURE() << "air cavities have no SimNIBS tag";
    } catch (const InputError& error) {
        EXPECT_NE(std::string(error.what()).find("\"air cavities\" (label 6)"), std::string::npos) << error.what();
    }
    EXPECT_TRUE(dir.files().empty()) << "nothing written";

    options.simnibs_table = {{"air cavities", 13}};
    write_tet_mesh(mesh, dir / "head.msh", options);
    // usc19-5: 1 scalp, 2 skull, 3 CSF, 4 grey matter, 5 white matter, 6 air cavities -> 5, 4, 3, 2, 1, 13.
    const std::map<Label, int> tag{{1, 5}, {2, 4}, {3, 3}, {4, 2}, {5, 1}, {6, 13}};
    nlohmann::json expected = {
        {"tetra", nlohmann::json::object()}, {"triangle", nlohmann::json::object()}, {"equal", true}};
    const Dims& d = head.dims();
    const auto at = [&](std::int64_t a, std::int64_t b, std::int64_t c) { return head.at_or({a, b, c}, 0); };
    auto add = [&](const char* type, int t, int n) {
        expected[type][std::to_string(t)] = expected[type].value(std::to_string(t), 0) + n;
    };
    for (std::int64_t c = 0; c < static_cast<std::int64_t>(d[2]); ++c)
        for (std::int64_t b = 0; b < static_cast<std::int64_t>(d[1]); ++b)
            for (std::int64_t a = 0; a < static_cast<std::int64_t>(d[0]); ++a) {
                const Label here = at(a, b, c);
                if (here != 0) add("tetra", tag.at(here), 6);
                // Each voxel face with two different sides, seen from its lower side: 2 triangles.
                for (const Index3& next : {Index3{a + 1, b, c}, Index3{a, b + 1, c}, Index3{a, b, c + 1}}) {
                    const Label there = at(next[0], next[1], next[2]);
                    if (here == there || (here != 0 && there != 0 && tag.at(here) == tag.at(there))) continue;
                    add("triangle", here == 0 || there == 0 ? 1005 : 1000 + ranked_first(tag.at(here), tag.at(there)),
                        2);
                }
                if (a == 0 || b == 0 || c == 0) { // faces on the grid's low sides
                    for (const bool edge : {a == 0, b == 0, c == 0})
                        if (edge && here != 0) add("triangle", 1005, 2);
                }
            }
    EXPECT_EQ(meshio_tags(dir / "head.msh"), expected) << "tets 5 scalp, 4 skull, 3 CSF, 2 GM, 1 WM, 13 air; surfaces";
    EXPECT_EQ(read_file_bytes(dir / "head.msh").substr(0, 25), std::string("$MeshFormat\n2.2 1 8\n\x01\0\0\0\n", 25))
        << "2.2 binary";

    // gmsh opens it and re-saves every element (all are in physical groups) with the same tags.
    ASSERT_TRUE(testing::run_gmsh({"head.msh", "-0", "-format", "msh22", "-o", "resaved.msh"}, dir.path()));
    EXPECT_EQ(meshio_tags(dir / "resaved.msh"), expected);

    // Each triangle faces out of the tissue of its tag (SimNIBS orients them so); outer ones out of the head.
    const TetMesh back = read_tet_mesh(dir / "head.msh");
    std::size_t checked = 0;
    for (std::size_t f = 0; f < back.faces.size(); ++f) {
        const Vec3 &p = back.vertices[back.faces[f][0]], &q = back.vertices[back.faces[f][1]],
                   &r = back.vertices[back.faces[f][2]];
        const Vec3 n = cross(q - p, r - p), centre = (1.0 / 3.0) * (p + q + r);
        const auto tag_at = [&](const Vec3& point) {
            const Label label = at(static_cast<std::int64_t>(std::floor(point[0] / 8)),
                                   static_cast<std::int64_t>(std::floor(point[1] / 8)),
                                   static_cast<std::int64_t>(std::floor(point[2] / 8)));
            return label == 0 ? 0 : tag.at(label);
        };
        const int behind = tag_at(centre - (0.5 / norm(n)) * n), in_front = tag_at(centre + (0.5 / norm(n)) * n);
        const int face_tag = back.face_sides[f].from + 1000;
        if (face_tag == 1005 && in_front == 0) EXPECT_NE(behind, 0) << "outer face " << f;
        else EXPECT_EQ(behind + 1000, face_tag) << "face " << f << " in front " << in_front;
        ++checked;
    }
    EXPECT_EQ(checked, back.faces.size());
}

/// DUNEuro's view of a mesh: per tet the conductivity it takes, read as dune-grid's GmshReader (version 2, fscanf
/// patterns, $Nodes right after the format block, dense node numbers) and DUNEuro's tensor reader do.
std::vector<double> duneuro_view(const std::filesystem::path& msh, const std::filesystem::path& con, int offset)
{
    std::FILE* file = std::fopen(msh.c_str(), "r");
    EXPECT_NE(file, nullptr);
    if (file == nullptr) return {};
    char word[512];
    auto expect_word = [&](const char* wanted) {
        EXPECT_EQ(std::fscanf(file, "%511s\n", word), 1);
        EXPECT_STREQ(word, wanted);
    };
    double version = 0;
    int type = 0, size = 0, nodes = 0, elements = 0;
    expect_word("$MeshFormat");
    EXPECT_EQ(std::fscanf(file, "%lg %d %d\n", &version, &type, &size), 3);
    EXPECT_TRUE(version >= 2.0 && version <= 2.2) << version;
    expect_word("$EndMeshFormat");
    expect_word("$Nodes");
    EXPECT_EQ(std::fscanf(file, "%d\n", &nodes), 1);
    for (int i = 1; i <= nodes; ++i) {
        int id = 0;
        double x[3];
        EXPECT_EQ(std::fscanf(file, "%d %lg %lg %lg\n", &id, &x[0], &x[1], &x[2]), 4);
        EXPECT_LE(id, nodes) << "dense node numbers only";
    }
    expect_word("$EndNodes");
    expect_word("$Elements");
    EXPECT_EQ(std::fscanf(file, "%d\n", &elements), 1);
    std::vector<int> physical;
    for (int e = 1; e <= elements; ++e) {
        int id = 0, element_type = 0, tags = 0, tag = 0, corner[4];
        EXPECT_EQ(std::fscanf(file, "%d %d %d ", &id, &element_type, &tags), 3);
        for (int t = 1; t <= tags; ++t) {
            EXPECT_EQ(std::fscanf(file, "%d ", &tag), 1);
            if (t == 1) physical.push_back(tag);
        }
        EXPECT_EQ(element_type, 4) << "tets only: a triangle would become a boundary segment";
        EXPECT_EQ(std::fscanf(file, "%d %d %d %d\n", &corner[0], &corner[1], &corner[2], &corner[3]), 4);
    }
    expect_word("$EndElements");
    std::fclose(file);
    std::ifstream values(con);
    std::vector<double> tensors;
    for (double value; values >> value;) tensors.push_back(value);
    EXPECT_TRUE(values.eof()) << "DUNEuro reads numbers until the end, nothing else";
    std::vector<double> conductivity;
    for (const int pe : physical) {
        EXPECT_LT(pe - offset, static_cast<int>(tensors.size())) << "physical " << pe;
        EXPECT_GE(pe - offset, 0);
        conductivity.push_back(pe - offset >= 0 && pe - offset < static_cast<int>(tensors.size())
                                   ? tensors[static_cast<std::size_t>(pe - offset)]
                                   : -1);
    }
    return conductivity;
}

TEST(DuneuroLayout, DuneGridsReaderAndDuneurosConductivitiesAgreeWithTheTissues)
{
    testing::TempDir dir;
    const TetMesh mesh = voxel_tets(coarse_head());
    const std::map<Label, double> sigma{{1, 0.43}, {2, 0.01}, {3, 1.79}, {4, 0.33}, {5, 0.14}, {6, 1e-6}};
    for (const int offset : {1, 0, 7}) {
        SCOPED_TRACE(offset);
        TetMeshWriteOptions options;
        options.numbering = TissueNumbering::duneuro;
        options.duneuro_tag_offset = offset;
        options.duneuro_conductivities_s_per_m = sigma;
        write_tet_mesh(mesh, dir / "head.msh", options);
        const std::vector<double> seen = duneuro_view(dir / "head.msh", dir / "head.con", offset);
        ASSERT_EQ(seen.size(), mesh.tets.size());
        for (std::size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], sigma.at(mesh.tet_labels[t])) << "tet " << t;
    }
    // meshio and gmsh read it too, names (without spaces) included.
    const testing::MeshioView view = testing::meshio_read(dir / "head.msh");
    EXPECT_EQ(view.cells, (std::map<std::string, std::size_t>{{"tetra", mesh.tets.size()}}));
    EXPECT_TRUE(testing::run_gmsh({"head.msh", "-0", "-format", "msh22", "-o", "resaved.msh"}, dir.path()));
    const TetMesh back = read_tet_mesh(dir / "head.msh");
    EXPECT_EQ(back.names.at(10), "grey_matter") << "offset 7: labels 1..6 -> tags 7..12, spaces as '_'";
    // A tissue without a conductivity: refused, nothing written.
    TetMeshWriteOptions options;
    options.numbering = TissueNumbering::duneuro;
    options.duneuro_conductivities_s_per_m = {{1, 0.43}};
    EXPECT_THROW(write_tet_mesh(mesh, dir / "other.msh", options), InputError);
    EXPECT_FALSE(std::filesystem::exists(dir / "other.msh"));
    EXPECT_FALSE(std::filesystem::exists(dir / "other.con"));
}

} // namespace
} // namespace tissuemesh::io
