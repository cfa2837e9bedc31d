#include "image/prep_report.h"

namespace tissuemesh::image {

PrepReport begin_report(const std::string& step, const LabelImage& image)
{
    PrepReport report;
    report.step = step;
    report.dims_before = image.dims();
    report.voxels_before = count_labels(image);
    return report;
}

void finish_report(PrepReport& report, const LabelImage& image)
{
    report.dims_after = image.dims();
    report.voxels_after = count_labels(image);
}

} // namespace tissuemesh::image
