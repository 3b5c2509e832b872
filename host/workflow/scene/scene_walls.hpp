// The walls of a scene file as the engine sees them: a plane is one engine plane, a box six inward
// infinite planes (five with open_top: the lid left out), a cylinder and a block host geometries
// (cylinder_wall.hpp, block_wall.hpp). Infinite planes make a closed box exact inside it; outside a box nothing may
// be, so nothing is lost.
#pragma once
#include <vector>

#include "workflow/scene/scene_spec.hpp"

namespace spreadmap::scene {

struct PlaneOf {
  Vec point, normal;
  std::string name;
};

// The engine planes of a plane or box wall (none for a cylinder).
std::vector<PlaneOf> planes_of(const WallSpec &wall);

// How deep a sphere (centre c, radius r) sinks into the wall at time 0: > 0 overlapping, > r its
// centre is on the wrong side (outside the box, behind the plane, inside a solid cylinder or a block). A
// tube's wall counts from both sides (a sphere outside it, which the tube ignores, must not
// straddle it either); -inf beyond a tube's ends.
double wall_overlap(const WallSpec &wall, const Vec &c, double r);

}  // namespace spreadmap::scene
