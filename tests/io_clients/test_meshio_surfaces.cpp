// meshio opens the surfaces we write, and we read the surfaces meshio writes. Not here: .vtp (meshio has no
// PolyData reader) and our labelled .ply (meshio 5.0's binary PLY reader takes the vertex list as a face's
// only property, so per-face labels after it derail it); both are checked by our own round trips.
#include <fstream>
#include <gtest/gtest.h>

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

TEST(MeshioOpensOurSurfaces, ObjOffStl)
{
    testing::TempDir dir;
    const InterfaceComplex sphere = testing::icosphere(2, 10.0, {1, 2, 3});
    for (const char* name : {"b.obj", "c.off", "d.stl"}) {
        write_surface(sphere, dir / name);
        // (STL stores corners per triangle; meshio merges equal ones, as we do.)
        EXPECT_EQ(meshio_counts(dir / name), concat(sphere.vertices.size(), " ", sphere.triangles.size(), "\n")) << name;
    }
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
