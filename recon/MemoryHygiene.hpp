#pragma once
// When a reconstruction gives memory back, and why: one place for the steps
// that change no result but keep a large ROI's peak (and a structure set's
// resident memory) down. Each is named for the moment it is called.
#include <cstddef>

namespace dfrecon {

/// After the planes' fields: they ran in batches of many planes, and the
/// slabs' fields take one or two planes at a time, which the batches'
/// blocks in the kernel scratch pool (cl/HostScratch) do not serve (a kept
/// block serves requests of at least two thirds its size). Kept, they would
/// stay resident through the slabs: 90 MB for the head CT bone.
void releaseAfterPlaneFields();

/// After the slabs ran on helper threads (`helpers` > 0): the helpers' heap
/// arenas keep what the slabs freed, and the steps after run on this
/// thread and cannot reuse it.
void releaseAfterSlabThreads(std::size_t helpers);

/// After a ROI's last kernel: the blocks the scratch pool keeps for the
/// next call (92 MB after the head CT bone's fields and slabs) would stay
/// resident through the checks and smoothing, where a large ROI peaks. The
/// next ROI faults its blocks in again, a few milliseconds against its
/// seconds.
void releaseAfterKernels();

/// After a whole ROI: what it freed stays resident in the heap arena of the
/// thread that ran it (a worker of `--all`, a slab helper), where the next
/// ROI on another thread cannot reuse it (the head CT's three ROIs on two
/// workers held BODY's and AIRWAY's freed arrays through BONE's peak).
void releaseAfterRoi();

}  // namespace dfrecon
