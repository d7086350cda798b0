#include "recon/Reconstruction.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>

#include "contours/PlaneGaps.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/StackedMeshCheck.hpp"
#include "geometry/TouchSeparation.hpp"
#include "recon/ContourSimplification.hpp"
#include "recon/LoftSmoothing.hpp"
#include "recon/MemoryHygiene.hpp"
#include "recon/ParallelSlabs.hpp"
#include "recon/PixelLattice.hpp"
#include "recon/ScopedSeconds.hpp"
#include "recon/SlabReconstructor.hpp"

// The driver: one run of planes (an ROI without empty planes between its
// contours) goes through five phases over one RunState, each reading what
// the ones before left there:
//   prepareSlices       contours simplified within their bound, touches opened
//   computePlaneFields  every plane's exact signed field and nearest ids
//   buildPieces         the bottom cap, the slabs (recon/ParallelSlabs), the top cap
//   checkAndRepair      the whole surface checked as floats, broken pieces closed again
//   smoothPieces        smooth mode: strips bent onto the interpolant, slab volumes
// reconstructRuns joins the runs of an ROI with empty planes.

namespace dfrecon {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// How far apart the points where contours of one plane touch are opened: a
// couple of micrometres, far below any contouring accuracy, yet many float
// steps at patient coordinates, so the opening survives a float mesh file.
constexpr double kTouchGapMm = 2e-3;

void addSlabStats(ReconstructionStats& into, const ReconstructionStats& slab) {
    into.strips += slab.strips;
    into.slidStrips += slab.slidStrips;
    into.rejectedStrips += slab.rejectedStrips;
    into.recursions += slab.recursions;
    into.deepestLevel = std::max(into.deepestLevel, slab.deepestLevel);
    into.limitClosings += slab.limitClosings;
    into.caps += slab.caps;
    into.fallbackSlabs += slab.fallbackSlabs;
    into.stepSlabs += slab.stepSlabs;
    into.fieldsSeconds += slab.fieldsSeconds;
    into.medialSeconds += slab.medialSeconds;
}

/// The options as this ROI reads them: a DICOM slab thickness says how far
/// each contour reaches along the normal, so the end caps go half of it
/// beyond the end contours unless the caller set the offset.
ReconstructionOptions optionsFor(const Roi& roi, const ReconstructionOptions& requested) {
    ReconstructionOptions options = requested;
    if (options.capOffsetMm < 0 && roi.slabThicknessMm > 0)
        options.capOffsetMm = 0.5 * roi.slabThicknessMm;
    if (options.maxDepth < 0) throw std::invalid_argument("reconstruct: max depth must be >= 0");
    return options;
}

/// What the phases of reconstructWithin hand on to each other, in the order
/// they fill it. The reconstructor reads the options, the grid and the
/// stats in place, so a RunState is made where it stays.
struct RunState {
    RunState(const Roi& roi, const ReconstructionOptions& requested)
        : roi(roi), options(optionsFor(roi, requested)) {}
    RunState(const RunState&) = delete;
    RunState& operator=(const RunState&) = delete;

    const Roi& roi;
    const ReconstructionOptions options;
    Reconstruction result;  // its stats filled by every phase
    // prepareSlices: the planes with contours, simplified, touches opened.
    std::vector<Slice> slices;
    // computePlaneFields: slice s's field is slice s of `fields`.
    SliceGrid grid;
    SliceFields fields;
    // buildPieces: pieces 0 (the bottom cap), s + 1 (the slab above slice
    // s) and topCap(); the layers' points are the builder's first
    // `contourVertices`, which never move.
    std::optional<SlabReconstructor> reconstructor;
    PlaneSections planes;     // the slices' net areas, once slices are prepared
    bool fromVoxels = false;  // contours on a pixel lattice (recon/PixelLattice)
    std::deque<Layer> layers;
    std::size_t contourVertices = 0;
    // checkAndRepair: the planes and loops the checks read.
    PieceStack stack;

    std::uint32_t topCap() const { return std::uint32_t(slices.size()); }
    SurfaceBuilder& builder() { return reconstructor->builder(); }

    /// How far the cap on slice `s` reaches up or down from its plane: the
    /// options' offset, or a share of the gap to the neighbouring plane (a
    /// lone plane stands for the image planes' spacing, as its contour
    /// volume counts it, 1 mm when nothing says what that is).
    CapReach capReach(std::size_t s, bool up) const {
        double gapMm = 0;
        if (slices.size() > 1) {
            gapMm = std::fabs(slices[s].zMm - slices[up ? s - 1 : s + 1].zMm);
        } else {
            const SpacingStats spacing = spacingOf(roi);
            gapMm = spacing.meanMm > 0              ? spacing.meanMm
                    : lonePlaneThicknessMm(roi) > 0 ? lonePlaneThicknessMm(roi)
                                                    : kUnknownLonePlaneThicknessMm;
        }
        return {up, capOffsetMm(options.capOffsetMm, gapMm, false), fromVoxels};
    }
    CapReach bottomReach() const { return capReach(0, false); }
    CapReach topReach() const { return capReach(slices.size() - 1, true); }
};

/// Phase 1: the planes with contours, each simplified within
/// options.contourErrorMm and with touching contours opened.
void prepareSlices(RunState& run) {
    ReconstructionStats& stats = run.result.stats;
    const ScopedSeconds timer(stats.simplifySeconds);
    for (const Slice& s : run.roi.slices) {
        if (s.contours.empty()) continue;
        Slice slice{s.zMm, {}};
        if (run.options.contourErrorMm > 0) {
            for (SimplifiedContour& c : simplifySlice(s.contours, run.options.contourErrorMm))
                slice.contours.push_back(std::move(c.points));
        } else {
            slice.contours = s.contours;
        }
        stats.touchesOpened += separateTouchingContours(slice.contours, kTouchGapMm);
        for (const Polygon& c : slice.contours) stats.contourPoints += c.size();
        run.slices.push_back(std::move(slice));
    }
    if (run.slices.empty())
        throw std::invalid_argument("ROI '" + run.roi.name + "' has no contours");
    stats.slices = run.slices.size();
    stats.slabs = run.slices.size() - 1;
}

/// Phase 2: every plane's exact field on one grid (progress 0 to 0.5).
void computePlaneFields(ocl::Runtime& runtime, RunState& run,
                        const std::function<void(double)>& progress) {
    ReconstructionStats& stats = run.result.stats;
    run.grid = gridForSlices(run.slices, run.options.pixelMm, kReconstructionGridPixels);
    stats.pixelMm = run.grid.pixelMm;
    {
        const ScopedSeconds timer(stats.fieldsSeconds);
        run.fields = computeSliceFields(
            runtime, run.slices, run.grid,
            [&](double f) {
                if (progress) progress(0.5 * f);
            },
            run.options.kernel);
    }
    releaseAfterPlaneFields();
}

/// Phase 3: the pieces, each checked on its own as it is built: the bottom
/// cap, the slabs on the free cores appended in order (progress 0.5 to 1),
/// the top cap.
void buildPieces(ocl::Runtime& runtime, RunState& run,
                 const std::function<void(double)>& progress) {
    ReconstructionStats& stats = run.result.stats;
    const auto start = Clock::now();
    const double fieldsBefore = stats.fieldsSeconds;
    run.planes = sectionsOf(run.slices);
    run.fromVoxels = followsPixelLattice(run.roi.slices);
    run.reconstructor.emplace(runtime, run.options, run.grid, stats, SurfaceBuilder{},
                              StackTraits{&run.planes, run.fromVoxels});
    SurfaceBuilder& builder = run.builder();
    for (const Slice& s : run.slices) run.layers.push_back(makeLayer(builder, s.zMm, s.contours));
    run.contourVertices = builder.soup().points.size();
    builder.setPiece(0);
    run.reconstructor->capLayer(run.layers[0], run.bottomReach(), run.fields, 0);
    // The caps' own stats are the main reconstructor's; the slabs' come
    // with them.
    const auto slabsStart = Clock::now();
    double slabThreadSeconds = 0;
    const std::vector<Vec3> contourPoints(
        builder.soup().points.begin(),
        builder.soup().points.begin() + std::ptrdiff_t(run.contourVertices));
    const std::size_t helpers =
        buildSlabs(runtime,
                   {run.options, run.grid, run.layers, run.fields, contourPoints,
                    StackTraits{&run.planes, run.fromVoxels}},
                   progress, [&](std::size_t s, BuiltSlab&& slab) {
                       builder.appendPart(std::move(slab.part));
                       if (slab.searched) run.reconstructor->markSearched(std::uint32_t(s + 1));
                       addSlabStats(stats, slab.stats);
                       slabThreadSeconds += slab.seconds;
                   });
    const double slabsWallSeconds = secondsSince(slabsStart);
    releaseAfterSlabThreads(helpers);
    builder.setPiece(run.topCap());
    run.reconstructor->capLayer(run.layers.back(), run.topReach(), run.fields,
                                run.slices.size() - 1);
    releaseAfterKernels();
    // The slabs' seconds count per thread, so the stages can add up to more
    // than the wall time; fields and axes inside are counted as theirs.
    stats.triangulationSeconds = secondsSince(start) - slabsWallSeconds + slabThreadSeconds -
                                 (stats.fieldsSeconds - fieldsBefore) - stats.medialSeconds;
}

/// Closes the pieces holding a defective triangle of the last check again
/// the guaranteed way (prism caps, prism slabs), and checks what changed.
void closeBrokenPiecesAgain(RunState& run) {
    MeshCheckReport& check = run.result.check;
    SurfaceBuilder& builder = run.builder();
    std::vector<bool> broken(run.slices.size() + 1, false);
    for (std::size_t t : check.defectiveTriangles) broken[builder.pieceOf(t)] = true;
    builder.dropPieces(broken);
    // Every pair of the triangles kept was clean (both triangles of a
    // meeting pair are dropped), so only the new pieces' triangles are
    // searched, unless the check stopped counting.
    const std::size_t kept = builder.triangleCount();
    for (std::uint32_t p = 0; p < broken.size(); ++p) {
        if (!broken[p]) continue;
        ++run.result.stats.repairedPieces;
        builder.setPiece(p);
        if (p == 0)
            run.reconstructor->guaranteedCapLayer(run.layers[0], run.bottomReach(), run.fields, 0);
        else if (p == run.topCap())
            run.reconstructor->guaranteedCapLayer(run.layers.back(), run.topReach(), run.fields,
                                                  run.slices.size() - 1);
        else
            run.reconstructor->closeSlabByPrisms(run.layers[p - 1], run.layers[p]);
    }
    builder.roundPointsToFloat();
    if (check.intersectingPairsCapped) {
        check = checkMesh(builder.soup());
    } else {
        std::vector<std::size_t> rebuilt(builder.triangleCount() - kept);
        std::iota(rebuilt.begin(), rebuilt.end(), kept);
        check = checkMeshNear(builder.soup(), rebuilt);
    }
}

/// Where the surface is still broken, between which planes (open ends are
/// what CapMode::None asks for).
void reportBrokenPieces(RunState& run) {
    Reconstruction& result = run.result;
    const std::vector<Slice>& slices = run.slices;
    std::vector<bool> reported(slices.size() + 1, run.options.cap == CapMode::None);
    for (std::size_t t : result.check.defectiveTriangles) {
        const std::uint32_t p = run.builder().pieceOf(t);
        if (reported[p]) continue;
        reported[p] = true;
        const double below =
            p == 0 ? slices[0].zMm - run.bottomReach().offsetMm : slices[p - 1].zMm;
        const double above =
            p == run.topCap() ? slices.back().zMm + run.topReach().offsetMm : slices[p].zMm;
        result.brokenPieces.push_back({below, above});
    }
    std::sort(result.brokenPieces.begin(), result.brokenPieces.end());
}

/// Phase 4: whatever the pieces' own checks missed is found on the whole
/// surface, and those pieces are closed again the guaranteed way: the
/// topology where pieces join, pieces nobody searched (prism closings), and,
/// where the stack cannot show that pieces meet only in their shared
/// contours (geometry/StackedMeshCheck), pairs across pieces. Checked as a
/// mesh file will hold it: mesh files store floats, and a gap of a few
/// nanometres between pieces can close in rounding.
void checkAndRepair(RunState& run) {
    const ScopedSeconds timer(run.result.stats.checkSeconds);
    SurfaceBuilder& builder = run.builder();
    builder.roundPointsToFloat();
    for (const Layer& layer : run.layers) {
        run.stack.planeZMm.push_back(builder.point(layer.vertexIds[0][0]).z);
        run.stack.planeLoops.push_back(layer.vertexIds);
    }
    run.stack.searched = run.reconstructor->searchedPieces();
    // Contour points never move from here on (repairs and smoothing leave
    // them), so their loops are tested once for all the checks below.
    run.stack.loopsKnownApart = planeLoopsApart(builder.soup(), run.stack);
    run.result.check = checkStackedMesh(builder.soup(), builder.pieces(), run.stack);
    if (!run.result.check.validSolid() && run.options.cap != CapMode::None)
        closeBrokenPiecesAgain(run);
    reportBrokenPieces(run);
}

/// Phase 5 (smooth mode, a valid surface of two planes or more): the strips
/// bent onto the C1 interpolant of the planes' fields and each slab brought
/// to the volume its sections imply (recon/LoftSmoothing), valid again
/// before it returns.
void smoothPieces(RunState& run, SurfaceBuilder::Released built) {
    Reconstruction& result = run.result;
    ReconstructionStats& stats = result.stats;
    const ScopedSeconds timer(stats.smoothSeconds);
    // Smoothing is where a large ROI peaks, and it copies every point (the
    // straight places it may go back to): the points that pieces closed
    // again no longer use go first (the slabs' parts came without theirs),
    // and so do the nearest ids, which only the medial axes read (the
    // interpolant reads the distances). Neither changes the surface: the
    // points left keep their order.
    removeUnusedPointsFrom(result.surface, run.contourVertices);
    std::vector<std::uint32_t>().swap(run.fields.nearestId);
    SliceInterpolant interpolant(run.fields);
    const PlaneSections& planes = run.planes;
    const LoftSmoothingStats smooth = smoothLofts(
        result.surface, {std::move(built.pieces), std::move(built.lofts), run.contourVertices},
        run.stack, interpolant,
        {planes, run.options.smoothToleranceMm, run.roi.frame, run.fromVoxels,
         run.options.coarsenRings},
        result.check);
    stats.smoothedVertices = smooth.movedVertices;
    stats.smoothRevertedPieces = smooth.revertedPieces;
    stats.smoothUnbentVertices = smooth.unbentVertices;
    stats.smoothHalfUnbentVertices = smooth.halfUnbentVertices;
    stats.smoothCoarsenedVertices = smooth.coarsenedVertices;
    stats.smoothFellBack = smooth.fellBack;
}

/// The guarantee every piece is built to keep: each of the first
/// `contourVertices` points (the contour points, made first and shared by
/// every piece) is a corner of some triangle. Checked, not assumed, so a
/// broken construction is an error, never a surface that silently lost a
/// contour point when unused points are dropped. O(T).
void requireContourPointsKept(const TriangleSoup& surface, std::size_t contourVertices) {
    std::vector<bool> used(contourVertices, false);
    for (const auto& t : surface.triangles)
        for (std::uint32_t v : t)
            if (v < contourVertices) used[v] = true;
    const auto lost = std::size_t(std::count(used.begin(), used.end(), false));
    if (lost > 0)
        throw std::logic_error("reconstruction: " + std::to_string(lost) + " of " +
                               std::to_string(contourVertices) +
                               " contour points are on no triangle (a defect of dfrecon; please "
                               "report it with the input)");
}

/// One run of planes, phase by phase (see the top); its working arrays go
/// when it returns.
Reconstruction reconstructWithin(ocl::Runtime& runtime, const Roi& roi,
                                 const ReconstructionOptions& requested,
                                 const std::function<void(double)>& progress) {
    RunState run(roi, requested);
    prepareSlices(run);
    computePlaneFields(runtime, run, progress);
    buildPieces(runtime, run, progress);
    checkAndRepair(run);
    SurfaceBuilder::Released built = run.builder().release();
    run.result.surface = std::move(built.soup);
    if (run.options.interpolation == Interpolation::Smooth && run.slices.size() > 1 &&
        run.result.check.validSolid())
        smoothPieces(run, std::move(built));
    requireContourPointsKept(run.result.surface, run.contourVertices);
    // Intermediate contours of discarded pieces leave points behind.
    removeUnusedPoints(run.result.surface);
    return std::move(run.result);
}

}  // namespace

namespace {

// The report of a surface made of disjoint parts from the parts' reports:
// counts, volume and area add; the examples and defective triangles are
// renumbered to the joined soup (each part's triangles follow the last).
void addDisjointCheck(MeshCheckReport& whole, const MeshCheckReport& part,
                      std::size_t triangleOffset) {
    const bool closed = whole.genus >= 0 && part.genus >= 0;
    whole.vertices += part.vertices;
    whole.triangles += part.triangles;
    whole.edges += part.edges;
    whole.degenerateTriangles += part.degenerateTriangles;
    whole.boundaryEdges += part.boundaryEdges;
    whole.nonManifoldEdges += part.nonManifoldEdges;
    whole.nonManifoldVertices += part.nonManifoldVertices;
    whole.misorientedEdges += part.misorientedEdges;
    whole.intersectingPairs += part.intersectingPairs;
    whole.intersectingPairsCapped = whole.intersectingPairsCapped || part.intersectingPairsCapped;
    for (const auto& [a, b] : part.intersectingExamples)
        if (whole.intersectingExamples.size() < 10)
            whole.intersectingExamples.push_back({a + triangleOffset, b + triangleOffset});
    for (std::size_t t : part.defectiveTriangles)
        whole.defectiveTriangles.push_back(t + triangleOffset);
    whole.components += part.components;
    whole.eulerCharacteristic += part.eulerCharacteristic;
    whole.genus = closed ? whole.genus + part.genus : -1;
    whole.volumeMm3 += part.volumeMm3;
    whole.areaMm2 += part.areaMm2;
}

// An ROI with planes left empty: each run on its own, joined (see the
// header). A lone plane's cap reaches half the plane's thickness
// (lonePlaneThicknessMm), as its contour volume counts it.
Reconstruction reconstructRuns(ocl::Runtime& runtime, const Roi& roi,
                               const ReconstructionOptions& requested,
                               const std::function<void(double)>& progress) {
    const std::vector<Roi> runs = planeRuns(roi);
    Reconstruction whole;
    whole.check.genus = 0;
    ReconstructionStats& s = whole.stats;
    s.runs = runs.size();
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const double done = double(k) / double(runs.size());
        Reconstruction part = reconstructWithin(runtime, runs[k], requested, [&](double f) {
            if (progress) progress(done + f / double(runs.size()));
        });
        const std::size_t trianglesBefore = whole.surface.triangles.size();
        appendSoup(whole.surface, part.surface);
        addDisjointCheck(whole.check, part.check, trianglesBefore);
        whole.brokenPieces.insert(whole.brokenPieces.end(), part.brokenPieces.begin(),
                                  part.brokenPieces.end());
        const ReconstructionStats& p = part.stats;
        s.pixelMm = std::max(s.pixelMm, p.pixelMm);
        s.slices += p.slices;
        s.contourPoints += p.contourPoints;
        s.slabs += p.slabs;
        addSlabStats(s, p);  // strips, closings, caps, fields' and axes' seconds
        s.touchesOpened += p.touchesOpened;
        s.repairedPieces += p.repairedPieces;
        s.smoothedVertices += p.smoothedVertices;
        s.smoothRevertedPieces += p.smoothRevertedPieces;
        s.smoothUnbentVertices += p.smoothUnbentVertices;
        s.smoothHalfUnbentVertices += p.smoothHalfUnbentVertices;
        s.smoothCoarsenedVertices += p.smoothCoarsenedVertices;
        s.smoothFellBack = s.smoothFellBack || p.smoothFellBack;
        s.simplifySeconds += p.simplifySeconds;
        s.triangulationSeconds += p.triangulationSeconds;
        s.checkSeconds += p.checkSeconds;
        s.smoothSeconds += p.smoothSeconds;
    }
    std::sort(whole.check.defectiveTriangles.begin(), whole.check.defectiveTriangles.end());
    std::sort(whole.brokenPieces.begin(), whole.brokenPieces.end());
    return whole;
}

}  // namespace

Reconstruction reconstructSurface(ocl::Runtime& runtime, const Roi& roi,
                                  const ReconstructionOptions& requested,
                                  const std::function<void(double)>& progress) {
    Reconstruction result = roi.restartsAt.empty()
                                ? reconstructWithin(runtime, roi, requested, progress)
                                : reconstructRuns(runtime, roi, requested, progress);
    releaseAfterRoi();
    return result;
}

}  // namespace dfrecon
