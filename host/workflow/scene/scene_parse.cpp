#include "workflow/scene/scene_parse.hpp"

#include <fmt/format.h>
#include <spreadmap/params.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/schema.hpp"
#include "core/suggest.hpp"
#include "workflow/scene/spreader_span.hpp"
#include "workflow/scene/scene_build.hpp"

namespace spreadmap::scene {
namespace sm = spreadmap;
namespace {

// Vectors are tables in the schemas (validate_params passes them through) and read by read_vector.
constexpr sm_param_v1 top_params[] = {
    sm::integer("version", 1, 1, 1, "format version of the scene file: 1"),
    sm::text("name", "scene", "the scene's name: the default output folder is runs/<name>"),
    sm::table("domain", "the simulated box: lo, hi [m] and the periodic axes"),
    sm::table("gravity", "gravitational acceleration [m/s^2]: a vector [gx, gy, gz] or off"),
    sm::table("contact", "the contact plugin (use: NAME) and its parameters, for particle-particle contacts"),
    sm::table("particles", "where the particles come from: file (CSV) or generate"),
    sm::table("walls", "a list of walls: type plane, box, cylinder, block or spreader"),
    sm::table("run", "duration, time step, outputs"),
};

constexpr sm_param_v1 domain_params[] = {
    sm::table("lo", "lower corner [m]: [x, y, z]"),
    sm::table("hi", "upper corner [m]: [x, y, z]"),
    sm::table("periodic", "periodic axes: a list of x, y, z (default none: a particle leaving is removed)"),
};

constexpr sm_param_v1 particle_params[] = {
    sm::text("file", "", "CSV file of particles, relative to the scene file"),
    sm::table("generate", "random non-overlapping spheres in a box, clear of the walls"),
    sm::number("density", "kg/m^3", 0, 1e6, 0,
               "density of particles the CSV gives neither density nor mass for (and of generated ones)"),
    sm::number("overlap_tolerance", "-", 0, 0.5, 1e-3,
               "largest initial overlap (with a particle or a wall) as a fraction of the smaller diameter"),
};

constexpr sm_param_v1 generate_params[] = {
    sm::table("lo", "lower corner of the box the centres are drawn in [m]"),
    sm::table("hi", "upper corner of that box [m]"),
    sm::integer("count", 1, 1e7, 0, "number of spheres"),
    sm::required_number("diameter", "m", 1e-7, 10, "sphere diameter (the median with sigma > 0)"),
    sm::number("sigma", "-", 0, 2, 0, "standard deviation of ln(diameter); 0 = all the same size"),
    sm::integer("seed", 0, 4294967295.0, 1, "random seed"),
    sm::table("velocity", "initial velocity of every sphere [m/s] (default 0)"),
};

constexpr sm_param_v1 wall_params[] = {
    sm::enumeration("type", "plane|box|cylinder|block|spreader", "plane",
                    "plane (infinite), box (six inward planes), cylinder, block (a solid box the particles stay "
                    "outside of), or spreader (a spreader plugin)"),
    sm::text("name", "", "name in messages and the log"),
    sm::table("point", "plane: a point of the plane [m]"),
    sm::table("normal", "plane: normal pointing to the particles' side (any length > 0)"),
    sm::table("lo", "box, block: lower corner [m]"),
    sm::table("hi", "box, block: upper corner [m]"),
    sm::boolean("open_top", false, "box: leave out the lid (the plane z = hi.z)"),
    sm::table("base", "cylinder: centre of its bottom end [m]"),
    sm::table("axis", "cylinder: axis direction (any length > 0), bottom to top; default [0, 0, 1]"),
    sm::number("radius", "m", 0, 100, 0, "cylinder: radius"),
    sm::number("height", "m", 0, 100, 0, "cylinder: length along the axis"),
    sm::boolean("inside", true, "cylinder: particles inside an open tube (true) or outside a solid cylinder"),
    sm::number("omega", "rad/s", -1e5, 1e5, 0, "cylinder: rotation rate about its axis (right-hand rule)"),
    sm::table("velocity", "translation velocity [m/s] (default 0)"),
    sm::number("start", "s", 0, 1e6, 0,
               "the translation (a spreader: its travel) starts at this time (at rest before)"),
    sm::number("stop", "s", 0, 1e6, 0,
               "the translation stops at this time (at rest after); default: it never stops. Not for a spreader"),
    sm::table("spreader", "spreader: the plugin (use: NAME) and its parameters as `spreadmap plugins NAME` lists them"),
};

constexpr sm_param_v1 run_params[] = {
    sm::required_number("duration", "s", 1e-9, 1e6, "simulated time"),
    sm::number("dt", "s", 0, 1, 0, "time step; 0 = automatic (safety x the critical step)"),
    sm::number("safety", "-", 1e-3, 1, 0.4, "automatic step as a fraction of the critical step"),
    sm::number("output_every", "s", 0, 1e6, 0, "time between outputs; 0 = 10 outputs over the duration"),
    sm::table("output_times", "explicit output times [s] instead of output_every"),
    sm::boolean("particles_csv", true, "write particles_NNNN.csv (every particle) at each output"),
    sm::boolean("contacts_csv", false, "write contacts_NNNN.csv (every particle-particle contact) at each output"),
    sm::number("overlap_limit", "-", 1e-4, 1, 0.1, "largest overlap while running, as a fraction of the diameter"),
    sm::integer("threads", 0, 1024, 0, "OpenMP threads; 0 = all cores"),
};

std::vector<std::string> names_of(const SchemaView &s) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < s.n; ++i) out.push_back(s.params[i].name);
  return out;
}

// The context every reader shares: the file, the diagnostics.
struct ParseContext {
  std::string file;
  Diagnostics &diag;

  Location at(const YAML::Node &n) const { return Location::of(file, n); }

  // A section against a schema; empty object when it is not a mapping (reported).
  nlohmann::json section(const sm_param_v1 *params, std::size_t n, const YAML::Node &node, const std::string &path,
                         const std::set<std::string> &skip = {}) const {
    return validate_params({params, n}, node, file, path, diag, skip);
  }

  // A 3-vector of quantities in `unit` (each element as users write numbers: "5 mm").
  std::optional<Vec> vector(const YAML::Node &node, const std::string &path, const char *unit, const char *doc,
                            double min = -1e6, double max = 1e6) const {
    if (!node || !node.IsSequence() || node.size() != 3) {
      diag.error(at(node), path, "expected a list of three numbers [x, y, z]",
                 fmt::format("{}; write e.g. [0 {}, 0 {}, 1 {}]", doc, unit, unit, unit));
      return std::nullopt;
    }
    const sm_param_v1 element = sm::number("component", unit, min, max, 0, doc);
    Vec v{};
    bool ok = true;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto j = validate_value(element, node[k], file, fmt::format("{}[{}]", path, k), diag);
      if (j.is_number()) v[k] = j.get<double>();
      else ok = false;
    }
    if (!ok) return std::nullopt;
    return v;
  }

  // A direction: a vector of length > 0, normalised.
  std::optional<Vec> direction(const YAML::Node &node, const std::string &path, const char *doc) const {
    auto v = vector(node, path, "-", doc);
    if (!v) return std::nullopt;
    const double len = std::sqrt((*v)[0] * (*v)[0] + (*v)[1] * (*v)[1] + (*v)[2] * (*v)[2]);
    if (!(len > 1e-12)) {
      diag.error(at(node), path, "the direction has zero length", "give a non-zero vector, e.g. [0, 0, 1]");
      return std::nullopt;
    }
    for (auto &c : *v) c /= len;
    return v;
  }
};

void read_domain(const ParseContext &r, const YAML::Node &node, SceneFile &s) {
  if (!node) {
    r.diag.error(r.at(node), "domain", "required section missing",
                 "add domain: {lo: [x, y, z], hi: [x, y, z]} (the box the particles live in)");
    return;
  }
  r.section(domain_params, std::size(domain_params), node, "domain");
  if (!node.IsMap()) return;
  for (const char *key : {"lo", "hi"})
    if (!node[key])
      r.diag.error(r.at(node), std::string("domain.") + key, "required value missing",
                   "add " + std::string(key) + ": [x, y, z] in m");
  const auto lo = node["lo"] ? r.vector(node["lo"], "domain.lo", "m", "lower corner") : std::nullopt;
  const auto hi = node["hi"] ? r.vector(node["hi"], "domain.hi", "m", "upper corner") : std::nullopt;
  if (lo && hi) {
    s.domain.lo = *lo;
    s.domain.hi = *hi;
    for (int a = 0; a < 3; ++a)
      if (!((*hi)[a] > (*lo)[a]))
        r.diag.error(r.at(node["hi"]), "domain.hi",
                     fmt::format("hi.{} = {:g} m is not above lo.{} = {:g} m", "xyz"[a], (*hi)[a], "xyz"[a], (*lo)[a]),
                     "make hi greater than lo along every axis");
  }
  if (const YAML::Node per = node["periodic"]) {
    if (!per.IsSequence()) {
      r.diag.error(r.at(per), "domain.periodic", "expected a list of axes such as [x, y]");
    } else {
      for (std::size_t k = 0; k < per.size(); ++k) {
        const std::string axis = per[k].IsScalar() ? lower(per[k].Scalar()) : "";
        if (axis == "x" || axis == "y" || axis == "z") s.domain.periodic[axis[0] - 'x'] = true;
        else r.diag.error(r.at(per[k]), fmt::format("domain.periodic[{}]", k), "not an axis: write x, y or z");
      }
    }
  }
}

void read_gravity(const ParseContext &r, const YAML::Node &node, SceneFile &s) {
  if (!node) return;
  if (node.IsScalar() && (lower(node.Scalar()) == "off" || lower(node.Scalar()) == "false")) {
    s.gravity = {0, 0, 0};
    return;
  }
  if (node.IsScalar()) {
    r.diag.error(r.at(node), "gravity", fmt::format("'{}' is neither off nor a vector", node.Scalar()),
                 "write gravity: off, or gravity: [0, 0, -9.81 m/s^2]");
    return;
  }
  if (auto g = r.vector(node, "gravity", "m/s^2", "gravitational acceleration", -1e4, 1e4)) s.gravity = *g;
}

// The plugin a section names with `use:` (the section `key`, e.g. contact or walls[1].spreader), or
// null with the problem reported: `use` missing (and a misspelt key that is likely it), or no such plugin.
const LoadedPlugin *named_plugin(const ParseContext &r, const YAML::Node &node, const std::string &kind,
                                 const std::string &key, PluginRegistry &registry, const std::string &fix) {
  if (!node["use"] || !node["use"].IsScalar()) {
    r.diag.error(r.at(node), key + ".use", "required value missing", fix);
    for (const auto &kv : node)  // a misspelt `use` is the likely cause: say which key it is
      if (closest(kv.first.as<std::string>(), {"use"}) == "use" && kv.first.as<std::string>() != "use")
        r.diag.error(r.at(kv.first), key + "." + kv.first.as<std::string>(), "unknown key", "did you mean 'use'?");
    return nullptr;
  }
  try {
    return &registry.get(kind, node["use"].Scalar());
  } catch (const Error &e) {
    r.diag.error(r.at(node["use"]), key + ".use", e.what());
    return nullptr;
  }
}

// The contact law's schema, or null when the plugin cannot be loaded (reported).
const LoadedPlugin *read_contact(const ParseContext &r, const YAML::Node &node, PluginRegistry &registry, SceneFile &s) {
  if (!node || !node.IsMap()) {
    r.diag.error(r.at(node), "contact", node ? "expected a mapping: {use: NAME, ...}" : "required section missing",
                 "add contact: {use: hooke_slider, ...}; spreadmap plugins --kind contact lists the laws");
    return nullptr;
  }
  const LoadedPlugin *law =
      named_plugin(r, node, "contact", "contact", registry, "name the contact law: use: hooke_slider");
  if (!law) return nullptr;
  s.law = node["use"].Scalar();
  s.pair_law = validate_params(SchemaView::of(*law->descriptor), node, r.file, "contact", r.diag, {"use"});
  return law;
}

void read_particles(const ParseContext &r, const YAML::Node &node, const fs::path &dir, SceneFile &s) {
  ParticleSource &p = s.particles;
  p.where = r.at(node);
  if (!node || !node.IsMap()) {
    r.diag.error(r.at(node), "particles", node ? "expected a mapping" : "required section missing",
                 "add particles: {file: particles.csv} or particles: {generate: {lo, hi, count, diameter}, density}");
    return;
  }
  const auto v = r.section(particle_params, std::size(particle_params), node, "particles");
  if (v.contains("density") && v["density"].is_number()) p.density = v["density"];
  if (v.contains("overlap_tolerance") && v["overlap_tolerance"].is_number())
    p.overlap_tolerance = v["overlap_tolerance"];
  const bool has_file = node["file"] && node["file"].IsScalar() && !node["file"].Scalar().empty();
  const YAML::Node gen = node["generate"];
  if (has_file == bool(gen)) {
    r.diag.error(r.at(node), "particles",
                 has_file ? "give file or generate, not both" : "no particles: neither file nor generate",
                 "write file: NAME.csv (x, y, z, radius, ... per line) or generate: {lo, hi, count, diameter}");
    return;
  }
  if (has_file) {
    const fs::path f = node["file"].Scalar();
    p.file = f.is_absolute() ? f : dir / f;
    return;
  }
  p.generate = true;
  const auto g = r.section(generate_params, std::size(generate_params), gen, "particles.generate");
  if (!gen.IsMap()) return;
  GeneratedParticles &out = p.generated;
  if (g.contains("count") && g["count"].is_number()) out.count = g["count"];
  if (g.contains("diameter") && g["diameter"].is_number()) out.diameter = g["diameter"];
  if (g.contains("sigma") && g["sigma"].is_number()) out.sigma = g["sigma"];
  if (g.contains("seed") && g["seed"].is_number()) out.seed = g["seed"];
  if (out.count < 1)
    r.diag.error(r.at(gen), "particles.generate.count", "required value missing", "add count: N (number of spheres)");
  for (const char *key : {"lo", "hi"})
    if (!gen[key])
      r.diag.error(r.at(gen), std::string("particles.generate.") + key, "required value missing",
                   "give the box the centres are drawn in: lo: [x, y, z], hi: [x, y, z] in m");
  if (gen["lo"])
    if (auto lo = r.vector(gen["lo"], "particles.generate.lo", "m", "lower corner")) out.lo = *lo;
  if (gen["hi"])
    if (auto hi = r.vector(gen["hi"], "particles.generate.hi", "m", "upper corner")) out.hi = *hi;
  if (gen["velocity"])
    if (auto vel = r.vector(gen["velocity"], "particles.generate.velocity", "m/s", "initial velocity"))
      out.velocity = *vel;
  if (!(p.density > 0))
    r.diag.error(r.at(node), "particles.density", "generated particles need a density",
                 "add density: 2500 kg/m^3 (for example) to the particles section");
}

// A spreader wall's plugin and its parameters (`spreader: {use: NAME, ...}`), checked by the plugin's
// schema and its own cross-checks.
void read_spreader(const ParseContext &r, const YAML::Node &wall, const std::string &path, PluginRegistry &registry,
                   const engine::Domain &domain, SpreaderWall &out) {
  const std::string at = path + ".spreader";
  const YAML::Node node = wall["spreader"];
  const char *fix = "write spreader: {use: NAME, ...}; spreadmap plugins --kind spreader lists the spreaders";
  if (!node || !node.IsMap()) {
    r.diag.error(r.at(node ? node : wall), at,
                 node ? "expected a mapping naming the plugin: {use: NAME, ...}" : "required value missing", fix);
    return;
  }
  const LoadedPlugin *plugin = named_plugin(r, node, "spreader", at, registry, fix);
  if (!plugin) return;
  out.use = node["use"].Scalar();
  out.params = validate_params(SchemaView::of(*plugin->descriptor), node, r.file, at, r.diag, {"use"});
  if (!r.diag.empty()) return;
  try {
    PluginInstance probe(*plugin, out.params.dump());
    if (const auto shortfall = spreader_span_shortfall(BoundSpreader{&probe, 0.0}.description(), domain);
        shortfall && shortfall->periodic)
      r.diag.error(r.at(node["y_centre"] ? node["y_centre"]
                        : node["length"] ? node["length"]
                                         : node),
                   at + ".y_centre", shortfall->what, shortfall->fix);
  } catch (const PluginError &e) {
    r.diag.error(r.at(node), at, e.what());
  }
}

std::string wall_label(const WallSpec &w, std::size_t k) {
  static const char *kinds[] = {"plane", "box", "cylinder", "block", "spreader"};
  return w.name.empty() ? fmt::format("walls[{}] ({})", k, kinds[int(w.kind)]) : w.name;
}

// One wall's keys as written: those its type requires, and those of the other wall types (refused, so
// that a typo in `type` is not silently another wall).
struct WallKeys {
  const ParseContext &r;
  const YAML::Node &w;
  const std::string &path;
  const std::string &type;

  bool need(const char *key, const char *what) const {
    if (w[key]) return true;
    r.diag.error(r.at(w), path + "." + key, fmt::format("required value missing for a {}", type), what);
    return false;
  }

  void refuse_foreign(std::initializer_list<const char *> keys) const {
    for (const char *key : keys)
      if (w[key])
        r.diag.error(
            r.at(w[key]), path + "." + key, fmt::format("not a key of a {} wall", type),
            "plane: point, normal; box: lo, hi, open_top; cylinder: base, axis, radius, height, inside, omega; "
            "block: lo, hi; spreader: spreader (its motion is the plugin's)");
  }
};

void read_spreader_wall(const WallKeys &keys, PluginRegistry &registry, const engine::Domain &domain, WallSpec &spec) {
  keys.refuse_foreign({"point", "normal", "lo", "hi", "open_top", "base", "axis", "radius", "height", "inside", "omega",
                       "velocity", "stop"});
  read_spreader(keys.r, keys.w, keys.path, registry, domain, spec.spreader);
  spec.spreader.time_offset = -spec.start;  // the plugin's time 0 (its start) at `start`, at rest before
}

void read_plane_wall(const WallKeys &keys, WallSpec &spec) {
  const ParseContext &r = keys.r;
  const YAML::Node &w = keys.w;
  keys.refuse_foreign({"lo", "hi", "open_top", "base", "axis", "radius", "height", "inside", "omega", "spreader"});
  if (keys.need("point", "add point: [x, y, z] (m), a point of the plane"))
    if (auto p = r.vector(w["point"], keys.path + ".point", "m", "a point of the plane")) spec.point = *p;
  if (keys.need("normal", "add normal: [nx, ny, nz], pointing to the particles' side"))
    if (auto n = r.direction(w["normal"], keys.path + ".normal", "normal into the particles' side")) spec.normal = *n;
}

// A box (particles inside) or a block (particles outside): two corners.
void read_box_wall(const WallKeys &keys, WallSpec &spec) {
  const ParseContext &r = keys.r;
  const YAML::Node &w = keys.w;
  const std::string &path = keys.path;
  if (spec.kind == WallKind::block)
    keys.refuse_foreign({"point", "normal", "open_top", "base", "axis", "radius", "height", "inside", "omega",
                         "spreader"});
  else
    keys.refuse_foreign({"point", "normal", "base", "axis", "radius", "height", "inside", "omega", "spreader"});
  std::optional<Vec> lo, hi;
  if (keys.need("lo", "add lo: [x, y, z] (m)")) lo = r.vector(w["lo"], path + ".lo", "m", "lower corner");
  if (keys.need("hi", "add hi: [x, y, z] (m)")) hi = r.vector(w["hi"], path + ".hi", "m", "upper corner");
  if (lo && hi) {
    spec.lo = *lo;
    spec.hi = *hi;
    for (int a = 0; a < 3; ++a)
      if (!((*hi)[a] > (*lo)[a]))
        r.diag.error(r.at(w["hi"]), path + ".hi",
                     fmt::format("hi.{} is not above lo.{}: the {} is empty", "xyz"[a], "xyz"[a], keys.type),
                     "make hi greater than lo along every axis");
  }
}

// `v`: the wall's host keys as validated (radius, height, inside and omega with their defaults).
void read_cylinder_wall(const WallKeys &keys, const nlohmann::json &v, WallSpec &spec) {
  const ParseContext &r = keys.r;
  const YAML::Node &w = keys.w;
  const std::string &path = keys.path;
  keys.refuse_foreign({"point", "normal", "lo", "hi", "open_top", "spreader"});
  CylinderWall &c = spec.cylinder;
  c = CylinderWall{{0, 0, 0}, {0, 0, 1}, 0, 0, {0, 0, 0}, 0, 0, 0, true};
  if (keys.need("base", "add base: [x, y, z] (m), the centre of its bottom end"))
    if (auto b = r.vector(w["base"], path + ".base", "m", "centre of the bottom end"))
      std::copy(b->begin(), b->end(), c.base);
  if (w["axis"])
    if (auto a = r.direction(w["axis"], path + ".axis", "axis direction")) std::copy(a->begin(), a->end(), c.axis);
  c.radius = v.contains("radius") && v["radius"].is_number() ? v["radius"].get<double>() : 0.0;
  c.height = v.contains("height") && v["height"].is_number() ? v["height"].get<double>() : 0.0;
  if (w["radius"] && v["radius"].is_number() && !(c.radius > 0))
    r.diag.error(r.at(w["radius"]), path + ".radius", "a cylinder needs radius > 0");
  if (w["height"] && v["height"].is_number() && !(c.height > 0))
    r.diag.error(r.at(w["height"]), path + ".height", "a cylinder needs height > 0");
  keys.need("radius", "add radius: R (m)");
  keys.need("height", "add height: H (m), its length along the axis");
  c.inside = v.contains("inside") && v["inside"].is_boolean() ? v["inside"].get<bool>() : true;
  c.omega = v.contains("omega") && v["omega"].is_number() ? v["omega"].get<double>() : 0.0;
  c.start = spec.start;
  c.stop = spec.stop;
  std::copy(spec.velocity.begin(), spec.velocity.end(), c.velocity);
}

// The wall's law: the particle-particle values with this wall's overrides (its keys of the law).
nlohmann::json wall_law_with_overrides(const ParseContext &r, const YAML::Node &w, const std::string &path,
                                       const LoadedPlugin *law, const std::set<std::string> &law_keys,
                                       const nlohmann::json &pair_law) {
  nlohmann::json out = pair_law;
  if (law) {
    YAML::Node own(YAML::NodeType::Map);
    for (const auto &kv : w)
      if (law_keys.count(kv.first.as<std::string>())) own[kv.first] = kv.second;
    const auto mine = validate_params(SchemaView::of(*law->descriptor), own, r.file, path, r.diag, {}, false);
    for (auto &[key, value] : mine.items()) out[key] = value;
  }
  return out;
}

// walls[k]: its host keys, the keys of its type, and its law; nullopt when it is no mapping or has no
// valid type (reported).
std::optional<WallSpec> read_wall(const ParseContext &r, const YAML::Node &w, std::size_t k, const LoadedPlugin *law,
                                  const std::set<std::string> &law_keys, PluginRegistry &registry, const SceneFile &s) {
  const std::string path = fmt::format("walls[{}]", k);
  WallSpec spec;
  spec.key_path = path;
  spec.where = r.at(w);
  if (!w.IsMap()) {
    r.diag.error(r.at(w), path, "expected a mapping with type: plane, box, cylinder, block or spreader");
    return std::nullopt;
  }
  // host keys here; the contact law's keys override the particle-particle law's values for this wall
  const auto v = r.section(wall_params, std::size(wall_params), w, path, law_keys);
  if (!v.contains("type") || !v["type"].is_string()) return std::nullopt;
  const std::string type = v["type"];
  spec.kind = type == "box"        ? WallKind::box
              : type == "cylinder" ? WallKind::cylinder
              : type == "block"    ? WallKind::block
              : type == "spreader" ? WallKind::spreader
                                   : WallKind::plane;
  if (v.contains("name") && v["name"].is_string()) spec.name = v["name"];
  if (v.contains("open_top") && v["open_top"].is_boolean()) spec.open_top = v["open_top"];
  if (v.contains("start") && v["start"].is_number()) spec.start = v["start"];
  spec.stop = std::numeric_limits<double>::infinity();
  if (w["stop"] && v.contains("stop") && v["stop"].is_number()) {
    spec.stop = v["stop"];
    if (!(spec.stop > spec.start))
      r.diag.error(r.at(w["stop"]), path + ".stop",
                   fmt::format("stop ({:g} s) is not after start ({:g} s)", spec.stop, spec.start),
                   "make stop later than start, or leave it out (the motion never stops)");
  }
  if (w["velocity"])
    if (auto vel = r.vector(w["velocity"], path + ".velocity", "m/s", "translation velocity")) spec.velocity = *vel;
  const WallKeys keys{r, w, path, type};
  switch (spec.kind) {
    case WallKind::spreader:
      read_spreader_wall(keys, registry, s.domain, spec);
      break;
    case WallKind::plane:
      read_plane_wall(keys, spec);
      break;
    case WallKind::box:
    case WallKind::block:
      read_box_wall(keys, spec);
      break;
    case WallKind::cylinder:
      read_cylinder_wall(keys, v, spec);
      break;
  }
  spec.law = wall_law_with_overrides(r, w, path, law, law_keys, s.pair_law);
  spec.name = wall_label(spec, k);
  return spec;
}

void read_walls(const ParseContext &r, const YAML::Node &node, const LoadedPlugin *law, PluginRegistry &registry,
                SceneFile &s) {
  if (!node) return;
  if (!node.IsSequence()) {
    r.diag.error(r.at(node), "walls", "expected a list of walls",
                 "write walls: [{type: plane, point: [...], normal: [...]}, ...]");
    return;
  }
  std::set<std::string> law_keys;
  if (law)
    for (const auto &n : names_of(SchemaView::of(*law->descriptor))) law_keys.insert(n);
  for (std::size_t k = 0; k < node.size(); ++k) {
    const YAML::Node w = node[k];
    if (!law && w.IsMap())  // no law to check the wall's law keys against (its problem is reported)
      for (const auto &kv : w)
        if (!SchemaView{wall_params, std::size(wall_params)}.find(kv.first.as<std::string>()))
          law_keys.insert(kv.first.as<std::string>());
    if (auto spec = read_wall(r, w, k, law, law_keys, registry, s)) s.walls.push_back(std::move(*spec));
  }
}

void read_run(const ParseContext &r, const YAML::Node &node, SceneFile &s) {
  if (!node) {
    r.diag.error(r.at(node), "run", "required section missing", "add run: {duration: 0.5 s}");
    return;
  }
  const auto v = r.section(run_params, std::size(run_params), node, "run");
  RunSpec &run = s.run;
  auto num = [&](const char *key, double &out) {
    if (v.contains(key) && v[key].is_number()) out = v[key];
  };
  num("duration", run.duration);
  num("dt", run.dt);
  num("safety", run.safety);
  num("overlap_limit", run.overlap_limit);
  double every = 0;
  num("output_every", every);
  if (v.contains("threads") && v["threads"].is_number()) run.threads = v["threads"];
  if (v.contains("particles_csv") && v["particles_csv"].is_boolean()) run.particles_csv = v["particles_csv"];
  if (v.contains("contacts_csv") && v["contacts_csv"].is_boolean()) run.contacts_csv = v["contacts_csv"];
  if (!(run.duration > 0)) return;
  if (const YAML::Node times = node.IsMap() ? node["output_times"] : YAML::Node()) {
    if (every > 0) r.diag.error(r.at(times), "run.output_times", "give output_every or output_times, not both");
    if (!times.IsSequence() || times.size() == 0) {
      r.diag.error(r.at(times), "run.output_times", "expected a list of times such as [0 s, 0.1 s, 0.2 s]");
      return;
    }
    const sm_param_v1 element =
        sm::number("output_times", "s", 0, run.duration, 0, "an output time within the duration");
    for (std::size_t k = 0; k < times.size(); ++k) {
      const auto t = validate_value(element, times[k], r.file, fmt::format("run.output_times[{}]", k), r.diag);
      if (!t.is_number()) continue;
      if (!run.output_times.empty() && !(t.get<double>() > run.output_times.back()))
        r.diag.error(r.at(times[k]), fmt::format("run.output_times[{}]", k), "output times must increase");
      run.output_times.push_back(t);
    }
    return;
  }
  const double step = every > 0 ? every : run.duration / 10;
  const auto n = static_cast<long>(std::floor(run.duration / step * (1 + 1e-12)));
  if (n > 100000) {
    r.diag.error(r.at(node["output_every"]), "run.output_every",
                 fmt::format("{} outputs over the duration: too many", n), "choose a longer output_every");
    return;
  }
  for (long k = 0; k <= n; ++k) run.output_times.push_back(double(k) * step);
  if (run.duration - run.output_times.back() > 1e-9 * run.duration) run.output_times.push_back(run.duration);
}

}  // namespace

bool is_scene_document(const YAML::Node &root) { return root.IsMap() && !root["stages"] && !root["scene"]; }

std::optional<SceneFile> parse_scene(const fs::path &file, const YAML::Node &root, PluginRegistry &registry,
                                     Diagnostics &diag) {
  const ParseContext r{file.string(), diag};
  SceneFile s;
  s.file = file;
  if (!root.IsMap()) {
    diag.error(r.at(root), "", "a scene file is a mapping of sections", "see docs/scenes.md");
    return std::nullopt;
  }
  const auto top = r.section(top_params, std::size(top_params), root, "");
  if (!root["version"]) diag.error(r.at(root), "version", "required value missing", "add version: 1 as the first line");
  s.name = top.contains("name") && top["name"].is_string() ? top["name"].get<std::string>() : "scene";
  read_domain(r, root["domain"], s);
  read_gravity(r, root["gravity"], s);
  const LoadedPlugin *law = read_contact(r, root["contact"], registry, s);
  read_particles(r, root["particles"], file.parent_path(), s);
  read_walls(r, root["walls"], law, registry, s);
  read_run(r, root["run"], s);
  if (!diag.empty()) return std::nullopt;
  // the laws' own checks across their parameters (bind) run now, before any work starts
  auto probe = [&](const nlohmann::json &params, const Location &where, const std::string &path) {
    try {
      PluginInstance instance(*law, params.dump());
    } catch (const PluginError &e) {
      diag.error(where, path, e.what());
    }
  };
  probe(s.pair_law, r.at(root["contact"]), "contact");
  for (const auto &w : s.walls) probe(w.law, w.where, w.key_path);
  if (!diag.empty()) return std::nullopt;
  return s;
}

}  // namespace spreadmap::scene
