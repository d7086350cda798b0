#pragma once
// A typed OpenCL buffer that owns its memory object (released on
// destruction, movable, not copyable) and knows its element count, so uploads
// and downloads cannot overrun it.
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "cl/ClError.hpp"
#include "cl/Runtime.hpp"

namespace dfrecon::ocl {

/// Waits for a queue's commands to finish when it goes out of scope, also
/// when an exception unwinds it: declared after the host memory that
/// kernels read or write (DeviceBuffer::over and ::reading), it keeps a
/// kernel from using that memory once it is freed. Errors while waiting are
/// dropped, as a destructor must not throw; the exception already on its
/// way says what went wrong.
class QueueDrain {
  public:
    explicit QueueDrain(cl::CommandQueue& queue) : queue_(queue) {}
    QueueDrain(const QueueDrain&) = delete;
    QueueDrain& operator=(const QueueDrain&) = delete;
    ~QueueDrain() {
        try {
            queue_.finish();
        } catch (...) {
        }
    }

  private:
    cl::CommandQueue& queue_;
};

template <class T>
class DeviceBuffer {
  public:
    DeviceBuffer() = default;

    /// Uninitialised device memory for `count` elements (at least one, as
    /// OpenCL forbids empty buffers).
    DeviceBuffer(Runtime& runtime, std::size_t count, cl_mem_flags flags = CL_MEM_READ_WRITE)
        : buffer_(allocate(runtime, flags, count, nullptr)), count_(count) {}

    /// Device memory holding a copy of `host`, copied at creation: no queue
    /// round trip, which costs more than the copy for the small tables most
    /// launches take.
    template <class Allocator>
    DeviceBuffer(Runtime& runtime, const std::vector<T, Allocator>& host,
                 cl_mem_flags flags = CL_MEM_READ_ONLY)
        // OpenCL takes the pointer as void*; with COPY_HOST_PTR it only reads.
        : buffer_(allocate(runtime, flags | CL_MEM_COPY_HOST_PTR, host.size(),
                           const_cast<T*>(host.data()))),
          count_(host.size()) {}

    /// Device memory over `host[0, count)` itself (CL_MEM_USE_HOST_PTR):
    /// devices that share host memory, as PoCL's CPU device does, write
    /// there with no copy; others keep a copy that mapForHost() brings back.
    /// `host` must stay allocated while the buffer lives.
    static DeviceBuffer over(Runtime& runtime, T* host, std::size_t count,
                             cl_mem_flags flags = CL_MEM_WRITE_ONLY) {
        DeviceBuffer buffer;
        buffer.buffer_ = allocate(runtime, flags | CL_MEM_USE_HOST_PTR, count, host);
        buffer.count_ = count;
        return buffer;
    }

    /// Device memory for kernels to read `host` from: on CPU devices the
    /// host memory itself (over(), read-only: PoCL took 150 µs to create a
    /// copy of 320 KB, measured alone), elsewhere a copy. `host` must stay
    /// allocated and unchanged while the buffer lives.
    template <class Allocator>
    static DeviceBuffer reading(Runtime& runtime, const std::vector<T, Allocator>& host) {
        if (runtime.device().kind != DeviceKind::Cpu) return DeviceBuffer(runtime, host);
        // OpenCL takes the pointer as void*; a read-only buffer only reads it.
        return over(runtime, const_cast<T*>(host.data()), host.size(), CL_MEM_READ_ONLY);
    }
    /// For a buffer made by over(): waits until the device's writes are in
    /// the host memory (a map for reading and its unmap; no copy where the
    /// memory is shared). With `blocking` false the map only joins the queue,
    /// for a later blocking call to wait on.
    void mapForHost(Runtime& runtime, bool blocking) const {
        if (count_ == 0) return;
        try {
            void* mapped = runtime.queue().enqueueMapBuffer(buffer_, blocking ? CL_TRUE : CL_FALSE,
                                                            CL_MAP_READ, 0, sizeof(T) * count_);
            runtime.queue().enqueueUnmapMemObject(buffer_, mapped);
        } catch (const cl::Error& e) {
            throw toClError(e);
        }
    }

    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;
    DeviceBuffer(DeviceBuffer&&) noexcept = default;
    DeviceBuffer& operator=(DeviceBuffer&&) noexcept = default;

    std::size_t size() const { return count_; }
    const cl::Buffer& get() const { return buffer_; }

    /// Blocking copy host → device; `host` must have size() elements.
    void upload(Runtime& runtime, const std::vector<T>& host) {
        if (host.size() != count_) throw std::length_error("DeviceBuffer::upload: size mismatch");
        if (count_ == 0) return;
        try {
            runtime.queue().enqueueWriteBuffer(buffer_, CL_TRUE, 0, sizeof(T) * count_,
                                               host.data());
        } catch (const cl::Error& e) {
            throw toClError(e);
        }
    }

    /// Blocking copy device → host of all elements.
    std::vector<T> download(Runtime& runtime) const {
        std::vector<T> host(count_);
        if (count_ == 0) return host;
        try {
            runtime.queue().enqueueReadBuffer(buffer_, CL_TRUE, 0, sizeof(T) * count_, host.data());
        } catch (const cl::Error& e) {
            throw toClError(e);
        }
        return host;
    }

  private:
    /// A buffer of `count` elements (one when empty, without `host`, as
    /// OpenCL forbids empty buffers); `host` as the flags say.
    static cl::Buffer allocate(Runtime& runtime, cl_mem_flags flags, std::size_t count, T* host) {
        if (count == 0) {
            flags &= ~cl_mem_flags(CL_MEM_COPY_HOST_PTR | CL_MEM_USE_HOST_PTR);
            host = nullptr;
        }
        try {
            return cl::Buffer(runtime.context(), flags, sizeof(T) * std::max<std::size_t>(count, 1),
                              host);
        } catch (const cl::Error& e) {
            throw toClError(e, "allocating " + std::to_string(sizeof(T) * count) + " bytes");
        }
    }

    cl::Buffer buffer_;
    std::size_t count_ = 0;
};

}  // namespace dfrecon::ocl
