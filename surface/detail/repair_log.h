// RepairLog: counts and located descriptions of what repair() changed, in the checker's wording.
#pragma once

#include <algorithm>
#include <string>

#include "core/error.h"
#include "surface/repair.h"

namespace tissuemesh::surface::detail {

class RepairLog {
public:
    RepairLog(const TissueNames& names, std::size_t max_actions, RepairReport& report)
        : names_(names), max_actions_(max_actions), report_(report)
    {
    }

    /// Stores an action under the cap (counts are the caller's).
    void add(RepairKind kind, const Vec3& location_mm, std::vector<Label> tissues, const std::string& what)
    {
        if (report_.actions.size() >= max_actions_) return;
        std::sort(tissues.begin(), tissues.end());
        tissues.erase(std::unique(tissues.begin(), tissues.end()), tissues.end());
        report_.actions.push_back({kind, location_mm, tissues, concat(what, " near (", format_mm(location_mm[0]), ", ",
                                                                      format_mm(location_mm[1]), ", ",
                                                                      format_mm(location_mm[2]), ") mm")});
    }

    /// "scalp|skull": a patch by tissue names (numbers where the complex has no names).
    std::string patch(const LabelPair& pair) const { return concat(tissue(pair.from), '|', tissue(pair.to)); }
    std::string tissue(Label label) const
    {
        const auto found = names_.find(label);
        return found != names_.end() && !found->second.empty() ? found->second : std::to_string(label);
    }
    RepairReport& report() { return report_; }

private:
    const TissueNames& names_;
    std::size_t max_actions_;
    RepairReport& report_;
};

} // namespace tissuemesh::surface::detail
