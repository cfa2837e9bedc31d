// TissueWording: how the surface steps name tissues, patches and places in what they report, one wording
// for the checker (DefectLog) and for repair (RepairLog).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/interface_complex.h"

namespace tissuemesh::surface::detail {

class TissueWording {
public:
    explicit TissueWording(const TissueNames& names) : names_(names) {}

    /// The tissue's name, or its number when it has none.
    std::string tissue(Label label) const
    {
        const auto found = names_.find(label);
        return found != names_.end() && !found->second.empty() ? found->second : std::to_string(label);
    }
    /// "scalp|skull": a patch (behind|in front) by tissue names.
    std::string patch(const LabelPair& pair) const { return concat(tissue(pair.from), '|', tissue(pair.to)); }
    /// "near (31.2, -4, 55.8) mm"
    static std::string near(const Vec3& p)
    {
        return concat("near (", format_mm(p[0]), ", ", format_mm(p[1]), ", ", format_mm(p[2]), ") mm");
    }
    /// Sorts the tissues, each kept once.
    static void sort_unique(std::vector<Label>& tissues)
    {
        std::sort(tissues.begin(), tissues.end());
        tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
    }

private:
    const TissueNames& names_;
};

} // namespace tissuemesh::surface::detail
