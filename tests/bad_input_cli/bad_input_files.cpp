#include "tests/bad_input_cli/bad_input_files.h"

#include <fstream>
#include <string>
#include <vector>

#include "io/surface_io.h"
#include "tests/io/make_test_images.h"
#include "tests/support/cli.h"
#include "tests/support/complexes.h"

namespace tissuemesh::testing {
namespace {

/// A Gmsh 2.2 mesh of one tet of tissue 1 with the given node lines and element lines.
std::string msh(const std::vector<std::string>& nodes, const std::vector<std::string>& elements)
{
    std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"brain\"\n$EndPhysicalNames\n";
    text += "$Nodes\n" + std::to_string(nodes.size()) + "\n";
    for (const auto& node : nodes) text += node + "\n";
    text += "$EndNodes\n$Elements\n" + std::to_string(elements.size()) + "\n";
    for (const auto& element : elements) text += element + "\n";
    return text + "$EndElements\n";
}

const std::vector<std::string> tet_nodes{"1 0 0 0", "2 20 0 0", "3 0 20 0", "4 0 0 20"};

void write_meshes(const std::filesystem::path& dir)
{
    write_text(dir / "ok.msh", msh(tet_nodes, {"1 4 2 1 1 1 2 3 4"}));
    write_text(dir / "flat.msh", msh({"1 0 0 0", "2 20 0 0", "3 0 20 0", "4 10 10 0"}, {"1 4 2 1 1 1 2 3 4"}));
    write_text(dir / "dangling.msh", msh(tet_nodes, {"1 4 2 1 1 1 2 3 9"}));
    write_text(dir / "nan.msh", msh({"1 0 0 0", "2 nan 0 0", "3 0 20 0", "4 0 0 20"}, {"1 4 2 1 1 1 2 3 4"}));
    write_text(dir / "no-tets.msh", msh(tet_nodes, {"1 2 2 1001 1 1 2 3"}));
    const std::string whole = msh(tet_nodes, {"1 4 2 1 1 1 2 3 4"});
    write_text(dir / "truncated.msh", whole.substr(0, whole.find("$Elements") + 12));
    write_text(dir / "bad.mesh", "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n20 0 0 0\n");
    // .vtu: one ASCII tet, then a triangle instead, a cut file and a point index past the points.
    const auto vtu = [](const std::string& type, const std::string& corners) {
        return "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPoints=\"4\" "
               "NumberOfCells=\"1\"><Points>"
               "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 20 0 0 0 20 0 0 0 "
               "20</DataArray></Points>"
               "<Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">" +
               corners +
               "</DataArray>"
               "<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">4</DataArray><DataArray type=\"UInt8\" "
               "Name=\"types\" "
               "format=\"ascii\">" +
               type +
               "</DataArray></Cells><CellData><DataArray type=\"UInt16\" Name=\"tissue\" format=\"ascii\">1"
               "</DataArray></CellData></Piece></UnstructuredGrid></VTKFile>\n";
    };
    write_text(dir / "ok.vtu", vtu("10", "0 1 2 3"));
    write_text(dir / "triangle.vtu", vtu("5", "0 1 2 3"));
    write_text(dir / "dangling.vtu", vtu("10", "0 1 2 9"));
    write_text(dir / "truncated.vtu", vtu("10", "0 1 2 3").substr(0, 300));
}

void write_surfaces(const std::filesystem::path& dir)
{
    InterfaceComplex box;
    add_box(box, {0, 0, 0}, {10, 10, 10}, 1, 0);
    box.names = {{0, "background"}, {1, "brain"}};
    io::write_surface(box, dir / "ok.ply");

    InterfaceComplex hole = box;
    hole.triangles.pop_back();
    hole.sides.pop_back();
    io::write_surface(hole, dir / "hole.ply");
    InterfaceComplex flipped = box;
    flip_triangle(flipped, 0);
    io::write_surface(flipped, dir / "flipped.ply");
    InterfaceComplex duplicate = box;
    duplicate.add_triangle(box.triangles[0], box.sides[0]);
    io::write_surface(duplicate, dir / "duplicate.ply");
    // A second vertex at the place of vertex 0, used by one triangle: the surface is open along its edges.
    InterfaceComplex twins = box;
    twins.vertices.push_back(box.vertices[box.triangles[0][0]]);
    twins.triangles[0][0] = static_cast<std::uint32_t>(twins.vertices.size() - 1);
    io::write_surface(twins, dir / "twin-vertices.ply");
    InterfaceComplex crossing = box;
    add_box(crossing, {5, 5, 5}, {15, 15, 15}, 2, 0);
    crossing.names[2] = "skull";
    io::write_surface(crossing, dir / "crossing.ply");

    const std::string ascii_head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    write_text(dir / "nan.ply", ascii_head + "0 0 0\nnan 1 0\n0 1 0\n3 0 1 2\n");
    write_text(dir / "dangling.ply", ascii_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    write_text(dir / "magic.ply", "plx\n" + ascii_head.substr(4));
    write_text(dir / "empty.ply", "");
    const std::string binary = read_text(dir / "ok.ply");
    write_text(dir / "truncated.ply", binary.substr(0, binary.size() - 20));
    write_text(dir / "counts.off", "OFF\n4 9 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 2\n");
    std::string stl(80, ' ');
    stl += std::string("\x0c\0\0\0", 4) + std::string(30, '\0'); // 12 triangles announced, 30 bytes given
    write_text(dir / "truncated.stl", stl);
}

void write_images(const std::filesystem::path& dir)
{
    // 2x2x2 voxels of 1 mm: ok.nii holds labels 0..7, the others one defect each.
    write_nifti(dir / "ok.nii", {}, {0, 1, 2, 3, 4, 5, 6, 7});
    write_nifti(dir / "one-label.nii", {}, {0, 0, 0, 0, 0, 0, 0, 0});
    NiftiSpec single;
    single.dims[1] = single.dims[2] = single.dims[3] = 1;
    write_nifti(dir / "one-voxel.nii", single, {3});
    NiftiSpec block;
    block.dims[1] = block.dims[2] = block.dims[3] = 4;
    std::vector<unsigned char> border(64, 0);
    border[0] = 2;          // a corner voxel: on the border
    border[1 + 4 + 16] = 1; // an inner voxel
    write_nifti(dir / "border.nii", block, border);
    NiftiSpec complex_type;
    complex_type.datatype = 32; // complex64
    complex_type.bitpix = 64;
    write_nifti(dir / "complex.nii", complex_type, std::vector<unsigned char>(64, 0));
    NiftiSpec inf_spacing;
    inf_spacing.spacing[2] = std::numeric_limits<float>::infinity();
    write_nifti(dir / "inf.nii", inf_spacing, {0, 1, 2, 3, 4, 5, 6, 7});

    write_text(dir / "magic.nrrd", "NRRX0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n12345678");
    write_text(dir / "short.nrrd", "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 2 2 2\nspacings: 1 1 1\n"
                                   "encoding: raw\n\n123");
    write_text(dir / "nofile.mhd", "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
                                   "ElementSpacing = 1 1 1\nElementDataFile = nowhere.raw\n");
    write_text(dir / "short.mha", "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\n"
                                  "ElementSpacing = 1 1 1\nElementDataFile = LOCAL\n\1\2");
}

void write_tables(const std::filesystem::path& dir)
{
    write_text(dir / "cond-unknown.json", R"({"liver": 0.2})");
    write_text(dir / "cond-label.json", R"({"7": 0.2})");
    write_text(dir / "cond-negative.json", R"({"brain": -0.3})");
    write_text(dir / "cond-text.json", R"({"brain": "high"})");
    write_text(dir / "cond-broken.json", R"({"brain": 0.3)");
    write_text(dir / "cond-tensor.json", R"({"brain": [1, 2, 3]})");
    write_text(dir / "sensors-header.csv", "a,b,c\n1,2,3\n");
    write_text(dir / "sensors-number.csv", "x,y,z\n1,two,3\n");
    write_text(dir / "names-broken.json", R"({"1": "scalp")");
    write_text(dir / "cond-empty.json", "");
    write_text(dir / "cond-twice.json", R"({"brain": 0.3, "BRAIN": 0.2})");
    write_text(dir / "cond-name-and-label.json", R"({"brain": 0.3, "1": 0.2})");
    write_text(dir / "cond-deep.json", R"({"brain": [[[0.3]]]})");
    write_text(dir / "cond-overflow.json", R"({"brain": 1e999})");
    // Montages for ok.msh (one tet with a corner at the origin and edges of 20 mm): a patch of radius 30 mm
    // around a corner covers the whole tet.
    const std::string header = "name,x,y,z,radius_mm,current_a\n";
    write_text(dir / "montage-empty.csv", "");
    write_text(dir / "montage-header-only.csv", header);
    write_text(dir / "montage-ma.csv", "x,y,z,radius_mm,current_ma\n0,0,0,30,1\n20,0,0,30,-1\n");
    write_text(dir / "montage-negative.csv", header + "Cz,0,0,0,-10,1e-3\nOz,20,0,0,30,-1e-3\n");
    write_text(dir / "montage-nan.csv", header + "Cz,0,0,0,30,1e-3\nOz,20,0,0,30,nan\n");
    write_text(dir / "montage-cut.csv", header + "Cz,0,0,0,30,1e-3\nOz,20,0");
    write_text(dir / "montage-twice.csv", header + "Cz,0,0,0,30,1e-3\nCz,20,0,0,30,-1e-3\n");
    write_text(dir / "montage-off.csv", header + "Cz,0,0,0,30,1e-3\nOz,100,100,100,2,-1e-3\n");
    write_text(dir / "montage-unbalanced.csv", header + "Cz,0,0,0,30,1e-3\nOz,20,0,0,30,-2e-3\n");
    write_text(dir / "sensors-empty.csv", "");
    write_text(dir / "sensors-nan.csv", "x,y,z\n1,2,3\n1,inf,3\n");
    write_text(dir / "sensors-no-z.csv", "x,y\n1,2\n");
    write_text(dir / "sensors-twice.csv", "name,x,y,z\nCz,0,0,20\nCz,20,0,0\n");
}

} // namespace

void write_bad_input_files(const std::filesystem::path& dir)
{
    write_meshes(dir);
    write_surfaces(dir);
    write_images(dir);
    write_tables(dir);
}

} // namespace tissuemesh::testing
