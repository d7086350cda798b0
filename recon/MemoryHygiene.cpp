#include "recon/MemoryHygiene.hpp"

#include "geometry/GlibcHeap.hpp"

#if defined(DFRECON_GLIBC_HEAP)
#include <malloc.h>
#endif

#include "cl/HostScratch.hpp"

namespace dfrecon {

namespace {

/// Gives the freed heap back to the system when more than 64 MB of it is
/// free (mallinfo2 counts every thread's arena); below that, the next steps
/// fault in again what was given back for less than it saves (the Brodmann
/// set's 41 small ROIs: a fifth more CPU trimmed after every ROI, 2 % more
/// trimmed after every ROI's slabs). O(free heap) when it trims.
void giveBackMuchFreedHeap() {
#if defined(DFRECON_GLIBC_HEAP)
    constexpr std::size_t kTrimFreedFromBytes = std::size_t(64) << 20;
    if (mallinfo2().fordblks > kTrimFreedFromBytes) malloc_trim(0);
#endif
}

}  // namespace

void releaseAfterPlaneFields() {
    ocl::releaseScratch();
}

void releaseAfterSlabThreads(std::size_t helpers) {
    if (helpers > 0) giveBackMuchFreedHeap();
}

void releaseAfterKernels() {
    ocl::releaseScratch();
}

void releaseAfterRoi() {
    giveBackMuchFreedHeap();
}

}  // namespace dfrecon
