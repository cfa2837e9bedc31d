// The one parser of the tools' tissue arguments (--max-volume scalp=8, --priority csf=1, --tissues 4,5,
// --source-tissues grey, ...): a tissue is a name in any case or a label number, checked against the tissues
// of the tool's input where the tool knows them.
#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/interface_complex.h"
#include "core/label_image.h"
#include "core/tet_mesh.h"

namespace tissuemesh::tools {

/// The tissues a tool's tissue arguments may name.
struct TissueTable {
    TissueNames names;       ///< names by label, matched in any case (an exact match wins over others)
    std::set<Label> present; ///< labels the input holds; empty: unknown, any label 0..65535 is taken
    std::string source;      ///< the input's file name, for the messages ("" when none)
};

/// Adds --labels FILE, the tissue names of a tool's label image (the formats io::read_tissue_names() reads), into
/// `names_file` (a string or a path), and returns the option for the tool's own settings.
template <typename File>
CLI::Option* add_labels_option(CLI::App& app, File& names_file)
{
    return app.add_option("--labels", names_file,
                          "Tissue names: JSON ({\"1\": \"scalp\"}), FreeSurfer LUT, ITK-SNAP labels or BIDS dseg.tsv");
}

/// The tissues of a label image: its names (from the file or --labels) and the labels of its voxels.
TissueTable tissue_table(const LabelImage& image, const std::string& source);
/// The tissues of an interface complex: its names and the labels on either side of its triangles.
TissueTable tissue_table(const InterfaceComplex& complex, const std::string& source);
/// The tissues of a tet mesh: its names and the labels of its tets.
TissueTable tissue_table(const TetMesh& mesh, const std::string& source);

/// Resolves one tissue argument of `option` ("--priority csf=1"), the text being a name of `table` in any
/// case, else a label number 0..65535 that the input holds (when table.present is known).
/// @throws InputError naming the option and the text: an unknown name lists the known tissues, a number out
///         of 0..65535 says the range, a label the input lacks lists the labels it has
Label parse_tissue(std::string_view text, const TissueTable& table, std::string_view option);

/// "4,5" or "grey,white": each comma-separated item by parse_tissue().
std::vector<Label> parse_tissue_list(std::string_view text, const TissueTable& table, std::string_view option);

/// One "TISSUE=VALUE" item of an option: the tissue resolved, the value's text left to the caller.
struct TissueSetting {
    Label tissue = 0;
    std::string value;
};

/// Splits `item` at its first '=' and resolves the tissue before it (messages start "OPTION ITEM: ").
/// @throws InputError when there is no '=' (showing `example`, e.g. "csf=2,3=1"), or as parse_tissue()
TissueSetting parse_tissue_setting(std::string_view item, const TissueTable& table, std::string_view option,
                                   std::string_view example);

} // namespace tissuemesh::tools
