#include "workflow/spreading/scene_model.hpp"

#include <concepts>
#include <set>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"

namespace spreadmap {
namespace {

using json = nlohmann::json;

// One list of keys per section, walked by the reader, the writer and set_host_key alike.
template <class S, class F>
requires std::same_as<std::remove_const_t<S>, Scene>
void fields(S &s, F &&f) {
  f("preset", s.preset);
  f("precision", s.precision);
  f("backend", s.backend);
  f("threads", s.threads);
  f("deterministic", s.deterministic);
  f("gravity", s.gravity);
}

template <class D, class F>
requires std::same_as<std::remove_const_t<D>, SpreadingBox>
void fields(D &d, F &&f) {
  f("length", d.length);
  f("width", d.width);
  f("height", d.height);
  f("periodic_x", d.periodic_x);
  f("periodic_y", d.periodic_y);
}

template <class P, class F>
requires std::same_as<std::remove_const_t<P>, Powder>
void fields(P &p, F &&f) {
  f("diameter", p.diameter);
  f("density", p.density);
  f("count", p.count);
  f("volume", p.volume);
  f("distribution", p.distribution);
  f("basis", p.basis);
  f("d10", p.d10);
  f("d50", p.d50);
  f("d90", p.d90);
  f("sigma", p.sigma);
  f("standard_deviation", p.standard_deviation);
  f("d_min", p.d_min);
  f("d_max", p.d_max);
  f("table", p.table);
  f("seed", p.seed);
  f("heap_from", p.heap_from);
  f("heap_to", p.heap_to);
  f("heap_top", p.heap_top);
  f("settle_time", p.settle_time);
  f("settle_speed", p.settle_speed);
  f("settle_fraction", p.settle_fraction);
  f("coarse_grain", p.coarse_grain);
}

template <class T, class F>
requires std::same_as<std::remove_const_t<T>, TimeSettings>
void fields(T &t, F &&f) {
  f("step", t.step);
  f("safety", t.safety);
  f("skin", t.skin);
  f("relax", t.relax);
  f("checkpoint_interval", t.checkpoint_interval);
  f("snapshots", t.snapshots);
  f("overlap_limit", t.overlap_limit);
  f("sleep", t.sleep);
  f("sleep_speed", t.sleep_speed);
  f("sleep_behind", t.sleep_behind);
}

template <class L, class F>
requires std::same_as<std::remove_const_t<L>, Layers>
void fields(L &l, F &&f) {
  f("count", l.count);
  f("thickness", l.thickness);
}

template <class M, class F>
requires std::same_as<std::remove_const_t<M>, Machine>
void fields(M &m, F &&f) {
  f("reservoir_from", m.reservoir_from);
  f("reservoir_length", m.reservoir_length);
  f("reservoir_depth", m.reservoir_depth);
  f("plate_length", m.plate_length);
  f("well_length", m.well_length);
  f("lip_length", m.lip_length);
  f("dosing", m.dosing);
  f("stroke_speed", m.stroke_speed);
  f("sleep_depth", m.sleep_depth);
}

template <class R, class F>
requires std::same_as<std::remove_const_t<R>, Roughness>
void fields(R &r, F &&f) {
  f("rq", r.rq);
  f("correlation_length", r.correlation_length);
  f("sphere_diameter", r.sphere_diameter);
}

template <class H, class F>
requires std::same_as<std::remove_const_t<H>, HeightMap>
void fields(H &h, F &&f) {
  f("file", h.file);
  f("digest", h.digest);
  f("sphere_diameter", h.sphere_diameter);
}

struct Writer {
  json &out;
  template <class T> void operator()(const char *key, const T &value) { out[key] = value; }
  void operator()(const char *key, const Precision &value) { out[key] = precision_name(value); }
};

template <class T> json written(const T &section) {
  json out = json::object();
  fields(section, Writer{out});
  return out;
}

// Reads the keys of one JSON object into typed fields; every problem names the source and the key.
class JsonReader {
 public:
  JsonReader(const json &in, std::string source, std::string path)
      : in_(in), source_(std::move(source)), path_(std::move(path)) {
    if (!in_.is_object()) fail(path_, "expected an object, found " + std::string(in_.type_name()));
  }

  void operator()(const char *key, double &v) {
    v = need(key, in_.contains(key) && at(key).is_number(), "a number").get<double>();
  }
  void operator()(const char *key, std::int64_t &v) {
    v = need(key, in_.contains(key) && at(key).is_number_integer(), "a whole number").get<std::int64_t>();
  }
  void operator()(const char *key, bool &v) {
    v = need(key, in_.contains(key) && at(key).is_boolean(), "true or false").get<bool>();
  }
  void operator()(const char *key, std::string &v) {
    v = need(key, in_.contains(key) && at(key).is_string(), "a string").get<std::string>();
  }
  void operator()(const char *key, json &v) { v = need(key, in_.contains(key), "present"); }
  void operator()(const char *key, Precision &v) {
    const std::string name = need(key, in_.contains(key) && at(key).is_string(), "double or float").get<std::string>();
    if (name != "double" && name != "float") fail(path_ + "." + key, "'" + name + "' is not double or float");
    v = name == "double" ? Precision::float64 : Precision::float32;
  }
  // A plugin's parameters: an object of SI values.
  json object(const char *key) {
    return need(key, in_.contains(key) && at(key).is_object(), "an object of parameters");
  }
  bool has(const char *key) const { return in_.contains(key); }
  JsonReader section(const char *key) {
    need(key, in_.contains(key), "an object");
    return JsonReader(at(key), source_, path_ + "." + key);
  }
  // After every known key was read: a key nothing reads is refused rather than dropped.
  void no_other_keys() const {
    for (const auto &item : in_.items())
      if (!seen_.count(item.key())) fail(path_ + "." + item.key(), "unknown key");
  }

 private:
  const json &at(const char *key) const { return in_.at(key); }
  const json &need(const char *key, bool ok, const char *expected) {
    seen_.insert(key);
    if (!in_.contains(key)) fail(path_ + "." + key, "missing");
    if (!ok) fail(path_ + "." + key, std::string("expected ") + expected + ", found " + at(key).dump());
    return at(key);
  }
  [[noreturn]] void fail(const std::string &key, const std::string &what) const {
    throw InputError(source_ + ": " + key + ": " + what +
                     "\n  a scene as spreadmap writes it (cases/cNNN/scene.json) has every key, in SI; run the "
                     "workflow again to write it anew");
  }

  const json &in_;
  std::string source_, path_;
  std::set<std::string> seen_;
};

template <class T> T read_section(JsonReader &parent, const char *key) {
  JsonReader r = parent.section(key);
  T out;
  fields(out, r);
  r.no_other_keys();
  return out;
}

}  // namespace

bool layered(const Scene &scene) { return scene.layers.count > 1 || scene.machine.has_value(); }

const char *precision_name(Precision precision) { return precision == Precision::float32 ? "float" : "double"; }

json to_json(const Scene &s) {
  json out = written(s);
  out["domain"] = written(s.domain);
  out["powder"] = written(s.powder);
  // absent at its default (every sphere at rest): hashes and scene files written before it unchanged
  if (s.powder.settle_fraction == 1) out["powder"].erase("settle_fraction");
  out["time"] = written(s.time);
  out["contact"] = {{"use", s.contact.use}, {"params", s.contact.params}};
  out["substrate"] = {{"law", s.substrate.law}};
  if (s.substrate.roughness) out["substrate"]["roughness"] = written(*s.substrate.roughness);  // flat: absent
  if (s.substrate.height_map) out["substrate"]["height_map"] = written(*s.substrate.height_map);
  out["spreader"] = {{"use", s.spreader.use}, {"params", s.spreader.params}, {"law", s.spreader.law}};
  if (layered(s)) out["layers"] = written(s.layers);  // absent for one layer on a plate: hashes unchanged
  if (s.machine) out["machine"] = written(*s.machine);
  return out;
}

Scene scene_from_json(const json &in_file, const std::string &source) {
  json in = in_file;
  if (in.contains("powder") && in["powder"].is_object() && !in["powder"].contains("settle_fraction"))
    in["powder"]["settle_fraction"] = 1.0;  // absent: its default (to_json leaves it out)
  Scene s;
  JsonReader top(in, source, "scene");
  fields(s, top);
  s.domain = read_section<SpreadingBox>(top, "domain");
  s.powder = read_section<Powder>(top, "powder");
  s.time = read_section<TimeSettings>(top, "time");
  JsonReader contact = top.section("contact");
  contact("use", s.contact.use);
  s.contact.params = contact.object("params");
  contact.no_other_keys();
  JsonReader substrate = top.section("substrate");
  s.substrate.law = substrate.object("law");
  if (substrate.has("roughness")) s.substrate.roughness = read_section<Roughness>(substrate, "roughness");
  if (substrate.has("height_map")) s.substrate.height_map = read_section<HeightMap>(substrate, "height_map");
  substrate.no_other_keys();
  JsonReader spreader = top.section("spreader");
  spreader("use", s.spreader.use);
  s.spreader.params = spreader.object("params");
  s.spreader.law = spreader.object("law");
  spreader.no_other_keys();
  if (top.has("layers")) s.layers = read_section<Layers>(top, "layers");
  if (top.has("machine")) s.machine = read_section<Machine>(top, "machine");
  top.no_other_keys();
  return s;
}

Scene read_scene_file(const std::filesystem::path &file) {
  json in;
  try {
    in = json::parse(read_text(file));
  } catch (const json::parse_error &e) {
    throw InputError(file.string() + ": not valid JSON (" + e.what() + ")");
  }
  return scene_from_json(in, file.string());
}

void write_scene_file(const std::filesystem::path &file, const Scene &scene) {
  write_atomic(file, to_json(scene).dump(2) + "\n");
}

void set_host_key(Scene &scene, const std::string &section, const std::string &key, const json &value) {
  bool found = false;
  const json one = {{key, value}};
  const std::string path = section.empty() ? "scene" : "scene." + section;
  JsonReader reader(one, "a value set on the scene", path);
  auto set = [&](const char *name, auto &field) {
    if (key != name) return;
    reader(name, field);
    found = true;
  };
  if (section.empty()) fields(scene, set);
  else if (section == "domain") fields(scene.domain, set);
  else if (section == "powder") fields(scene.powder, set);
  else if (section == "time") fields(scene.time, set);
  else if (section == "layers") fields(scene.layers, set);
  else if (section == "machine" && scene.machine) fields(*scene.machine, set);
  if (!found) throw InputError(path + "." + key + ": the scene has no such key");
}

}  // namespace spreadmap
