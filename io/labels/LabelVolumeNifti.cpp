// NIfTI label volumes through niftilib's nifti2_io (Debian libnifti2-dev),
// which reads NIfTI-1 and NIfTI-2, plain or gzip (znzlib).
//
// niftilib allocates nvox·nbyper bytes from the header and reads into
// them, so the header is read alone first (read_data = 0), its sizes, the
// memory budget and the file's length are checked, and only then the data.
// niftilib also mends what it should report: a pixdim that is not positive
// becomes 1, a vox_offset it cannot use is replaced, and every NaN or
// infinite float sample becomes 0. The raw header is read again to see what
// the file says, and float samples are scanned as stored.
#include <nifti2_io.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "contours/InputError.hpp"
#include "io/files/AtomicWrite.hpp"
#include "io/labels/LabelVolumeDetail.hpp"

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

SampleType niftiSampleType(const std::string& path, int datatype) {
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

// What the header on disk says where niftilib mends it.
struct RawHeader {
    double voxOffset = 0;
    double pixdim[4] = {0, 0, 0, 0};
    std::uint64_t headerBytes = 0;  // the smallest vox_offset of a single file
};

RawHeader rawHeader(const std::string& path) {
    int version = 0;
    void* raw = nifti_read_header(path.c_str(), &version, 0);
    if (!raw) throw InputError(path, 0, "not a readable NIfTI file (bad or truncated header)");
    RawHeader h;
    if (version == 1) {
        const auto* n1 = static_cast<const nifti_1_header*>(raw);
        h.voxOffset = n1->vox_offset;
        for (int a = 0; a < 4; ++a) h.pixdim[a] = n1->pixdim[a];
        h.headerBytes = 352;
    } else {
        const auto* n2 = static_cast<const nifti_2_header*>(raw);
        h.voxOffset = double(n2->vox_offset);
        for (int a = 0; a < 4; ++a) h.pixdim[a] = n2->pixdim[a];
        h.headerBytes = 544;
    }
    std::free(raw);
    return h;
}

VolumeGeometry geometryOf(const std::string& path, const nifti_image& image,
                          const std::array<int, 3>& size, const RawHeader& raw) {
    // sform when it is set (it may carry shear, and is what registration
    // tools write); otherwise the qform, which niftilib builds from the
    // quaternion, qfac and pixdim (or, for qform_code 0, the ANALYZE-style
    // diag(pixdim) with origin 0).
    const bool useSform = image.sform_code > 0;
    if (!useSform)
        for (int a = 1; a <= 3; ++a)
            // niftilib quietly uses 1 for a pixdim that is not positive; a
            // label map with such a spacing is broken, so say so instead.
            if (!(raw.pixdim[a] > 0) || !std::isfinite(raw.pixdim[a])) {
                std::ostringstream s;
                s << "pixdim[" << a << "] is " << raw.pixdim[a]
                  << "; spacing must be positive and finite";
                throw InputError(path, 0, s.str());
            }
    const nifti_dmat44& m = useSform ? image.sto_xyz : image.qto_xyz;
    std::array<std::array<double, 3>, 3> steps{};
    std::array<double, 3> origin{};
    for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a) steps[a][c] = kRasToLps[c] * m.m[c][a];
        origin[c] = kRasToLps[c] * m.m[c][3];
    }
    return geometryFromSteps(path, size, steps, origin);
}

// The first float sample as stored that is NaN or infinite (niftilib loads
// it as 0), or -1. One pass over the data through znzlib. O(voxels).
template <class Float, class Bits>
std::int64_t firstNonFinite(const std::string& path, std::uint64_t offset, std::uint64_t count,
                            bool swapped) {
    znzFile file = znzopen(path.c_str(), "rb", gzipped(path) ? 1 : 0);
    if (znz_isnull(file)) throw InputError(path, 0, "cannot reopen the data");
    std::vector<Bits> chunk(std::size_t(1) << 16);
    std::int64_t found = -1;
    if (znzseek(file, znz_off_t(offset), SEEK_SET) < 0) count = 0;
    for (std::uint64_t done = 0; done < count && found < 0;) {
        const std::size_t want = std::size_t(std::min<std::uint64_t>(chunk.size(), count - done));
        const std::size_t got = znzread(chunk.data(), sizeof(Bits), want, file);
        for (std::size_t k = 0; k < got && found < 0; ++k) {
            Bits bits = chunk[k];
            if (swapped) {
                Bits reversed = 0;
                for (std::size_t b = 0; b < sizeof(Bits); ++b)
                    reversed = Bits(reversed << 8 | ((bits >> (8 * b)) & 0xff));
                bits = reversed;
            }
            Float value;
            std::memcpy(&value, &bits, sizeof value);
            if (!std::isfinite(value)) found = std::int64_t(done + k);
        }
        if (got < want) break;
        done += got;
    }
    znzclose(file);
    return found;
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
    const SampleType type = niftiSampleType(path, image->datatype);
    const std::uint64_t voxels =
        std::uint64_t(size[0]) * std::uint64_t(size[1]) * std::uint64_t(size[2]);
    if (image->nbyper != int(sampleBytes(type)) || image->nvox != std::int64_t(voxels))
        throw InputError(path, 0, "inconsistent header (voxel count or bytes per voxel)");
    const std::string memory = memoryProblem(voxels, sampleBytes(type));
    if (!memory.empty()) throw InputError(path, 0, memory);
    const RawHeader raw = rawHeader(path);
    const VolumeGeometry geometry = geometryOf(path, *image, size, raw);
    LinearScale scale;
    // scl_slope 0 means "no scaling" in NIfTI; niftilib already turns a
    // non-finite slope into 0.
    if (image->scl_slope != 0 && std::isfinite(image->scl_slope)) {
        if (!std::isfinite(image->scl_inter)) throw InputError(path, 0, "scl_inter is not finite");
        scale = {image->scl_slope, image->scl_inter};
    }

    // The data start where the header says, or the file is refused: a
    // vox_offset niftilib cannot use it replaces, and reads the wrong bytes.
    if (!(raw.voxOffset >= double(raw.headerBytes)) || raw.voxOffset > 1e18 ||
        image->iname_offset != std::int64_t(raw.voxOffset)) {
        std::ostringstream s;
        s << "vox_offset " << raw.voxOffset << " is not where data can start (from "
          << raw.headerBytes << " bytes, within the file)";
        throw InputError(path, 0, s.str());
    }
    // The file must be able to hold the samples before they are allocated.
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
    if (type == SampleType::Float32 || type == SampleType::Float64) {
        const bool swapped = image->byteorder != nifti_short_order();
        const std::uint64_t offset = std::uint64_t(image->iname_offset);
        const std::int64_t bad =
            type == SampleType::Float32
                ? firstNonFinite<float, std::uint32_t>(path, offset, voxels, swapped)
                : firstNonFinite<double, std::uint64_t>(path, offset, voxels, swapped);
        if (bad >= 0) {
            const std::uint64_t nx = std::uint64_t(size[0]), ny = std::uint64_t(size[1]);
            const std::uint64_t at = std::uint64_t(bad);
            throw InputError(path, 0,
                             "voxel (" + std::to_string(at % nx) + ", " +
                                 std::to_string(at / nx % ny) + ", " +
                                 std::to_string(at / (nx * ny)) +
                                 ") holds NaN or infinity, not a finite label (niftilib would "
                                 "read it as 0)");
        }
    }
    LabelVolume volume;
    volume.geometry = geometry;
    volume.labels = labelsFromSamples(path, image->data, type, geometry, scale);
    return volume;
}

namespace {

int niftiTypeOf(SampleType type) {
    switch (type) {
        case SampleType::UInt8:
            return DT_UINT8;
        case SampleType::UInt16:
            return DT_UINT16;
        case SampleType::Int16:
            return DT_INT16;
        case SampleType::Int32:
            return DT_INT32;
        default:
            throw std::invalid_argument("writeNiftiSamples: unsupported sample type");
    }
}

}  // namespace

void writeNiftiSamples(const std::string& path, const VolumeGeometry& geometry, const void* data,
                       SampleType type) {
    const int datatype = niftiTypeOf(type);
    std::lock_guard<std::mutex> lock(niftiMutex());
    nifti_set_debug_level(0);
    writeAtomically(path, [&](const std::string& temporary) {
        const std::int64_t dims[8] = {
            3, geometry.size[0], geometry.size[1], geometry.size[2], 1, 1, 1, 1};
        Image image(nifti_make_new_nim(dims, datatype, 0));
        if (!image) throw std::bad_alloc();
        const std::size_t bytes = geometry.voxelCount() * sampleBytes(type);
        image->data = std::malloc(bytes);  // nifti_image_free releases it
        if (!image->data) throw std::bad_alloc();
        std::memcpy(image->data, data, bytes);
        // Index → RAS: the LPS steps and origin with x and y negated.
        nifti_dmat44 m{};
        for (int c = 0; c < 3; ++c) {
            for (int a = 0; a < 3; ++a)
                m.m[c][a] = kRasToLps[c] * geometry.spacingMm[a] * geometry.direction[a][c];
            m.m[c][3] = kRasToLps[c] * geometry.originMm[c];
        }
        m.m[3][3] = 1;
        image->sto_xyz = m;
        image->sto_ijk = nifti_dmat44_inverse(m);
        image->sform_code = NIFTI_XFORM_SCANNER_ANAT;
        // The qform too, for readers that ignore the sform; exact for the
        // orthogonal grids written here.
        nifti_dmat44_to_quatern(m, &image->quatern_b, &image->quatern_c, &image->quatern_d,
                                &image->qoffset_x, &image->qoffset_y, &image->qoffset_z, nullptr,
                                nullptr, nullptr, &image->qfac);
        image->qform_code = NIFTI_XFORM_SCANNER_ANAT;
        image->qto_xyz = m;
        image->qto_ijk = image->sto_ijk;
        image->dx = image->pixdim[1] = geometry.spacingMm[0];
        image->dy = image->pixdim[2] = geometry.spacingMm[1];
        image->dz = image->pixdim[3] = geometry.spacingMm[2];
        image->xyz_units = NIFTI_UNITS_MM;
        image->nifti_type = NIFTI_FTYPE_NIFTI1_1;
        if (nifti_set_filenames(image.get(), temporary.c_str(), 0, 1) != 0)
            throw std::runtime_error("cannot write " + path + ": niftilib refused the name");
        nifti_image_write(image.get());  // reports nothing; the file is read back instead
        Image back(nifti_image_read(temporary.c_str(), 0));
        return back && back->nx == geometry.size[0] && back->ny == geometry.size[1] &&
               back->nz == geometry.size[2] && back->datatype == datatype;
    });
}

}  // namespace dfrecon::labelvolume
