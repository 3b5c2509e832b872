// Time for a built scene: advance it to a time, starting and stopping the plane walls' motions (a
// wall whose translation starts later than 0, or stops) exactly at their times on the way. Stateless
// and idempotent: a velocity already set is set again to the same value.
#pragma once
#include "workflow/scene/scene_build.hpp"

namespace spreadmap::scene {

// Returns false when keep_going asked to stop (checked every `every` steps).
template <class Real>
bool advance_scene(SceneRun<Real> &run, double t,
                   const typename engine::Simulation<Real>::StepCallback &keep_going = {}, std::uint64_t every = 100);

}  // namespace spreadmap::scene
