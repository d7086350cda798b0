#pragma once
// The OpenCL C sources of kernels/*.cl, compiled into the binary so that the
// program never depends on files next to it at run time.
#include <string>
#include <string_view>
#include <vector>

namespace dfrecon::kernels {

struct KernelSource {
    std::string_view fileName;  // e.g. "closest_segment_2d.cl"
    std::string_view text;
};

/// All embedded sources, in file-name order.
const std::vector<KernelSource>& embeddedKernelSources();

/// The text of one embedded file; throws std::out_of_range naming the file
/// if it was not embedded.
std::string_view kernelSource(std::string_view fileName);

}  // namespace dfrecon::kernels
