#pragma once
// The one place that includes the OpenCL C++ bindings, so every target sees
// the same version macros (set by the dfrecon_opencl CMake target).
#if defined(__GNUC__)
#pragma GCC system_header
#endif
#include <CL/opencl.hpp>
