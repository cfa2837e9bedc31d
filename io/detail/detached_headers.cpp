#include "io/detail/detached_headers.h"

#include <sstream>
#include <string>

#include "core/atomic_file.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

/// Geometry in ITK's LPS frame: x and y of RAS negated.
struct LpsGeometry {
    Vec3 origin;
    std::array<Vec3, 3> axes; ///< unit direction of each index axis
};

LpsGeometry to_lps(const LabelImage& image)
{
    LpsGeometry lps;
    // 0 - x rather than -x: no "-0" in the headers.
    lps.origin = {0 - image.origin_mm()[0], 0 - image.origin_mm()[1], image.origin_mm()[2]};
    const Mat3& d = image.direction();
    for (int axis = 0; axis < 3; ++axis) lps.axes[axis] = {0 - d[axis], 0 - d[3 + axis], d[6 + axis]};
    return lps;
}

std::string meta_image_header(const LabelImage& image, std::size_t width, const std::string& data_file)
{
    const LpsGeometry lps = to_lps(image);
    std::ostringstream out;
    out.precision(17);
    out << "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
           "CompressedData = False\nTransformMatrix =";
    // MetaImage lists the axis directions one after another.
    for (const Vec3& axis : lps.axes) out << ' ' << axis[0] << ' ' << axis[1] << ' ' << axis[2];
    out << "\nOffset = " << lps.origin[0] << ' ' << lps.origin[1] << ' ' << lps.origin[2]
        << "\nCenterOfRotation = 0 0 0\nElementSpacing = " << image.spacing_mm()[0] << ' ' << image.spacing_mm()[1]
        << ' ' << image.spacing_mm()[2] << "\nDimSize = " << image.dims()[0] << ' ' << image.dims()[1] << ' '
        << image.dims()[2] << "\nElementType = " << (width == 1 ? "MET_UCHAR" : "MET_USHORT")
        << "\nElementDataFile = " << data_file << "\n";
    return out.str();
}

std::string nrrd_header(const LabelImage& image, std::size_t width, const std::string& data_file)
{
    const LpsGeometry lps = to_lps(image);
    std::ostringstream out;
    out.precision(17);
    out << "NRRD0004\ntype: " << (width == 1 ? "uint8" : "uint16") << "\ndimension: 3\n"
        << "space: left-posterior-superior\nsizes: " << image.dims()[0] << ' ' << image.dims()[1] << ' '
        << image.dims()[2] << "\nspace directions:";
    // NRRD's space directions are the axis vectors scaled by the spacing.
    for (int axis = 0; axis < 3; ++axis) {
        const Vec3 v = image.spacing_mm()[axis] * lps.axes[axis];
        out << " (" << v[0] << ',' << v[1] << ',' << v[2] << ')';
    }
    out << "\nkinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: (" << lps.origin[0] << ','
        << lps.origin[1] << ',' << lps.origin[2] << ")\ndata file: " << data_file << "\n";
    return out.str();
}

} // namespace

void write_detached_image(const LabelImage& image, const fs::path& path)
{
    const std::size_t width = label_width(image);
    const std::string data_file = path.filename().string() + ".raw";
    const bool meta_image = full_extension(path) == ".mhd";
    // The data first: the header never names a file that is not there yet.
    write_text_atomically(path.parent_path() / data_file, encode_labels(image, width));
    write_text_atomically(path, meta_image ? meta_image_header(image, width, data_file)
                                           : nrrd_header(image, width, data_file));
}

} // namespace tissuemesh::io::detail
