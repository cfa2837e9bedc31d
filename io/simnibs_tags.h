// SimNIBS's tissue numbers (its ElementTags), from tissue names, for meshes SimNIBS, FieldTrip and Brainstorm read.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/tet_mesh.h"

namespace tissuemesh::io {

/// One tissue SimNIBS knows by number (simnibs/utils/mesh_element_properties.py, ElementTags).
struct SimnibsTissue {
    int tag = 0;                             ///< volume tag; its surfaces carry 1000 + tag
    std::string name;                        ///< SimNIBS's own name ("WM", "Scalp", ...)
    std::vector<std::string> accepted_names; ///< names we map to it (compared as simnibs_name_key() gives them)
};

/// The tissues with a standard SimNIBS tag and the names accepted for each: white matter 1, grey matter 2,
/// CSF 3, bone/skull 4, scalp/skin 5, eyes 6, compact bone 7, spongy bone 8, blood 9, muscle 10, edema 11,
/// fat 12 (the full table: docs/interop.md).
const std::vector<SimnibsTissue>& simnibs_tissues();

/// How names are compared: lower case, '_' and '-' as spaces, runs of spaces as one, trimmed ("Grey_Matter" ->
/// "grey matter").
std::string simnibs_name_key(const std::string& name);

/// A user's table: tissue name (compared by simnibs_name_key()) or label number -> SimNIBS volume tag (1..999).
using SimnibsTagTable = std::map<std::string, int>;

/// Reads a JSON object {"air cavities": 13, "6": 13}.
/// @throws IoError when the file is missing, over 1 MiB or not a JSON object; InputError when a value is not an
///         integer in 1..999 or a key is empty or given twice (by its name key or label value)
SimnibsTagTable read_simnibs_tag_table(const std::filesystem::path& path);

/// The SimNIBS tag of every tissue of `mesh.tet_labels`: from `table` by label number, then by name, then from
/// simnibs_tissues() by name. Never a silent default.
/// @throws InputError naming every tissue without a tag (and the fix: a table), a key of `table` that names no
///         tissue of the mesh, or two tissues given one tag by the built-in names (merging them must be asked
///         for in the table)
std::map<Label, int> simnibs_tags(const TetMesh& mesh, const SimnibsTagTable& table = {});

/// The surface tag SimNIBS gives the faces between volume tags `a` and `b` (a != b): 1000 + the one its
/// mesher's hierarchy ranks first (1, 2, 9, 3, 4, 8, 7, 6, 11, 10, 12, 5, then the others in ascending order).
/// Faces on the outside of the mesh carry 1005 whatever their tissue (charm's add_outer_as = skin).
int simnibs_face_tag(int a, int b);

} // namespace tissuemesh::io
