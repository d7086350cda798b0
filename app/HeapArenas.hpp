#pragma once
// How many heaps glibc's malloc keeps for a multi-threaded dfrecon process.
// glibc gives threads that allocate at the same time arenas of their own, up
// to eight per core, and memory freed in one arena serves only the threads
// that later allocate from it. dfrecon's ROI workers, slab helpers and
// OpenCL threads come and go, so each of many arenas kept its own high-water
// mark: the head CT's three ROIs (`dfrecon-bench structure-set`, two
// workers) peaked at 450-510 MiB with the default and at 420-490 MiB with
// one arena per core (MALLOC_ARENA_MAX=2 on this 2-core machine), CPU time
// paired 1.05 and 1.00 (medians of two farm-bench calls, 2026-11-30).
#include <algorithm>
#include <cstdlib>
#include <thread>

#include "geometry/GlibcHeap.hpp"

#if defined(DFRECON_GLIBC_HEAP)
#include <malloc.h>
#endif

namespace dfrecon::app {

/// One malloc arena per core (glibc's heap only: geometry/GlibcHeap;
/// elsewhere nothing), unless the user set MALLOC_ARENA_MAX. Call first in
/// main, before any thread starts.
inline void oneHeapArenaPerCore() {
#if defined(DFRECON_GLIBC_HEAP)
    if (std::getenv("MALLOC_ARENA_MAX")) return;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    mallopt(M_ARENA_MAX, int(cores));
#endif
}

}  // namespace dfrecon::app
