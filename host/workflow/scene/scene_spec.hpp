// A scene file (`spreadmap simulate SCENE.yaml`) as a typed value: everything SI, every path
// absolute, every choice checked. docs/scenes.md is the reference of the file's keys.
#pragma once
#include <array>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/diagnostics.hpp"
#include "engine/domain.hpp"
#include "workflow/scene/block_wall.hpp"
#include "workflow/scene/cylinder_wall.hpp"

namespace spreadmap::scene {

namespace fs = std::filesystem;
using Vec = std::array<double, 3>;

enum class WallKind { plane, box, cylinder, block, spreader };

// A spreader plugin as a wall (`type: spreader`), moving as it describes itself through the plugin ABI.
struct SpreaderWall {
  std::string use;                                   // the spreader plugin
  nlohmann::json params = nlohmann::json::object();  // its parameters (validated, SI)
  double time_offset = 0;  // the plugin sees time t + time_offset (< 0: still at rest before its start)
};

struct WallSpec {
  WallKind kind = WallKind::plane;
  std::string name;      // for messages and the log: the `name` key, else "walls[k] (plane)"
  std::string key_path;  // "walls[2]": where messages point
  Location where;
  Vec point{0, 0, 0}, normal{0, 0, 1};  // plane: a point on it and the normal into the particle side
  Vec lo{0, 0, 0}, hi{0, 0, 0};         // box: particles live inside; block: the solid (at time 0)
  bool open_top = false;                // box: no lid (the plane at hi.z is left out)
  CylinderWall cylinder{};              // cylinder
  SpreaderWall spreader;                // spreader
  Vec velocity{0, 0, 0};                // planes, boxes and blocks translate; a cylinder's motion is in it
  double start = 0;                     // the motion starts at this time [s]
  double stop = std::numeric_limits<double>::infinity();  // and stops at this one [s]
  nlohmann::json law;                   // the contact law's parameters for this wall (SI)
};

// The block a `block` wall describes: its corners at time 0, moving with its velocity from start to stop.
inline BlockWall block_of(const WallSpec &w) {
  return {{w.lo[0], w.lo[1], w.lo[2]}, {w.hi[0], w.hi[1], w.hi[2]}, {w.velocity[0], w.velocity[1], w.velocity[2]},
          w.start, w.stop};
}

// Generated particles: random non-overlapping spheres in a box (the heap generator), clear of every
// wall, which then fall or settle as the scene makes them (pouring).
struct GeneratedParticles {
  Vec lo{0, 0, 0}, hi{0, 0, 0};
  long count = 0;
  double diameter = 0, sigma = 0;  // sigma > 0: lognormal sizes with median `diameter`
  long seed = 1;
  Vec velocity{0, 0, 0};
};

struct ParticleSource {
  fs::path file;  // a CSV (engine/csv_input.hpp), or empty
  bool generate = false;
  GeneratedParticles generated;
  double density = 0;            // [kg/m^3] for particles without a density or mass column; 0 = none given
  double overlap_tolerance = 0;  // largest initial overlap allowed, as a fraction of the smaller diameter
  Location where;                // the `particles` section
};

struct RunSpec {
  double duration = 0;               // [s]
  double dt = 0;                     // [s], 0 = automatic
  double safety = 0.4;               // automatic step / critical step
  std::vector<double> output_times;  // ascending, the last one is `duration`
  bool particles_csv = true;
  bool contacts_csv = false;
  double overlap_limit = 0.1;
  double skin = 0;  // [m], 0 = the engine's automatic skin
  bool sleep = false;
  double sleep_speed = 0;  // [m/s]: below it a particle may fall asleep (engine/settings.hpp)
  long threads = 0;
  bool log_engine = true;  // the engine's messages at info (one scene) or at debug (a workflow's many cases)
};

struct SceneFile {
  fs::path file;
  std::string name;
  engine::Domain domain;
  Vec gravity{0, 0, -9.81};
  std::string law;  // the contact plugin's name
  nlohmann::json pair_law;
  std::vector<WallSpec> walls;
  ParticleSource particles;
  RunSpec run;
  std::string backend = "cpu";  // cpu | cuda | auto: where the steps run (a workflow's scene.backend)
};

// Is this YAML document a scene file (rather than a workflow)? A workflow has `stages` or `scene`
// at its top level; anything else is read as a scene file.
bool is_scene_document(const YAML::Node &root);

}  // namespace spreadmap::scene
