#include "io/detail/nifti_header.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>
#include <optional>

#include <zlib.h>

#include "core/error.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t nifti1_size = 348;
constexpr std::size_t nifti2_size = 540;

template <typename T>
T field(const unsigned char* header, std::size_t offset, bool swap)
{
    std::array<unsigned char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), header + offset, sizeof(T));
    if (swap)
        for (std::size_t b = 0; b < sizeof(T) / 2; ++b) std::swap(bytes[b], bytes[sizeof(T) - 1 - b]);
    T value;
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
}

/// Byte offsets of the fields both NIfTI versions hold, which differ in where and as what they store them: `Int`
/// is the type of dim[], `Float` of pixdim[], the scaling and the orientation, `Code` of qform_code and sform_code.
template <typename Int, typename Float, typename Code>
struct NiftiLayout {
    std::size_t dim, pixdim, datatype, bitpix, scl_slope, scl_inter, qform_code, sform_code, quatern, srow;
};

// Offsets in the order of NiftiLayout's fields, from the NIfTI-1 and NIfTI-2 header definitions.
constexpr NiftiLayout<std::int16_t, float, std::int16_t> nifti1_layout{40, 76, 70, 72, 112, 116, 252, 254, 256, 280};
constexpr NiftiLayout<std::int64_t, double, std::int32_t> nifti2_layout{16, 104, 12, 14, 176, 184, 344, 348, 352, 400};

/// Reads the fields of `at` into `f` (all but vox_offset, which NIfTI-1 stores as a float to be checked).
template <typename Int, typename Float, typename Code>
void read_shared_fields(NiftiHeader& f, const unsigned char* header, bool swap, const NiftiLayout<Int, Float, Code>& at)
{
    for (std::size_t n = 0; n < 8; ++n) {
        f.dim[n] = field<Int>(header, at.dim + sizeof(Int) * n, swap);
        f.pixdim[n] = field<Float>(header, at.pixdim + sizeof(Float) * n, swap);
    }
    f.datatype = field<std::int16_t>(header, at.datatype, swap);
    f.bitpix = field<std::int16_t>(header, at.bitpix, swap);
    f.scl_slope = field<Float>(header, at.scl_slope, swap);
    f.scl_inter = field<Float>(header, at.scl_inter, swap);
    f.qform_code = field<Code>(header, at.qform_code, swap);
    f.sform_code = field<Code>(header, at.sform_code, swap);
    for (std::size_t n = 0; n < 6; ++n) f.quatern[n] = field<Float>(header, at.quatern + sizeof(Float) * n, swap);
    for (std::size_t n = 0; n < 12; ++n) f.srow[n] = field<Float>(header, at.srow + sizeof(Float) * n, swap);
}

std::size_t read_header_bytes(const fs::path& path, std::array<unsigned char, nifti2_size>& header)
{
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw IoError(concat(path.string(), ": cannot be opened; check the permissions"));
    const int got = gzread(file, header.data(), static_cast<unsigned>(header.size()));
    gzclose(file);
    if (got < 0)
        throw IoError(concat(path.string(), ": corrupt gzip data; the file is damaged, copy or export it again"));
    return static_cast<std::size_t>(got);
}

NiftiHeader parse_fields(const std::string& name, const unsigned char* header, std::size_t got)
{
    const std::string not_nifti = ": not a NIfTI file (";
    const std::string fix = "); check that the file is a .nii image and not renamed or damaged";
    if (got < 4) throw IoError(concat(name, not_nifti, "only ", got, " bytes, a header needs 348", fix));
    const auto size = field<std::int32_t>(header, 0, false);
    const auto swapped = field<std::int32_t>(header, 0, true);
    const bool swap = size != 348 && size != 540;
    const std::int32_t header_size = swap ? swapped : size;
    if (header_size != 348 && header_size != 540)
        throw IoError(
            concat(name, not_nifti, "wrong magic: header size field is ", size, ", expected 348 or 540", fix));
    NiftiHeader f;
    f.swapped = swap;
    if (header_size == 348) {
        if (got < nifti1_size)
            throw IoError(concat(name, ": truncated NIfTI header (", got,
                                 " of 348 bytes); the file is incomplete, copy it again"));
        if (std::memcmp(header + 344, "n+1", 4) != 0)
            throw IoError(concat(name, not_nifti,
                                 "wrong magic: expected \"n+1\" at byte 344; a "
                                 "two-file .hdr/.img pair must be converted to .nii",
                                 fix));
        read_shared_fields(f, header, swap, nifti1_layout);
        const float offset = field<float>(header, 108, swap);
        // NaN or absurd offsets become -1 so that the vox_offset check below rejects them.
        f.vox_offset = std::isfinite(offset) && offset >= 0 && offset < 1e15f ? static_cast<std::int64_t>(offset) : -1;
    } else {
        f.version = 2;
        if (got < nifti2_size)
            throw IoError(concat(name, ": truncated NIfTI-2 header (", got,
                                 " of 540 bytes); the file is incomplete, copy it again"));
        if (std::memcmp(header + 4, "n+2", 4) != 0)
            throw IoError(concat(name, not_nifti, "wrong magic: expected \"n+2\" at byte 4", fix));
        read_shared_fields(f, header, swap, nifti2_layout);
        f.vox_offset = field<std::int64_t>(header, 168, swap);
    }
    return f;
}

/// Bits per voxel of NIfTI's one-value datatypes (integers and floats up to 64 bits), 0 for others.
int scalar_bits(int datatype)
{
    switch (datatype) {
    case 2:
    case 256: return 8;
    case 4:
    case 512: return 16;
    case 8:
    case 16:
    case 768: return 32;
    case 64:
    case 1024:
    case 1280: return 64;
    default: return 0;
    }
}

// NIfTI datatypes holding several values per voxel: complex and RGB(A).
bool is_multi_valued(int datatype)
{
    return datatype == 32 || datatype == 128 || datatype == 1792 || datatype == 2048 || datatype == 2304;
}

} // namespace

NiftiHeader check_nifti_header(const fs::path& path)
{
    const std::string name = path.string();
    std::array<unsigned char, nifti2_size> header{};
    const std::size_t got = read_header_bytes(path, header);
    if (got == 0) throw IoError(concat(name, ": the file is empty; write or copy it again"));
    NiftiHeader f = parse_fields(name, header.data(), got);

    const std::int64_t rank = f.dim[0];
    if (rank < 1 || rank > 7)
        throw IoError(concat(name, ": corrupt NIfTI header, dim[0] (the number of axes) is ", rank,
                             ", expected 1..7; the file is damaged"));
    Dims& dims = f.dims;
    for (std::int64_t axis = 1; axis <= rank; ++axis) {
        if (f.dim[axis] <= 0)
            throw InputError(concat(name, ": dimension ", axis - 1, " is ", f.dim[axis],
                                    "; every axis needs at least one voxel. The header is corrupt"));
        if (axis > 3 && f.dim[axis] > 1)
            throw InputError(concat(name, ": a ", rank, "D image with ", f.dim[axis], " values along axis ", axis - 1,
                                    "; a label map holds one value per voxel. Extract one volume"));
        if (axis <= 3) dims[axis - 1] = static_cast<std::size_t>(f.dim[axis]);
    }
    if (is_multi_valued(f.datatype))
        throw InputError(concat(name, ": NIfTI datatype ", f.datatype,
                                " stores several values per voxel "
                                "(a vector, RGB or complex image); a label map holds one value per voxel"));
    // Checked here because the nifti library prints to stderr when it meets an unknown datatype.
    if (scalar_bits(f.datatype) == 0)
        throw IoError(concat(name, ": unsupported NIfTI datatype ", f.datatype,
                             "; save the label map as an integer or float image"));
    // The datatype decides the voxel size (as in the nifti library); a wrong bitpix is ignored.
    f.bitpix = scalar_bits(f.datatype);
    for (std::int64_t axis = 1; axis <= std::min<std::int64_t>(rank, 3); ++axis) {
        const double s = f.pixdim[axis];
        if (!std::isfinite(s) || s <= 0)
            throw InputError(concat(name, ": spacing along axis ", axis - 1, " is ", s, " mm (pixdim[", axis,
                                    "]); it must be a positive finite number. Fix "
                                    "the header or the writer that produced it"));
    }
    // ITK aborts the process (vnl's assert_finite) on a non-finite orientation: checked before it sees one.
    // 1e9 mm bounds coordinates far beyond any scanner, so that products stay finite too.
    const auto sane = [](double value) { return std::isfinite(value) && std::abs(value) <= 1e9; };
    if (f.qform_code > 0 && !std::all_of(f.quatern.begin(), f.quatern.end(), sane))
        throw InputError(concat(name, ": the qform (quatern_b/c/d, qoffset_x/y/z) holds a non-finite or absurd value; "
                                      "the header is corrupt. Fix the writer, or set qform_code to 0"));
    if (f.sform_code > 0 && !std::all_of(f.srow.begin(), f.srow.end(), sane))
        throw InputError(concat(name, ": the sform (srow_x/y/z) holds a non-finite or absurd value; the header is "
                                      "corrupt. Fix the writer, or set sform_code to 0"));
    if (f.vox_offset < (f.version == 1 ? 348 : 540))
        throw IoError(concat(name, ": corrupt NIfTI header, vox_offset is ", f.vox_offset,
                             ", inside the header; the file is damaged"));
    const std::uint64_t needed = checked_voxel_bytes(name, dims, static_cast<std::size_t>(f.bitpix / 8));
    const std::uint64_t size = uncompressed_size(path);
    const auto data_start = static_cast<std::uint64_t>(f.vox_offset);
    require_payload(name, needed, size > data_start ? size - data_start : 0);
    f.max_buffer_bytes = needed / static_cast<std::uint64_t>(f.bitpix / 8) * 8;
    return f;
}

void require_finite_float_voxels(const fs::path& path, const NiftiHeader& header)
{
    const std::size_t width = header.datatype == 16 ? 4 : header.datatype == 64 ? 8 : 0;
    if (width == 0) return;
    const std::string name = path.string();
    gzFile file = gzopen(path.c_str(), "rb");
    if (file == nullptr) throw IoError(concat(name, ": cannot be opened; check the permissions"));
    const std::uint64_t count = header.dims[0] * header.dims[1] * header.dims[2];
    const auto offset = static_cast<z_off_t>(header.vox_offset);
    bool ok = gzseek(file, offset, SEEK_SET) == offset;
    std::vector<unsigned char> chunk(width << 18);
    std::uint64_t voxel = 0;
    std::optional<std::uint64_t> bad;
    while (ok && voxel < count && !bad) {
        const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(count - voxel, chunk.size() / width));
        const int got = gzread(file, chunk.data(), static_cast<unsigned>(want * width));
        ok = got == static_cast<int>(want * width);
        for (std::size_t v = 0; ok && v < want; ++v) {
            unsigned char* bytes = chunk.data() + v * width;
            if (header.swapped) std::reverse(bytes, bytes + width);
            double value = 0;
            if (width == 4) {
                float f = 0;
                std::memcpy(&f, bytes, 4);
                value = f;
            } else {
                std::memcpy(&value, bytes, 8);
            }
            if (!std::isfinite(value)) {
                bad = voxel + v;
                break;
            }
        }
        voxel += want;
    }
    gzclose(file);
    if (!ok) throw IoError(concat(name, ": truncated or corrupt voxel data; copy or export the file again"));
    if (bad) {
        const Dims& d = header.dims;
        throw InputError(concat(name, ": voxel (", *bad % d[0], ", ", (*bad / d[0]) % d[1], ", ", *bad / (d[0] * d[1]),
                                ") holds a value that is not a finite number; labels must be whole numbers. Fix the "
                                "segmentation (its NaN voxels would otherwise be read as background)"));
    }
}

} // namespace tissuemesh::io::detail
