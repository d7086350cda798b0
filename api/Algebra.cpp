#include "dfrecon/Algebra.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "api/Stopwatch.hpp"
#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"

namespace dfrecon {

namespace {

// Planes closer than this are one plane (DICOM's DS precision, and the
// tolerance readers put planes together by).
constexpr double kMergedPlanesWithinMm = 1e-3;

// The planes of `rois`, in `frame` (z along its normal), sorted, merged
// within kMergedPlanesWithinMm.
std::vector<double> planesOf(const std::vector<const Roi*>& rois, const PlaneFrame& frame) {
    std::vector<double> zs;
    for (const Roi* roi : rois) {
        Roi copy = *roi;
        changeFrame(copy, frame);
        for (const Slice& s : copy.slices) zs.push_back(s.zMm);
    }
    std::sort(zs.begin(), zs.end());
    std::vector<double> merged;
    for (double z : zs)
        if (merged.empty() || z - merged.back() > kMergedPlanesWithinMm) merged.push_back(z);
    return merged;
}

// The middle gap between consecutive planes (0 for fewer than two).
double typicalSpacing(const std::vector<double>& zs) {
    if (zs.size() < 2) return 0;
    std::vector<double> gaps;
    for (std::size_t k = 1; k < zs.size(); ++k) gaps.push_back(zs[k] - zs[k - 1]);
    std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(gaps.size() / 2), gaps.end());
    return gaps[gaps.size() / 2];
}

// `zs` continued by whole spacings below and above, as far as [lo, hi].
std::vector<double> extendedPlanes(std::vector<double> zs, double lo, double hi, double spacing) {
    if (zs.empty() || !(spacing > 0)) return zs;
    std::vector<double> below, above;
    for (double z = zs.front() - spacing; z >= lo - kMergedPlanesWithinMm; z -= spacing)
        below.push_back(z);
    for (double z = zs.back() + spacing; z <= hi + kMergedPlanesWithinMm; z += spacing)
        above.push_back(z);
    std::reverse(below.begin(), below.end());
    below.insert(below.end(), zs.begin(), zs.end());
    below.insert(below.end(), above.begin(), above.end());
    return below;
}

// The box's extent in `frame`'s coordinates.
void frameExtent(const Box3& box, const PlaneFrame& frame, Vec3& lo, Vec3& hi) {
    lo = {INFINITY, INFINITY, INFINITY};
    hi = {-INFINITY, -INFINITY, -INFINITY};
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner{(c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                          (c & 4) ? box.hi.z : box.lo.z};
        const Vec3 p = frame.fromPatient(corner);
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
}

// The ROI's reconstructed surface, which must be a valid closed solid for
// inside and outside to mean anything.
TriangleSoup solidOf(ocl::Runtime& runtime, const Roi& roi, const RoiReconstructOptions& options) {
    RoiSurface s = reconstructRoi(runtime, roi, options);
    if (!s.check.validSolid())
        throw std::invalid_argument("the reconstructed surface of ROI '" + roi.name +
                                    "' is not a valid closed solid, so its inside is not defined");
    return std::move(s.surface);
}

const Roi& roiNamed(const ContourSet& set, const std::string& name) {
    const Roi* roi = set.findRoi(name);
    if (!roi) throw std::invalid_argument("no ROI named '" + name + "' in the structure set");
    return *roi;
}

}  // namespace

StructureAlgebraResult evaluateRoiExpression(ocl::Runtime& runtime, const ContourSet& set,
                                             const RoiExpression& expression,
                                             const StructureAlgebraOptions& options) {
    StructureAlgebraResult out;
    out.expression = marginsOnRois(expression);
    std::vector<const Roi*> rois;
    for (const std::string& name : out.expression.rois()) rois.push_back(&roiNamed(set, name));
    const PlaneFrame frame = rois.front()->frame;
    for (const Roi* roi : rois)
        if (std::abs(std::abs(dot(roi->frame.n, frame.n)) - 1) > 1e-9)
            throw std::invalid_argument("ROI '" + roi->name + "' is drawn on planes (" +
                                        roi->frame.orientationName() + ") not parallel to '" +
                                        rois.front()->name + "''s (" + frame.orientationName() +
                                        "); an expression reads ROIs of one plane direction");

    const Stopwatch watch;
    std::map<std::string, TriangleSoup> surfaces;
    // Progress: the surfaces a third, the sections most of the rest.
    const bool withSurface = options.surfaceVoxelMm > 0;
    const double sectionsEnd = withSurface ? 0.85 : 1.0;
    auto report = [&](double fraction) {
        if (options.progress) options.progress(fraction);
    };
    for (const Roi* roi : rois) {
        TriangleSoup s = solidOf(runtime, *roi, options.surfaces);
        out.surfaceVolumesMm3[roi->name] = measureSurface(s).volumeMm3;
        surfaces.emplace(roi->name, std::move(s));
        report(0.33 * double(surfaces.size()) / double(rois.size()));
    }
    out.surfacesSeconds = watch.total();

    ExpressionField field(out.expression, surfaces, frame, options.backend, &runtime);
    Vec3 lo, hi;
    const Box3 support = field.support();
    if (support.lo.x > support.hi.x || support.lo.y > support.hi.y || support.lo.z > support.hi.z)
        throw std::invalid_argument("'" + expression.name + "' = " + expression.text() +
                                    " is empty: its ROIs do not overlap");
    frameExtent(support, frame, lo, hi);
    if (options.planesMm.empty()) {
        const std::vector<double> own = planesOf(rois, frame);
        // ROIs of one plane have no spacing of their own: the set's other
        // ROIs of this plane direction give it, else a slab thickness.
        double spacing = typicalSpacing(own);
        if (!(spacing > 0)) {
            std::vector<const Roi*> parallel;
            for (const Roi& roi : set.rois)
                if (!roi.defect && std::abs(std::abs(dot(roi.frame.n, frame.n)) - 1) <= 1e-9)
                    parallel.push_back(&roi);
            for (const Roi* roi : parallel) {
                const double gap = typicalSpacing(planesOf({roi}, frame));
                if (gap > 0 && (!(spacing > 0) || gap < spacing)) spacing = gap;
            }
            for (const Roi* roi : rois)
                if (!(spacing > 0) && roi->slabThicknessMm > 0) spacing = roi->slabThicknessMm;
        }
        out.planesMm = extendedPlanes(own, lo.z, hi.z, spacing);
    } else {
        for (double z : options.planesMm)
            if (z >= lo.z - kMergedPlanesWithinMm && z <= hi.z + kMergedPlanesWithinMm)
                out.planesMm.push_back(z);
        std::sort(out.planesMm.begin(), out.planesMm.end());
    }

    const PlaneField inPlanes = [&](const std::vector<Vec3>& planePoints) {
        std::vector<Vec3> patient(planePoints.size());
        for (std::size_t k = 0; k < planePoints.size(); ++k)
            patient[k] = frame.toPatient(planePoints[k]);
        return field.values(patient);
    };
    const Stopwatch sectionWatch;
    PlaneSectionOptions sections = options.sections;
    sections.zeroToleranceMm = std::max(sections.zeroToleranceMm, field.toleranceMm());
    if (options.progress)
        sections.progress = [&](double planes) { report(0.33 + (sectionsEnd - 0.33) * planes); };
    out.roi.slices =
        planeSections(inPlanes, out.planesMm, {lo.x, hi.x, lo.y, hi.y}, sections, &out.sections);
    out.sectionsSeconds = sectionWatch.total();
    if (out.roi.slices.empty())
        throw std::invalid_argument("'" + expression.name + "' = " + expression.text() +
                                    " has no section on any plane: it is empty");
    // The exact surface in space, where the field's slope allows sampling
    // it (a flat ellipsoid axis makes it steep along that axis) and its
    // values are cheap (an eight-octant margin's gauge is found on the host:
    // a minute for a 20 mm sphere's surface).
    constexpr double kSteepestForSurface = 50;
    if (options.surfaceVoxelMm > 0 && field.lipschitzInSpace() <= kSteepestForSurface &&
        !field.hasOctantMargins()) {
        const Stopwatch surfaceWatch;
        SolidSurfaceOptions surfaceOptions;
        surfaceOptions.voxelMm = options.surfaceVoxelMm;
        const SpaceField inSpace = [&](const std::vector<Vec3>& p) { return field.values(p); };
        out.surface = solidSurface(inSpace, field.lipschitzInSpace(), support, surfaceOptions,
                                   &out.surfaceStats);
        // Moving vertices onto the exact boundary can fold the mesh where two
        // sheets pass within a voxel; the mesher's own vertices then serve.
        TriangleSoup asWritten = *out.surface;
        roundPointsToFloat(asWritten);
        if (!checkMesh(asWritten).validSolid()) {
            surfaceOptions.projectVertices = false;
            out.surface = solidSurface(inSpace, field.lipschitzInSpace(), support, surfaceOptions,
                                       &out.surfaceStats);
            out.surfaceStats.projected = false;
        }
        out.surfaceSeconds = surfaceWatch.total();
    }
    report(1.0);
    out.roi.name = expression.name;
    out.roi.frame = frame;
    out.roi.colour = options.colour;
    out.roi.interpretedType = options.interpretedType;
    return out;
}

StructureAlgebraResult combineRois(ocl::Runtime& runtime, const ContourSet& set,
                                   const std::string& definition,
                                   const StructureAlgebraOptions& options) {
    std::vector<std::string> names;
    for (const Roi& roi : set.rois) names.push_back(roi.name);
    return evaluateRoiExpression(runtime, set, parseRoiExpression(definition, names), options);
}

StructureAlgebraResult marginRoi(ocl::Runtime& runtime, const ContourSet& set,
                                 const std::string& roiName, const DirectionalMargin& margin,
                                 const std::string& newName,
                                 const StructureAlgebraOptions& options) {
    roiNamed(set, roiName);
    if (margin.grows() && margin.shrinks())
        throw std::invalid_argument("margin " + margin.text() +
                                    " both grows and shrinks; give all values one sign");
    RoiExpression e;
    e.name = newName;
    ExpressionNode leaf;
    leaf.roi = roiName;
    e.nodes.push_back(leaf);
    if (!margin.isZero()) {
        ExpressionNode m;
        m.kind = ExpressionNode::Kind::Margin;
        m.left = 0;
        m.margin = margin;
        e.nodes.push_back(m);
        e.root = 1;
    }
    return evaluateRoiExpression(runtime, set, e, options);
}

DistanceHistograms roiDistanceHistograms(ocl::Runtime& runtime, const ContourSet& set,
                                         const std::string& oar, const std::string& target,
                                         const RoiReconstructOptions& surfaces,
                                         const DistanceHistogramOptions& options) {
    const Roi &oarRoi = roiNamed(set, oar), &targetRoi = roiNamed(set, target);
    const TriangleSoup oarSolid = solidOf(runtime, oarRoi, surfaces);
    const TriangleSoup targetSolid = solidOf(runtime, targetRoi, surfaces);
    return distanceHistograms(oarSolid, targetSolid, options, &runtime);
}

}  // namespace dfrecon
