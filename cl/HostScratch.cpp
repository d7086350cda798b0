#include "cl/HostScratch.hpp"

#include <map>
#include <mutex>
#include <new>
#include <unordered_map>

namespace dfrecon::ocl {

namespace {

constexpr std::align_val_t kAlignment{64};

// Free blocks by size, and the size of each block lent out (a kept block
// may be larger than the request it serves).
struct Kept {
    std::mutex mutex;
    std::multimap<std::size_t, void*> free;
    std::unordered_map<void*, std::size_t> lent;
    std::size_t freeBytes = 0;
};

Kept& kept() {
    // Never destroyed: containers with static storage may give blocks back
    // after it would have been.
    static Kept* const instance = new Kept;
    return *instance;
}

}  // namespace

void* takeScratch(std::size_t bytes) {
    if (bytes < kScratchPooledFrom) return ::operator new(bytes, kAlignment);
    Kept& k = kept();
    {
        const std::lock_guard<std::mutex> lock(k.mutex);
        const auto fit = k.free.lower_bound(bytes);
        if (fit != k.free.end() && fit->first <= bytes + bytes / 2) {
            void* block = fit->second;
            k.lent.emplace(block, fit->first);
            k.freeBytes -= fit->first;
            k.free.erase(fit);
            return block;
        }
    }
    void* block = ::operator new(bytes, kAlignment);
    try {
        const std::lock_guard<std::mutex> lock(k.mutex);
        k.lent.emplace(block, bytes);
    } catch (...) {
        ::operator delete(block, kAlignment);
        throw;
    }
    return block;
}

void giveScratch(void* block, std::size_t bytes) noexcept {
    if (!block) return;
    if (bytes < kScratchPooledFrom) {
        ::operator delete(block, kAlignment);
        return;
    }
    Kept& k = kept();
    std::size_t size = bytes;
    {
        const std::lock_guard<std::mutex> lock(k.mutex);
        const auto lent = k.lent.find(block);
        if (lent != k.lent.end()) {
            size = lent->second;
            k.lent.erase(lent);
        }
        if (k.freeBytes + size <= kScratchKeptBytes) {
            try {
                k.free.emplace(size, block);
                k.freeBytes += size;
                return;
            } catch (...) {
                // No room to note it: free it below instead.
            }
        }
    }
    ::operator delete(block, kAlignment);
}

std::size_t keptScratchBytes() {
    Kept& k = kept();
    const std::lock_guard<std::mutex> lock(k.mutex);
    return k.freeBytes;
}

void releaseScratch() noexcept {
    Kept& k = kept();
    std::multimap<std::size_t, void*> free;
    {
        const std::lock_guard<std::mutex> lock(k.mutex);
        free.swap(k.free);
        k.freeBytes = 0;
    }
    for (const auto& [size, block] : free) ::operator delete(block, kAlignment);
}

}  // namespace dfrecon::ocl
