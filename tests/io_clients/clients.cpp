#include "tests/io_clients/clients.h"

#include <fstream>
#include <gtest/gtest.h>

#include "tests/support/programs.h"

namespace tissuemesh::testing {
namespace fs = std::filesystem;
namespace {

// Debian's interpreter, where python3-meshio is installed (another python3 may come first on PATH).
const char* const python = "/usr/bin/python3";

const char* const read_script = R"PY(
import json, re, sys
import numpy as np
import meshio
m = meshio.read(sys.argv[1])
out = {"points": len(m.points), "cells": {}, "tets": {}, "volumes": {}, "sets": sorted(m.cell_sets.keys())}
for block in m.cells:
    out["cells"][block.type] = out["cells"].get(block.type, 0) + len(block.data)
label_keys = ["gmsh:physical", "medit:ref", "tetgen:ref", "tissue"]
set_label = {}
for name, blocks in m.cell_sets.items():
    found = re.search(r"(\d+)$", name)
    if found and name != "gmsh:bounding_entities":
        for b, members in enumerate(blocks):
            for c in np.asarray(members, dtype=int).tolist():
                set_label[(b, c)] = int(found.group(1))
for b, block in enumerate(m.cells):
    if block.type != "tetra":
        continue
    p = m.points[block.data[:, :4]]
    volumes = np.abs(np.einsum("ij,ij->i", p[:, 1] - p[:, 0], np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0]))) / 6
    labels = None
    for key in label_keys:
        if key in m.cell_data:
            labels = np.asarray(m.cell_data[key][b]).astype(int).tolist()
            break
    if labels is None:
        labels = [set_label.get((b, c), 0) for c in range(len(block.data))]
    for label, volume in zip(labels, volumes.tolist()):
        out["tets"][str(label)] = out["tets"].get(str(label), 0) + 1
        out["volumes"][str(label)] = out["volumes"].get(str(label), 0.0) + volume
print(json.dumps(out))
)PY";

const char* const write_script = R"PY(
import sys
import numpy as np
import meshio
pts = np.array([[x, y, z] for z in (0, 1) for y in (0, 1) for x in (0, 1, 2)], dtype=float)
kuhn = [(0, 1, 3, 7), (0, 1, 5, 7), (0, 2, 3, 7), (0, 2, 6, 7), (0, 4, 5, 7), (0, 4, 6, 7)]
tets, labels = [], []
for cube in (0, 1):
    for t in kuhn:
        tets.append([(cube + (c & 1)) + 3 * (((c >> 1) & 1) + 2 * ((c >> 2) & 1)) for c in t])
        labels.append(cube + 1)
tets, labels = np.array(tets), np.array(labels)
out, fmt, binary = sys.argv[1], sys.argv[2], sys.argv[3] == "1"
cells, cell_data, point_data = [("tetra", tets)], {}, {}
if fmt.startswith("gmsh"):
    # One block per tissue entity; each node on the entity of the first tissue using it (4.1 needs it).
    cells = [("tetra", tets[labels == 1]), ("tetra", tets[labels == 2])]
    cell_data = {"gmsh:physical": [np.full(6, 1), np.full(6, 2)], "gmsh:geometrical": [np.full(6, 1), np.full(6, 2)]}
    point_data = {"gmsh:dim_tags": np.array([[3, 1 if p[0] <= 1 else 2] for p in pts])}
elif fmt == "medit":
    cell_data = {"medit:ref": [labels]}
elif fmt == "tetgen":
    cell_data = {"tetgen:ref": [labels]}
elif fmt.startswith("vtu"):
    # "vtu": inline base64, zlib (meshio's default); "vtu-raw": base64 uncompressed; "vtu-lzma"; "vtu-ascii".
    cell_data = {"tissue": [labels], "volume": [np.full(12, 1.0 / 6)]}
    point_data = {"phi": pts[:, 0] + 2 * pts[:, 1]}
options = {"binary": binary} if fmt.startswith("gmsh") else {}
if fmt.startswith("vtu"):
    options = {"binary": fmt != "vtu-ascii", "compression": {"vtu": "zlib", "vtu-lzma": "lzma"}.get(fmt)}
    fmt = "vtu"
mesh = meshio.Mesh(pts, cells, cell_data=cell_data, point_data=point_data)
if fmt == "abaqus":
    mesh.cell_sets = {"tissue1": [np.where(labels == 1)[0]], "tissue2": [np.where(labels == 2)[0]]}
meshio.write(out, mesh, file_format=fmt, **options)
)PY";

fs::path script(const fs::path& folder, const char* name, const char* text)
{
    const fs::path path = folder / name;
    std::ofstream(path) << text;
    return path;
}

bool succeeded(const CliResult& result, const std::string& what)
{
    if (result.exit_code == 127) {
        ADD_FAILURE() << what << ": the program is missing; scripts/setup installs python3-meshio and gmsh";
        return false;
    }
    if (result.exit_code != 0) {
        ADD_FAILURE() << what << " exited " << result.exit_code << ": " << result.err.substr(0, 2000);
        return false;
    }
    return true;
}

} // namespace

MeshioView meshio_read(const fs::path& file)
{
    MeshioView view;
    const fs::path program = script(file.parent_path(), "meshio_read.py", read_script);
    const CliResult result = run_program(python, {program.string(), file.string()});
    if (!succeeded(result, "meshio reading " + file.filename().string())) return view;
    const nlohmann::json json = nlohmann::json::parse(result.out);
    view.points = json.at("points").get<std::size_t>();
    for (const auto& [type, count] : json.at("cells").items()) view.cells[type] = count.get<std::size_t>();
    for (const auto& [label, count] : json.at("tets").items())
        view.tets_per_label[static_cast<Label>(std::stoi(label))] = count.get<std::size_t>();
    for (const auto& [label, volume] : json.at("volumes").items())
        view.volume_per_label[static_cast<Label>(std::stoi(label))] = volume.get<double>();
    view.cell_sets = json.at("sets").get<std::vector<std::string>>();
    view.ok = true;
    return view;
}

bool meshio_write_two_cubes(const fs::path& file, const std::string& format, bool binary)
{
    const fs::path program = script(file.parent_path(), "meshio_write.py", write_script);
    return succeeded(run_program(python, {program.string(), file.string(), format, binary ? "1" : "0"}),
                     "meshio writing " + file.filename().string());
}

bool run_gmsh(const std::vector<std::string>& args, const fs::path& working_dir)
{
    return succeeded(run_program("gmsh", args, working_dir), "gmsh");
}

const TetMesh& client_sample() { return nested_cubes_mesh(); }

std::map<Label, std::size_t> tets_per_label(const TetMesh& mesh)
{
    std::map<Label, std::size_t> counts;
    for (const Label label : mesh.tet_labels) ++counts[label];
    return counts;
}

} // namespace tissuemesh::testing
