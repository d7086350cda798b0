#pragma once
// Host memory for the tables and lists that kernels read and write, kept
// from one call to the next. A large block that goes back to the C heap is
// often returned to the system (glibc trims the heap's top and unmaps large
// blocks), so the next call faults the same amount in again, page by page:
// on the bench's 10 000-segment field that was up to 500 faults and 0.8 ms
// of a 5.5 ms call (docs/fields.md). Blocks lent from here stay mapped.
#include <cstddef>
#include <type_traits>
#include <vector>

namespace dfrecon::ocl {

/// Blocks smaller than this come from the C++ heap as usual: they are
/// cheap to fault in, and the heap reuses them.
constexpr std::size_t kScratchPooledFrom = std::size_t(64) << 10;
/// At most this many bytes of free blocks are kept; a block given back
/// beyond it is freed at once.
constexpr std::size_t kScratchKeptBytes = std::size_t(128) << 20;

/// At least `bytes` of host memory aligned to 64 bytes: a kept block if one
/// fits (no more than half as large again), else a new one. Thread-safe;
/// O(log kept blocks). Throws std::bad_alloc.
void* takeScratch(std::size_t bytes);
/// Gives back a block from takeScratch(bytes) with the same `bytes`.
void giveScratch(void* block, std::size_t bytes) noexcept;
/// Bytes of free blocks kept now (for tests and reports).
std::size_t keptScratchBytes();
/// Frees every kept block (for a long-lived process that is done with
/// kernels); blocks still lent stay valid.
void releaseScratch() noexcept;

/// A standard allocator over takeScratch/giveScratch, stateless, so
/// containers that use it move and swap as with std::allocator.
template <class T>
struct ScratchAllocator {
    using value_type = T;
    ScratchAllocator() = default;
    template <class U>
    ScratchAllocator(const ScratchAllocator<U>&) noexcept {}
    T* allocate(std::size_t count) { return static_cast<T*>(takeScratch(count * sizeof(T))); }
    void deallocate(T* block, std::size_t count) noexcept { giveScratch(block, count * sizeof(T)); }
    template <class U>
    bool operator==(const ScratchAllocator<U>&) const noexcept {
        return true;
    }
    template <class U>
    bool operator!=(const ScratchAllocator<U>&) const noexcept {
        return false;
    }
};

/// `count` uninitialised elements of a trivial type in scratch memory,
/// given back when it goes: for buffers a kernel fills, where a vector
/// would first write every element.
template <class T>
class ScratchArray {
    static_assert(std::is_trivially_default_constructible_v<T> &&
                  std::is_trivially_destructible_v<T>);

  public:
    explicit ScratchArray(std::size_t count)
        : data_(count ? static_cast<T*>(takeScratch(count * sizeof(T))) : nullptr), count_(count) {}
    ~ScratchArray() { giveScratch(data_, count_ * sizeof(T)); }
    ScratchArray(const ScratchArray&) = delete;
    ScratchArray& operator=(const ScratchArray&) = delete;

    T* data() const { return data_; }
    std::size_t size() const { return count_; }

  private:
    T* data_;
    std::size_t count_;
};

/// A vector whose large buffers are kept for reuse (ScratchAllocator).
template <class T>
using ScratchVector = std::vector<T, ScratchAllocator<T>>;

}  // namespace dfrecon::ocl
