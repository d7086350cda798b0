#pragma once
// The floating-point type the kernels compute in, chosen in one place: REAL
// in kernels/real.cl is double where the device has fp64, else float, and
// the host's buffers hold the matching cl_double/cl_float types.
#include <string>
#include <type_traits>

#include "cl/OpenCL.hpp"

namespace dfrecon::ocl {

/// Build options that define the kernels' REAL: "-DREAL=double
/// -DREAL_IS_DOUBLE" (fp64 enabled) or "-DREAL=float".
inline std::string realOptions(bool doublePrecision) {
    return doublePrecision ? "-DREAL=double -DREAL_IS_DOUBLE" : "-DREAL=float";
}

/// The same, for the host type `Real` (cl_double or cl_float) of the buffers.
template <class Real>
std::string realOptions() {
    static_assert(std::is_same_v<Real, cl_double> || std::is_same_v<Real, cl_float>);
    return realOptions(std::is_same_v<Real, cl_double>);
}

/// Calls run(Real{}, Real4{}) with (cl_double, cl_double4) when
/// `doublePrecision`, else with (cl_float, cl_float4), and returns what it
/// returns: host code written once as a generic lambda over the device's
/// precision, which is known only at run time.
template <class Run>
decltype(auto) withRealTypes(bool doublePrecision, Run&& run) {
    if (doublePrecision) return run(cl_double{}, cl_double4{});
    return run(cl_float{}, cl_float4{});
}

}  // namespace dfrecon::ocl
