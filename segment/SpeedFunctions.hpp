#pragma once
// Speed functions F > 0 per vertex for the eikonal solvers (the paper's
// §2.4): from the surface's curvature, the "edge repulsive" F1 = 1 + e·κ and
// the "edge attractive" F2 = 1 / (1 + m·κ) of its eq. 3, and from a scalar
// given per vertex (a texture, a dose): F = 1 / (1 + m·|∇I|).
//
// κ is the total curvature |κ1| + |κ2| per vertex (1/mm) from the discrete
// operators of Meyer, Desbrun, Schröder & Barr (2003): mean curvature from
// the cotangent Laplacian and Gaussian curvature from the angle deficit,
// both over the mixed Voronoi area; κ1,2 = H ± √(H² − K) gives
// |κ1| + |κ2| = 2|H| where K ≥ 0 and 2√(H² − K) where K < 0.
//
// The weights e and m are lengths (mm). On a sharp crease the discrete κ
// grows like 1/(edge length) on a one-vertex-wide band, so the time it takes
// a front to cross the crease with F2 is about 1.4·m for a 90° crease,
// whatever the resolution; on smooth parts (radius R) m·κ = 2m/R. The
// default, defaultCurvatureWeight, makes crossing a 90° crease cost about
// as much as crossing one region of a k-region segmentation: enough for
// borders to settle on creases (the cube test), while curvature much
// gentler than the regions' size changes the speed little.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "segment/MeshGraph.hpp"

namespace dfrecon {

enum class SpeedKind { Uniform, EdgeRepulsive, EdgeAttractive };

/// The one list of the speeds' names, which the command line parses and
/// reports print (report/EnumNames.hpp reads it); toString and parseSpeedKind
/// read it too.
inline constexpr std::array<std::pair<const char*, SpeedKind>, 3> kSpeedKindNames{{
    {"uniform", SpeedKind::Uniform},
    {"repulsive", SpeedKind::EdgeRepulsive},
    {"attractive", SpeedKind::EdgeAttractive},
}};

/// The name of `kind` in kSpeedKindNames. O(1).
const char* toString(SpeedKind kind);
/// The kind named `name` in kSpeedKindNames; throws std::invalid_argument
/// listing the names.
SpeedKind parseSpeedKind(const std::string& name);

/// √(area / regions) in mm: the size of one region if the surface were cut
/// into `regions` equal square-ish pieces.
double defaultCurvatureWeight(const MeshGraph& graph, int regions = 10);

/// |κ1| + |κ2| per vertex in 1/mm; 0 at mesh-boundary vertices (no
/// reliable estimate there). O(T).
std::vector<double> totalCurvature(const MeshGraph& graph);

/// F per vertex for `kind` with curvature weight `weightMm` (e of F1, m of
/// F2; ignored for Uniform). weightMm ≤ 0 means defaultCurvatureWeight. O(T).
std::vector<double> curvatureSpeed(const MeshGraph& graph, SpeedKind kind, double weightMm = 0);

/// F = 1 / (1 + weight·|∇I|) per vertex for a scalar I given per vertex
/// (weight in mm per unit of I), |∇I| averaged over the triangles around the
/// vertex by area. Throws std::invalid_argument for a wrong size or a
/// negative weight. O(T).
std::vector<double> scalarGradientSpeed(const MeshGraph& graph, const std::vector<double>& values,
                                        double weight);

}  // namespace dfrecon
