#pragma once
// One OpenCL device ready for work: its context, an in-order queue, and a
// cache of programs built from the embedded kernels/*.cl sources.
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "cl/Devices.hpp"
#include "cl/OpenCL.hpp"

namespace dfrecon::ocl {

/// Asks Runtime for a second queue on a runtime's context (below).
struct ShareContext {};

class Runtime {
  public:
    /// Opens the device chosen by chooseDevice(spec). Throws ClError.
    explicit Runtime(const std::string& deviceSpec = {});
    explicit Runtime(DeviceInfo device);
    /// A runtime on `other`'s device and context with an in-order queue of
    /// its own (a worker beside other workers: no item waits for another's
    /// kernels), sharing its programs: each is built once however many
    /// workers use it (a build costs a tenth of a second or more, even
    /// from PoCL's cache). Thread-safe against `other`'s use. Throws
    /// ClError.
    Runtime(Runtime& other, ShareContext);

    const DeviceInfo& device() const { return device_; }
    cl::Context& context() { return context_; }
    cl::CommandQueue& queue() { return queue_; }

    /// The program made of the named embedded sources, concatenated in order
    /// (shared helpers first), built once per runtime and options string.
    /// A failed build throws ClError whose message carries the build log.
    const cl::Program& program(const std::vector<std::string>& sourceFiles,
                               const std::string& options = {});

    /// Builds OpenCL C `source` (not cached); `label` names it in errors.
    /// A failed build throws ClError whose message carries the build log.
    cl::Program buildProgram(const std::string& source, const std::string& label,
                             const std::string& options = {});

    /// A fresh kernel object (kernels hold argument state, so callers get
    /// their own) from program(sourceFiles).
    cl::Kernel kernel(const std::vector<std::string>& sourceFiles, const std::string& name);

  private:
    // Built programs by sources and options, shared by the runtimes of
    // one context.
    struct ProgramCache {
        std::mutex mutex;
        std::map<std::string, cl::Program> programs;
    };

    DeviceInfo device_;
    cl::Context context_;
    cl::CommandQueue queue_;
    std::shared_ptr<ProgramCache> programs_ = std::make_shared<ProgramCache>();
};

/// The work-group size of every 1D launch, always given explicitly: PoCL
/// builds one work-group function per local size, and a size left to the
/// runtime follows the global size, so launches of ever new sizes (the
/// recursion's windows, an eikonal front) would each compile again.
inline constexpr std::size_t kGroupSize1D = 64;

/// Rounds `n` up to a multiple of `multiple` (global sizes must be multiples
/// of the work-group size).
inline std::size_t roundUp(std::size_t n, std::size_t multiple) {
    return (n + multiple - 1) / multiple * multiple;
}

}  // namespace dfrecon::ocl
