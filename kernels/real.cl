// The floating-point type of every kernel that computes in REAL, defined once:
// double where the device has fp64, else float. The host chooses it with
// ocl::realOptions (cl/Precision.hpp), which passes -DREAL=double
// -DREAL_IS_DOUBLE or -DREAL=float; programs list this file first.
#ifndef REAL
#define REAL float
#endif
#if defined(REAL_IS_DOUBLE)
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
#define CONCAT(a, b) CONCAT_(a, b)
#define CONCAT_(a, b) a##b
#define REAL2 CONCAT(REAL, 2)
#define REAL4 CONCAT(REAL, 4)
