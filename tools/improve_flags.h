// The mesh improver's flags and log line, shared by tm-tetra, tm-refine and tm-improve.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "io/read_label_image.h"
#include "tools/memory_limit.h"
#include "volume/improve_mesh.h"

namespace tissuemesh::tools {

struct ImproveFlags {
    volume::ImproveOptions options;
    bool off = false; ///< --no-improve (tm-tetra, tm-refine)
    bool keep_interfaces = false;
    CLI::Option* insert_below = nullptr;
    bool keep_voxel_sides = false; ///< --improve-keep-voxel-sides (the tool's --image)

    /// `with_switch`: the tool improves by default and takes --no-improve.
    void add_to(CLI::App& app, bool with_switch)
    {
        if (with_switch)
            app.add_flag("--no-improve", off,
                         "Keep the mesh as meshed: no smoothing, flips or insertion of the improver");
        app.add_option("--improve-target-deg", options.target_dihedral_deg,
                       "Improver: work on tets whose smallest dihedral angle is below this (degrees)")
            ->check(CLI::Range(1.0, 70.0))
            ->capture_default_str();
        app.add_option("--improve-passes", options.max_passes, "Improver: rounds over the tets below the target")
            ->check(CLI::Range(1, 100))
            ->capture_default_str();
        insert_below =
            app.add_option(
                   "--improve-insert-below-deg", options.insert_below_deg,
                   "Improver: insert nodes for tets whose smallest dihedral angle is below this (0: never; given, it "
                   "turns insertion on where the tool leaves it off)")
                ->check(CLI::Range(0.0, 70.0))
                ->capture_default_str();
        app.add_option("--improve-max-face-deviation", options.max_face_deviation,
                       "Improver: interface faces it makes stay this close to the surface, as a fraction of the "
                       "surface's mean edge (0.03 of 2.4 mm edges is 0.07 mm); in the last round a tet left under "
                       "0.95 of the target that nothing else lifts may get faces up to 8 times as far")
            ->check(CLI::Range(0.0, 1.0))
            ->capture_default_str();
        app.add_option("--improve-parts", options.parts,
                       "Improver: cut the mesh into this many parts, improved side by side, then bands around the "
                       "faces between them (0: one per 200 000 tets, an even number, at least 2 from 20 000 tets "
                       "on, at most 8; 1: the whole mesh at once). The result depends on this, not on the thread "
                       "count")
            ->check(CLI::Range(0, 64))
            ->capture_default_str();
        app.add_flag("--improve-keep-interfaces", keep_interfaces,
                     "Improver: interface nodes stay where they are and none is added on interfaces");
        app.add_flag("--improve-keep-voxel-sides", keep_voxel_sides,
                     "Improver: no interface move, flip or split carries the centre of a voxel of --image next to "
                     "another tissue across (but for tets left under half the target): the Dice against it stays "
                     "as meshed, the smallest angles may be a little lower");
    }

    /// The tool's --image for --improve-keep-voxel-sides, its size checked against the memory limit before its voxels
    /// are read: the labels (2 bytes a voxel) and a flag per voxel for those next to another label. An empty image
    /// when the switch is off.
    LabelImage read_voxel_image(const std::string& path, const MemoryLimit& memory) const
    {
        if (!keep_voxel_sides) return {};
        return io::read_label_image(path,
                                    {.before_voxels = image_memory_check(memory, path, 3,
                                                                         "crop it (tm-prep --crop-pad 2), or leave "
                                                                         "--improve-keep-voxel-sides out")});
    }

    /// The improver's options from the flags; `image` is the tool's --image (read; null or empty when not given),
    /// which --improve-keep-voxel-sides needs.
    /// @throws InputError when --improve-insert-below-deg is given above --improve-target-deg, or
    ///         --improve-keep-voxel-sides without an image
    volume::ImproveOptions to_options(const LabelImage* image = nullptr) const
    {
        volume::ImproveOptions o = options;
        if (keep_voxel_sides && (image == nullptr || image->empty()))
            throw InputError("--improve-keep-voxel-sides needs the label image the surfaces come from: give --image "
                             "clean.nii.gz (or leave --improve-keep-voxel-sides out)");
        o.voxel_image = keep_voxel_sides ? image : nullptr;
        if (keep_interfaces) o.move_interface_nodes = false, o.insert_on_interfaces = false;
        if (insert_below != nullptr && insert_below->count() > 0) {
            // The improver works only below its target, so a higher insertion bound would act as the target.
            if (o.insert_below_deg > o.target_dihedral_deg)
                throw InputError(concat("--improve-insert-below-deg ", o.insert_below_deg,
                                        " is above --improve-target-deg ", o.target_dihedral_deg,
                                        "; the improver inserts only in tets below its target: give "
                                        "0..",
                                        o.target_dihedral_deg, " or raise the target"));
            o.insert = o.insert_below_deg > 0;
        }
        if (o.insert_below_deg <= 0) o.insert = false;
        return o;
    }
};

/// "smallest dihedral 0.21 -> 18.3 deg, 1st percentile 9.1 -> 24.0 deg, ... in 1.2 s"
inline std::string improve_line(const volume::ImproveReport& r)
{
    return concat(
        "improved: smallest dihedral ", format_mm(r.before.min_dihedral_deg, 2), " -> ",
        format_mm(r.after.min_dihedral_deg, 2), " deg, 1st percentile ", format_mm(r.before.p1_min_dihedral_deg, 1),
        " -> ", format_mm(r.after.p1_min_dihedral_deg, 1), " deg, tets under 10 deg ", r.before.tets_under_10_deg,
        " -> ", r.after.tets_under_10_deg, " (", r.smoothed_nodes, " moves, ",
        r.edges_removed + r.faces_removed + r.interface_edges_flipped, " flips (", r.interface_edges_flipped,
        " on interfaces), ", r.nodes_inserted + r.nodes_inserted_on_interfaces, " new nodes, ",
        r.nodes_inserted_on_interfaces, " of them on interfaces",
        r.refused_by_voxels > 0 ? concat("; ", r.refused_by_voxels, " edits refused by the voxels") : std::string(),
        r.refused_crossing_boundary > 0
            ? concat("; ", r.refused_crossing_boundary, " refused for crossing the outer boundary")
            : std::string(),
        ") in ", format_mm(r.seconds, 2), " s (", format_mm(r.cpu_seconds, 2), " s CPU",
        r.parts > 1 ? concat("; ", r.parts, " parts, ", r.bands, " bands") : std::string(), ")");
}

} // namespace tissuemesh::tools
