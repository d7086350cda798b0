#pragma once
// Errors of the OpenCL layer. Every message names the OpenCL call that failed
// and the symbolic name of its error code, e.g.
//   "clBuildProgram failed: CL_BUILD_PROGRAM_FAILURE (-11)".
#include <stdexcept>
#include <string>

#include "cl/OpenCL.hpp"

namespace dfrecon::ocl {

/// Symbolic name of an OpenCL error code ("CL_OUT_OF_RESOURCES"), or
/// "unknown OpenCL error" for codes outside the standard and KHR ranges.
const char* errorName(cl_int code);

/// Thrown for any failed OpenCL call or missing device/platform.
class ClError : public std::runtime_error {
  public:
    ClError(std::string call, cl_int code, const std::string& detail = {});
    /// For errors that are not a failed call (no device matches, ...).
    explicit ClError(const std::string& message);
    const std::string& call() const { return call_; }
    cl_int code() const { return code_; }

  private:
    std::string call_;
    cl_int code_ = CL_SUCCESS;
};

/// Converts the C++ bindings' exception into ours, keeping call and code.
ClError toClError(const cl::Error& error, const std::string& detail = {});

}  // namespace dfrecon::ocl
