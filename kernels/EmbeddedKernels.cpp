#include "kernels/EmbeddedKernels.hpp"

#include <stdexcept>

namespace dfrecon::kernels {

std::string_view kernelSource(std::string_view fileName) {
    for (const KernelSource& source : embeddedKernelSources())
        if (source.fileName == fileName) return source.text;
    throw std::out_of_range("no embedded OpenCL source named '" + std::string(fileName) + "'");
}

}  // namespace dfrecon::kernels
