#include "recon/ParallelSlabs.hpp"

#include <atomic>
#include <chrono>
#include <mutex>

#include "geometry/CoreBudget.hpp"
#include "recon/SlabReconstructor.hpp"
#include "recon/StepSlabs.hpp"

namespace dfrecon {

std::size_t buildSlabs(ocl::Runtime& runtime, const SlabStack& stack,
                       const std::function<void(double)>& progress,
                       const std::function<void(std::size_t, BuiltSlab&&)>& append) {
    const std::size_t slabs = stack.layers.size() - 1;
    std::vector<BuiltSlab> built(slabs);
    std::mutex finishedMutex;
    std::vector<bool> finished(slabs, false);
    std::size_t finishedCount = 0;
    std::size_t appended = 0;  // slabs handed to `append`, by the calling thread only
    std::atomic<std::size_t> next{0};
    auto appendFinished = [&] {
        std::unique_lock<std::mutex> lock(finishedMutex);
        while (appended < slabs && finished[appended]) {
            BuiltSlab slab = std::move(built[appended]);
            lock.unlock();
            append(appended, std::move(slab));
            lock.lock();
            ++appended;
        }
    };
    auto work = [&](ocl::Runtime& queue, bool caller, const std::atomic<bool>& stop) {
        ReconstructionStats stats;
        SlabReconstructor slab(queue, stack.options, stack.grid, stats,
                               SurfaceBuilder(stack.contourPoints), stack.traits);
        for (std::size_t s; !stop && (s = next++) < slabs;) {
            stats = {};
            const auto start = std::chrono::steady_clock::now();
            slab.builder().setPiece(std::uint32_t(s + 1));
            const bool step = stack.options.interpolation == Interpolation::Smooth &&
                              stack.options.stepBetweenRepeats && isStepSlab(stack.layers, s) &&
                              slab.stepSlab(stack.layers[s], stack.layers[s + 1]);
            if (!step)
                slab.originalSlab(stack.layers[s], stack.layers[s + 1], stack.fields, s, s + 1);
            BuiltSlab out;
            out.part = slab.takePart(stack.contourPoints.size(), out.searched);
            out.stats = stats;
            out.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::size_t done = 0;
            {
                const std::lock_guard<std::mutex> lock(finishedMutex);
                built[s] = std::move(out);
                finished[s] = true;
                done = ++finishedCount;
            }
            if (!caller) continue;
            if (progress) progress(0.5 + 0.5 * double(done) / double(slabs + 1));
            appendFinished();
        }
    };
    const std::size_t helpers = runOnFreeCores(
        helpersFor(slabs, 2), [&](std::size_t worker, const std::atomic<bool>& stop) {
            if (worker == 0) return work(runtime, true, stop);
            ocl::Runtime own(runtime, ocl::ShareContext{});
            work(own, false, stop);
        });
    appendFinished();
    return helpers;
}

}  // namespace dfrecon
