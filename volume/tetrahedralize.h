// Constrained Delaunay tetrahedralization of an interface complex (TetGen), keeping every interface.
#pragma once

#include <cstddef>
#include <map>

#include "core/interface_complex.h"
#include "core/progress.h"
#include "core/tet_mesh.h"
#include "volume/improve_mesh.h"

namespace tissuemesh::volume {

/// Options for tetrahedralize(). Lengths in mm, volumes in mm^3, angles in degrees.
/// With preserve_interfaces, TetGen (1.5) refuses every new point that would encroach an interface
/// triangle, so the size and quality bounds are met only where the interface triangles are no larger than
/// the tets asked for: remesh the surface to the target size first. The report says how far they were met.
struct TetrahedralizeOptions {
    bool preserve_interfaces = true;                   ///< no Steiner point on any interface (TetGen -Y): interface
                                                       ///< triangles become tet faces unchanged
    bool improve_quality = true;                       ///< refine for the two bounds below (TetGen -q)
    double max_radius_edge_ratio = 2.0;                ///< circumradius / shortest edge bound (>= 1.0 for TetGen)
    double min_dihedral_deg = 5.0;                     ///< smallest dihedral angle bound
    double max_volume_mm3 = 0;                         ///< bound on every tet's volume (0: none)
    std::map<Label, double> max_volume_per_tissue_mm3; ///< per-tissue bounds (override the global one)
    int optimisation_level = 2;                        ///< mesh optimisation passes, 0..10 (TetGen -O)
    bool mesh_background_cavities = true;              ///< keep tets of the background tissue enclosed by other tissues
                                                       ///< (they carry the background label); false drops them
    bool layer_points = false;  ///< give TetGen nodes inside the tissue layers, about an edge off the interface
                                ///< vertices (detail/layer_points.h), so fewer of its tets span a layer
    bool improve = true;        ///< improve TetGen's tets with improve_mesh() against the complex
                                ///< (slivers and flat tets next to the interfaces)
    ImproveOptions improvement; ///< its options
};

/// What tetrahedralize() did.
struct TetrahedralizeReport {
    std::size_t input_vertices = 0;
    std::size_t input_triangles = 0;
    std::size_t nodes = 0;
    std::size_t tets = 0;
    std::size_t layer_points = 0;    ///< nodes given inside the layers (options.layer_points)
    std::size_t steiner_points = 0;  ///< nodes added by TetGen (inside tissues with -Y)
    std::size_t interface_faces = 0; ///< output faces that lie on interfaces or the outer boundary
    /// Input triangles TetGen split into several faces. With -Y it keeps them whole, save rarely: on the
    /// decimated 1 mm usc19-5 head it put one point on an edge where the surface creases (2 of 2.07 M
    /// triangles split, the interface unchanged: its parts cover it exactly).
    std::size_t split_interface_triangles = 0;
    double min_dihedral_deg = 0;            ///< smallest dihedral angle of the result
    double max_radius_edge_ratio = 0;       ///< largest circumradius / shortest edge of the result
    std::size_t tets_over_volume_bound = 0; ///< tets larger than their (global or tissue) volume bound
    std::string switches;                   ///< the TetGen command line used
    double seconds = 0;
    bool improved = false;     ///< improve_mesh() ran; `improvement` says what it did
    ImproveReport improvement; ///< (its `before` figures are TetGen's mesh)
};

/// Builds a conforming tetrahedral mesh whose tets never cross an interface of `complex`. Each tet's
/// tissue comes from the complex itself: a tet on an interface face takes the tissue on its side of that
/// face (faces know their two tissues and their orientation), and labels spread across the other faces.
/// Tets outside the outermost surfaces (the background around the object) are not meshed.
/// @pre  `complex` is fit for tetrahedralization (surface::check_complex(complex).ok())
/// @post every tet positively oriented; faces/face_sides hold the interface and boundary faces; the mesh
///       passes check_mesh() (conforming, interfaces present and rightly labelled, no tissues touching elsewhere)
/// @throws InputError when the complex is not fit (names the first defect, tissues and place), or an option is out of
///         its range (radius-edge bound below 1, optimisation level outside 0..10, a tissue bound not positive or
///         for a tissue the complex lacks)
/// @throws AlgorithmError when TetGen fails or crashes (its diagnosis, the place in mm when known, and a hint),
///         or when its mesh fails check_mesh() (the first problems and a hint)
TetMesh tetrahedralize(const InterfaceComplex& complex, const TetrahedralizeOptions& options = {},
                       const Progress& progress = {}, TetrahedralizeReport* report = nullptr);

} // namespace tissuemesh::volume
