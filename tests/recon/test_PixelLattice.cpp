// Contours on a pixel lattice (label maps) and the smooth surface between
// them: the voxels bound the structure, so no bent vertex may leave the
// union of its slab's two planes' regions.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/MeshCheck.hpp"
#include "geometry/SurfaceMeasures.hpp"
#include "io/contours/SlicesFile.hpp"
#include "recon/PixelLattice.hpp"
#include "recon/Reconstruction.hpp"
#include "tests/CpuRuntime.hpp"

namespace dfrecon {
namespace {

// How far p lies outside the union of the regions of `slices` (even-odd over
// their contours: holes count), 0 inside. O(points).
double outsideUnion(Point2 p, const std::vector<const Slice*>& slices) {
    double nearest = INFINITY;
    for (const Slice* slice : slices) {
        int crossings = 0;
        for (const Polygon& contour : slice->contours) {
            crossings += windingNumber(p, contour) != 0;
            nearest = std::min(nearest, distanceToBoundary(p, contour));
        }
        if (crossings % 2 == 1) return 0;
    }
    return nearest;
}

TEST(PixelLattice, LabelMapBordersAreOnALatticeFreehandContoursAreNot) {
    const ContourSet balls =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/voxel-balls.slices").contours;
    EXPECT_TRUE(followsPixelLattice(balls.rois[0].slices));
    Slice circle{0, {circlePolygon({0.3, -1.1}, 10, 64)}};
    EXPECT_FALSE(followsPixelLattice({circle, circle}));
    // A lattice shifted off the origin is a lattice (a square of 40 points
    // 1 mm apart; its edges' steps, 1 mm, are the lattice's).
    Polygon edge;
    for (int k = 0; k < 10; ++k) edge.push_back({0.25 + k, 0.25});
    for (int k = 0; k < 10; ++k) edge.push_back({10.25, 0.25 + k});
    for (int k = 0; k < 10; ++k) edge.push_back({10.25 - k, 10.25});
    for (int k = 0; k < 10; ++k) edge.push_back({0.25, 10.25 - k});
    Slice square{0, {edge}};
    std::vector<Slice> squares(8, square);
    for (std::size_t k = 0; k < squares.size(); ++k) squares[k].zMm = double(k);
    EXPECT_TRUE(followsPixelLattice(squares));
}

TEST(PixelLattice, SmoothSurfaceStaysWithinTheVoxelsOfALabelMap) {
    // Two overlapping balls voxelised at 1 mm, contoured by dfrecon convert
    // from a label volume (half-pixel staircases): the default smooth surface
    // bent 2 % of its vertices up to 0.07 mm beyond both neighbouring planes'
    // regions; kept within them, none is.
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/voxel-balls.slices").contours;
    const Roi& roi = set.rois[0];
    const Reconstruction r = reconstructSurface(cpuRuntime(), roi);
    const MeshCheckReport check = checkMesh(r.surface);
    EXPECT_TRUE(check.validSolid());
    EXPECT_GT(r.stats.smoothedVertices, 0u);
    EXPECT_NEAR(check.volumeMm3 / contourVolumeMm3(roi), 1.0, 0.01);
    std::vector<const Slice*> planes;
    for (const Slice& s : roi.slices)
        if (!s.contours.empty()) planes.push_back(&s);
    double worst = 0;
    for (const Vec3& p : r.surface.points) {
        for (std::size_t k = 0; k + 1 < planes.size(); ++k)
            if (p.z > planes[k]->zMm + 1e-4 && p.z < planes[k + 1]->zMm - 1e-4)
                worst = std::max(worst, outsideUnion({p.x, p.y}, {planes[k], planes[k + 1]}));
    }
    EXPECT_LE(worst, 0.01);
}

TEST(PixelLattice, TheEndsOfALabelMapAreItsLastVoxelLayers) {
    // The balls' end planes hold small sections above larger ones: a flat
    // cap following the staircase's slope narrowed to its lid and held less
    // than the last voxel layer. From voxels, the cap is that layer: a prism
    // of the end section, half a spacing deep, to the cubic millimetre.
    const ContourSet set =
        readSlicesFile(std::string(DFRECON_TEST_DATA) + "/recon/voxel-balls.slices").contours;
    const Roi& roi = set.rois[0];
    for (const Interpolation mode : {Interpolation::Smooth, Interpolation::Linear}) {
        ReconstructionOptions options;
        options.interpolation = mode;
        const Reconstruction r = reconstructSurface(cpuRuntime(), roi, options);
        ASSERT_TRUE(checkMesh(r.surface).validSolid());
        const Slice& first = roi.slices.front();
        const Slice& last = roi.slices.back();
        const double halfSpacing = 0.5 * (roi.slices[1].zMm - first.zMm);
        double firstArea = 0, lastArea = 0;
        for (const Polygon& c : first.contours) firstArea += signedArea(c);
        for (const Polygon& c : last.contours) lastArea += signedArea(c);
        EXPECT_NEAR(volumeBelowPlane(r.surface, first.zMm), firstArea * halfSpacing, 1e-3);
        EXPECT_NEAR(checkMesh(r.surface).volumeMm3 - volumeBelowPlane(r.surface, last.zMm),
                    lastArea * halfSpacing, 1e-3);
    }
}

}  // namespace
}  // namespace dfrecon
