// The tissuemesh Python module: numpy in, numpy out, one function per step of the chain (label image + affine ->
// interface complex -> tet mesh -> assessment -> potentials), each a thin call of the library's public function.
// Keyword arguments set the fields of the step's options struct of the same names; fields added to a struct later
// keep their defaults here. Library errors become tissuemesh.InputError (a ValueError), tissuemesh.IoError (an
// OSError) and tissuemesh.AlgorithmError (a RuntimeError) with the library's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "core/error.h"
#include "fem/conductivities.h"
#include "fem/solve_potential.h"
#include "image/phantom.h"
#include "io/read_label_image.h"
#include "io/surface_io.h"
#include "io/tet_mesh_io.h"
#include "io/write_label_image.h"
#include "python/src/convert.h"
#include "surface/extract_interfaces.h"
#include "volume/assess.h"
#include "volume/tetrahedralize.h"

namespace tissuemesh::python {
namespace {

using Path = std::filesystem::path;

py::tuple phantom(const std::string& name, double voxel_mm)
{
    return from_image(image::make_phantom(name, {.voxel_mm = voxel_mm}).image);
}

py::tuple read_image(const Path& path, const std::optional<Path>& labels)
{
    io::ReadImageOptions options;
    if (labels) options.names_json = *labels;
    return from_image(io::read_label_image(path, options));
}

py::dict extract(const py::array& labels, const py::array& affine, const py::dict& names,
                 const std::vector<Label>& tissues, Label background, const std::map<Label, int>& priority)
{
    surface::ExtractOptions options;
    options.tissues = tissues;
    options.background = background;
    options.priority = priority;
    return from_complex(surface::extract_interfaces(to_image(labels, affine, names), options));
}

py::dict tetrahedralize(const py::dict& surface, double max_volume_mm3,
                        const std::map<Label, double>& max_volume_per_tissue_mm3, double max_radius_edge_ratio,
                        double min_dihedral_deg, bool preserve_interfaces, bool improve_quality, int optimisation_level,
                        bool mesh_background_cavities)
{
    volume::TetrahedralizeOptions options;
    options.max_volume_mm3 = max_volume_mm3;
    options.max_volume_per_tissue_mm3 = max_volume_per_tissue_mm3;
    options.max_radius_edge_ratio = max_radius_edge_ratio;
    options.min_dihedral_deg = min_dihedral_deg;
    options.preserve_interfaces = preserve_interfaces;
    options.improve_quality = improve_quality;
    options.optimisation_level = optimisation_level;
    options.mesh_background_cavities = mesh_background_cavities;
    return from_mesh(volume::tetrahedralize(to_complex(surface), options));
}

py::dict assess(const py::dict& mesh, const py::array& labels, const py::array& affine,
                const std::map<Label, double>& priority, double error_weight, double shape_weight)
{
    volume::AssessOptions options;
    options.priority = priority;
    options.error_weight = error_weight;
    options.shape_weight = shape_weight;
    const volume::Assessment a = volume::assess_elements(to_mesh(mesh), to_image(labels, affine, py::dict()), options);
    py::dict tissues;
    for (const auto& [label, t] : a.tissues)
        tissues[py::int_(label)] = py::dict(py::arg("dice") = t.dice, py::arg("mesh_volume_mm3") = t.mesh_volume_mm3,
                                            py::arg("voxel_volume_mm3") = t.voxel_volume_mm3,
                                            py::arg("error_volume_mm3") = t.error_volume_mm3);
    py::dict out;
    out["majority"] = py::array_t<Label>(static_cast<py::ssize_t>(a.majority.size()), a.majority.data());
    out["error_volume_mm3"] =
        py::array_t<double>(static_cast<py::ssize_t>(a.error_volume_mm3.size()), a.error_volume_mm3.data());
    out["quality_key"] = py::array_t<double>(static_cast<py::ssize_t>(a.quality_key.size()), a.quality_key.data());
    out["min_dihedral_deg"] =
        py::array_t<double>(static_cast<py::ssize_t>(a.min_dihedral_deg.size()), a.min_dihedral_deg.data());
    out["tissues"] = tissues;
    out["total_error_volume_mm3"] = a.total_error_volume_mm3;
    return out;
}

fem::DipoleModel dipole_model(const std::string& name)
{
    if (name == "venant") return fem::DipoleModel::venant;
    if (name == "subtraction") return fem::DipoleModel::subtraction;
    if (name == "partial-integration") return fem::DipoleModel::partial_integration;
    throw InputError(concat("dipole_model \"", name, "\" is none of venant, subtraction, partial-integration"));
}

/// Potentials (V) at the nodes. Electrodes: (centre_mm (3), radius_mm, current_a) each; dipoles: (position_mm (3),
/// moment_am (3)) each; conductivities: {name or label: S/m}, the others from the head defaults by name.
py::array_t<double> solve(const py::dict& mesh_dict, const std::map<std::string, double>& conductivities,
                          const std::vector<std::tuple<Vec3, double, double>>& electrodes,
                          const std::vector<std::pair<Vec3, Vec3>>& dipoles, const std::string& model)
{
    const TetMesh mesh = to_mesh(mesh_dict);
    fem::ConductivityTable table;
    for (const auto& [key, sigma] : conductivities) table[key] = fem::isotropic(sigma);
    fem::PotentialProblem problem;
    for (const auto& [centre, radius, current] : electrodes) {
        fem::Electrode electrode;
        electrode.centre_mm = centre;
        electrode.radius_mm = radius;
        electrode.current_a = current;
        problem.electrodes.push_back(electrode);
    }
    for (const auto& [position, moment] : dipoles) {
        fem::Dipole dipole;
        dipole.position_mm = position;
        dipole.moment_am = moment;
        problem.dipoles.push_back(dipole);
    }
    problem.dipole_model = dipole_model(model);
    const std::vector<double> phi = fem::solve_potential(mesh, fem::resolve_conductivities(mesh, table), problem);
    return py::array_t<double>(static_cast<py::ssize_t>(phi.size()), phi.data());
}

void write_mesh(const py::dict& mesh, const Path& path, const std::string& tissue_numbering, bool binary)
{
    io::TetMeshWriteOptions options;
    options.binary = binary;
    if (tissue_numbering == "simnibs") options.numbering = io::TissueNumbering::simnibs;
    else if (tissue_numbering != "labels")
        throw InputError(concat("tissue_numbering \"", tissue_numbering,
                                "\" is none of labels, simnibs (for DUNEuro use tm-convert)"));
    io::write_tet_mesh(to_mesh(mesh), path, options);
}

} // namespace
} // namespace tissuemesh::python

PYBIND11_MODULE(_tissuemesh, m)
{
    using namespace tissuemesh;
    using namespace tissuemesh::python;
    m.doc() =
        "tissuemesh: tissue-labelled voxel images to boundary-conforming tetrahedral FE models (numpy in, numpy out)";
    static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
    static py::exception<IoError> io_error(m, "IoError", PyExc_OSError);
    static py::exception<AlgorithmError> algorithm_error(m, "AlgorithmError", PyExc_RuntimeError);
    py::register_exception_translator([](std::exception_ptr error) {
        try {
            if (error) std::rethrow_exception(error);
        } catch (const InputError& e) {
            PyErr_SetString(input_error.ptr(), e.what());
        } catch (const IoError& e) {
            PyErr_SetString(io_error.ptr(), e.what());
        } catch (const AlgorithmError& e) {
            PyErr_SetString(algorithm_error.ptr(), e.what());
        }
    });
    using py::arg;
    m.def("phantom", &phantom,
          "A phantom label image by name (\"spheres4\": scalp 1, skull 2, CSF 3, brain 4): (labels, affine, names)",
          arg("name"), arg("voxel_mm") = 1.0);
    m.def("read_label_image", &read_image,
          "Reads a label image (NIfTI, NRRD, MetaImage, Inrimage, MGH/MGZ, raw + JSON): "
          "(labels [i, j, k], affine, names); `labels` names the tissues from a table (JSON, FreeSurfer LUT, ITK-SNAP, "
          "BIDS tsv)",
          arg("path"), arg("labels") = py::none());
    m.def(
        "write_label_image",
        [](const Path& path, const py::array& labels, const py::array& affine, const py::dict& names) {
            io::write_label_image(to_image(labels, affine, names), path);
        },
        arg("path"), arg("labels"), arg("affine"), arg("names") = py::dict());
    m.def("extract_interfaces", &extract,
          "Tissue interfaces of a label image [i, j, k] with its voxel-to-world affine: a surface dict", arg("labels"),
          arg("affine"), arg("names") = py::dict(), arg("tissues") = std::vector<Label>{}, arg("background") = Label{0},
          arg("priority") = std::map<Label, int>{});
    const volume::TetrahedralizeOptions t;
    m.def("tetrahedralize", &tetrahedralize,
          "A labelled tet mesh (TetGen) keeping every interface of a surface dict: a mesh dict", arg("surface"),
          arg("max_volume_mm3") = t.max_volume_mm3, arg("max_volume_per_tissue_mm3") = std::map<Label, double>{},
          arg("max_radius_edge_ratio") = t.max_radius_edge_ratio, arg("min_dihedral_deg") = t.min_dihedral_deg,
          arg("preserve_interfaces") = t.preserve_interfaces, arg("improve_quality") = t.improve_quality,
          arg("optimisation_level") = t.optimisation_level,
          arg("mesh_background_cavities") = t.mesh_background_cavities);
    const volume::AssessOptions a;
    m.def("assess", &assess,
          "Every tet against the label image: majority, error volume, quality key per tet; per tissue Dice",
          arg("mesh"), arg("labels"), arg("affine"), arg("priority") = std::map<Label, double>{},
          arg("error_weight") = a.error_weight, arg("shape_weight") = a.shape_weight);
    m.def("solve", &solve,
          "Nodal potentials (V): electrodes [(centre_mm, radius_mm, current_a)], dipoles [(position_mm, moment_am)]",
          arg("mesh"), arg("conductivities") = std::map<std::string, double>{},
          arg("electrodes") = std::vector<std::tuple<Vec3, double, double>>{},
          arg("dipoles") = std::vector<std::pair<Vec3, Vec3>>{}, arg("dipole_model") = "venant");
    m.def(
        "read_surface", [](const Path& path) { return from_complex(io::read_surface(path)); }, arg("path"));
    m.def(
        "write_surface",
        [](const py::dict& surface, const Path& path, bool ascii) {
            io::write_surface(to_complex(surface), path, io::SurfaceWriteOptions{.ascii = ascii, .ply_comments = {}});
        },
        arg("surface"), arg("path"), arg("ascii") = false);
    m.def(
        "read_mesh", [](const Path& path) { return from_mesh(io::read_tet_mesh(path)); }, arg("path"));
    m.def("write_mesh", &write_mesh,
          "Writes a mesh dict; the extension picks the format (.msh, .vtu, .mesh, .node, .inp)", arg("mesh"),
          arg("path"), arg("tissue_numbering") = "labels", arg("binary") = false);
}
