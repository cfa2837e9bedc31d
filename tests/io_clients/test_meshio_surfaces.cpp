// meshio opens the surfaces we write, with their labels where the format and meshio's reader hold them, and we
// read the surfaces meshio writes. What meshio cannot read, whatever the writer does: .vtp (meshio has no
// PolyData reader) and the labels of a binary .ply (meshio 5.0's binary PLY reader, like its newest one, takes
// each face property as one column after the other instead of face by face, so any per-face property after the
// vertex list derails it); for those formats our own round trips check the labels, and `tm-convert --ascii`
// writes a PLY meshio reads with them.
#include <fstream>
#include <gtest/gtest.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/surface_io.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

const char* const python = "/usr/bin/python3";

/// "points triangles" as meshio counts them.
std::string meshio_counts(const std::filesystem::path& file)
{
    const std::filesystem::path script = file.parent_path() / "counts.py";
    std::ofstream(script) << "import sys, meshio\nm = meshio.read(sys.argv[1])\n"
                             "print(len(m.points), sum(len(b.data) for b in m.cells if b.type == 'triangle'))\n";
    const testing::CliResult result = testing::run_program(python, {script.string(), file.string()});
    EXPECT_EQ(result.exit_code, 0) << "meshio reading " << file.filename() << ": " << result.err.substr(0, 2000)
                                   << (result.exit_code == 127 ? " (python3 missing: run scripts/setup)" : "");
    return result.out;
}

/// Enclosed volume of a closed, outward-oriented surface (divergence theorem), mm^3.
double enclosed_volume(const InterfaceComplex& complex)
{
    double volume = 0;
    for (const Triangle& t : complex.triangles)
        volume += dot(complex.vertices[t[0]], cross(complex.vertices[t[1]], complex.vertices[t[2]])) / 6.0;
    return volume;
}

/// Two tissues (1 inside 2, 0 outside): an icosphere of radius 10 mm in one of 20 mm, with the inner sphere's
/// triangles labelled {1, 2} and the outer ones {2, 0}.
InterfaceComplex two_spheres()
{
    InterfaceComplex complex = testing::icosphere(2, 10.0, {1, 2, 3});
    for (LabelPair& pair : complex.sides) pair = {1, 2};
    const InterfaceComplex outer = testing::icosphere(2, 20.0, {1, 2, 3});
    const auto offset = static_cast<std::uint32_t>(complex.vertices.size());
    complex.vertices.insert(complex.vertices.end(), outer.vertices.begin(), outer.vertices.end());
    for (const Triangle& t : outer.triangles)
        complex.add_triangle({t[0] + offset, t[1] + offset, t[2] + offset}, {2, 0});
    complex.names = {{1, "brain"}, {2, "scalp"}};
    return complex;
}

/// meshio's view of a file: "points triangles", then per triangle the labels meshio found in `key_a` and
/// `key_b` (cell data), or "-" when it has none.
std::string meshio_labels(const std::filesystem::path& file, const std::string& key_a, const std::string& key_b)
{
    const std::filesystem::path script = file.parent_path() / "labels.py";
    std::ofstream(script)
        << "import sys, meshio, numpy as np\nm = meshio.read(sys.argv[1])\n"
           "tri = [i for i, b in enumerate(m.cells) if b.type == 'triangle']\n"
           "out = [len(m.points), sum(len(m.cells[i].data) for i in tri)]\n"
           "for key in sys.argv[2:]:\n"
           "    out.append(' '.join(str(int(v)) for i in tri for v in np.asarray(m.cell_data[key][i]))"
           " if key in m.cell_data else '-')\n"
           "print('\\n'.join(str(x) for x in out))\n";
    const testing::CliResult result = testing::run_program(python, {script.string(), file.string(), key_a, key_b});
    EXPECT_EQ(result.exit_code, 0) << "meshio reading " << file.filename() << ": " << result.err.substr(0, 2000);
    return result.out;
}

TEST(MeshioOpensOurSurfaces, ObjOffStlBinaryAndAscii)
{
    testing::TempDir dir;
    const InterfaceComplex sphere = testing::icosphere(2, 10.0, {1, 2, 3});
    for (const bool ascii : {false, true})
        for (const char* name : {"b.obj", "c.off", "d.stl"}) {
            const std::filesystem::path file = dir / concat(ascii ? "ascii-" : "", name);
            write_surface(sphere, file, SurfaceWriteOptions{.ascii = ascii});
            // (STL stores corners per triangle; meshio merges equal ones, as we do.)
            EXPECT_EQ(meshio_counts(file), concat(sphere.vertices.size(), " ", sphere.triangles.size(), "\n")) << file;
        }
    EXPECT_EQ(read_file_bytes(dir / "ascii-d.stl").rfind("solid tissuemesh\n", 0), 0u);
}

TEST(MeshioOpensOurSurfaces, AsciiPlyWithItsLabels)
{
    testing::TempDir dir;
    const InterfaceComplex complex = two_spheres();
    write_surface(complex, dir / "a.ply", SurfaceWriteOptions{.ascii = true});
    std::string from, to;
    for (const LabelPair& pair : complex.sides)
        from += concat(from.empty() ? "" : " ", pair.from), to += concat(to.empty() ? "" : " ", pair.to);
    EXPECT_EQ(meshio_labels(dir / "a.ply", "label_a", "label_b"),
              concat(complex.vertices.size(), "\n", complex.triangles.size(), "\n", from, "\n", to, "\n"));
    // And we read it back whole, names included.
    const InterfaceComplex back = read_surface(dir / "a.ply");
    EXPECT_EQ(back.vertices, complex.vertices);
    EXPECT_EQ(back.triangles, complex.triangles);
    EXPECT_EQ(back.sides, complex.sides);
    EXPECT_EQ(back.names, complex.names);
}

TEST(MeshioOpensOurSurfaces, ObjWithOneGroupPerTissuePair)
{
    // meshio numbers the groups of an .obj in file order (obj:group_ids); our groups are the tissue pairs.
    testing::TempDir dir;
    const InterfaceComplex complex = two_spheres();
    write_surface(complex, dir / "a.obj");
    const std::string view = meshio_labels(dir / "a.obj", "obj:group_ids", "none");
    std::string groups;
    for (const LabelPair& pair : complex.sides) groups += concat(groups.empty() ? "" : " ", pair.from == 1 ? 0 : 1);
    EXPECT_EQ(view, concat(complex.vertices.size(), "\n", complex.triangles.size(), "\n", groups, "\n-\n"));
}

TEST(MeshioOpensOurSurfaces, BinaryPlyHeaderUsesOnlyTypeNamesMeshioKnows)
{
    // meshio's binary PLY reader knows the sized integer names and float/double, not uchar/ushort (its ASCII
    // reader knows both). Its layout limit (see the top of this file) is not ours to fix; its types are.
    testing::TempDir dir;
    write_surface(two_spheres(), dir / "a.ply");
    const std::string bytes = read_file_bytes(dir / "a.ply");
    const std::string header = bytes.substr(0, bytes.find("end_header"));
    for (const char* known : {"property double x", "property list uint8 uint32 vertex_indices",
                              "property uint16 label_a", "property uint16 label_b"})
        EXPECT_NE(header.find(known), std::string::npos) << known;
    for (const char* unknown : {"uchar", "ushort", " uint ", " short ", " char "})
        EXPECT_EQ(header.find(unknown), std::string::npos) << unknown;
}

TEST(WeReadMeshioSurfaces, ObjOffPlyAndBothStls)
{
    testing::TempDir dir;
    std::ofstream(dir / "write.py")
        << "import sys, numpy as np, meshio\n"
           "pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)\n"
           "tri = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)\n"
           "m = meshio.Mesh(pts, [('triangle', tri)])\n"
           "for name in ['a.obj', 'b.off', 'c.ply']: meshio.write(sys.argv[1] + '/' + name, m)\n"
           "meshio.write(sys.argv[1] + '/d.stl', m, binary=False)\n"
           "meshio.write(sys.argv[1] + '/e.stl', m, binary=True)\n";
    const testing::CliResult result = testing::run_program(python, {(dir / "write.py").string(), dir.path().string()});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    for (const char* name : {"a.obj", "b.off", "c.ply", "d.stl", "e.stl"}) {
        const InterfaceComplex complex = read_surface(dir / name);
        EXPECT_EQ(complex.vertices.size(), 4u) << name;
        EXPECT_EQ(complex.triangles.size(), 4u) << name;
        EXPECT_NEAR(enclosed_volume(complex), 1.0 / 6.0, 1e-7) << name << ": the unit corner tet, outward";
    }
}

} // namespace
} // namespace tissuemesh::io
