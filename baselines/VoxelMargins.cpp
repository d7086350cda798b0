#include "baselines/VoxelMargins.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "api/Stopwatch.hpp"
#include "baselines/ExternalCommand.hpp"
#include "baselines/RowCrossings.hpp"

namespace dfrecon {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The mask on its grid: voxel (i, j, k) at index (k·ny + j)·nx + i, centred
// at (x0 + i·h, y0 + j·h, z0 + k·h).
struct VoxelMask {
    int nx = 0, ny = 0, nz = 0;
    double h = 0;
    double x0 = 0, y0 = 0, z0 = 0;
    std::vector<std::uint8_t> inside;

    std::size_t layer() const { return std::size_t(nx) * std::size_t(ny); }
    std::size_t count() const { return layer() * std::size_t(nz); }
};

void checkArguments(const char* function, const Roi& roi, double voxelMm, double marginMm) {
    const std::string name = function;
    if (!(voxelMm > 0) || !std::isfinite(voxelMm))
        throw std::invalid_argument(name + ": the voxel size must be positive");
    if (!std::isfinite(marginMm)) throw std::invalid_argument(name + ": the margin is not finite");
    if (roi.slices.empty() || extentOf(roi).empty)
        throw std::invalid_argument(name + ": ROI '" + roi.name + "' has no contours");
}

// Fills plane `slice` even-odd at the voxel centres of one layer.
void fillLayer(const Slice& slice, const VoxelMask& grid, std::uint8_t* layer) {
    std::vector<double> crossings;
    for (int j = 0; j < grid.ny; ++j) {
        const double y = grid.y0 + j * grid.h;
        // Half-open in y (a vertex on the row counts once) and in x (a centre
        // on the first crossing is in, on the second out): even-odd along the
        // row, inside between the 1st and 2nd crossing, the 3rd and 4th, ...
        rowCrossings(slice, y, crossings);
        std::uint8_t* row = layer + std::size_t(j) * std::size_t(grid.nx);
        for (std::size_t c = 0; c + 1 < crossings.size(); c += 2) {
            const double first = std::ceil((crossings[c] - grid.x0) / grid.h);
            const double end = std::ceil((crossings[c + 1] - grid.x0) / grid.h);
            const int from = int(std::clamp(first, 0.0, double(grid.nx)));
            const int to = int(std::clamp(end, 0.0, double(grid.nx)));
            std::fill(row + from, row + std::max(from, to), std::uint8_t(1));
        }
    }
}

// The planning-system stack of the ROI on a grid padded for `marginMm`
// (VoxelMargins.hpp says which voxels are in).
VoxelMask rasterise(const Roi& roi, double h, double marginMm) {
    const Extent3 extent = extentOf(roi);
    const std::vector<Slice>& slices = roi.slices;
    const std::size_t planes = slices.size();
    // How far the end planes reach: half their one gap (a lone plane: half
    // its slab thickness, or half a voxel, one layer of centres).
    const double lone = roi.slabThicknessMm > 0 ? roi.slabThicknessMm : h;
    const double lowGap = planes > 1 ? slices[1].zMm - slices[0].zMm : lone;
    const double highGap = planes > 1 ? slices[planes - 1].zMm - slices[planes - 2].zMm : lone;
    // Where each plane's stretch of z starts; the last ends at `top`.
    std::vector<double> starts(planes);
    starts[0] = slices[0].zMm - 0.5 * lowGap;
    for (std::size_t p = 1; p < planes; ++p) starts[p] = 0.5 * (slices[p - 1].zMm + slices[p].zMm);
    const double top = slices[planes - 1].zMm + 0.5 * highGap;

    const int pad = int(std::ceil(std::abs(marginMm) / h)) + 2;
    VoxelMask grid;
    grid.h = h;
    grid.nx = int(std::ceil((extent.max[0] - extent.min[0]) / h)) + 2 * pad;
    grid.ny = int(std::ceil((extent.max[1] - extent.min[1]) / h)) + 2 * pad;
    grid.x0 = extent.min[0] + (0.5 - pad) * h;
    grid.y0 = extent.min[1] + (0.5 - pad) * h;
    // Centres on the first plane, so that evenly spaced planes at a multiple
    // of the voxel size each get whole layers.
    const int below = int(std::ceil((slices[0].zMm - starts[0]) / h)) + pad;
    const int above = int(std::ceil((top - slices[0].zMm) / h)) + pad;
    grid.nz = below + above + 1;
    grid.z0 = slices[0].zMm - below * h;
    grid.inside.assign(grid.count(), 0);

    int filled = -1;  // the plane the last filled layer took
    for (int k = 0; k < grid.nz; ++k) {
        const double z = grid.z0 + k * h;
        if (z < starts[0] || z >= top) continue;
        const int plane =
            int(std::upper_bound(starts.begin(), starts.end(), z) - starts.begin()) - 1;
        std::uint8_t* layer = grid.inside.data() + std::size_t(k) * grid.layer();
        if (plane == filled) {
            // The layer below took the same plane: the same pixels.
            std::copy_n(layer - grid.layer(), grid.layer(), layer);
        } else {
            fillLayer(slices[std::size_t(plane)], grid, layer);
        }
        filled = plane;
    }
    return grid;
}

std::size_t maskVoxels(const VoxelMask& grid) {
    return std::size_t(std::count(grid.inside.begin(), grid.inside.end(), std::uint8_t(1)));
}

// Squared margin in voxel units, with room for its rounding (0.3 mm at
// 0.1 mm voxels is 2.9999999999999996 voxels): the squared distances
// compared with it are whole numbers.
double squaredRadius(double marginMm, double h) {
    const double r = std::abs(marginMm) / h;
    return r * r + 1e-9 * (1 + r * r);
}

// 1D squared distance transform (Felzenszwalb & Huttenlocher 2012, the lower
// envelope of the parabolas (q - p)² + f(p)), written here because OpenCV
// has no 3D transform and no 1D one that takes sampled costs: out(q) =
// min_p (q - p)² + f(p), infinite where every f is. Exact for the whole
// numbers it is given. O(n).
void lowerEnvelope(const std::vector<double>& f, std::vector<double>& out, std::vector<int>& sites,
                   std::vector<double>& bounds) {
    const int n = int(f.size());
    sites.resize(std::size_t(n));
    bounds.resize(std::size_t(n) + 1);
    int k = -1;  // the envelope's last parabola
    for (int q = 0; q < n; ++q) {
        if (f[std::size_t(q)] == kInfinity) continue;
        // Drop the parabolas this one hides; the first one's bound is -∞, so
        // it stays unless there is none yet.
        double s = -kInfinity;
        while (k >= 0) {
            const int p = sites[std::size_t(k)];
            s = ((f[std::size_t(q)] + double(q) * q) - (f[std::size_t(p)] + double(p) * p)) /
                (2.0 * (q - p));
            if (s > bounds[std::size_t(k)]) break;
            --k;
        }
        ++k;
        sites[std::size_t(k)] = q;
        bounds[std::size_t(k)] = s;
        bounds[std::size_t(k) + 1] = kInfinity;
    }
    out.assign(std::size_t(n), kInfinity);
    if (k < 0) return;
    int at = 0;
    for (int q = 0; q < n; ++q) {
        while (bounds[std::size_t(at) + 1] < q) ++at;
        const double d = q - sites[std::size_t(at)];
        out[std::size_t(q)] = d * d + f[std::size_t(sites[std::size_t(at)])];
    }
}

// Squared distance, in voxels², from every voxel centre to the nearest
// centre of a voxel whose inside flag is `feature`; infinite where there is
// none. OpenVDB's level sets are not used: their distances come from a
// narrow band renormalised by fast sweeping, first order, not the exact
// distances between centres. OpenCV's DIST_MASK_PRECISE transform is exact
// in 2D and keeps the image's outside out of it; it returns float
// distances, squared and rounded back to the whole numbers they are (exact
// for those that decide a margin: a square within 2^22 is rounded within
// 0.5, and larger ones, far beyond any margin, cannot come near one).
std::vector<double> squaredDistances(const VoxelMask& grid, std::uint8_t feature) {
    const std::size_t layerSize = grid.layer();
    std::vector<double> squared(grid.count(), kInfinity);
    cv::Mat source(grid.ny, grid.nx, CV_8U), distance;
    for (int k = 0; k < grid.nz; ++k) {
        const std::uint8_t* layer = grid.inside.data() + std::size_t(k) * layerSize;
        double* out = squared.data() + std::size_t(k) * layerSize;
        // OpenCV measures to the nearest zero pixel: the features are zero.
        bool any = false;
        for (int j = 0; j < grid.ny; ++j) {
            std::uint8_t* row = source.ptr<std::uint8_t>(j);
            for (int i = 0; i < grid.nx; ++i) {
                const bool isFeature =
                    layer[std::size_t(j) * std::size_t(grid.nx) + std::size_t(i)] == feature;
                row[i] = isFeature ? 0 : 1;
                any = any || isFeature;
            }
        }
        if (!any) continue;  // OpenCV would give huge finite values instead
        cv::distanceTransform(source, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
        for (int j = 0; j < grid.ny; ++j) {
            const float* row = distance.ptr<float>(j);
            for (int i = 0; i < grid.nx; ++i) {
                const double d = row[i];
                out[std::size_t(j) * std::size_t(grid.nx) + std::size_t(i)] = std::round(d * d);
            }
        }
    }
    // Along z, column by column.
    std::vector<double> column(std::size_t(grid.nz)), envelope;
    std::vector<int> sites;
    std::vector<double> bounds;
    for (std::size_t at = 0; at < layerSize; ++at) {
        for (int k = 0; k < grid.nz; ++k)
            column[std::size_t(k)] = squared[std::size_t(k) * layerSize + at];
        lowerEnvelope(column, envelope, sites, bounds);
        for (int k = 0; k < grid.nz; ++k)
            squared[std::size_t(k) * layerSize + at] = envelope[std::size_t(k)];
    }
    return squared;
}

VoxelMarginResult resultOf(std::size_t voxels, double h, const Stopwatch& watch) {
    VoxelMarginResult result;
    result.voxels = voxels;
    result.volumeMm3 = double(voxels) * h * h * h;
    result.seconds = watch.total();
    return result;
}

// A folder of its own under the temporary directory, removed with this.
class ScratchFolder {
  public:
    ScratchFolder() {
        std::string pattern =
            (std::filesystem::temp_directory_path() / "dfrecon-voxel-margin-XXXXXX").string();
        if (!::mkdtemp(pattern.data()))
            throw std::runtime_error("cannot make a temporary folder " + pattern + ": " +
                                     std::strerror(errno));
        path_ = pattern;
    }
    ~ScratchFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    std::string operator/(const char* name) const { return (path_ / name).string(); }

  private:
    std::filesystem::path path_;
};

// The mask (or its complement) as a MetaImage with its data in the same
// file; io/ has no MetaImage writer (its volumes are NRRD), and these few
// lines are all ITK's reader in plastimatch needs.
void writeMaskMha(const std::string& path, const VoxelMask& grid, bool inverted) {
    std::ofstream file(path, std::ios::binary);
    std::ostringstream header;
    header.precision(17);
    header << "ObjectType = Image\nNDims = 3\nBinaryData = True\n"
              "BinaryDataByteOrderMSB = False\nCompressedData = False\n"
              "TransformMatrix = 1 0 0 0 1 0 0 0 1\n"
           << "Offset = " << grid.x0 << ' ' << grid.y0 << ' ' << grid.z0 << '\n'
           << "ElementSpacing = " << grid.h << ' ' << grid.h << ' ' << grid.h << '\n'
           << "DimSize = " << grid.nx << ' ' << grid.ny << ' ' << grid.nz << '\n'
           << "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    file << header.str();
    if (inverted) {
        std::vector<std::uint8_t> complement(grid.inside.size());
        std::transform(grid.inside.begin(), grid.inside.end(), complement.begin(),
                       [](std::uint8_t v) { return std::uint8_t(v ^ 1); });
        file.write(reinterpret_cast<const char*>(complement.data()),
                   std::streamsize(complement.size()));
    } else {
        file.write(reinterpret_cast<const char*>(grid.inside.data()),
                   std::streamsize(grid.inside.size()));
    }
    if (!file.flush()) throw std::runtime_error("cannot write " + path);
}

// The distance map plastimatch wrote: a MetaImage of float or double values
// in the file after its header (what plastimatch 1.9 writes for .mha).
std::vector<double> readDistanceMha(const std::string& path, const VoxelMask& grid) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("plastimatch wrote no " + path);
    std::string line, type;
    std::vector<long> dims;
    bool local = false;
    while (std::getline(file, line)) {
        const std::size_t equals = line.find('=');
        if (equals == std::string::npos) continue;
        std::string key = line.substr(0, equals), value = line.substr(equals + 1);
        key.erase(key.find_last_not_of(" \t\r") + 1);
        value.erase(0, value.find_first_not_of(" \t"));
        value.erase(value.find_last_not_of(" \t\r") + 1);
        if (key == "ElementType") type = value;
        if (key == "DimSize") {
            std::istringstream in(value);
            dims.assign(std::istream_iterator<long>(in), std::istream_iterator<long>());
        }
        if ((key == "CompressedData" || key == "BinaryDataByteOrderMSB") && value != "False")
            throw std::runtime_error(path + ": " + key + " = " + value + " is not read here");
        if (key == "ElementDataFile") {
            local = value == "LOCAL";
            break;
        }
    }
    if (!local) throw std::runtime_error(path + ": no data in the file (ElementDataFile LOCAL)");
    if (dims != std::vector<long>{grid.nx, grid.ny, grid.nz})
        throw std::runtime_error(path + ": DimSize is not the mask's");
    std::vector<double> values(grid.count());
    if (type == "MET_FLOAT") {
        std::vector<float> raw(grid.count());
        file.read(reinterpret_cast<char*>(raw.data()), std::streamsize(raw.size() * sizeof(float)));
        std::copy(raw.begin(), raw.end(), values.begin());
    } else if (type == "MET_DOUBLE") {
        file.read(reinterpret_cast<char*>(values.data()),
                  std::streamsize(values.size() * sizeof(double)));
    } else {
        throw std::runtime_error(path + ": ElementType " + type + " is not read here");
    }
    if (!file) throw std::runtime_error(path + ": shorter than its DimSize");
    return values;
}

}  // namespace

VoxelMarginResult edtVoxelMargin(const Roi& roi, double voxelMm, double marginMm) {
    const Stopwatch watch;
    checkArguments("edtVoxelMargin", roi, voxelMm, marginMm);
    const VoxelMask grid = rasterise(roi, voxelMm, marginMm);
    if (marginMm == 0) return resultOf(maskVoxels(grid), voxelMm, watch);
    const double r2 = squaredRadius(marginMm, voxelMm);
    const bool grow = marginMm > 0;
    // Growing measures to the mask, shrinking to the voxels outside it.
    const std::vector<double> squared = squaredDistances(grid, grow ? 1 : 0);
    std::size_t voxels = 0;
    for (std::size_t at = 0; at < squared.size(); ++at)
        voxels += grow ? squared[at] <= r2 : grid.inside[at] && squared[at] > r2;
    return resultOf(voxels, voxelMm, watch);
}

VoxelMarginResult plastimatchVoxelMargin(const Roi& roi, double voxelMm, double marginMm) {
    const Stopwatch watch;
    checkArguments("plastimatchVoxelMargin", roi, voxelMm, marginMm);
    const VoxelMask grid = rasterise(roi, voxelMm, marginMm);
    if (marginMm == 0) return resultOf(maskVoxels(grid), voxelMm, watch);
    const bool grow = marginMm > 0;
    const ScratchFolder folder;
    const std::string mask = folder / "mask.mha", map = folder / "dmap.mha";
    // plastimatch's map is 0 on the boundary voxels of its input and, inside,
    // the distance to them, not to the voxels outside: shrinking therefore
    // maps the complement, whose outside distances are those to it.
    writeMaskMha(mask, grid, !grow);
    runCommand({"plastimatch", "dmap", "--input", mask, "--output", map, "--algorithm", "maurer"},
               folder / "plastimatch.log");
    const std::vector<double> distance = readDistanceMha(map, grid);
    const double r2 = squaredRadius(marginMm, voxelMm);
    std::size_t voxels = 0;
    for (std::size_t at = 0; at < distance.size(); ++at) {
        // The voxel's side comes from the mask, so the map's sign convention
        // (inside negative by default, positive with --inside-positive) does
        // not matter; the square rounds to the whole number of voxels² that
        // distances between centres are.
        const double d = std::abs(distance[at]) / voxelMm;
        const bool within = std::round(d * d) <= r2;
        voxels += grow ? grid.inside[at] || within : grid.inside[at] && !within;
    }
    return resultOf(voxels, voxelMm, watch);
}

}  // namespace dfrecon
