#pragma once
// Structure algebra on contours: margins (grow, shrink, per patient
// direction), unions, intersections, differences and exclusive ors of ROIs,
// as one expression ("Ring = (PTV + 20) - (PTV + 3)"), evaluated exactly
// against the ROIs' reconstructed surfaces and written back as contours on
// planes. What `dfrecon margin` and `dfrecon combine` compute, without the
// files.
//
// The solid of an ROI is its reconstructed surface (dfrecon/Reconstruct,
// the default reconstruction: it passes through every contour). A margin of
// M mm is the set of points within M of that solid (Minkowski sum with a
// ball; with per-axis values, an ellipsoid), a negative margin the points
// at least |M| inside it; the field of algebra/SolidField combines the
// exact distances, and algebra/PlaneSections draws its zero set on each
// plane: every contour vertex lies on the exact boundary (within 1e-4 mm,
// or 5 % of the lattice step where the boundary passes near a sample).
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "algebra/DistanceHistograms.hpp"
#include "algebra/PlaneSections.hpp"
#include "algebra/RoiExpression.hpp"
#include "algebra/SolidField.hpp"
#include "algebra/SolidSurface.hpp"
#include "cl/Runtime.hpp"
#include "contours/ContourSet.hpp"
#include "dfrecon/Reconstruct.hpp"

namespace dfrecon {

struct StructureAlgebraOptions {
    RoiReconstructOptions surfaces;  // how each ROI's solid is reconstructed
    PlaneSectionOptions sections;    // the lattice (stepMm: 0.25 mm)
    /// The planes of the result, mm along its frame's normal; empty: the
    /// planes of the ROIs it reads, continued at their spacing as far as
    /// the result reaches beyond them (a growth). ROIs of a single plane
    /// take the smallest spacing of the set's ROIs of that plane direction,
    /// else their slab thickness.
    std::vector<double> planesMm;
    DistanceBackend backend = DistanceBackend::Device;
    /// > 0: also the result's exact surface in space (algebra/SolidSurface)
    /// on voxels of this size (mm), where the field allows (no flat
    /// ellipsoid axis).
    double surfaceVoxelMm = 0;
    /// Called with the fraction of the work done (the ROIs' surfaces, then
    /// the planes' sections, then the surface in space), for a progress bar;
    /// none: not called. Overrides sections.progress.
    std::function<void(double)> progress;
    std::optional<Rgb> colour;    // of the new ROI; none: the writer's default
    std::string interpretedType;  // of the new ROI; empty: the writer's default
};

struct StructureAlgebraResult {
    Roi roi;                       // the new ROI, in the frame of the first ROI read
    RoiExpression expression;      // with its margins on the ROIs (marginsOnRois)
    std::vector<double> planesMm;  // every plane looked at (those with a section are roi.slices)
    PlaneSectionStats sections;
    /// The solids the expression read: each ROI's reconstructed surface's volume (mm³).
    std::map<std::string, double> surfaceVolumesMm3;
    /// The exact surface (patient mm, outward), when surfaceVoxelMm > 0,
    /// the field's Lipschitz bound in space is at most 50 and no margin has
    /// eight octants; else none.
    /// Its vertices lie on the exact boundary, unless moving them there
    /// made the mesh invalid (surfaceStats.projected false: then within a
    /// voxel of it, as OpenVDB's mesher put them).
    std::optional<TriangleSoup> surface;
    SolidSurfaceStats surfaceStats;
    double surfacesSeconds = 0, sectionsSeconds = 0, surfaceSeconds = 0;
};

/// Evaluates a parsed expression (parseRoiExpression) on `set`. Throws
/// ExpressionError for a margin that is not exact (marginsOnRois),
/// std::invalid_argument for ROIs whose planes are not parallel, an ROI
/// whose surface is not a valid closed solid, or an expression empty on
/// every plane; InputError for an ROI with a defect; ClError on device
/// failure. O(reconstructions + boundary samples × distance queries).
StructureAlgebraResult evaluateRoiExpression(ocl::Runtime& runtime, const ContourSet& set,
                                             const RoiExpression& expression,
                                             const StructureAlgebraOptions& options = {});

/// parseRoiExpression(definition, the set's names), then evaluateRoiExpression.
StructureAlgebraResult combineRois(ocl::Runtime& runtime, const ContourSet& set,
                                   const std::string& definition,
                                   const StructureAlgebraOptions& options = {});

/// ROI `roiName` grown (or shrunk) by `margin`, named `newName`.
StructureAlgebraResult marginRoi(ocl::Runtime& runtime, const ContourSet& set,
                                 const std::string& roiName, const DirectionalMargin& margin,
                                 const std::string& newName,
                                 const StructureAlgebraOptions& options = {});

/// The overlap-volume histogram and distance-to-target histogram
/// (algebra/DistanceHistograms) of ROI `oar` against ROI `target`, each
/// reconstructed with `surfaces` and required to be a valid closed solid.
/// Throws as evaluateRoiExpression. O(reconstructions + cells · log T).
DistanceHistograms roiDistanceHistograms(ocl::Runtime& runtime, const ContourSet& set,
                                         const std::string& oar, const std::string& target,
                                         const RoiReconstructOptions& surfaces = {},
                                         const DistanceHistogramOptions& options = {});

}  // namespace dfrecon
