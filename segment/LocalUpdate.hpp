#pragma once
// The local eikonal update on one triangle, in C++: the text of
// kernels/eikonal_update.cl compiled as C++ with REAL = double, so that fast
// marching, the fast iterative method's C++ reference and its OpenCL kernel
// share one implementation (see that file for the mathematics). O(1).
#include <cmath>

namespace dfrecon {

namespace eikonal {
using std::sqrt;
#define REAL double
#define EIKONAL_FN inline
#include "kernels/eikonal_update.cl"
#undef EIKONAL_FN
#undef REAL
}  // namespace eikonal

/// How the front reached a vertex (EIKONAL_VIA_* of the shared update).
enum class Upwind : int {
    AlongA = EIKONAL_VIA_A,
    AlongB = EIKONAL_VIA_B,
    AcrossFace = EIKONAL_VIA_FACE,
};

/// One triangle update (kernels/eikonal_update.cl, eikonal_triangle_update).
struct TriangleUpdate {
    double time = 0;
    Upwind upwind = Upwind::AlongA;
    double weightB = 0;  // where the characteristic crosses AB: 0 at A, 1 at B
};

/// The triangle an update runs over, seen from the corner C it updates: the
/// lengths of its edges CA and CB and the cosine of its angle at C.
struct UpdateCorner {
    double lengthA = 0, lengthB = 0, cosC = 0;
};

/// C's arrival time from A's (ta) and B's (tb) over `corner`'s triangle at
/// `slowness`; across the face only when `acrossFace` (else along an edge).
inline TriangleUpdate triangleUpdate(double ta, double tb, const UpdateCorner& corner,
                                     double slowness, bool acrossFace) {
    TriangleUpdate result;
    int via = 0;
    result.time =
        eikonal::eikonal_triangle_update(ta, tb, corner.lengthA, corner.lengthB, corner.cosC,
                                         slowness, acrossFace ? 1 : 0, &via, &result.weightB);
    result.upwind = Upwind(via);
    return result;
}

inline int upwindLabel(const TriangleUpdate& update, int labelA, int labelB) {
    return eikonal::eikonal_upwind_label(int(update.upwind), labelA, labelB);
}

}  // namespace dfrecon
