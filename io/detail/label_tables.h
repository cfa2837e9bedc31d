// Tissue-name tables other tools write: FreeSurfer colour tables (FreeSurferColorLUT.txt), ITK-SNAP label
// description files, and BIDS `*_dseg.tsv` sidecars.
#pragma once

#include <string>

#include "core/label_image.h"

namespace tissuemesh::io::detail {

/// The text table formats parse_label_table() reads.
enum class LabelTableFormat {
    freesurfer_lut, ///< "<label> <name> <r> <g> <b> <a>" per line, '#' comments (FreeSurferColorLUT.txt)
    itksnap,        ///< "<label> <r> <g> <b> <alpha> <visible> <mesh> "<name>"" per line, '#' comments
    bids_tsv,       ///< tab-separated with a header row holding "index" and "name" (BIDS *_dseg.tsv)
};

/// Which text format `text` is in: a `.tsv` name is BIDS; otherwise the first line that is neither blank
/// nor a comment decides (a double quote: ITK-SNAP; else a FreeSurfer colour table).
LabelTableFormat detect_label_table(const std::string& text, bool tsv_name);

/// The names of a table in `format`; `what` (the file) names it in messages. Blank lines, '#' comments and
/// Windows line ends are accepted. Names are trimmed and must not be empty.
/// @throws InputError "<file> line <n>: <problem>; <fix>" when a line does not fit the format, a label is not
///         an integer in 0..65535, a label appears twice, or the table names nothing
TissueNames parse_label_table(const std::string& text, const std::string& what, LabelTableFormat format);

} // namespace tissuemesh::io::detail
