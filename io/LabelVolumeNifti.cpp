// NIfTI label volumes through niftilib's nifti2_io (Debian libnifti2-dev),
// which reads NIfTI-1 and NIfTI-2, plain or gzip (znzlib).
//
// niftilib allocates nvox·nbyper bytes from the header and reads into
// them, so the header is read alone first (read_data = 0), its sizes and
// the file's length are checked, and only then the data.
#include <nifti2_io.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>

#include "io/InputError.hpp"
#include "io/LabelVolumeDetail.hpp"

namespace dfrecon::labelvolume {

namespace {

// niftilib keeps its debug level (what it prints) in a global.
std::mutex& niftiMutex() {
    static std::mutex mutex;
    return mutex;
}

struct ImageFree {
    void operator()(nifti_image* image) const { nifti_image_free(image); }
};
using Image = std::unique_ptr<nifti_image, ImageFree>;

SampleType sampleTypeOf(const std::string& path, int datatype) {
    switch (datatype) {
        case DT_INT8:
            return SampleType::Int8;
        case DT_UINT8:
            return SampleType::UInt8;
        case DT_INT16:
            return SampleType::Int16;
        case DT_UINT16:
            return SampleType::UInt16;
        case DT_INT32:
            return SampleType::Int32;
        case DT_UINT32:
            return SampleType::UInt32;
        case DT_INT64:
            return SampleType::Int64;
        case DT_UINT64:
            return SampleType::UInt64;
        case DT_FLOAT32:
            return SampleType::Float32;
        case DT_FLOAT64:
            return SampleType::Float64;
        default: {
            const char* name = nifti_datatype_string(datatype);
            throw InputError(path, 0,
                             std::string("datatype ") + (name ? name : "?") + " (" +
                                 std::to_string(datatype) + ") is not a scalar number");
        }
    }
}

bool gzipped(const std::string& path) {
    return path.size() >= 3 && (path.compare(path.size() - 3, 3, ".gz") == 0 ||
                                path.compare(path.size() - 3, 3, ".GZ") == 0);
}

// NIfTI's (x, y, z) are RAS; LPS negates x and y.
constexpr double kRasToLps[3] = {-1, -1, 1};

VolumeGeometry geometryOf(const std::string& path, const nifti_image& image,
                          const std::array<int, 3>& size) {
    // sform when it is set (it may carry shear, and is what registration
    // tools write); otherwise the qform, which niftilib builds from the
    // quaternion, qfac and pixdim (or, for qform_code 0, the ANALYZE-style
    // diag(pixdim) with origin 0).
    const bool useSform = image.sform_code > 0;
    if (!useSform)
        for (int a = 1; a <= 3; ++a)
            // niftilib quietly uses 1 for a non-positive pixdim; a label map
            // with such a spacing is broken, so say so instead.
            if (!(image.pixdim[a] > 0) || !std::isfinite(image.pixdim[a]))
                throw InputError(path, 0,
                                 "pixdim[" + std::to_string(a) + "] is " +
                                     std::to_string(image.pixdim[a]) +
                                     "; spacing must be positive");
    const nifti_dmat44& m = useSform ? image.sto_xyz : image.qto_xyz;
    std::array<std::array<double, 3>, 3> steps{};
    std::array<double, 3> origin{};
    for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) steps[a][c] = kRasToLps[c] * m.m[c][a];
        origin[c] = kRasToLps[c] * m.m[c][3];
    }
    return geometryFromSteps(path, size, steps, origin);
}

}  // namespace

LabelVolume readNiftiLabelVolume(const std::string& path) {
    std::lock_guard<std::mutex> lock(niftiMutex());
    nifti_set_debug_level(0);  // errors come back as InputError, not on stderr

    // Pass 1: the header only.
    Image image(nifti_image_read(path.c_str(), 0));
    if (!image) throw InputError(path, 0, "not a readable NIfTI file (bad or truncated header)");
    if (image->nifti_type != NIFTI_FTYPE_NIFTI1_1 && image->nifti_type != NIFTI_FTYPE_NIFTI2_1)
        throw InputError(path, 0,
                         "not a single-file NIfTI image (ANALYZE or .hdr/.img pair, type " +
                             std::to_string(image->nifti_type) + ")");
    const std::int64_t ndim = image->dim[0];
    if (ndim < 1 || ndim > 7)
        throw InputError(path, 0, "dim[0] is " + std::to_string(ndim) + ", not 1 to 7");
    std::vector<std::uint64_t> sizes;
    for (std::int64_t a = 1; a <= ndim; ++a) {
        if (image->dim[a] < 1)
            throw InputError(path, 0,
                             "dim[" + std::to_string(a) + "] is " + std::to_string(image->dim[a]));
        sizes.push_back(std::uint64_t(image->dim[a]));
    }
    const std::array<int, 3> size = checkedSizes(path, sizes);
    const SampleType type = sampleTypeOf(path, image->datatype);
    const std::uint64_t voxels =
        std::uint64_t(size[0]) * std::uint64_t(size[1]) * std::uint64_t(size[2]);
    if (image->nbyper != int(sampleBytes(type)) || image->nvox != std::int64_t(voxels))
        throw InputError(path, 0, "inconsistent header (voxel count or bytes per voxel)");
    const VolumeGeometry geometry = geometryOf(path, *image, size);
    LinearScale scale;
    // scl_slope 0 means "no scaling" in NIfTI; niftilib already turns a
    // non-finite slope into 0.
    if (image->scl_slope != 0 && std::isfinite(image->scl_slope)) {
        if (!std::isfinite(image->scl_inter)) throw InputError(path, 0, "scl_inter is not finite");
        scale = {image->scl_slope, image->scl_inter};
    }

    // The file must be able to hold the samples before they are allocated.
    if (image->iname_offset < 0)
        throw InputError(path, 0, "negative vox_offset " + std::to_string(image->iname_offset));
    std::error_code ec;
    const std::uint64_t fileBytes = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(path, 0, "cannot measure the file");
    const std::uint64_t needed =
        std::uint64_t(image->iname_offset) + voxels * std::uint64_t(image->nbyper);
    // Deflate codes at most 258 bytes in 2 bits (1032:1); the slack covers
    // gzip's headers of a tiny stream.
    const std::uint64_t available = gzipped(path) ? fileBytes * 1032 + 1024 : fileBytes;
    requireBytes(path, needed, available, "the file");

    // Pass 2: the data (niftilib swaps bytes to the host's order).
    if (nifti_image_load(image.get()) != 0 || !image->data)
        throw InputError(path, 0, "truncated or unreadable image data");
    LabelVolume volume;
    volume.geometry = geometry;
    volume.labels = labelsFromSamples(path, image->data, type, geometry, scale);
    return volume;
}

}  // namespace dfrecon::labelvolume
