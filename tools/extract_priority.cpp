#include "tools/extract_priority.h"

#include <algorithm>
#include <charconv>

#include "core/error.h"
#include "surface/thin_first_priority.h"

namespace tissuemesh::tools {

std::map<Label, int> parse_extract_priority(const std::vector<std::string>& items, const LabelImage& image,
                                            Label background, const TissueTable& table, std::string_view option)
{
    const bool automatic = std::find(items.begin(), items.end(), "auto") != items.end();
    if (automatic && items.size() > 1)
        throw InputError(concat(option, " auto ranks every tissue itself: give it alone (", option,
                                " auto) or give TISSUE=N pairs (", option, " csf=2,3=1)"));
    if (automatic) return surface::thin_first_priority(image, background);
    std::map<Label, int> priority;
    for (const std::string& item : items) {
        const TissueSetting setting = parse_tissue_setting(item, table, option, "csf=2,3=1");
        int number = 0;
        const auto [end, error] =
            std::from_chars(setting.value.data(), setting.value.data() + setting.value.size(), number);
        if (setting.value.empty() || error != std::errc{} || end != setting.value.data() + setting.value.size())
            throw InputError(concat(option, " ", item, ": expected TISSUE=INTEGER (e.g. ", option, " csf=2,3=1)"));
        priority[setting.tissue] = number;
    }
    return priority;
}

nlohmann::json priority_summary(const std::map<Label, int>& priority)
{
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [label, value] : priority) out[std::to_string(label)] = value;
    return out;
}

} // namespace tissuemesh::tools
