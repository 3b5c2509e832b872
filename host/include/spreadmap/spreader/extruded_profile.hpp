// A solid made by extruding a convex x–z profile along y over a finite length (flat end faces):
// a disc profile (a turning cylinder) or a rounded rectangle (a flat body). Given the profile's signed
// distance and outward normal at a point's (x, z), this combines them with the point's offset
// along y into the exact signed distance and outward normal of the finite solid, so that spheres
// near an end face or rim are handled too (a sphere beyond the end by more than its radius never
// touches).
#pragma once
#include <spreadmap/hd.hpp>

namespace spreadmap::spreader {

// Closest-point answer of a 2-D profile in the x–z plane at one point.
template <class Real> struct ProfileDistance {
  Real distance;  // signed: > 0 outside the profile, < 0 inside [m]
  Real nx, nz;    // unit outward normal of the nearest boundary point
};

// Signed distance and outward normal of a rectangle with rounded lower corners, in coordinates
// relative to its centre (u along x, w along z). Half sizes hx, hz; lower corner radius rho
// (<= min(hx, hz); 0: sharp corners).
template <class Real>
SM_HD ProfileDistance<Real> rounded_rectangle_distance(Real u, Real w, Real hx, Real hz, Real rho) {
  const Real su = u < Real(0) ? Real(-1) : Real(1), sw = w < Real(0) ? Real(-1) : Real(1);
  const Real corner = w < Real(0) ? rho : Real(0);
  // Fold into the first quadrant; (qx, qz) is the offset from the rectangle shrunk by `corner`.
  const Real qx = su * u - (hx - corner), qz = sw * w - (hz - corner);
  if (qx > Real(0) && qz > Real(0)) {  // facing a corner: nearest point on its arc
    const Real q = std::sqrt(qx * qx + qz * qz);
    return {q - corner, su * qx / q, sw * qz / q};
  }
  if (qx >= qz) return {qx - corner, su, Real(0)};  // nearest point on a vertical face
  return {qz - corner, Real(0), sw};                // nearest point on the top or bottom face
}

// Signed 3-D distance of the point to the extruded solid, and the outward unit normal of its
// nearest surface point. dy = y - y_centre, half_length = length / 2. For a point inside the
// solid the normal is that of the nearest face (least penetration).
template <class Real>
SM_HD Real extruded_distance(const ProfileDistance<Real> &profile, Real dy, Real half_length, Vec3<Real> &normal) {
  const Real axial = (dy < Real(0) ? -dy : dy) - half_length;  // > 0 beyond an end face
  const Real side = dy < Real(0) ? Real(-1) : Real(1);
  if (profile.distance > Real(0) && axial > Real(0)) {  // nearest point on a rim
    const Real d = std::sqrt(profile.distance * profile.distance + axial * axial);
    normal = {profile.distance * profile.nx / d, side * axial / d, profile.distance * profile.nz / d};
    return d;
  }
  if (profile.distance >= axial) {  // nearest point on the profile's surface
    normal = {profile.nx, Real(0), profile.nz};
    return profile.distance;
  }
  normal = {Real(0), side, Real(0)};  // nearest point on an end face
  return axial;
}

}  // namespace spreadmap::spreader
