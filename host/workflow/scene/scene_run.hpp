// Time for a built scene: advance it to a time, starting the plane walls' delayed motions (a wall
// whose translation starts later than 0) exactly at their start on the way. Stateless and
// idempotent: a motion already started is set again to the same velocity.
#pragma once
#include "workflow/scene/scene_build.hpp"

namespace spreadmap::scene {

// Returns false when keep_going asked to stop (checked every `every` steps).
template <class Real>
bool advance_scene(SceneRun<Real> &run, double t,
                   const typename engine::Simulation<Real>::StepCallback &keep_going = {}, std::uint64_t every = 100);

}  // namespace spreadmap::scene
