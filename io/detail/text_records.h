// Helpers for the line-oriented text mesh formats (Medit, TetGen, Abaqus).
#pragma once

#include <string>
#include <string_view>

#include "core/label_image.h"

namespace tissuemesh::io::detail {

/// `text` with everything from `marker` to the end of each line blanked out (line and byte positions kept).
std::string without_comments(const std::string& text, std::string_view marker);

/// Tissue names from lines "<marker> tissuemesh tissue <label> <name>" that our writers add as comments.
void read_name_comments(const std::string& text, std::string_view marker, TissueNames& names);

/// The comment lines read_name_comments() understands, one per named tissue.
std::string format_name_comments(const TissueNames& names, std::string_view marker);

/// A label from a number that must be an integer in 0..65535; `fail` is called otherwise.
template <typename Fail>
Label checked_label(double value, Fail&& fail)
{
    if (!(value >= 0 && value <= 65535 && value == static_cast<double>(static_cast<long long>(value)))) fail(value);
    return static_cast<Label>(value);
}

} // namespace tissuemesh::io::detail
