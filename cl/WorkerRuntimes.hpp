#pragma once
// One OpenCL runtime per worker thread of a command that runs items at once
// (reconstruct --jobs, batch --jobs): a shared in-order queue would make each
// item wait for the others' kernels, so every worker gets its own queue on
// the same device, in one context, so that each program is built once for
// all workers.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cl/Runtime.hpp"

namespace dfrecon::ocl {

class WorkerRuntimes {
  public:
    /// Opens worker 0's runtime at once, so that a device that cannot be
    /// opened fails the command before any work (throws ClError).
    WorkerRuntimes(const std::string& deviceSpec, std::size_t workers)
        : runtimes_(std::max<std::size_t>(1, workers)) {
        runtimes_[0] = std::make_unique<Runtime>(deviceSpec);
    }

    /// Worker `worker`'s runtime, opened on its first use. Each worker asks
    /// for its own only, so workers need no lock. O(1) after the first call.
    Runtime& operator[](std::size_t worker) {
        if (!runtimes_[worker])
            runtimes_[worker] = std::make_unique<Runtime>(*runtimes_[0], ShareContext{});
        return *runtimes_[worker];
    }

    const Runtime& first() const { return *runtimes_[0]; }

  private:
    std::vector<std::unique_ptr<Runtime>> runtimes_;
};

}  // namespace dfrecon::ocl
