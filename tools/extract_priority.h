// The extraction's priority rule as the tools take it (tm-extract --priority, tm-assess --extract-priority):
// TISSUE=N pairs or "auto". Apart from tools/tissue_arguments.h because "auto" ranks tissues with surface/, which
// the other tools and the benchmarks linking the tools' runner need not link.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/label_image.h"
#include "tools/tissue_arguments.h"

namespace tissuemesh::tools {

/// The priority rule of extraction (tm-extract --priority, tm-assess --extract-priority), one `items` entry per
/// comma-separated item: TISSUE=N pairs (a tissue of `table` = an integer; the higher wins ambiguous cubes), or
/// "auto" alone: every tissue of `image` but `background` ranked by its thickness, the thinnest first
/// (surface/thin_first_priority.h). No items: no priority (the plain Kuhn rule).
/// @throws InputError naming `option`: "auto" among other items, an item not TISSUE=INTEGER, or as parse_tissue()
std::map<Label, int> parse_extract_priority(const std::vector<std::string>& items, const LabelImage& image,
                                            Label background, const TissueTable& table, std::string_view option);

/// A priority for a tool's JSON summary: {"3": 1, ...}, by label number.
nlohmann::json priority_summary(const std::map<Label, int>& priority);

} // namespace tissuemesh::tools
