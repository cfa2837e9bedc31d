// Collects defects for check_complex(): exact counts, stored defects capped per kind, in the wording
// shared by every check (tissue names, patches, locations: tissue_wording.h).
#pragma once

#include <string>

#include "surface/check_complex.h"
#include "surface/detail/tissue_wording.h"

namespace tissuemesh::surface::detail {

class DefectLog : public TissueWording {
public:
    DefectLog(const InterfaceComplex& complex, std::size_t max_per_kind, CheckReport& report)
        : TissueWording(complex.names), complex_(complex), max_per_kind_(max_per_kind), report_(report)
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
        sort_unique(defect.tissues);
        report_.defects.push_back(std::move(defect));
    }

    const InterfaceComplex& complex() const { return complex_; }

    /// "scalp|skull triangle 123": the triangle's patch (behind|in front) and index.
    std::string triangle(std::uint32_t t) const { return concat(patch(complex_.sides[t]), " triangle ", t); }
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
