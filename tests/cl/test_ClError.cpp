// Error messages name the OpenCL call and the code's symbolic name.
#include <gtest/gtest.h>

#include "cl/ClError.hpp"

using namespace dfrecon::ocl;

TEST(ClError, NamesCodes) {
    EXPECT_STREQ(errorName(CL_SUCCESS), "CL_SUCCESS");
    EXPECT_STREQ(errorName(CL_OUT_OF_RESOURCES), "CL_OUT_OF_RESOURCES");
    EXPECT_STREQ(errorName(CL_INVALID_KERNEL_NAME), "CL_INVALID_KERNEL_NAME");
    EXPECT_STREQ(errorName(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
    EXPECT_STREQ(errorName(-12345), "unknown OpenCL error");
}

TEST(ClError, MessageCarriesCallCodeAndDetail) {
    const ClError e("clCreateBuffer", CL_INVALID_BUFFER_SIZE, "allocating 0 bytes");
    EXPECT_EQ(e.call(), "clCreateBuffer");
    EXPECT_EQ(e.code(), CL_INVALID_BUFFER_SIZE);
    EXPECT_STREQ(e.what(),
                 "clCreateBuffer failed: CL_INVALID_BUFFER_SIZE (-61)\nallocating 0 bytes");
}

TEST(ClError, ConvertsBindingExceptions) {
    const ClError e = toClError(cl::Error(CL_DEVICE_NOT_FOUND, "clGetDeviceIDs"));
    EXPECT_EQ(e.call(), "clGetDeviceIDs");
    EXPECT_STREQ(e.what(), "clGetDeviceIDs failed: CL_DEVICE_NOT_FOUND (-1)");
}
