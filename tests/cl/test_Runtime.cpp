// Programs from embedded sources, the program cache, build logs and buffers.
#include <gtest/gtest.h>

#include <thread>

#include "cl/ClError.hpp"
#include "cl/DeviceBuffer.hpp"
#include "cl/Runtime.hpp"
#include "kernels/EmbeddedKernels.hpp"

using namespace dfrecon;
using namespace dfrecon::ocl;

TEST(Runtime, KernelSourcesAreEmbedded) {
    EXPECT_FALSE(kernels::embeddedKernelSources().empty());
    EXPECT_NE(kernels::kernelSource("closest_segment_2d.cl").find("tile_candidates"),
              std::string_view::npos);
    EXPECT_THROW(kernels::kernelSource("nope.cl"), std::out_of_range);
}

TEST(Runtime, BuildsAndCachesPrograms) {
    Runtime runtime("cpu");
    // The planar field program: its shared prelude first.
    const std::vector<std::string> sources{"real.cl", "closest_segment_2d.cl"};
    const cl::Program& first = runtime.program(sources);
    const cl::Program& second = runtime.program(sources);
    EXPECT_EQ(first(), second());
    EXPECT_NO_THROW(runtime.kernel(sources, "signed_distance_2d"));
    EXPECT_THROW(runtime.kernel(sources, "no_such_kernel"), ClError);
    EXPECT_THROW(runtime.program({"missing.cl"}), ClError);
}

// Workers' runtimes: one context, a queue each, each program built once.
TEST(Runtime, RuntimesSharingAContextShareProgramsNotQueues) {
    Runtime first("cpu");
    Runtime second(first, ShareContext{});
    EXPECT_EQ(first.context()(), second.context()());
    EXPECT_NE(first.queue()(), second.queue()());
    const std::vector<std::string> sources{"real.cl", "closest_segment_2d.cl"};
    EXPECT_EQ(second.program(sources)(), first.program(sources)());
    EXPECT_NO_THROW(first.kernel(sources, "signed_distance_2d"));
    // Both queues run work at once, from two threads, each its own.
    const cl::Program program = first.buildProgram(
        "__kernel void twice(__global const int* in, __global int* out) {"
        "  out[get_global_id(0)] = 2 * in[get_global_id(0)]; }",
        "twice.cl");
    auto run = [&](Runtime& runtime, int base, std::vector<cl_int>& output) {
        std::vector<cl_int> input(4096);
        for (std::size_t i = 0; i < input.size(); ++i) input[i] = base + int(i);
        const DeviceBuffer<cl_int> in(runtime, input);
        DeviceBuffer<cl_int> out(runtime, input.size());
        cl::Kernel kernel(program, "twice");
        kernel.setArg(0, in.get());
        kernel.setArg(1, out.get());
        for (int repeat = 0; repeat < 20; ++repeat)
            runtime.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(input.size()),
                                                 cl::NDRange(64));
        output = out.download(runtime);
    };
    std::vector<cl_int> a, b;
    std::thread other([&] { run(second, 1000, b); });
    run(first, 0, a);
    other.join();
    ASSERT_EQ(a.size(), 4096u);
    ASSERT_EQ(b.size(), 4096u);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i], 2 * int(i));
        EXPECT_EQ(b[i], 2 * (1000 + int(i)));
    }
}

TEST(Runtime, BuildFailureShowsTheLog) {
    Runtime runtime("cpu");
    try {
        runtime.buildProgram("__kernel void broken(__global int* x) { x[0] = undeclared_name; }",
                             "broken.cl");
        FAIL();
    } catch (const ClError& e) {
        const std::string message = e.what();
        EXPECT_EQ(e.call(), "clBuildProgram");
        EXPECT_NE(message.find("CL_BUILD_PROGRAM_FAILURE"), std::string::npos) << message;
        EXPECT_NE(message.find("broken.cl"), std::string::npos) << message;
        EXPECT_NE(message.find("undeclared_name"), std::string::npos) << message;
    }
}

TEST(Runtime, DeviceBufferRoundTripsAndChecksSizes) {
    Runtime runtime("cpu");
    const std::vector<cl_int> data = {1, -2, 3, 1 << 30};
    DeviceBuffer<cl_int> buffer(runtime, data, CL_MEM_READ_WRITE);
    EXPECT_EQ(buffer.size(), 4u);
    EXPECT_EQ(buffer.download(runtime), data);
    EXPECT_THROW(buffer.upload(runtime, {1, 2}), std::length_error);
    DeviceBuffer<cl_int> moved = std::move(buffer);
    EXPECT_EQ(moved.download(runtime), data);
    DeviceBuffer<cl_float> empty(runtime, 0);
    EXPECT_TRUE(empty.download(runtime).empty());
}

// A buffer over host memory: what a kernel writes is in the host vector once
// mapForHost returns, on the CPU device (shared memory) as on any other.
TEST(Runtime, DeviceBufferOverHostMemorySeesKernelWrites) {
    Runtime runtime("cpu");
    const cl::Program program = runtime.buildProgram(
        "__kernel void twice(__global const int* in, __global int* out) {"
        "  out[get_global_id(0)] = 2 * in[get_global_id(0)]; }",
        "twice.cl");
    const std::vector<cl_int> input = {1, -2, 3, 1 << 20, 7};
    std::vector<cl_int> output(input.size(), 0);
    const DeviceBuffer<cl_int> in(runtime, input);
    const auto out = DeviceBuffer<cl_int>::over(runtime, output.data(), output.size());
    cl::Kernel kernel(program, "twice");
    kernel.setArg(0, in.get());
    kernel.setArg(1, out.get());
    runtime.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(input.size()));
    out.mapForHost(runtime, true);
    EXPECT_EQ(output, (std::vector<cl_int>{2, -4, 6, 1 << 21, 14}));
    // Empty host data makes a valid (one-element) buffer either way.
    EXPECT_EQ(DeviceBuffer<cl_int>(runtime, std::vector<cl_int>{}).size(), 0u);
    EXPECT_EQ(DeviceBuffer<cl_int>::over(runtime, nullptr, 0).size(), 0u);
}

// A buffer for reading host data: kernels see the vector's values; on the
// CPU device the buffer is the vector's own memory (no copy), so a change
// made after the buffer was created still reaches the kernel. A QueueDrain
// going out of scope leaves nothing running on its queue.
TEST(Runtime, DeviceBufferReadingIsTheHostMemoryOnTheCpu) {
    Runtime runtime("cpu");
    const cl::Program program = runtime.buildProgram(
        "__kernel void twice(__global const int* in, __global int* out) {"
        "  out[get_global_id(0)] = 2 * in[get_global_id(0)]; }",
        "twice.cl");
    std::vector<cl_int> input = {1, -2, 3};
    std::vector<cl_int> output(input.size(), 0);
    const auto in = DeviceBuffer<cl_int>::reading(runtime, input);
    const auto out = DeviceBuffer<cl_int>::over(runtime, output.data(), output.size());
    input[1] = 5;
    {
        const QueueDrain drain(runtime.queue());
        cl::Kernel kernel(program, "twice");
        kernel.setArg(0, in.get());
        kernel.setArg(1, out.get());
        runtime.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(input.size()));
    }
    out.mapForHost(runtime, true);
    EXPECT_EQ(output, (std::vector<cl_int>{2, 10, 6}));
    EXPECT_EQ(DeviceBuffer<cl_int>::reading(runtime, std::vector<cl_int>{}).size(), 0u);
}
