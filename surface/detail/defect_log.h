// Collects defects for check_complex(): exact counts, stored defects capped per kind, and the
// wording shared by every check (tissue names, patches, locations).
#pragma once

#include <algorithm>
#include <string>

#include "core/error.h"
#include "surface/check_complex.h"

namespace tissuemesh::surface::detail {

class DefectLog {
public:
    DefectLog(const InterfaceComplex& complex, std::size_t max_per_kind, CheckReport& report)
        : complex_(complex), max_per_kind_(max_per_kind), report_(report)
    {
    }

    /// Counts a defect of `kind`; builds and stores it (make() returns a Defect) only under the cap,
    /// so that millions of defects cost no string formatting.
    template <typename Make>
    void add(DefectKind kind, Make&& make)
    {
        std::size_t& count = report_.counts[static_cast<std::size_t>(kind)];
        if (count++ >= max_per_kind_) return;
        Defect defect = make();
        defect.kind = kind;
        std::sort(defect.tissues.begin(), defect.tissues.end());
        defect.tissues.erase(std::unique(defect.tissues.begin(), defect.tissues.end()), defect.tissues.end());
        report_.defects.push_back(std::move(defect));
    }

    const InterfaceComplex& complex() const { return complex_; }

    /// The tissue's name, or its number.
    std::string tissue(Label label) const
    {
        const auto found = complex_.names.find(label);
        return found != complex_.names.end() && !found->second.empty() ? found->second : std::to_string(label);
    }
    /// "scalp|skull triangle 123": the triangle's patch (behind|in front) and index.
    std::string triangle(std::uint32_t t) const
    {
        const LabelPair& pair = complex_.sides[t];
        return concat(tissue(pair.from), '|', tissue(pair.to), " triangle ", t);
    }
    /// "near (31.2, -4, 55.8) mm"
    static std::string near(const Vec3& p)
    {
        return concat("near (", format_mm(p[0]), ", ", format_mm(p[1]), ", ", format_mm(p[2]), ") mm");
    }
    Vec3 centroid(std::uint32_t t) const
    {
        const Triangle& tri = complex_.triangles[t];
        return (1.0 / 3.0) * (complex_.vertices[tri[0]] + complex_.vertices[tri[1]] + complex_.vertices[tri[2]]);
    }

private:
    const InterfaceComplex& complex_;
    std::size_t max_per_kind_;
    CheckReport& report_;
};

} // namespace tissuemesh::surface::detail
