// The resolved scene as a typed value: every number in SI, every key present and checked. The
// workflow's scene is parsed and validated once (scene_section.hpp) into a Scene; every later stage reads
// this value. A plugin's parameters stay the validated SI JSON object the plugin ABI takes.
//
// cases/cNNN/scene.json is to_json(scene).dump(2): the JSON form has the same keys, types and
// order (alphabetical) as the resolved JSON scene always had, so case and heap hashes are stable.
#pragma once
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace spreadmap {

struct SpreadingBox {
  double length = 0, width = 0, height = 0;  // m, from the origin
  bool periodic_x = false, periodic_y = true;
};

struct Powder {
  double diameter = 0, density = 0;  // m, kg/m^3
  std::int64_t count = 0;            // spheres (ignored when volume > 0)
  double volume = 0;                 // m^3 of solid
  std::string distribution;          // mono | lognormal | normal | table
  std::string basis;                 // number | volume | mass: what d10/d50/d90 and table fractions count
  double d10 = 0, d50 = 0, d90 = 0;  // m; d10 = d90 = 0: lognormal by d50 and sigma, normal by d50 and std
  double sigma = 0;                  // lognormal: standard deviation of ln d
  double standard_deviation = 0;     // normal: m
  double d_min = 0, d_max = 0;       // truncation, m; 0 = the default
  nlohmann::json table;              // table: SI rows [{diameter, fraction}] or [{from, to, fraction}], else null
  std::int64_t seed = 0;
  double heap_from = 0, heap_to = 0, heap_top = 0;  // m
  double settle_time = 0, settle_speed = 0;         // s, m/s
  double settle_fraction = 1;                       // of the spheres slower than settle_speed to end settling
  double coarse_grain = 1;
};

struct TimeSettings {
  double step = 0, safety = 0, skin = 0, relax = 0, checkpoint_interval = 0;
  std::int64_t snapshots = 0;
  double overlap_limit = 0;
  bool sleep = false;
  double sleep_speed = 0, sleep_behind = 0;
};

// A plugin the scene names and its parameters (validated, SI), as the plugin's create() takes them.
struct PluginChoice {
  std::string use;
  nlohmann::json params = nlohmann::json::object();
};

// The spreader geometry and the contact law between the particles and the spreader.
struct SpreaderChoice : PluginChoice {
  nlohmann::json law = nlohmann::json::object();
};

// A rough substrate (scene.substrate.roughness): a layer of fixed spheres over the plate whose tops
// follow a Gaussian height field (scene/rough_substrate.hpp; the case set-up in
// workflow/spreading/layer_feed.hpp).
struct Roughness {
  double rq = 0;                  // m, R_q of the spheres' tops
  double correlation_length = 0;  // m, lag at which the field's autocorrelation falls to 1/e
  double sphere_diameter = 0;     // m; 0 = the powder's D50 by volume (after coarse graining)
};

// A measured substrate (scene.substrate.height_map): the same layer of fixed spheres, their tops on
// a surface read from a CSV file (workflow/spreading/height_map_file.hpp). The file is read again where
// the substrate is built; its digest, taken when the scene was resolved, makes a changed file a
// different scene (and is checked where the file is read).
struct HeightMap {
  std::string file;            // absolute path
  std::string digest;          // stable_hash of the file's text
  double sphere_diameter = 0;  // m; 0 = the powder's D50 by volume (after coarse graining)
};

// The contact law between the particles and the substrate plane, and the substrate's roughness or
// measured surface (at most one): absent (the default) for the flat plate, and then out of the
// scene's JSON form, so the hashes of flat scenes stand.
struct Substrate {
  nlohmann::json law = nlohmann::json::object();
  std::optional<Roughness> roughness;
  std::optional<HeightMap> height_map;
};

// Spreading layer upon layer: after each pass the platform drops by `thickness`, a new heap of the
// same powder is fed and spread onto the bed. count 1 (the default) is a single pass onto the plate;
// the section then stays out of the scene's JSON form, so the hashes of single-layer scenes stand.
struct Layers {
  std::int64_t count = 1;
  double thickness = 50e-6;  // m, the platform's drop between two passes
};

// A powder-bed machine (scene.machine; workflow/machine/machine_layout.hpp): along x a plate behind
// the feed, the feed's reservoir (its floor a piston), a transfer plate, the build well (its floor the
// platform), a lip and the overflow, a pit the powder falls out of the domain through. The plates'
// tops are the plane z = 0 the spreader's gap is measured from. Before layer k the platform drops by
// the layer thickness and the piston rises by dosing x thickness (strokes at stroke_speed); the
// spreader then spreads from behind the feed over the well into the overflow. Absent (the default):
// the heap in front of the spreader on a plate, and the section stays out of the scene's JSON form.
struct Machine {
  double reservoir_from = 6e-3, reservoir_length = 5e-3, reservoir_depth = 4e-3;  // m
  double plate_length = 1e-3, well_length = 10e-3, lip_length = 1e-3;            // m
  double dosing = 2;                                                              // piston rise / thickness
  double stroke_speed = 5e-3;                                                     // m/s
  double sleep_depth = 0;  // m; with time.sleep, spheres this far below the last layer's bottom may sleep
  // Which layer's places the platform and piston take in this scene (layer_scene() sets it; 0: the
  // places they start from). Not a key: it is not in the scene's JSON form.
  int layer = 0;
};

enum class Precision { float64, float32 };

struct Scene {
  std::string preset = "quick";  // quick | standard | paper | paper_full
  Precision precision = Precision::float64;
  std::string backend = "auto";  // auto | cpu | cuda
  std::int64_t threads = 0;      // 0 = all cores
  bool deterministic = true;
  double gravity = 9.81;  // m/s^2 along -z
  SpreadingBox domain;
  Powder powder;
  TimeSettings time;
  PluginChoice contact;  // particle-particle law
  Substrate substrate;
  SpreaderChoice spreader;
  Layers layers;
  std::optional<Machine> machine;
};

// Whether a case spreads layer by layer into layer_K folders: several layers, or any machine.
bool layered(const Scene &scene);

// "double" or "float", as scene.json writes it.
const char *precision_name(Precision precision);

nlohmann::json to_json(const Scene &scene);
// Throws InputError naming `source` (a file or "the resolved scene") and the key that is missing,
// of the wrong type or unknown.
Scene scene_from_json(const nlohmann::json &json, const std::string &source);
// A case's scene.json (cases/cNNN/scene.json), checked as above.
Scene read_scene_file(const std::filesystem::path &file);
// Writes it (atomically), as read_scene_file reads it.
void write_scene_file(const std::filesystem::path &file, const Scene &scene);

// Sets one host key (section "" for the top level: precision, gravity ...; else domain, powder,
// time, layers or machine) from an SI JSON value of the key's type; throws InputError for a key the scene lacks.
void set_host_key(Scene &scene, const std::string &section, const std::string &key, const nlohmann::json &value);

}  // namespace spreadmap
