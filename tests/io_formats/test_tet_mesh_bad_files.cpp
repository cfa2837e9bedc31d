// Broken mesh files are refused with the file name, the problem and a fix, and before any allocation
// the file's size cannot justify.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/tet_mesh_io.h"
#include "tests/io/expect_error.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

using testing::expect_error;
using testing::nested_cubes_mesh;

std::string slurp(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void put(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
}

/// The .msh variants (2.2 and 4.1, ASCII and binary) and .mesh, each with its file name, then `last` (.node or .inp).
std::vector<std::pair<std::string, TetMeshWriteOptions>> file_variants(const std::string& last)
{
    return {{"a.msh", {}},
            {"b.msh", {MshVersion::v2_2, true}},
            {"c.msh", {MshVersion::v4_1, false}},
            {"d.msh", {MshVersion::v4_1, true}},
            {"e.mesh", {}},
            {last, {}}};
}

TEST(TetMeshBadFiles, TruncatedFilesOfEveryVariantAreRefused)
{
    testing::TempDir dir;
    const auto variants = file_variants("f.node");
    for (const auto& [name, options] : variants) {
        write_tet_mesh(nested_cubes_mesh(), dir / name, options);
        const std::string bytes = slurp(dir / (name == "f.node" ? "f.ele" : name));
        for (const double fraction : {0.1, 0.5, 0.9}) {
            SCOPED_TRACE(name + " cut at " + std::to_string(fraction));
            const std::string cut =
                bytes.substr(0, static_cast<std::size_t>(fraction * static_cast<double>(bytes.size())));
            put(dir / (name == "f.node" ? "f.ele" : name), cut);
            try {
                read_tet_mesh(dir / name);
                ADD_FAILURE() << "a truncated file was accepted";
            } catch (const Error& e) {
                const std::string message = e.what();
                EXPECT_NE(message.find(name.substr(0, 2)), std::string::npos) << message;
                EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            }
        }
    }
}

TEST(TetMeshBadFiles, CountsBeyondTheDataAreRefusedBeforeAllocating)
{
    testing::TempDir dir;
    put(dir / "a.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4000000000\n1 0 0 0\n$EndNodes\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "a.msh"); },
                          {"a.msh", "expected 4000000000 nodes but only", "truncated"});
    put(dir / "b.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 99999999999 1 99999999999\n$EndNodes\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "b.msh"); }, {"b.msh", "99999999999 nodes"});
    std::string binary = "$MeshFormat\n4.1 1 8\n";
    const int one = 1;
    binary.append(reinterpret_cast<const char*>(&one), 4);
    binary += "\n$EndMeshFormat\n$Nodes\n";
    for (const std::uint64_t v : {std::uint64_t{1}, std::uint64_t{1} << 60, std::uint64_t{1}, std::uint64_t{1} << 60})
        binary.append(reinterpret_cast<const char*>(&v), 8);
    put(dir / "c.msh", binary);
    expect_error<IoError>([&] { read_tet_mesh(dir / "c.msh"); }, {"c.msh", "nodes but only"});
    put(dir / "d.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n123456789012\n0 0 0 0\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "d.mesh"); }, {"d.mesh", "123456789012 vertices"});
    put(dir / "e.node", "2000000000 3 0 0\n1 0 0 0\n");
    put(dir / "e.ele", "0 4 1\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "e.node"); }, {"e.node", "2000000000 nodes"});
}

TEST(TetMeshBadFiles, DanglingNodesAndNonFiniteCoordinatesAreInputErrors)
{
    testing::TempDir dir;
    const std::string nodes = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";
    put(dir / "a.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n" + nodes + "$Elements\n1\n1 4 2 1 1 1 2 3 9\n$EndElements\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "a.msh"); }, {"a.msh", "node 9, which does not exist"});
    put(dir / "b.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 nan\n$EndNodes\n"
        "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "b.msh"); }, {"b.msh", "non-finite"});
    put(dir / "c.msh",
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n3 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
        "$EndNodes\n$Elements\n1 1 1 1\n3 1 4 1\n1 1 2 3 5\n$EndElements\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "c.msh"); }, {"c.msh", "node 5, which does not exist"});
    put(dir / "d.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                        "Tetrahedra\n1\n1 2 3 7 1\nEnd\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "d.mesh"); }, {"d.mesh", "vertex index 7 is outside 1..4"});
    put(dir / "e.node", "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n");
    put(dir / "e.ele", "1 4 1\n1 1 2 3 5 1\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "e.ele"); }, {"e.ele", "node 5 does not exist"});
    put(dir / "f.inp", "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n*ELEMENT, TYPE=C3D4, ELSET=brain\n1, 1, 2, 3, 4\n");
    expect_error<InputError>([&] { read_tet_mesh(dir / "f.inp"); }, {"f.inp", "node 4, which does not exist"});
}

TEST(TetMeshBadFiles, UnsupportedVariantsAndUnknownFilesSayWhatToDo)
{
    testing::TempDir dir;
    put(dir / "a.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "a.msh"); }, {"a.msh", "format 3.0 is not supported", "msh22"});
    put(dir / "b.msh", "solid x\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "b.msh"); }, {"b.msh", "not a Gmsh file"});
    put(dir / "c.msh",
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 99 0 1\n$EndElements\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "c.msh"); }, {"c.msh", "element type 99 is not supported"});
    put(dir / "d.mesh", "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n1\n");
    expect_error<IoError>([&] { read_tet_mesh(dir / "d.mesh"); }, {"d.mesh", "SolAtVertices\" is not supported"});
    expect_error<IoError>([&] { read_tet_mesh(dir / "missing.msh"); }, {"missing.msh"});
    expect_error<IoError>([&] { read_tet_mesh(dir / "e.vtu"); }, {"e.vtu"}); // missing
    expect_error<IoError>([&] { write_tet_mesh(nested_cubes_mesh(), dir / "f.xyz"); },
                          {"f.xyz", "unknown mesh format", ".inp"});
    expect_error<IoError>([&] { write_tet_mesh(nested_cubes_mesh(), dir / "no" / "g.msh"); }, {"g.msh"});
    EXPECT_EQ(dir.files(), (std::vector<std::string>{"a.msh", "b.msh", "c.msh", "d.mesh"})) << "nothing half-written";
}

} // namespace
} // namespace tissuemesh::io

namespace tissuemesh::io {
namespace {

TEST(TetMeshBadFiles, CorruptedBytesGiveAnErrorOrAValidMeshNeverACrash)
{
    testing::TempDir dir;
    const auto variants = file_variants("f.inp");
    std::uint32_t state = 12345; // a fixed LCG: the same corruptions on every run
    auto next = [&] { return state = state * 1664525u + 1013904223u; };
    for (const auto& [name, options] : variants) {
        write_tet_mesh(nested_cubes_mesh(), dir / name, options);
        const std::string bytes = slurp(dir / name);
        int refused = 0;
        for (int trial = 0; trial < 100; ++trial) {
            std::string corrupt = bytes;
            for (int k = 0; k < 4; ++k) corrupt[next() % corrupt.size()] = static_cast<char>(next() >> 24);
            put(dir / name, corrupt);
            try {
                const TetMesh mesh = read_tet_mesh(dir / name);
                validate_indices(mesh, name); // whatever was accepted is a consistent mesh
            } catch (const Error&) {
                ++refused;
            }
        }
        EXPECT_GT(refused, 0) << name << ": some corruption must be noticed";
    }
}

} // namespace
} // namespace tissuemesh::io
