// Broken and unsupported .vtu files are refused with the file, the problem and a fix, before any
// allocation their bytes cannot justify.
#include <fstream>
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/read_vtu.h"
#include "io/tet_mesh_io.h"
#include "tests/io/expect_error.h"
#include "tests/io_formats/vtu_variants.h"
#include "tests/support/cli.h"
#include "tests/support/programs.h"

namespace tissuemesh::io {
namespace {

using testing::expect_error;
using testing::nested_cubes_mesh;

void put(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream(path, std::ios::binary) << bytes;
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// A tiny ASCII .vtu: one tet (or what `cells` says), 4 points.
std::string tiny(const std::string& types = "10", const std::string& connectivity = "0 1 2 3",
                 const std::string& points = "4")
{
    return concat("<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"", points,
                  "\" NumberOfCells=\"1\">"
                  "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 0 0 "
                  "1</DataArray></Points>"
                  "<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">",
                  connectivity,
                  "</DataArray>"
                  "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray>"
                  "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">",
                  types,
                  "</DataArray></Cells>"
                  "</Piece></UnstructuredGrid></VTKFile>\n");
}

TEST(VtuBadFiles, TruncatedFilesOfEveryEncodingAreRefused)
{
    testing::TempDir dir;
    std::vector<std::pair<std::string, std::string>> files;
    write_vtu(nested_cubes_mesh(), dir / "ours.vtu", {}, {}, VtuEncoding::compressed);
    for (const char* format : {"binary", "appended"})
        for (const bool compressed : {false, true})
            files.push_back(
                {concat(format, compressed ? "-zlib" : "", ".vtu"),
                 testing::VtuVariantWriter({format, false, compressed, true, true}).file(nested_cubes_mesh())});
    files.push_back(
        {"base64.vtu", testing::VtuVariantWriter({"appended", true, true, false, false}).file(nested_cubes_mesh())});
    files.push_back(
        {"ascii.vtu", testing::VtuVariantWriter({"ascii", false, false, false, true}).file(nested_cubes_mesh())});
    std::ifstream ours(dir / "ours.vtu", std::ios::binary);
    files.push_back({"ours.vtu", std::string(std::istreambuf_iterator<char>(ours), {})});
    for (const auto& [name, bytes] : files)
        for (const double fraction : {0.05, 0.3, 0.6, 0.9, 0.99}) {
            SCOPED_TRACE(concat(name, " cut at ", fraction));
            put(dir / name, bytes.substr(0, static_cast<std::size_t>(fraction * static_cast<double>(bytes.size()))));
            try {
                read_vtu(dir / name);
                ADD_FAILURE() << "a truncated file was accepted";
            } catch (const Error& e) {
                EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
                EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
            }
        }
}

TEST(VtuBadFiles, SizesBeyondTheDataAreRefusedBeforeAllocating)
{
    testing::TempDir dir;
    put(dir / "a.vtu", tiny("10", "0 1 2 3", "400000000000"));
    expect_error<IoError>([&] { read_vtu(dir / "a.vtu"); },
                          {"a.vtu", "holds 12 values where 1200000000000 are needed"});
    // A zlib header claiming 2^40 bytes in one block made of 16 compressed bytes.
    std::string claim =
        testing::VtuVariantWriter({"appended", false, true, true, true, 1 << 20}).file(nested_cubes_mesh());
    const std::size_t mark = claim.find('_', claim.find("<AppendedData")) + 1;
    const std::uint64_t huge = std::uint64_t{1} << 40;
    claim.replace(mark + 8, 8, reinterpret_cast<const char*>(&huge), 8);
    claim.replace(mark + 16, 8, reinterpret_cast<const char*>(&huge), 8);
    put(dir / "b.vtu", claim);
    expect_error<IoError>([&] { read_vtu(dir / "b.vtu"); }, {"b.vtu", "bytes where the piece needs"});
    std::string blocks = claim;
    const std::uint64_t many = std::uint64_t{1} << 59;
    blocks.replace(mark, 8, reinterpret_cast<const char*>(&many), 8);
    put(dir / "c.vtu", blocks);
    expect_error<IoError>([&] { read_vtu(dir / "c.vtu"); }, {"c.vtu", "compressed blocks but only"});
}

TEST(VtuBadFiles, OtherCellsPiecesAndSettingsAreNamed)
{
    testing::TempDir dir;
    const std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> cases{
        {"triangle.vtu", tiny("5"), {"cell 0 is a triangle (VTK type 5)", "only tetrahedra", "Extract Cells By Type"}},
        {"hex.vtu", tiny("12"), {"hexahedron (VTK type 12)"}},
        {"pieces.vtu",
         replaced(tiny(), "</Piece>", "</Piece><Piece NumberOfPoints=\"0\" NumberOfCells=\"0\"></Piece>"),
         {"2 pieces", "Merge Blocks"}},
        {"big.vtu", replaced(tiny(), "<VTKFile", "<VTKFile byte_order=\"BigEndian\""), {"BigEndian", "LittleEndian"}},
        {"lzma.vtu",
         replaced(tiny(), "<VTKFile", "<VTKFile compressor=\"vtkLZMADataCompressor\""),
         {"vtkLZMADataCompressor", "zlib"}},
        {"poly.vtu", replaced(tiny(), "UnstructuredGrid\"", "PolyData\""), {"type \"PolyData\"", ".vtp"}},
        {"nocells.vtu",
         replaced(tiny(), "Name=\"connectivity\"", "Name=\"conn\""),
         {"no <Cells> DataArray \"connectivity\""}},
        {"type.vtu", replaced(tiny(), "Float64", "Float16"), {"type \"Float16\"", "Float32"}},
        {"word.vtu", replaced(tiny(), "0 1 2 3", "0 1 two 3"), {"\"two 3\", not a number"}},
        {"xml.vtu", "<?xml version=\"1.0\"?>\n<Mesh/>", {"the first tag is <Mesh>"}},
        {"empty.vtu", "", {"no <VTKFile> tag"}},
        {"unclosed.vtu", replaced(tiny(), "</Cells>", "</Points>"), {"</Points> closes <Cells>"}},
        {"offsets.vtu", replaced(tiny(), ">4</DataArray>", ">3</DataArray>"), {"cell 0 ends at offset 3"}},
        {"base64.vtu",
         replaced(tiny(), "Name=\"offsets\" format=\"ascii\">4", "Name=\"offsets\" format=\"binary\">!!"),
         {"not valid base64"}},
        {"appended.vtu",
         replaced(tiny(), "format=\"ascii\">4</DataArray>", "format=\"appended\" offset=\"0\"/>"),
         {"has no <AppendedData>"}}};
    for (const auto& [name, text, parts] : cases) {
        SCOPED_TRACE(name);
        put(dir / name, text);
        try {
            read_tet_mesh(dir / name);
            ADD_FAILURE() << "accepted";
        } catch (const IoError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(name), std::string::npos) << message;
            for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        }
    }
}

TEST(VtuBadFiles, DanglingIndicesAndBadLabelsAreInputErrors)
{
    testing::TempDir dir;
    put(dir / "a.vtu", tiny("10", "0 1 2 4"));
    expect_error<InputError>([&] { read_vtu(dir / "a.vtu"); }, {"a.vtu", "cell 0 refers to point 4 of 4"});
    put(dir / "b.vtu", replaced(tiny(), "</Cells>",
                                "</Cells><CellData><DataArray type=\"Int32\" Name=\"tissue\" "
                                "format=\"ascii\">70000</DataArray></CellData>"));
    expect_error<InputError>([&] { read_vtu(dir / "b.vtu"); }, {"b.vtu", "tissue label 70000", "0..65535"});
    put(dir / "c.vtu", replaced(tiny(), "0 0 0 1 0 0", "nan 0 0 1 0 0"));
    expect_error<InputError>([&] { read_vtu(dir / "c.vtu"); }, {"c.vtu"});
}

} // namespace
} // namespace tissuemesh::io
