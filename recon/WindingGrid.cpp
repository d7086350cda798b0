#include "recon/WindingGrid.hpp"

#include "cl/DeviceBuffer.hpp"

namespace dfrecon {

std::vector<int> windingGrid(ocl::Runtime& runtime, const std::vector<Polygon>& contours,
                             const SliceGrid& grid) {
    std::vector<cl_float4> segments;
    for (const Polygon& polygon : contours)
        for (std::size_t k = 0; k < polygon.size(); ++k) {
            const Point2 a = polygon[k] - grid.originMm;
            const Point2 b = polygon[(k + 1) % polygon.size()] - grid.originMm;
            segments.push_back({{float(a.x), float(a.y), float(b.x), float(b.y)}});
        }
    ocl::DeviceBuffer<cl_float4> segmentBuffer(runtime, segments);
    ocl::DeviceBuffer<cl_int> windingBuffer(runtime, grid.pixelCount(), CL_MEM_WRITE_ONLY);

    cl::Kernel kernel = runtime.kernel({"winding_number.cl"}, "winding_number_grid");
    try {
        kernel.setArg(0, segmentBuffer.get());
        kernel.setArg(1, cl_uint(segments.size()));
        kernel.setArg(2, cl_float(grid.pixelMm));
        kernel.setArg(3, cl_uint(grid.width));
        kernel.setArg(4, cl_uint(grid.height));
        kernel.setArg(5, windingBuffer.get());
        // Global size padded to 16 for GPU-friendly shapes; the kernel skips
        // the padding. The runtime picks the work-group size.
        runtime.queue().enqueueNDRangeKernel(
            kernel, cl::NullRange,
            cl::NDRange(ocl::roundUp(std::size_t(grid.width), 16),
                        ocl::roundUp(std::size_t(grid.height), 16)));
    } catch (const cl::Error& e) {
        throw ocl::toClError(e, "winding_number_grid");
    }
    const std::vector<cl_int> result = windingBuffer.download(runtime);
    return std::vector<int>(result.begin(), result.end());
}

std::vector<int> windingGridReference(const std::vector<Polygon>& contours, const SliceGrid& grid) {
    std::vector<int> winding(grid.pixelCount(), 0);
    for (int j = 0; j < grid.height; ++j)
        for (int i = 0; i < grid.width; ++i) {
            const Point2 p = grid.pixelCentre(i, j);
            int w = 0;
            for (const Polygon& polygon : contours) w += windingNumber(p, polygon);
            winding[std::size_t(j) * std::size_t(grid.width) + std::size_t(i)] = w;
        }
    return winding;
}

}  // namespace dfrecon
