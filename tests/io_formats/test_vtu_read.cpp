// .vtu files read back: ours (both encodings) with their arrays, and every other encoding VTK allows.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "tests/io_formats/mesh_compare.h"
#include "tests/io_formats/vtu_variants.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

using testing::nested_cubes_mesh;
using testing::tet_set;

std::vector<double> node_values(const TetMesh& mesh)
{
    std::vector<double> phi;
    for (const Vec3& p : mesh.vertices) phi.push_back(1e-3 * p[0] - 0.25 * p[2] + 1.0 / 3.0);
    return phi;
}

TEST(VtuRead, OurFilesReadBackWithEveryArrayInBothEncodings)
{
    testing::TempDir dir;
    std::vector<Vec3> field;
    std::vector<double> index;
    for (std::size_t t = 0; t < nested_cubes_mesh().tets.size(); ++t)
        field.push_back({1.0 * static_cast<double>(t), -0.5, 1e-7}), index.push_back(static_cast<double>(t));
    for (const VtuEncoding encoding : {VtuEncoding::compressed, VtuEncoding::ascii}) {
        SCOPED_TRACE(encoding == VtuEncoding::ascii ? "ascii" : "compressed");
        write_vtu(nested_cubes_mesh(), dir / "a.vtu", {make_vtu_array("potential_V", node_values(nested_cubes_mesh()))},
                  {make_vtu_vectors("E_V_per_m", field), make_vtu_array("index", index, true)}, encoding);
        const VtuContent back = read_vtu(dir / "a.vtu");
        EXPECT_EQ(back.mesh.vertices, nested_cubes_mesh().vertices) << "raw doubles or 17 significant digits: exact";
        EXPECT_EQ(tet_set(back.mesh), tet_set(nested_cubes_mesh()));
        EXPECT_EQ(back.mesh.tets, nested_cubes_mesh().tets) << "positively oriented tets keep their vertex order";
        EXPECT_EQ(back.label_array, "tissue");
        ASSERT_EQ(back.point_arrays.size(), 1u);
        ASSERT_EQ(back.cell_arrays.size(), 2u) << "the label array is the mesh's labels, not an extra array";
        ASSERT_NE(back.point_array("potential_V"), nullptr);
        EXPECT_EQ(back.point_array("potential_V")->values, node_values(nested_cubes_mesh()));
        const VtuArray* e = back.cell_array("E_V_per_m");
        ASSERT_NE(e, nullptr);
        EXPECT_EQ(e->components, 3);
        EXPECT_FALSE(e->integer);
        EXPECT_EQ(e->values, make_vtu_vectors("", field).values);
        EXPECT_TRUE(back.cell_array("index")->integer);
        EXPECT_EQ(back.cell_array("index")->values, index);
        EXPECT_EQ(back.mesh.faces.size(), 0u) << ".vtu files keep no interface faces";
        const auto volumes = testing::tissue_volumes(read_tet_mesh(dir / "a.vtu"));
        EXPECT_NEAR(volumes.at(1), 56.0, 1e-9);
        EXPECT_NEAR(volumes.at(2), 8.0, 1e-9);
    }
}

TEST(VtuRead, EveryEncodingHeaderAndNumberTypeReads)
{
    testing::TempDir dir;
    int n = 0;
    for (const std::string format : {"ascii", "binary", "appended"})
        for (const bool base64 : {false, true})
            for (const bool compressed : {false, true})
                for (const bool header64 : {false, true})
                    for (const bool wide : {false, true}) {
                        if (format != "appended" && base64) continue;
                        if (format == "ascii" && (compressed || header64)) continue;
                        const testing::VtuVariant variant{format, base64, compressed, header64, wide};
                        SCOPED_TRACE(concat(format, base64 ? " base64" : "", compressed ? " zlib" : "",
                                            header64 ? " UInt64" : " UInt32", wide ? " 64-bit" : " 32-bit"));
                        const auto file = dir / concat("v", n++, ".vtu");
                        std::ofstream(file, std::ios::binary)
                            << testing::VtuVariantWriter(variant).file(nested_cubes_mesh());
                        const VtuContent back = read_vtu(file);
                        EXPECT_EQ(tet_set(back.mesh), tet_set(nested_cubes_mesh()));
                        ASSERT_EQ(back.mesh.vertices.size(), nested_cubes_mesh().vertices.size());
                        // Float64 binary is exact; Float32 keeps 7 digits, the ASCII of this writer 10 (coordinates
                        // within 0..4 mm).
                        const double tolerance = wide && format != "ascii" ? 0.0 : 1e-6;
                        for (std::size_t p = 0; p < nested_cubes_mesh().vertices.size(); ++p)
                            for (int c = 0; c < 3; ++c)
                                ASSERT_NEAR(back.mesh.vertices[p][c], nested_cubes_mesh().vertices[p][c], tolerance);
                        const VtuArray* phi = back.point_array("phi");
                        ASSERT_NE(phi, nullptr);
                        for (std::size_t p = 0; p < nested_cubes_mesh().vertices.size(); ++p)
                            ASSERT_NEAR(phi->values[p],
                                        nested_cubes_mesh().vertices[p][0] + 2 * nested_cubes_mesh().vertices[p][1],
                                        3 * tolerance);
                    }
    EXPECT_EQ(n, 26);
}

} // namespace
} // namespace tissuemesh::io
