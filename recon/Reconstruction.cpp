#include "recon/Reconstruction.hpp"

#include "geometry/GlibcHeap.hpp"

#if defined(DFRECON_GLIBC_HEAP)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <exception>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "cl/HostScratch.hpp"
#include "contours/PlaneGaps.hpp"
#include "geometry/CoreBudget.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/StackedMeshCheck.hpp"
#include "geometry/TouchSeparation.hpp"
#include "geometry/UnionFind.hpp"
#include "recon/ContourSimplification.hpp"
#include "recon/IsoContours.hpp"
#include "recon/LoftSmoothing.hpp"
#include "recon/MedialAxis.hpp"
#include "recon/PrismClosing.hpp"
#include "recon/StripStitching.hpp"
#include "recon/SurfaceBuilder.hpp"

namespace dfrecon {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

/// What one slab's medial axes connect: contours of both sides (indices into
/// the slab's field slices) and the axes between them.
struct Component {
    std::vector<std::uint32_t> lower, upper;
    std::vector<std::size_t> axes;
};

std::vector<Component> connectByAxes(const std::vector<MedialAxis>& axes, std::size_t lowerCount,
                                     std::size_t upperCount) {
    const std::size_t contours = lowerCount + upperCount;
    UnionFind sets(contours + axes.size());
    for (std::size_t a = 0; a < axes.size(); ++a) {
        for (const MedialPixel& p : axes[a].pixels) {
            if (p.lowerId != kNoPrimitive) {
                const std::uint32_t c = PrimitiveId::decode(p.lowerId).contour;
                if (c < lowerCount) sets.join(contours + a, c);
            }
            if (p.upperId != kNoPrimitive) {
                const std::uint32_t c = PrimitiveId::decode(p.upperId).contour;
                if (c < upperCount) sets.join(contours + a, lowerCount + c);
            }
        }
    }
    std::vector<Component> components;
    std::vector<std::size_t> slot(contours + axes.size(), SIZE_MAX);
    auto componentOf = [&](std::size_t node) -> Component& {
        const std::size_t root = sets.find(node);
        if (slot[root] == SIZE_MAX) {
            slot[root] = components.size();
            components.emplace_back();
        }
        return components[slot[root]];
    };
    for (std::size_t c = 0; c < lowerCount; ++c) componentOf(c).lower.push_back(std::uint32_t(c));
    for (std::size_t c = 0; c < upperCount; ++c)
        componentOf(lowerCount + c).upper.push_back(std::uint32_t(c));
    for (std::size_t a = 0; a < axes.size(); ++a) componentOf(contours + a).axes.push_back(a);
    return components;
}

// How far apart the points where contours of one plane touch are opened: a
// couple of micrometres, far below any contouring accuracy, yet many float
// steps at patient coordinates, so the opening survives a float mesh file.
constexpr double kTouchGapMm = 2e-3;

class SurfaceReconstructor final : public CapSite {
  public:
    SurfaceReconstructor(ocl::Runtime& runtime, const ReconstructionOptions& options,
                         const SliceGrid& grid, ReconstructionStats& stats,
                         SurfaceBuilder builder = {})
        : runtime_(runtime),
          options_(options),
          grid_(grid),
          stats_(stats),
          builder_(std::move(builder)) {}

    SurfaceBuilder& builder() override { return builder_; }

    /// The slab between two original slices, whose fields are slices
    /// `lowerSlice` and `upperSlice` of `fields`.
    void originalSlab(const Layer& lower, const Layer& upper, const SliceFields& fields,
                      std::size_t lowerSlice, std::size_t upperSlice) {
        const std::size_t before = builder_.triangleCount();
        const LayerPart x = part(lower, all(lower)), y = part(upper, all(upper));
        const bool built = slab(x, y, fields, lowerSlice, upperSlice, 0);
        // Pieces are built one connected part at a time; parts that lie close
        // in projection (an ending contour's lid under a neighbour's
        // intermediate strips, say) can still meet, and coincidences can
        // leave a piece torn. The slab is then closed as one prism piece
        // instead, which is valid by construction and stays within the slab.
        if (!built || !isCleanPiece(before, {&x, &y})) {
            builder_.truncateTriangles(before);
            // The closing is then the whole piece, its pairs searched as
            // floats by closeByPrisms when it holds.
            if (closeSlabByPrisms(lower, upper)) markSearched();
            ++stats_.fallbackSlabs;
        } else {
            markSearched();
        }
    }

    /// Per piece, whether its own pairs were searched (clean) at the
    /// coordinates a mesh file holds: the whole check need not search them
    /// again (geometry/StackedMeshCheck).
    const std::vector<bool>& searchedPieces() const { return searched_; }
    void markSearched(std::uint32_t piece) {
        if (searched_.size() <= piece) searched_.resize(piece + 1, false);
        searched_[piece] = true;
    }

    /// Hands over what was built since the builder held only its first
    /// `sharedPoints` points, with whether its piece was searched, and
    /// forgets it (intermediate layers included): the next slab starts
    /// afresh on the same points.
    SurfacePart takePart(std::size_t sharedPoints, bool& searched) {
        const std::uint32_t piece = builder_.piece();
        searched = piece < searched_.size() && searched_[piece];
        searched_.clear();
        layers_.clear();
        return builder_.takePart(sharedPoints);
    }

    /// The guaranteed closing of the slab between two layers: one prism
    /// piece over all their contours. True when it holds as floats
    /// (closeByPrisms).
    bool closeSlabByPrisms(const Layer& lower, const Layer& upper) {
        return closeByPrisms(builder_, part(lower, all(lower)), part(upper, all(upper)),
                             0.5 * (lower.zMm + upper.zMm));
    }

    /// Caps every contour of `end` (up or down from its plane) by `offsetMm`
    /// as a piece of its own (recon/Caps).
    void capLayer(const Layer& end, bool up, double offsetMm, const SliceFields& fields,
                  std::size_t slice) {
        const LayerPart whole = part(end, all(end));
        stats_.caps += whole.contours.size();
        capEndsAsPiece(*this, options_.cap, whole, {up, offsetMm}, fields, slice);
    }

    /// The guaranteed cap: the end contours extruded under a flat lid.
    void prismCapLayer(const Layer& end, bool up, double offsetMm) {
        prismCap(builder_, part(end, all(end)), up, offsetMm);
    }

  private:
    /// Defects that no triangles added later can mend: two triangles
    /// meeting, an edge used three times or twice the same way, a degenerate
    /// triangle. (A vertex of several fans or a border can still close.)
    static bool hasLastingDefect(const MeshCheckReport& part) {
        return part.intersectingPairs > 0 || part.nonManifoldEdges > 0 ||
               part.misorientedEdges > 0 || part.degenerateTriangles > 0;
    }

    /// Are the triangles added since `before` a clean piece: no two meeting,
    /// every edge used once or twice and consistently, every vertex one fan,
    /// nothing degenerate, and (unless ends stay open) the only border the
    /// contours of `sides`?
    bool isCleanPiece(std::size_t before, std::initializer_list<const LayerPart*> sides) const {
        // As a mesh file will hold it, as the whole surface is checked: a
        // clean piece's pairs need no second search there.
        TriangleSoup triangles = builder_.trianglesSince(before);
        roundPointsToFloat(triangles);
        // A strip's own pairs were searched as it was built.
        const MeshCheckReport piece =
            checkMeshKnowing(triangles, builder_.cleanGroupsSince(before));
        std::size_t contourEdges = 0;
        for (const LayerPart* side : sides)
            for (std::uint32_t c : side->contours) contourEdges += side->layer->contours[c].size();
        const bool borderRight =
            options_.cap == CapMode::None || piece.boundaryEdges == contourEdges;
        return !hasLastingDefect(piece) && piece.nonManifoldVertices == 0 && borderRight;
    }

    /// Do the triangles added since `before` doom the piece they are part
    /// of, whatever else it gets (hasLastingDefect), so that it would fail
    /// isCleanPiece?
    bool breakTheirPiece(std::size_t before) const {
        return hasLastingDefect(checkMesh(builder_.trianglesSince(before)));
    }

    // What caps ask of the reconstruction (CapSite).
    bool isCleanCap(std::size_t before, const LayerPart& end) override {
        if (!isCleanPiece(before, {&end})) return false;
        markSearched();
        return true;
    }
    void markSearched() { markSearched(builder_.piece()); }
    const Layer& addIsolineLayer(double zMm, std::vector<Polygon> isolines,
                                 const LayerPart& of) override {
        if (emptyIsNegative(of, {of.layer, {}}))
            for (Polygon& p : isolines) std::reverse(p.begin(), p.end());
        layers_.push_back(makeLayer(builder_, zMm, std::move(isolines)));
        return layers_.back();
    }
    void joinLayers(const LayerPart& lower, const SliceFields& lowerField, const LayerPart& upper,
                    const SliceFields& upperField) override {
        slab(lower, upper, pairOf(lowerField, 0, upperField, 0), 0, 1, 1);
    }

    /// Caps the contours of `end` that end inside a slab, up or down from
    /// its plane (the slab is checked as one piece).
    void cap(const LayerPart& end, bool up, double offsetMm, const SliceFields& fields,
             std::size_t slice) {
        if (end.contours.empty()) return;
        stats_.caps += end.contours.size();
        capEnds(*this, options_.cap, end, {up, offsetMm}, fields, slice);
    }

    static std::vector<std::uint32_t> all(const Layer& layer) {
        std::vector<std::uint32_t> ids(layer.contours.size());
        std::iota(ids.begin(), ids.end(), 0u);
        return ids;
    }
    static LayerPart part(const Layer& layer, std::vector<std::uint32_t> contours) {
        return {&layer, std::move(contours)};
    }
    static LayerPart subset(const LayerPart& of, const std::vector<std::uint32_t>& local) {
        LayerPart out{of.layer, {}};
        for (std::uint32_t c : local) out.contours.push_back(of.contours[c]);
        return out;
    }

    /// Is the outermost contour of these parts a hole? The fields of such
    /// parts alone are negative in the empty space inside the holes (the
    /// sign comes from the winding number), so axes and isolines, which
    /// follow the negative region, run against the contours' orientation and
    /// are turned around. Parts of whole slices never are.
    static bool emptyIsNegative(const LayerPart& a, const LayerPart& b) {
        double largest = 0, sign = 1;
        for (const LayerPart* p : {&a, &b})
            for (std::uint32_t c : p->contours) {
                const double area = signedArea(p->layer->contours[c]);
                if (std::abs(area) > largest) largest = std::abs(area), sign = area;
            }
        return sign < 0;
    }

    /// The window of the ROI's grid around `parts`: everything later steps
    /// read of their fields (the negative regions, their borders and the
    /// isolines) lies inside the parts' contours, and the margin is the one
    /// the whole grid keeps, so the window answers as the whole grid would
    /// at a fraction of the pixels.
    SliceGrid windowAround(const std::vector<LayerPart>& parts) const {
        Box2 box;
        for (const LayerPart& p : parts)
            for (std::uint32_t c : p.contours)
                for (Point2 q : p.layer->contours[c]) box.add(q);
        return windowOf(grid_, box, kGridMarginPx);
    }

    /// The fields of `parts`, one slice each, in order, on `grid` (nullopt:
    /// the window around them).
    SliceFields fieldsOf(const std::vector<LayerPart>& parts,
                         std::optional<SliceGrid> grid) override {
        std::vector<Slice> slices;
        for (const LayerPart& p : parts) {
            Slice& slice = slices.emplace_back(Slice{p.layer->zMm, {}});
            for (std::uint32_t c : p.contours) slice.contours.push_back(p.layer->contours[c]);
        }
        const auto start = Clock::now();
        SliceFields fields = computeSliceFields(
            runtime_, slices, grid ? *grid : windowAround(parts), {}, options_.kernel);
        stats_.fieldsSeconds += secondsSince(start);
        return fields;
    }

    /// Slice `ia` of `a` and slice `ib` of `b` as a two-slice stack, so a
    /// field computed once serves both halves of a recursion.
    static SliceFields pairOf(const SliceFields& a, std::size_t ia, const SliceFields& b,
                              std::size_t ib) {
        if (a.grid.originMm.x != b.grid.originMm.x || a.grid.originMm.y != b.grid.originMm.y ||
            a.grid.width != b.grid.width || a.grid.height != b.grid.height)
            throw std::logic_error("pairOf: fields on different grids");
        SliceFields pair;
        pair.grid = a.grid;
        const std::size_t pixels = a.grid.pixelCount();
        for (const auto& [f, i] : {std::pair{&a, ia}, std::pair{&b, ib}}) {
            pair.zMm.push_back(f->zMm[i]);
            const auto from = std::ptrdiff_t(i * pixels), to = from + std::ptrdiff_t(pixels);
            pair.distanceMm.insert(pair.distanceMm.end(), f->distanceMm.begin() + from,
                                   f->distanceMm.begin() + to);
            pair.nearestId.insert(pair.nearestId.end(), f->nearestId.begin() + from,
                                  f->nearestId.begin() + to);
        }
        return pair;
    }

    /// Joins `lower` to `upper`; `fields` holds their fields (slice
    /// `a` = lower's contours in order, `b` = upper's). False when a slab of
    /// the stack proper (depth 0) was given up half-built because its caps
    /// already meet: the caller closes it by prisms.
    bool slab(const LayerPart& lower, const LayerPart& upper, const SliceFields& fields,
              std::size_t a, std::size_t b, int depth) {
        stats_.deepestLevel = std::max(stats_.deepestLevel, depth);
        const double middle = 0.5 * (lower.layer->zMm + upper.layer->zMm);
        std::vector<MedialAxis> axes;
        SliceSum sum;
        if (!lower.contours.empty() && !upper.contours.empty()) {
            const auto start = Clock::now();
            sum = sumSlices(fields, a, b);
            axes = traceMedialAxes(fields, a, b, sum);
            if (depth > 0 && emptyIsNegative(lower, upper))
                for (MedialAxis& axis : axes) std::reverse(axis.pixels.begin(), axis.pixels.end());
            stats_.medialSeconds += secondsSince(start);
        }
        const std::vector<Component> components =
            connectByAxes(axes, lower.contours.size(), upper.contours.size());
        LayerPart endingLower{lower.layer, {}}, endingUpper{upper.layer, {}};
        for (const Component& c : components) {
            if (!c.axes.empty()) continue;
            for (std::uint32_t k : c.lower) endingLower.contours.push_back(lower.contours[k]);
            for (std::uint32_t k : c.upper) endingUpper.contours.push_back(upper.contours[k]);
        }
        if (depth == 0) {
            // Ends of the stack proper: capped as the user chose. Caps come
            // first because, between planes, the lids of contours ending
            // below and above both reach the middle of the gap, and where
            // they meet there (label maps' neighbouring regions, which touch
            // in projection) the slab is given up before the costly part.
            const std::size_t capsBefore = builder_.triangleCount();
            const double offsetMm =
                capOffsetMm(options_.capOffsetMm, upper.layer->zMm - lower.layer->zMm, true);
            cap(endingLower, true, offsetMm, fields, a);
            cap(endingUpper, false, offsetMm, fields, b);
            if (builder_.triangleCount() > capsBefore && breakTheirPiece(capsBefore)) return false;
        }
        for (const Component& c : components) {
            if (c.axes.empty()) continue;  // ending: capped above or closed below
            const LayerPart x = subset(lower, c.lower), y = subset(upper, c.upper);
            if (!(c.lower.size() == 1 && c.upper.size() == 1 && c.axes.size() == 1 &&
                  strip(x, y, axes[c.axes[0]], fields.grid, c.lower[0], c.upper[0]))) {
                if (depth >= options_.maxDepth) {
                    closeByPrisms(builder_, x, y, middle);
                    ++stats_.limitClosings;
                } else {
                    // A component that is the whole slab has the fields
                    // in hand already.
                    const bool whole = x.contours.size() == lower.contours.size() &&
                                       y.contours.size() == upper.contours.size();
                    if (whole)
                        recurse(x, y, depth, fields, a, b, &sum);
                    else
                        recurse(x, y, depth, fieldsOf({x, y}, std::nullopt), 0, 1, nullptr);
                }
            }
        }
        if (depth > 0) {
            closeByPrisms(builder_, endingLower, {}, middle);
            closeByPrisms(builder_, {}, endingUpper, middle);
        }
        return true;
    }

    bool strip(const LayerPart& x, const LayerPart& y, const MedialAxis& axis,
               const SliceGrid& axisGrid, std::uint32_t lowerLocal, std::uint32_t upperLocal) {
        const Layer& lower = *x.layer;
        const Layer& upper = *y.layer;
        const std::uint32_t p = x.contours[0], q = y.contours[0];
        const auto lowerAt =
            positionsAlongAxis(axis, axisGrid, lower.contours[p], lowerLocal, true);
        if (!lowerAt) return false;
        const auto upperAt =
            positionsAlongAxis(axis, axisGrid, upper.contours[q], upperLocal, false);
        if (!upperAt) return false;
        const std::size_t before = builder_.triangleCount();
        stitchStrip(builder_, lower.vertexIds[p], *lowerAt, upper.vertexIds[q], *upperAt);
        builder_.markLoftSince(before);
        // Contours that zigzag or lean far can make a strip fold through
        // itself; such a band is solved again with an intermediate contour
        // instead (and at the limit closed by prisms, which cannot fold).
        // Searched as a mesh file will hold it, as its piece is checked, so
        // that check need not search these pairs again.
        TriangleSoup band = builder_.trianglesSince(before);
        roundPointsToFloat(band);
        if (countSelfIntersections(band) > 0) {
            builder_.truncateTriangles(before);
            ++stats_.rejectedStrips;
            return false;
        }
        builder_.markSearchedTogetherSince(before);
        ++stats_.strips;
        return true;
    }

    /// The paper's Fig. 7: the medial axis becomes a contour half-way, and
    /// both halves are solved again.
    /// Slices `a` and `b` of `fields` hold the fields of exactly x and y (a
    /// whole slab passes its own, not a copy), `knownSum` (if set) their sum.
    void recurse(const LayerPart& x, const LayerPart& y, int depth, const SliceFields& fields,
                 std::size_t a, std::size_t b, const SliceSum* knownSum) {
        const auto start = Clock::now();
        const SliceSum sum = knownSum ? *knownSum : sumSlices(fields, a, b);
        std::vector<Polygon> isolines = zeroIsolines(sum.sumMm, fields.grid);
        // Pixel-step isolines carry far more points than the surface needs.
        Slice middle{0.5 * (x.layer->zMm + y.layer->zMm), {}};
        for (SimplifiedContour& c : simplifySlice(isolines, 0.25 * grid_.pixelMm))
            if (c.points.size() >= 3) middle.contours.push_back(std::move(c.points));
        // Isolines keep the negative side on their left; contours keep the solid.
        if (emptyIsNegative(x, y))
            for (Polygon& p : middle.contours) std::reverse(p.begin(), p.end());
        stats_.medialSeconds += secondsSince(start);
        if (middle.contours.empty()) {
            closeByPrisms(builder_, x, y, middle.zMm);
            ++stats_.limitClosings;
            return;
        }
        ++stats_.recursions;
        layers_.push_back(makeLayer(builder_, middle.zMm, std::move(middle.contours)));
        const Layer& mid = layers_.back();
        const LayerPart m = part(mid, all(mid));
        // Only the intermediate contours' field is new; x's and y's are reused.
        const SliceFields middleField = fieldsOf({m}, fields.grid);
        slab(x, m, pairOf(fields, a, middleField, 0), 0, 1, depth + 1);
        slab(m, y, pairOf(middleField, 0, fields, b), 0, 1, depth + 1);
    }

    ocl::Runtime& runtime_;
    const ReconstructionOptions& options_;
    const SliceGrid& grid_;
    ReconstructionStats& stats_;
    SurfaceBuilder builder_;
    std::vector<bool> searched_;  // per piece
    std::deque<Layer> layers_;    // intermediate contours; LayerParts point into it
};

/// One slab built apart: its part of the surface, whether its piece's own
/// pairs were searched, the counts it added and the seconds it took.
struct BuiltSlab {
    SurfacePart part;
    bool searched = false;
    ReconstructionStats stats;
    double seconds = 0;
};

void addSlabStats(ReconstructionStats& into, const ReconstructionStats& slab) {
    into.strips += slab.strips;
    into.rejectedStrips += slab.rejectedStrips;
    into.recursions += slab.recursions;
    into.deepestLevel = std::max(into.deepestLevel, slab.deepestLevel);
    into.limitClosings += slab.limitClosings;
    into.caps += slab.caps;
    into.fallbackSlabs += slab.fallbackSlabs;
    into.fieldsSeconds += slab.fieldsSeconds;
    into.medialSeconds += slab.medialSeconds;
}

/// The slabs between neighbouring layers, slab s as piece s + 1, built on
/// the calling thread and on the cores left free (geometry/CoreBudget). A
/// slab reads only its two layers' contour points and the planes' fields,
/// so each thread builds on a builder of its own that starts with the
/// `contourPoints`, and the calling thread hands each slab to `append` in
/// slab order as soon as it and those before it are done (so few finished
/// parts wait at once); appended in that order, the parts make the same
/// surface, point for point, whatever the number of threads. Helper
/// threads get their own OpenCL queue on `runtime`'s context. Progress
/// (0.5 to 1, as slabs finish) is reported from the calling thread only.
/// An exception in any thread is rethrown here once all have stopped.
/// Returns how many helper threads ran.
std::size_t buildSlabs(ocl::Runtime& runtime, const ReconstructionOptions& options,
                       const SliceGrid& grid, const std::deque<Layer>& layers,
                       const SliceFields& fields, const std::vector<Vec3>& contourPoints,
                       const std::function<void(double)>& progress,
                       const std::function<void(std::size_t, BuiltSlab&&)>& append) {
    const std::size_t slabs = layers.size() - 1;
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
        SurfaceReconstructor slab(queue, options, grid, stats, SurfaceBuilder(contourPoints));
        for (std::size_t s; !stop && (s = next++) < slabs;) {
            stats = {};
            const auto start = Clock::now();
            slab.builder().setPiece(std::uint32_t(s + 1));
            slab.originalSlab(layers[s], layers[s + 1], fields, s, s + 1);
            BuiltSlab out;
            out.part = slab.takePart(contourPoints.size(), out.searched);
            out.stats = stats;
            out.seconds = secondsSince(start);
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

/// reconstructSurface's work; its working arrays go when it returns.
Reconstruction reconstructWithin(ocl::Runtime& runtime, const Roi& roi,
                                 const ReconstructionOptions& requested,
                                 const std::function<void(double)>& progress) {
    ReconstructionOptions options = requested;
    // A DICOM slab thickness says how far each contour reaches along the
    // normal, so the end caps go half of it beyond the end contours.
    if (options.capOffsetMm < 0 && roi.slabThicknessMm > 0)
        options.capOffsetMm = 0.5 * roi.slabThicknessMm;
    if (options.maxDepth < 0) throw std::invalid_argument("reconstruct: max depth must be >= 0");
    Reconstruction result;
    ReconstructionStats& stats = result.stats;

    auto start = Clock::now();
    std::vector<Slice> slices;
    for (const Slice& s : roi.slices) {
        if (s.contours.empty()) continue;
        Slice slice{s.zMm, {}};
        if (options.contourErrorMm > 0) {
            for (SimplifiedContour& c : simplifySlice(s.contours, options.contourErrorMm))
                slice.contours.push_back(std::move(c.points));
        } else {
            slice.contours = s.contours;
        }
        stats.touchesOpened += separateTouchingContours(slice.contours, kTouchGapMm);
        for (const Polygon& c : slice.contours) stats.contourPoints += c.size();
        slices.push_back(std::move(slice));
    }
    stats.simplifySeconds = secondsSince(start);
    if (slices.empty()) throw std::invalid_argument("ROI '" + roi.name + "' has no contours");
    stats.slices = slices.size();
    stats.slabs = slices.size() - 1;

    const SliceGrid grid = gridForSlices(slices, options.pixelMm, kReconstructionGridPixels);
    stats.pixelMm = grid.pixelMm;
    start = Clock::now();
    auto fieldProgress = [&](double f) {
        if (progress) progress(0.5 * f);
    };
    SliceFields fields = computeSliceFields(runtime, slices, grid, fieldProgress, options.kernel);
    stats.fieldsSeconds = secondsSince(start);
    // The planes' fields ran in batches of many planes; the slabs' fields
    // take one or two planes at a time, which the batches' blocks in the
    // scratch pool do not serve (a kept block serves requests of at least
    // two thirds its size). Kept, they would stay resident through the
    // slabs: 90 MB for the head CT bone.
    ocl::releaseScratch();
    start = Clock::now();
    const double fieldsAndMedialBefore = stats.fieldsSeconds;
    SurfaceReconstructor reconstructor(runtime, options, grid, stats);
    std::deque<Layer> layers;
    for (const Slice& s : slices)
        layers.push_back(makeLayer(reconstructor.builder(), s.zMm, s.contours));
    // The contour points are the builder's first vertices; every later one
    // (intermediate contours, lids, refinement) may move in smooth mode.
    const std::size_t contourVertices = reconstructor.builder().soup().points.size();
    const SpacingStats spacing = spacingOf(roi);
    // A lone plane stands for the image planes' spacing, as its contour
    // volume counts it (1 mm when nothing says what that is).
    const double endSpacing = spacing.meanMm > 0              ? spacing.meanMm
                              : lonePlaneThicknessMm(roi) > 0 ? lonePlaneThicknessMm(roi)
                                                              : 1.0;
    auto capOffset = [&](std::size_t s, bool up) {
        const std::size_t neighbour = up ? s - 1 : s + 1;
        const double gap =
            slices.size() > 1 ? std::fabs(slices[s].zMm - slices[neighbour].zMm) : endSpacing;
        return capOffsetMm(options.capOffsetMm, gap, false);
    };
    // Pieces: 0 the bottom cap, s + 1 the slab above slice s, the last the
    // top cap. Each lies between its planes and meets them only in their
    // contours, so the surface is valid when every piece is.
    SurfaceBuilder& builder = reconstructor.builder();
    const std::uint32_t topCap = std::uint32_t(slices.size());
    builder.setPiece(0);
    reconstructor.capLayer(layers[0], false, capOffset(0, false), fields, 0);
    // The slabs on the free cores, then appended in order (the caps' own
    // stats are the main reconstructor's). Their seconds count per thread,
    // so the stages can add up to more than the wall time.
    const auto slabsStart = Clock::now();
    double slabThreadSeconds = 0;
    const std::size_t helpers =
        buildSlabs(runtime, options, grid, layers, fields,
                   {builder.soup().points.begin(),
                    builder.soup().points.begin() + std::ptrdiff_t(contourVertices)},
                   progress, [&](std::size_t s, BuiltSlab&& slab) {
                       builder.appendPart(std::move(slab.part));
                       if (slab.searched) reconstructor.markSearched(std::uint32_t(s + 1));
                       addSlabStats(stats, slab.stats);
                       slabThreadSeconds += slab.seconds;
                   });
    const double slabsWallSeconds = secondsSince(slabsStart);
    // The helpers' heap arenas keep what the slabs freed; the steps after
    // run on this thread and cannot reuse it.
    if (helpers > 0) giveBackMuchFreedHeap();
    builder.setPiece(topCap);
    reconstructor.capLayer(layers.back(), true, capOffset(slices.size() - 1, true), fields,
                           slices.size() - 1);
    // This ROI's kernels are done: the blocks the scratch pool keeps for the
    // next call (cl/HostScratch; 92 MB after the head CT bone's fields and
    // slabs) would stay resident through the checks and smoothing, where a
    // large ROI peaks. The next ROI faults its blocks in again, a few
    // milliseconds against its seconds.
    ocl::releaseScratch();
    // Time spent on fields and axes inside the recursion is counted there.
    stats.triangulationSeconds = secondsSince(start) - slabsWallSeconds + slabThreadSeconds -
                                 (stats.fieldsSeconds - fieldsAndMedialBefore) -
                                 stats.medialSeconds;

    // Whatever the pieces' own checks missed is found on the whole surface,
    // and those pieces are closed again the guaranteed way: the topology
    // where pieces join, pieces nobody searched (prism closings), and, where
    // the stack cannot show that pieces meet only in their shared contours
    // (geometry/StackedMeshCheck), pairs across pieces.
    // Checked as a mesh file will hold it: mesh files store floats, and a
    // gap of a few nanometres between pieces can close in rounding.
    start = Clock::now();
    builder.roundPointsToFloat();
    PieceStack stack;
    for (const Layer& layer : layers) {
        stack.planeZMm.push_back(builder.point(layer.vertexIds[0][0]).z);
        stack.planeLoops.push_back(layer.vertexIds);
    }
    stack.searched = reconstructor.searchedPieces();
    // Contour points never move from here on (repairs and smoothing leave
    // them), so their loops are tested once for all the checks below.
    stack.loopsKnownApart = planeLoopsApart(builder.soup(), stack);
    result.check = checkStackedMesh(builder.soup(), builder.pieces(), stack);
    if (!result.check.validSolid() && options.cap != CapMode::None) {
        std::vector<bool> broken(slices.size() + 1, false);
        for (std::size_t t : result.check.defectiveTriangles) broken[builder.pieceOf(t)] = true;
        builder.dropPieces(broken);
        // Every pair of the triangles kept was clean (both triangles of a
        // meeting pair are dropped), so only the new pieces' triangles are
        // searched, unless the check stopped counting.
        const std::size_t kept = builder.triangleCount();
        for (std::uint32_t p = 0; p < broken.size(); ++p) {
            if (!broken[p]) continue;
            ++stats.repairedPieces;
            builder.setPiece(p);
            if (p == 0)
                reconstructor.prismCapLayer(layers[0], false, capOffset(0, false));
            else if (p == topCap)
                reconstructor.prismCapLayer(layers.back(), true,
                                            capOffset(slices.size() - 1, true));
            else
                reconstructor.closeSlabByPrisms(layers[p - 1], layers[p]);
        }
        builder.roundPointsToFloat();
        if (result.check.intersectingPairsCapped) {
            result.check = checkMesh(builder.soup());
        } else {
            std::vector<std::size_t> rebuilt(builder.triangleCount() - kept);
            std::iota(rebuilt.begin(), rebuilt.end(), kept);
            result.check = checkMeshNear(builder.soup(), rebuilt);
        }
    }
    // Where it is still broken, say between which planes (open ends are
    // what CapMode::None asks for).
    std::vector<bool> reported(slices.size() + 1, options.cap == CapMode::None);
    for (std::size_t t : result.check.defectiveTriangles) {
        const std::uint32_t p = builder.pieceOf(t);
        if (reported[p]) continue;
        reported[p] = true;
        const double below = p == 0 ? slices[0].zMm - capOffset(0, false) : slices[p - 1].zMm;
        const double above =
            p == topCap ? slices.back().zMm + capOffset(slices.size() - 1, true) : slices[p].zMm;
        result.brokenPieces.push_back({below, above});
    }
    std::sort(result.brokenPieces.begin(), result.brokenPieces.end());
    stats.checkSeconds = secondsSince(start);
    SurfaceBuilder::Released built = builder.release();
    result.surface = std::move(built.soup);
    if (options.interpolation == Interpolation::Smooth && slices.size() > 1 &&
        result.check.validSolid()) {
        start = Clock::now();
        // Smoothing is where a large ROI peaks, and it copies every point
        // (the straight places it may go back to): the points that pieces
        // closed again no longer use go first (the slabs' parts came
        // without theirs), and so do the nearest ids, which only the
        // medial axes read (the interpolant reads the distances). Neither
        // changes the surface: the points left keep their order.
        removeUnusedPointsFrom(result.surface, contourVertices);
        std::vector<std::uint32_t>().swap(fields.nearestId);
        SliceInterpolant interpolant(fields);
        const PlaneSections planes = sectionsOf(slices);
        const LoftSmoothingStats smooth = smoothLofts(
            result.surface, {std::move(built.pieces), std::move(built.lofts), contourVertices},
            stack, interpolant, {planes, options.smoothToleranceMm, roi.frame}, result.check);
        stats.smoothedVertices = smooth.movedVertices;
        stats.smoothRevertedPieces = smooth.revertedPieces;
        stats.smoothUnbentVertices = smooth.unbentVertices;
        stats.smoothFellBack = smooth.fellBack;
        stats.smoothSeconds = secondsSince(start);
    }
    // Intermediate contours of discarded pieces leave points behind.
    removeUnusedPoints(result.surface);
    return result;
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
    std::size_t pointsBefore = 0;
    for (std::size_t k = 0; k < runs.size(); ++k) {
        const double done = double(k) / double(runs.size());
        Reconstruction part = reconstructWithin(runtime, runs[k], requested, [&](double f) {
            if (progress) progress(done + f / double(runs.size()));
        });
        const std::size_t trianglesBefore = whole.surface.triangles.size();
        pointsBefore = whole.surface.points.size();
        whole.surface.points.insert(whole.surface.points.end(), part.surface.points.begin(),
                                    part.surface.points.end());
        for (std::array<std::uint32_t, 3> t : part.surface.triangles) {
            for (std::uint32_t& v : t) v += std::uint32_t(pointsBefore);
            whole.surface.triangles.push_back(t);
        }
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
    // What the reconstruction freed stays resident in the heap arena of the
    // thread that ran it (a worker of `--all`, a slab helper), where the
    // next ROI on another thread cannot reuse it: with the head CT's three
    // ROIs on two workers the process held BODY's and AIRWAY's freed
    // arrays through BONE's peak.
    giveBackMuchFreedHeap();
    return result;
}

}  // namespace dfrecon
