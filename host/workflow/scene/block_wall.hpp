// A block wall of a scene file: a solid axis-aligned box the particles stay outside of (a plate, a
// step, a piston, a build platform), given to the engine as a geometry (engine::GeometryWall) with an
// ops table the host builds itself, as cylinder_wall.hpp does. Unlike the `box` wall (six infinite
// planes, exact only inside it), a block is exact all around: a sphere touches its nearest point,
// on a face, an edge or a corner, so blocks side by side build a step, a well or a trench, and a
// sphere in a concave corner between two blocks touches both.
//
// The block spans [lo, hi] at time 0 and translates with `velocity` between times `start` and `stop`
// (at rest before and after): a piston rising by a dosing height, a platform lowered by a layer.
// Overlap = sphere radius - distance of its centre to the block's surface (a centre inside the block
// is pushed out through its nearest face); the normal points from the surface into the sphere. SI.
#pragma once
#include <spreadmap/geometry.hpp>

#include <cmath>

namespace spreadmap::scene {

struct BlockWall {
  double lo[3], hi[3];  // corners at time 0 [m]
  double velocity[3];   // [m/s]
  double start, stop;   // the translation runs from start to stop [s]

  // How long the block has moved by time t [s].
  template <class Real> SM_HD Real time_moved(Real t) const {
    return t < Real(start) ? Real(0) : t > Real(stop) ? Real(stop - start) : t - Real(start);
  }

  template <class Real> SM_HD bool operator()(const Vec3<Real> &p, Real r, Real t, WallHit<Real> &hit) const {
    const Real moved = time_moved(t);
    const Real q[3] = {p.x - Real(velocity[0]) * moved, p.y - Real(velocity[1]) * moved,
                       p.z - Real(velocity[2]) * moved};
    Real outside[3];  // the centre's distance beyond each pair of faces (0 between them)
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      outside[a] = q[a] < Real(lo[a]) ? q[a] - Real(lo[a]) : q[a] > Real(hi[a]) ? q[a] - Real(hi[a]) : Real(0);
      inside = inside && outside[a] == Real(0);
    }
    Real dist;  // signed distance of the centre to the surface, < 0 inside
    Vec3<Real> n;
    if (!inside) {
      const Vec3<Real> e{outside[0], outside[1], outside[2]};
      dist = norm(e);
      if (!(r - dist > Real(0))) return false;
      n = e * (Real(1) / dist);
    } else {  // through the nearest face
      dist = -(q[0] - Real(lo[0]));
      n = {Real(-1), Real(0), Real(0)};
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
          const Real depth = side == 0 ? q[a] - Real(lo[a]) : Real(hi[a]) - q[a];
          if (-depth > dist) {
            dist = -depth;
            Real v[3] = {0, 0, 0};
            v[a] = side == 0 ? Real(-1) : Real(1);
            n = {v[0], v[1], v[2]};
          }
        }
    }
    const bool moving = t > Real(start) && t < Real(stop);
    hit.overlap = r - dist;
    hit.normal = n;
    hit.velocity = {moving ? Real(velocity[0]) : Real(0), moving ? Real(velocity[1]) : Real(0),
                    moving ? Real(velocity[2]) : Real(0)};
    return true;
  }

  double max_surface_speed() const {
    return std::sqrt(velocity[0] * velocity[0] + velocity[1] * velocity[1] + velocity[2] * velocity[2]);
  }
  // Nothing for the spreading figures: a block is not a spreader.
  void describe(sm_spreader_description_v2 *) const {}
  void pose(double t, sm_spreader_pose_v2 *out) const {
    const double moved = time_moved(t);
    for (int a = 0; a < 3; ++a) out->reference[a] = lo[a] + velocity[a] * moved;
  }
};

// The ops table the engine calls for a BlockWall (`self` points to one).
inline const sm_spreader_ops_v2 &block_wall_ops() { return detail::GeometryOps<BlockWall>::table; }

}  // namespace spreadmap::scene
