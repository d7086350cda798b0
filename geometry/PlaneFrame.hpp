#pragma once
// Where an ROI's slice planes lie in patient space. Contours are stored in
// plane coordinates (x, y in the plane, z along its normal); the frame maps
// them to patient (DICOM LPS) millimetres. Axial stacks use the identity, so
// their coordinates are the patient coordinates unchanged.
#include "geometry/Vec3.hpp"

namespace dfrecon {

/// An orthonormal, right-handed basis: patient = x·u + y·v + z·n. For the
/// identity both maps return their argument bit for bit (x·1 + y·0 + z·0).
struct PlaneFrame {
    Vec3 u{1, 0, 0}, v{0, 1, 0}, n{0, 0, 1};

    bool isIdentity() const {
        return u == Vec3{1, 0, 0} && v == Vec3{0, 1, 0} && n == Vec3{0, 0, 1};
    }
    Vec3 toPatient(Vec3 p) const { return p.x * u + p.y * v + p.z * n; }
    Vec3 fromPatient(Vec3 p) const { return {dot(p, u), dot(p, v), dot(p, n)}; }
    /// "axial", "sagittal", "coronal" when n is a patient axis, else "oblique".
    const char* orientationName() const;
};

/// The frame whose normal is `normal` (need not be unit length; must not be
/// zero). For a patient axis the in-plane axes are the other two in cyclic
/// order (n = x: u = y, v = z; n = y: u = z, v = x; n = z: identity), so
/// sagittal and coronal stacks get their natural image axes; otherwise u is
/// the patient axis least aligned with n, made orthogonal to it.
PlaneFrame frameWithNormal(Vec3 normal);

/// The frame readers settle on for planes normal to a patient axis (within
/// 1e-9): frameWithNormal(+axis). Every axial stack then has the identity,
/// whichever way its source's axes ran (a RAS label volume, slices stored
/// feet first), so its plane coordinates are patient LPS coordinates; a
/// sagittal stack has (y, z, x), a coronal one (z, x, y). Any other frame is
/// returned unchanged. O(1).
PlaneFrame canonicalFrame(const PlaneFrame& frame);

}  // namespace dfrecon
