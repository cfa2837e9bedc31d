#include "io/detail/itk_image_io.h"

#include <algorithm>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <itkByteSwapper.h>
#include <itkImageIOBase.h>
#include <itkImageIOFactory.h>
// Included for its side effect: with ITK_IO_FACTORY_REGISTER_MANAGER it registers the NIfTI, NRRD and
// MetaImage ImageIO factories that CreateImageIO() looks up.
#include <itkImageFileReader.h>
#include <itkMetaDataObject.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/detail/voxel_decode.h"

namespace tissuemesh::io::detail {
namespace fs = std::filesystem;

namespace {

/// Silences ITK and the libraries under it (MetaIO writes to std::cerr) while a read or write runs:
/// library code never prints. What they say is kept for the error message.
class QuietItk {
public:
    QuietItk() : saved_(std::cerr.rdbuf(captured_.rdbuf())) { itk::Object::GlobalWarningDisplayOff(); }
    ~QuietItk() { std::cerr.rdbuf(saved_); }
    QuietItk(const QuietItk&) = delete;
    QuietItk& operator=(const QuietItk&) = delete;

private:
    std::ostringstream captured_;
    std::streambuf* saved_;
};

/// ITK's descriptions span several lines and name source files; keep the last non-empty line.
std::string one_line(const std::string& text)
{
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line)) {
        line.erase(0, line.find_first_not_of(" \t"));
        if (!line.empty()) last = line;
    }
    return last.empty() ? "unknown ITK error" : last;
}

VoxelType voxel_type_of(const std::string& name, const itk::ImageIOBase& io)
{
    using C = itk::IOComponentEnum;
    const C type = io.GetComponentType();
    const std::size_t size = io.GetComponentSize();
    const bool is_signed =
        type == C::CHAR || type == C::SHORT || type == C::INT || type == C::LONG || type == C::LONGLONG;
    if (type == C::FLOAT) return VoxelType::f32;
    if (type == C::DOUBLE) return VoxelType::f64;
    if (type != C::LDOUBLE && type != C::UNKNOWNCOMPONENTTYPE) {
        switch (size) {
        case 1: return is_signed ? VoxelType::i8 : VoxelType::u8;
        case 2: return is_signed ? VoxelType::i16 : VoxelType::u16;
        case 4: return is_signed ? VoxelType::i32 : VoxelType::u32;
        case 8: return is_signed ? VoxelType::i64 : VoxelType::u64;
        default: break;
        }
    }
    throw IoError(concat(name, ": unsupported voxel type ", itk::ImageIOBase::GetComponentTypeAsString(type),
                         "; save the label map as an integer or float image"));
}

void reject_vectors(const std::string& name, const itk::ImageIOBase& io, Dims& dims)
{
    const unsigned rank = io.GetNumberOfDimensions();
    if (io.GetNumberOfComponents() > 1) {
        if (name.ends_with(".seg.nrrd"))
            throw InputError(concat(name, ": a segmentation with ", io.GetNumberOfComponents(),
                                    " layers (overlapping segments); only single-layer label maps are "
                                    "supported. In 3D Slicer, export the segmentation as a labelmap volume"));
        throw InputError(concat(name, ": ", io.GetNumberOfComponents(),
                                " values per voxel (a vector or "
                                "colour image); a label map holds one value per voxel. Extract one component"));
    }
    for (unsigned axis = 0; axis < rank; ++axis) {
        const auto size = io.GetDimensions(axis);
        if (axis >= 3 && size > 1)
            throw InputError(concat(name, ": a ", rank, "D image with ", size, " values along axis ", axis,
                                    "; a label map holds one value per voxel. Extract one volume"));
        if (axis < 3) dims[axis] = size;
    }
}

/// Slicer's segment keys: Segment{N}_Name, Segment{N}_LabelValue (N + 1 in old files), Segment{N}_Layer.
TissueNames read_segment_names(const std::string& name, const itk::MetaDataDictionary& dictionary)
{
    TissueNames names;
    std::set<std::string> layers;
    for (int n = 0;; ++n) {
        const std::string prefix = concat("Segment", n, "_");
        std::string segment_name, value_text, layer;
        if (!itk::ExposeMetaData(dictionary, prefix + "Name", segment_name)) break;
        long value = n + 1;
        if (itk::ExposeMetaData(dictionary, prefix + "LabelValue", value_text)) {
            try {
                value = std::stol(value_text);
            } catch (const std::exception&) {
                value = -1;
            }
        }
        if (value < 0 || value > 65535)
            throw InputError(concat(name, ": segment ", n, " (", segment_name, ") has label value '", value_text,
                                    "'; expected an integer in 0..65535. Fix the Segment", n, "_LabelValue key"));
        if (itk::ExposeMetaData(dictionary, prefix + "Layer", layer)) layers.insert(layer);
        names[static_cast<Label>(value)] = segment_name;
    }
    if (layers.size() > 1)
        throw InputError(concat(name, ": a segmentation with ", layers.size(),
                                " layers (overlapping "
                                "segments); only single-layer label maps are supported. In 3D Slicer, "
                                "export the segmentation as a labelmap volume"));
    return names;
}

/// 3D Slicer's segmentation keys: one segment per label present in the image or named (background 0
/// excluded; a named label without voxels is an empty segment), all in layer 0, with a colour from a fixed palette.
itk::MetaDataDictionary segment_dictionary(const LabelImage& image)
{
    static constexpr double palette[6][3] = {{0.90, 0.70, 0.60}, {0.95, 0.95, 0.85}, {0.55, 0.75, 0.95},
                                             {0.60, 0.60, 0.60}, {0.95, 0.95, 0.95}, {0.85, 0.35, 0.30}};
    itk::MetaDataDictionary dictionary;
    const auto put = [&](const std::string& key, const std::string& value) {
        itk::EncapsulateMetaData<std::string>(dictionary, key, value);
    };
    put("Segmentation_MasterRepresentation", "Binary labelmap");
    put("Segmentation_ContainedRepresentationNames", "Binary labelmap|");
    put("Segmentation_ReferenceImageExtentOffset", "0 0 0");
    const Dims& dims = image.dims();
    std::set<Label> labels;
    for (const auto& [label, voxels] : count_labels(image)) labels.insert(label);
    for (const auto& [label, tissue] : image.names()) labels.insert(label);
    labels.erase(0);
    int n = 0;
    for (const Label label : labels) {
        const std::string prefix = concat("Segment", n, "_");
        const double* colour = palette[n++ % 6];
        put(prefix + "ID", concat("Segment_", label));
        put(prefix + "Name", image.name_of(label));
        put(prefix + "NameAutoGenerated", image.names().count(label) ? "0" : "1");
        put(prefix + "LabelValue", std::to_string(label));
        put(prefix + "Layer", "0");
        put(prefix + "Color", concat(colour[0], " ", colour[1], " ", colour[2]));
        put(prefix + "ColorAutoGenerated", "1");
        put(prefix + "Extent", concat("0 ", dims[0] - 1, " 0 ", dims[1] - 1, " 0 ", dims[2] - 1));
        put(prefix + "Tags", "|");
    }
    return dictionary;
}

/// An image's geometry (on a LabelImage whose labels are still 0), its stored voxel bytes and their type.
struct StoredVoxels {
    LabelImage grid;
    std::vector<unsigned char> bytes;
    VoxelType type = VoxelType::u8;
};

StoredVoxels read_with(itk::ImageIOBase& io, const std::string& name, std::uint64_t max_payload_bytes,
                       const BeforeVoxels& before_voxels)
{
    io.ReadImageInformation();
    Dims dims{1, 1, 1};
    reject_vectors(name, io, dims);
    const VoxelType type = voxel_type_of(name, io);
    const unsigned rank = std::min(io.GetNumberOfDimensions(), 3u);
    Vec3 spacing{1, 1, 1}, origin{0, 0, 0};
    Mat3 direction = identity_matrix();
    for (unsigned axis = 0; axis < rank; ++axis) {
        spacing[axis] = io.GetSpacing(axis);
        origin[axis] = io.GetOrigin(axis);
        const std::vector<double> column = io.GetDirection(axis);
        for (unsigned row = 0; row < rank; ++row) direction[3 * row + axis] = column[row];
    }
    // ITK is LPS; our world is RAS: negate the x and y rows.
    origin[0] = -origin[0];
    origin[1] = -origin[1];
    for (int column = 0; column < 6; ++column) direction[column] = -direction[column];
    const std::uint64_t needed = checked_voxel_bytes(name, dims, voxel_type_size(type));
    validate_geometry(name, dims, spacing, direction);
    require_payload(name, needed, max_payload_bytes);
    if (before_voxels) before_voxels(dims, spacing, voxel_type_size(type));

    std::vector<unsigned char> bytes(static_cast<std::size_t>(needed));
    itk::ImageIORegion region(io.GetNumberOfDimensions());
    for (unsigned axis = 0; axis < io.GetNumberOfDimensions(); ++axis) {
        region.SetIndex(axis, 0);
        region.SetSize(axis, io.GetDimensions(axis));
    }
    io.SetIORegion(region);
    io.Read(bytes.data());
    return {LabelImage(dims, spacing, origin, direction), std::move(bytes), type};
}

/// Opens `path` with the ITK ImageIO its content calls for and reads it with read_with(); ITK's
/// exceptions become IoError. `use` gets the ImageIO and the stored voxels.
template <typename Use>
auto read_through_itk(const fs::path& path, std::uint64_t max_payload_bytes, const BeforeVoxels& before_voxels, Use use)
{
    const std::string name = path.string();
    const QuietItk quiet;
    try {
        const itk::ImageIOBase::Pointer io =
            itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::IOFileModeEnum::ReadMode);
        if (!io)
            throw IoError(concat(name, ": not a readable ", full_extension(path),
                                 " image (wrong magic or "
                                 "corrupt header); check that the file is not renamed or damaged"));
        io->SetFileName(path.string());
        return use(*io, read_with(*io, name, max_payload_bytes, before_voxels));
    } catch (const itk::ExceptionObject& e) {
        throw IoError(concat(name, ": cannot be read (", one_line(e.GetDescription()),
                             "); the file is damaged or truncated, copy or export it again"));
    }
}

} // namespace

LabelImage read_itk_label_image(const fs::path& path, std::uint64_t max_payload_bytes,
                                const BeforeVoxels& before_voxels)
{
    const std::string name = path.string();
    return read_through_itk(path, max_payload_bytes, before_voxels, [&](itk::ImageIOBase& io, StoredVoxels stored) {
        const bool big_endian = itk::ByteSwapper<std::uint16_t>::SystemIsBigEndian();
        decode_labels(name, stored.bytes.data(), stored.type, big_endian, stored.grid);
        stored.grid.names() = read_segment_names(name, io.GetMetaDataDictionary());
        return std::move(stored.grid);
    });
}

GreyImage read_itk_grey_image(const fs::path& path, std::uint64_t max_payload_bytes)
{
    return read_through_itk(path, max_payload_bytes, {}, [&](itk::ImageIOBase&, StoredVoxels stored) {
        const bool big_endian = itk::ByteSwapper<std::uint16_t>::SystemIsBigEndian();
        GreyImage image{std::move(stored.grid), {}};
        image.values = to_finite_floats(path.string(), stored.bytes.data(), stored.type, big_endian, image.grid);
        return image;
    });
}

void write_itk_label_image(const LabelImage& image, const fs::path& path, const std::string& name, bool slicer_segments)
{
    const QuietItk quiet;
    const Label largest = image.labels().empty() ? 0 : *std::max_element(image.labels().begin(), image.labels().end());
    const bool narrow = largest <= 255;
    std::vector<unsigned char> bytes;
    if (narrow) bytes.assign(image.labels().begin(), image.labels().end());
    try {
        const itk::ImageIOBase::Pointer io =
            itk::ImageIOFactory::CreateImageIO(path.c_str(), itk::IOFileModeEnum::WriteMode);
        if (!io) throw IoError(concat(name, ": ITK cannot write this file type; use .nii.gz"));
        io->SetNumberOfDimensions(3);
        const Mat3& d = image.direction();
        for (unsigned axis = 0; axis < 3; ++axis) {
            io->SetDimensions(axis, image.dims()[axis]);
            io->SetSpacing(axis, image.spacing_mm()[axis]);
            // RAS -> LPS: negate x and y.
            // (0 - x rather than -x: no "-0" in the headers.)
            io->SetOrigin(axis, axis < 2 ? 0 - image.origin_mm()[axis] : image.origin_mm()[axis]);
            io->SetDirection(axis, std::vector<double>{0 - d[axis], 0 - d[3 + axis], d[6 + axis]});
        }
        io->SetPixelType(itk::IOPixelEnum::SCALAR);
        io->SetComponentType(narrow ? itk::IOComponentEnum::UCHAR : itk::IOComponentEnum::USHORT);
        io->SetNumberOfComponents(1);
        const std::string extension = full_extension(path);
        io->SetUseCompression(extension != ".nii" && extension != ".nhdr" && extension != ".mhd");
        io->SetFileName(path.string());
        io->SetMetaDataDictionary(slicer_segments ? segment_dictionary(image) : itk::MetaDataDictionary());
        itk::ImageIORegion region(3);
        for (unsigned axis = 0; axis < 3; ++axis) region.SetSize(axis, image.dims()[axis]);
        io->SetIORegion(region);
        io->Write(narrow ? static_cast<const void*>(bytes.data()) : static_cast<const void*>(image.labels().data()));
    } catch (const itk::ExceptionObject& e) {
        throw IoError(concat(name, ": cannot write (", one_line(e.GetDescription()),
                             "); check the folder's permissions and free space"));
    }
}

} // namespace tissuemesh::io::detail
