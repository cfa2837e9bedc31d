// RepairLog: counts and located descriptions of what repair() changed, in the checker's wording.
#pragma once

#include <string>

#include "surface/detail/tissue_wording.h"
#include "surface/repair.h"

namespace tissuemesh::surface::detail {

class RepairLog : public TissueWording {
public:
    RepairLog(const TissueNames& names, std::size_t max_actions, RepairReport& report)
        : TissueWording(names), max_actions_(max_actions), report_(report)
    {
    }

    /// Stores an action under the cap (counts are the caller's).
    void add(RepairKind kind, const Vec3& location_mm, std::vector<Label> tissues, const std::string& what)
    {
        if (report_.actions.size() >= max_actions_) return;
        sort_unique(tissues);
        report_.actions.push_back({kind, location_mm, tissues, concat(what, ' ', near(location_mm))});
    }

    RepairReport& report() { return report_; }

private:
    std::size_t max_actions_;
    RepairReport& report_;
};

} // namespace tissuemesh::surface::detail
