#pragma once
// The OpenCL runtime a test program's tests share: PoCL's CPU device, made
// on first use (a runtime per test would build the kernels again each time).
#include "cl/Runtime.hpp"

namespace dfrecon {

inline ocl::Runtime& cpuRuntime() {
    static ocl::Runtime instance("cpu");
    return instance;
}

}  // namespace dfrecon
