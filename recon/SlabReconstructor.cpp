#include "recon/SlabReconstructor.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "geometry/MeshCheck.hpp"
#include "geometry/UnionFind.hpp"
#include "recon/ContourSimplification.hpp"
#include "recon/IsoContours.hpp"
#include "recon/ScopedSeconds.hpp"
#include "recon/SlidingSections.hpp"
#include "recon/StripStitching.hpp"

namespace dfrecon {

namespace {

// Where one side of a slab's part holds less than this share of the other's
// area (a plane that barely cuts the structure: a speck under a large
// section), the pair is not joined by one strip at the top level (a cone
// from the speck holds a third of what the sections imply) but through an
// intermediate contour, and that contour's level may rise up to
// kSmallSideLevelSlabs slab heights to enclose its target area (the summed
// fields stay high far from the speck; the union of the two regions still
// bounds it). AAL at 2 mm, label 25: its speck of 6.5 mm2 under 522 mm2
// held 198 of the slab's 528 mm3, now 512 (docs/reconstruction.md, "A plane
// that barely cuts the structure").
constexpr double kSmallSideAreaRatio = 0.2;
constexpr double kSmallSideLevelSlabs = 10;

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

/// Defects that no triangles added later can mend: two triangles meeting,
/// an edge used three times or twice the same way, a degenerate triangle.
/// (A vertex of several fans or a border can still close.)
bool hasLastingDefect(const MeshCheckReport& part) {
    return part.intersectingPairs > 0 || part.nonManifoldEdges > 0 || part.misorientedEdges > 0 ||
           part.degenerateTriangles > 0;
}

std::vector<std::uint32_t> all(const Layer& layer) {
    std::vector<std::uint32_t> ids(layer.contours.size());
    std::iota(ids.begin(), ids.end(), 0u);
    return ids;
}

LayerPart whole(const Layer& layer) {
    return {&layer, all(layer)};
}

LayerPart subset(const LayerPart& of, const std::vector<std::uint32_t>& local) {
    LayerPart out{of.layer, {}};
    for (std::uint32_t c : local) out.contours.push_back(of.contours[c]);
    return out;
}

/// Slice `ia` of `a` and slice `ib` of `b` as a two-slice stack, so a field
/// computed once serves both halves of a recursion.
SliceFields pairOf(const SliceFields& a, std::size_t ia, const SliceFields& b, std::size_t ib) {
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

/// The net area of a part's contours (outer counter-clockwise, holes
/// clockwise). O(points).
double netAreaMm2(const LayerPart& part) {
    double area = 0;
    for (std::uint32_t c : part.contours) area += signedArea(part.layer->contours[c]);
    return area;
}

/// Whether one side of a slab's part is far smaller than the other
/// (kSmallSideAreaRatio): where a plane barely cuts a structure (a speck
/// under a large section, an area's floor lying between two planes).
bool oneSideFarSmaller(const LayerPart& x, const LayerPart& y) {
    const double ax = std::abs(netAreaMm2(x)), ay = std::abs(netAreaMm2(y));
    return std::min(ax, ay) < kSmallSideAreaRatio * std::max(ax, ay);
}

/// The intermediate contour half-way between parts x and y, whose fields
/// are `sides`, from their sum `sumMm`: its zero set, raised (up to the
/// slab's height, in mm of the summed distance; kSmallSideLevelSlabs
/// heights where one side is far smaller) where it encloses less than
/// the mean of x's and y's areas times `areaRatio` (the planes' trend there,
/// hermiteAreaRatio), within the union of their regions (isolinesEnclosing).
/// Parts whose outermost contour is a hole keep the zero set.
std::vector<Polygon> middleIsolines(const std::vector<float>& sumMm, const SlabFields& sides,
                                    const LayerPart& x, const LayerPart& y, double areaRatio) {
    const SliceGrid& grid = sides.fields.grid;
    if (outermostIsHole(x, y)) return zeroIsolines(sumMm, grid);
    const std::size_t pixels = grid.pixelCount();
    const float* lower = sides.fields.distanceMm.data() + sides.lower * pixels;
    const float* upper = sides.fields.distanceMm.data() + sides.upper * pixels;
    std::vector<float> either(pixels);
    for (std::size_t k = 0; k < pixels; ++k) either[k] = std::min(lower[k], upper[k]);
    return isolinesEnclosing(sumMm, grid,
                             {0.5 * (netAreaMm2(x) + netAreaMm2(y)) * areaRatio,
                              std::abs(y.layer->zMm - x.layer->zMm) *
                                  (oneSideFarSmaller(x, y) ? kSmallSideLevelSlabs : 1.0),
                              &either});
}

}  // namespace

SlabReconstructor::SlabReconstructor(ocl::Runtime& runtime, const ReconstructionOptions& options,
                                     const SliceGrid& grid, ReconstructionStats& stats,
                                     SurfaceBuilder builder, StackTraits stack)
    : runtime_(runtime),
      options_(options),
      grid_(grid),
      stats_(stats),
      builder_(std::move(builder)),
      stack_(stack) {}

void SlabReconstructor::originalSlab(const Layer& lower, const Layer& upper,
                                     const SliceFields& fields, std::size_t lowerSlice,
                                     std::size_t upperSlice) {
    const std::size_t before = builder_.triangleCount();
    const LayerPart x = whole(lower), y = whole(upper);
    const bool built = slab(x, y, {fields, lowerSlice, upperSlice}, 0);
    // Pieces are built one connected part at a time; parts that lie close in
    // projection (an ending contour's lid under a neighbour's intermediate
    // strips, say) can still meet, and coincidences can leave a piece torn.
    // The slab is then closed as one prism piece instead, which is valid by
    // construction and stays within the slab.
    if (!built || !isCleanPiece(before, {&x, &y})) {
        builder_.truncateTriangles(before);
        // The closing is then the whole piece, its pairs searched as floats
        // by closeByPrisms when it holds.
        if (closeSlabByPrisms(lower, upper)) markSearched();
        ++stats_.fallbackSlabs;
    } else {
        markSearched();
    }
}

void SlabReconstructor::markSearched(std::uint32_t piece) {
    if (searched_.size() <= piece) searched_.resize(piece + 1, false);
    searched_[piece] = true;
}

SurfacePart SlabReconstructor::takePart(std::size_t sharedPoints, bool& searched) {
    const std::uint32_t piece = builder_.piece();
    searched = piece < searched_.size() && searched_[piece];
    searched_.clear();
    layers_.clear();
    return builder_.takePart(sharedPoints);
}

bool SlabReconstructor::closeSlabByPrisms(const Layer& lower, const Layer& upper) {
    return closeByPrisms(builder_, whole(lower), whole(upper), 0.5 * (lower.zMm + upper.zMm));
}

bool SlabReconstructor::stepSlab(const Layer& lower, const Layer& upper) {
    const std::size_t before = builder_.triangleCount();
    if (!closeSlabByPrisms(lower, upper)) {
        builder_.truncateTriangles(before);
        return false;
    }
    markSearched();
    ++stats_.stepSlabs;
    return true;
}

void SlabReconstructor::capLayer(const Layer& end, CapReach reach, const SliceFields& fields,
                                 std::size_t slice) {
    const LayerPart ends = whole(end);
    stats_.caps += ends.contours.size();
    capEndsAsPiece(*this, options_.cap, ends, reach, fields, slice);
}

void SlabReconstructor::guaranteedCapLayer(const Layer& end, CapReach reach,
                                           const SliceFields& fields, std::size_t slice) {
    guaranteedCap(builder_, whole(end), reach, fields, slice);
}

/// Are the triangles added since `before` a clean piece: no two meeting,
/// every edge used once or twice and consistently, every vertex one fan,
/// nothing degenerate, and (unless ends stay open) the only border the
/// contours of `sides`?
bool SlabReconstructor::isCleanPiece(std::size_t before,
                                     std::initializer_list<const LayerPart*> sides) const {
    // As a mesh file will hold it, as the whole surface is checked: a clean
    // piece's pairs need no second search there.
    TriangleSoup triangles = builder_.trianglesSince(before);
    roundPointsToFloat(triangles);
    // A strip's own pairs were searched as it was built.
    const MeshCheckReport piece = checkMeshKnowing(triangles, builder_.cleanGroupsSince(before));
    std::size_t contourEdges = 0;
    for (const LayerPart* side : sides)
        for (std::uint32_t c : side->contours) contourEdges += side->layer->contours[c].size();
    const bool borderRight = options_.cap == CapMode::None || piece.boundaryEdges == contourEdges;
    return !hasLastingDefect(piece) && piece.nonManifoldVertices == 0 && borderRight;
}

/// Do the triangles added since `before` doom the piece they are part of,
/// whatever else it gets (hasLastingDefect), so that it would fail
/// isCleanPiece?
bool SlabReconstructor::breakTheirPiece(std::size_t before) const {
    return hasLastingDefect(checkMesh(builder_.trianglesSince(before)));
}

bool SlabReconstructor::isCleanCap(std::size_t before, const LayerPart& end) {
    if (!isCleanPiece(before, {&end})) return false;
    markSearched();
    return true;
}

const Layer& SlabReconstructor::addIsolineLayer(double zMm, std::vector<Polygon> isolines,
                                                const LayerPart& of) {
    if (outermostIsHole(of))
        for (Polygon& p : isolines) std::reverse(p.begin(), p.end());
    layers_.push_back(makeLayer(builder_, zMm, std::move(isolines)));
    return layers_.back();
}

void SlabReconstructor::joinLayers(const LayerPart& lower, const SliceFields& lowerField,
                                   const LayerPart& upper, const SliceFields& upperField) {
    slab(lower, upper, {pairOf(lowerField, 0, upperField, 0)}, 1);
}

/// Caps the contours of `end` that end inside a slab, up or down from its
/// plane (the slab is checked as one piece).
void SlabReconstructor::cap(const LayerPart& end, CapReach reach, const SliceFields& fields,
                            std::size_t slice) {
    if (end.contours.empty()) return;
    stats_.caps += end.contours.size();
    capEnds(*this, options_.cap, end, reach, fields, slice);
}

/// The window of the ROI's grid around `parts`: everything later steps read
/// of their fields (the negative regions, their borders and the isolines)
/// lies inside the parts' contours, and the margin is the one the whole grid
/// keeps, so the window answers as the whole grid would at a fraction of the
/// pixels.
SliceGrid SlabReconstructor::windowAround(const std::vector<LayerPart>& parts) const {
    Box2 box;
    for (const LayerPart& p : parts)
        for (std::uint32_t c : p.contours)
            for (Point2 q : p.layer->contours[c]) box.add(q);
    return windowOf(grid_, box, kGridMarginPx);
}

/// The fields of `parts`, one slice each, in order, on `grid` (nullopt: the
/// window around them).
SliceFields SlabReconstructor::fieldsOf(const std::vector<LayerPart>& parts,
                                        std::optional<SliceGrid> grid) {
    std::vector<Slice> slices;
    for (const LayerPart& p : parts) {
        Slice& slice = slices.emplace_back(Slice{p.layer->zMm, {}});
        for (std::uint32_t c : p.contours) slice.contours.push_back(p.layer->contours[c]);
    }
    const ScopedSeconds timer(stats_.fieldsSeconds);
    return computeSliceFields(runtime_, slices, grid ? *grid : windowAround(parts), {},
                              options_.kernel);
}

/// Joins `lower` to `upper`, whose fields `sides` holds. False when a slab
/// of the stack proper (depth 0) was given up half-built because its caps
/// already meet: the caller closes it by prisms.
bool SlabReconstructor::slab(const LayerPart& lower, const LayerPart& upper, SlabFields sides,
                             int depth) {
    const SliceFields& fields = sides.fields;
    stats_.deepestLevel = std::max(stats_.deepestLevel, depth);
    const double middle = 0.5 * (lower.layer->zMm + upper.layer->zMm);
    std::vector<MedialAxis> axes;
    SliceSum sum;
    if (!lower.contours.empty() && !upper.contours.empty()) {
        const ScopedSeconds timer(stats_.medialSeconds);
        sum = sumSlices(fields, sides.lower, sides.upper);
        axes = traceMedialAxes(fields, sides.lower, sides.upper, sum);
        if (depth > 0 && outermostIsHole(lower, upper))
            for (MedialAxis& axis : axes) std::reverse(axis.pixels.begin(), axis.pixels.end());
    }
    const std::vector<Component> components =
        connectByAxes(axes, lower.contours.size(), upper.contours.size());
    LayerPart endingLower{lower.layer, {}}, endingUpper{upper.layer, {}};
    for (const Component& c : components) {
        if (!c.axes.empty()) continue;
        for (std::uint32_t k : c.lower) endingLower.contours.push_back(lower.contours[k]);
        for (std::uint32_t k : c.upper) endingUpper.contours.push_back(upper.contours[k]);
    }
    if (depth == 0 && options_.joinSlidSections && !stack_.fromVoxels)
        joinSlidSections(endingLower, endingUpper);
    if (depth == 0) {
        // Ends of the stack proper: capped as the user chose. Caps come first
        // because, between planes, the lids of contours ending below and
        // above both reach the middle of the gap, and where they meet there
        // (label maps' neighbouring regions, which touch in projection) the
        // slab is given up before the costly part.
        const std::size_t capsBefore = builder_.triangleCount();
        const double offsetMm =
            capOffsetMm(options_.capOffsetMm, upper.layer->zMm - lower.layer->zMm, true);
        cap(endingLower, {true, offsetMm, stack_.fromVoxels}, fields, sides.lower);
        cap(endingUpper, {false, offsetMm, stack_.fromVoxels}, fields, sides.upper);
        if (builder_.triangleCount() > capsBefore && breakTheirPiece(capsBefore)) return false;
    }
    for (const Component& c : components) {
        if (c.axes.empty()) continue;  // ending: capped above or closed below
        const LayerPart x = subset(lower, c.lower), y = subset(upper, c.upper);
        if (c.lower.size() == 1 && c.upper.size() == 1 && c.axes.size() == 1 &&
            !(depth == 0 && oneSideFarSmaller(x, y)) &&
            strip(x, y, axes[c.axes[0]], fields.grid, c.lower[0], c.upper[0]))
            continue;
        if (depth >= options_.maxDepth) {
            closeByPrisms(builder_, x, y, middle);
            ++stats_.limitClosings;
            continue;
        }
        // A component that is the whole slab has the fields in hand already.
        const bool wholeSlab = x.contours.size() == lower.contours.size() &&
                               y.contours.size() == upper.contours.size();
        if (wholeSlab)
            recurse(x, y, depth, sides, &sum);
        else
            recurse(x, y, depth, {fieldsOf({x, y}, std::nullopt)}, nullptr);
    }
    if (depth > 0) {
        closeByPrisms(builder_, endingLower, {}, middle);
        closeByPrisms(builder_, {}, endingUpper, middle);
    }
    return true;
}

void SlabReconstructor::joinSlidSections(LayerPart& endingLower, LayerPart& endingUpper) {
    const double heightMm = endingUpper.layer->zMm - endingLower.layer->zMm;
    std::vector<bool> lowerJoined(endingLower.contours.size(), false),
        upperJoined(endingUpper.contours.size(), false);
    for (const SlidPair& pair : matchSlidingSections(endingLower, endingUpper, heightMm)) {
        const std::uint32_t p = endingLower.contours[pair.lower],
                            q = endingUpper.contours[pair.upper];
        const Layer &lower = *endingLower.layer, &upper = *endingUpper.layer;
        const auto [lowerAt, upperAt] = slidCorrespondence(lower.contours[p], upper.contours[q]);
        // Not a loft band: the slices' interpolant has no zero set between
        // sections that do not overlap, so smoothing leaves it straight. A
        // band that folds through itself goes; the two are capped instead.
        if (!stitchUnfolded(lower.vertexIds[p], lowerAt, upper.vertexIds[q], upperAt, false))
            continue;
        lowerJoined[pair.lower] = upperJoined[pair.upper] = true;
        ++stats_.slidStrips;
    }
    auto keepUnjoined = [](LayerPart& part, const std::vector<bool>& joined) {
        std::vector<std::uint32_t> left;
        for (std::size_t i = 0; i < part.contours.size(); ++i)
            if (!joined[i]) left.push_back(part.contours[i]);
        part.contours = std::move(left);
    };
    keepUnjoined(endingLower, lowerJoined);
    keepUnjoined(endingUpper, upperJoined);
}

bool SlabReconstructor::strip(const LayerPart& x, const LayerPart& y, const MedialAxis& axis,
                              const SliceGrid& axisGrid, std::uint32_t lowerLocal,
                              std::uint32_t upperLocal) {
    const Layer& lower = *x.layer;
    const Layer& upper = *y.layer;
    const std::uint32_t p = x.contours[0], q = y.contours[0];
    const auto lowerAt = positionsAlongAxis(axis, axisGrid, lower.contours[p], lowerLocal, true);
    if (!lowerAt) return false;
    const auto upperAt = positionsAlongAxis(axis, axisGrid, upper.contours[q], upperLocal, false);
    if (!upperAt) return false;
    // Contours that zigzag or lean far can make a strip fold through itself;
    // such a band is solved again with an intermediate contour instead (and
    // at the limit closed by prisms, which cannot fold).
    if (!stitchUnfolded(lower.vertexIds[p], *lowerAt, upper.vertexIds[q], *upperAt, true)) {
        ++stats_.rejectedStrips;
        return false;
    }
    ++stats_.strips;
    return true;
}

bool SlabReconstructor::stitchUnfolded(const std::vector<std::uint32_t>& lowerIds,
                                       const AxisPositions& lowerAt,
                                       const std::vector<std::uint32_t>& upperIds,
                                       const AxisPositions& upperAt, bool loft) {
    const std::size_t before = builder_.triangleCount();
    stitchStrip(builder_, lowerIds, lowerAt, upperIds, upperAt);
    if (loft) builder_.markLoftSince(before);
    // Searched as a mesh file will hold it, as its piece is checked, so that
    // check need not search these pairs again.
    TriangleSoup band = builder_.trianglesSince(before);
    roundPointsToFloat(band);
    if (countSelfIntersections(band) > 0) {
        builder_.truncateTriangles(before);
        return false;
    }
    builder_.markSearchedTogetherSince(before);
    return true;
}

/// The paper's Fig. 7: the medial axis becomes a contour half-way, and both
/// halves are solved again. `sides` holds the fields of exactly x and y (a
/// whole slab passes its own, not a copy), `knownSum` (if set) their sum.
void SlabReconstructor::recurse(const LayerPart& x, const LayerPart& y, int depth, SlabFields sides,
                                const SliceSum* knownSum) {
    Slice middle{0.5 * (x.layer->zMm + y.layer->zMm), {}};
    {
        const ScopedSeconds timer(stats_.medialSeconds);
        const SliceSum sum =
            knownSum ? *knownSum : sumSlices(sides.fields, sides.lower, sides.upper);
        // The sections' trend (a waist between the planes, a small section
        // under a growing one) sets how much the middle encloses.
        const double areaRatio = stack_.planes ? hermiteAreaRatio(*stack_.planes, middle.zMm) : 1.0;
        std::vector<Polygon> isolines = middleIsolines(sum.sumMm, sides, x, y, areaRatio);
        // Pixel-step isolines carry far more points than the surface needs.
        for (SimplifiedContour& c : simplifySlice(isolines, 0.25 * grid_.pixelMm))
            if (c.points.size() >= 3) middle.contours.push_back(std::move(c.points));
        // Isolines keep the negative side on their left; contours keep the solid.
        if (outermostIsHole(x, y))
            for (Polygon& p : middle.contours) std::reverse(p.begin(), p.end());
    }
    if (middle.contours.empty()) {
        closeByPrisms(builder_, x, y, middle.zMm);
        ++stats_.limitClosings;
        return;
    }
    ++stats_.recursions;
    layers_.push_back(makeLayer(builder_, middle.zMm, std::move(middle.contours)));
    const Layer& mid = layers_.back();
    const LayerPart m = whole(mid);
    // Only the intermediate contours' field is new; x's and y's are reused.
    const SliceFields middleField = fieldsOf({m}, sides.fields.grid);
    slab(x, m, {pairOf(sides.fields, sides.lower, middleField, 0)}, depth + 1);
    slab(m, y, {pairOf(middleField, 0, sides.fields, sides.upper)}, depth + 1);
}

}  // namespace dfrecon
