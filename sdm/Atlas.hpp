#pragma once
// The texture atlas of a mesh (paper §3.2): every triangle gets its own
// chart, an affine map into a 2D texture — here a similarity (rotation,
// translation and one scale for the whole atlas), so a texel is a square of
// the same size in mm on every triangle — and the charts are packed in rows
// with no two sharing a texel. The distance maps are sampled once per texel.
//
// Sampling bound (paper §5, Lemma 2): with no shear and equal scales
// s_x = s_y = texelMm, adjacent samples are at most √2·texelMm apart in 3D.
// Texels are assigned conservatively (every texel whose square touches the
// triangle) and sample the triangle's point nearest to the texel centre, so
// every point of the surface lies within √2·texelMm of a sample of its own
// triangle; a distance map is 1-Lipschitz, so that is also its largest error
// between samples.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/Polygon.hpp"
#include "geometry/TriangleSoup.hpp"

namespace dfrecon {

struct AtlasOptions {
    /// Width and height in texels when maxErrorMm is 0: the texel size is
    /// then the smallest at which every chart fits.
    int sizeTexels = 512;
    /// When > 0, the texel size is chosen so the sampling bound is this
    /// (texelMm = maxErrorMm / √2) and the atlas is as large as that needs.
    double maxErrorMm = 0;
    /// Refuse atlases larger than this many texels (memory guard).
    std::size_t maxTexels = std::size_t(1) << 26;
};

/// One triangle's chart: its rectangle of texels and its corners in texel
/// coordinates (texel (i, j) is the square [i, i+1] × [j, j+1]).
struct TriangleChart {
    int x = 0, y = 0;  // the rectangle's first texel
    int width = 0, height = 0;
    Point2 corners[3];  // in the soup's corner order
};

struct Atlas {
    int width = 0, height = 0;
    double texelMm = 0;                       // a texel's edge in mm on every chart
    std::vector<TriangleChart> charts;        // one per triangle of the soup
    std::vector<std::int32_t> texelTriangle;  // row-major; -1 for texels no chart uses

    /// Paper §5, Lemma 2 for these charts: no point of the surface is
    /// farther than this from the sample of a texel on its triangle.
    double samplingBoundMm() const;
    std::size_t usedTexels() const;
};

/// Builds the atlas of `soup`. Throws std::invalid_argument when the charts
/// cannot fit (more triangles than texels) or the atlas would exceed
/// options.maxTexels. O(T log T + texels) for a given texel size; a fixed
/// size searches the texel size by bisection (O(T) per step).
Atlas buildAtlas(const TriangleSoup& soup, const AtlasOptions& options = {});

/// The surface points the atlas samples: for every used texel (grouped by
/// triangle), its index, its triangle and the triangle's point nearest to
/// the texel centre's preimage. O(used texels).
struct AtlasSamples {
    std::vector<std::uint32_t> texel;
    std::vector<std::uint32_t> triangle;
    std::vector<Vec3> point;
};
AtlasSamples atlasSamples(const Atlas& atlas, const TriangleSoup& soup);

}  // namespace dfrecon
