#include "workflow/spreading/machine_layout.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <nlohmann/json.hpp>

#include "workflow/spreading/powder_sizes.hpp"

namespace spreadmap {

MachineLayout machine_layout(const Scene &scene) {
  const Machine &m = *scene.machine;
  MachineLayout out{};
  out.reservoir_from = m.reservoir_from;
  out.reservoir_to = out.reservoir_from + m.reservoir_length;
  out.well_from = out.reservoir_to + m.plate_length;
  out.well_to = out.well_from + m.well_length;
  out.overflow_from = out.well_to + m.lip_length;
  out.thickness = scene.layers.thickness;
  out.dosing = m.dosing;
  out.reservoir_depth = m.reservoir_depth;
  const double deepest = std::max(m.reservoir_depth, double(scene.layers.count) * scene.layers.thickness);
  out.bottom = -(deepest + 2 * size_distribution(scene.powder).upper());
  return out;
}

double stroke_time(const Scene &scene) {
  const Machine &m = *scene.machine;
  return std::max(1.0, m.dosing) * scene.layers.thickness / m.stroke_speed;
}

double sleep_below(const Scene &scene) {
  if (!scene.machine || !(scene.machine->sleep_depth > 0)) return -std::numeric_limits<double>::infinity();
  return -(scene.layers.thickness + scene.machine->sleep_depth);
}

namespace {

// A block spanning the strip's width (and beyond it, so that a periodic image never sees its end).
scene::WallSpec block(const std::string &name, double x0, double x1, double bottom, double top, double width,
                      const nlohmann::json &law) {
  scene::WallSpec w;
  w.kind = scene::WallKind::block;
  w.name = name;
  w.key_path = "scene.machine";
  w.lo = {x0, -width, bottom - 1e-3};
  w.hi = {x1, 2 * width, top};
  w.law = law;
  return w;
}

// The block moved by `rise` along z at `speed` from time 0 (at rest after).
scene::WallSpec moving(scene::WallSpec w, double rise, double speed) {
  if (rise == 0) return w;
  w.velocity = {0, 0, rise > 0 ? speed : -speed};
  w.start = 0;
  w.stop = std::abs(rise) / speed;
  return w;
}

}  // namespace

std::vector<scene::WallSpec> machine_walls(const Scene &scene, bool strokes) {
  const MachineLayout l = machine_layout(scene);
  const int k = scene.machine->layer;
  const int from = strokes ? std::max(0, k - 1) : k;
  const double width = scene.domain.width, speed = scene.machine->stroke_speed;
  const nlohmann::json &law = scene.substrate.law;
  const double left = -width;  // behind the domain: nothing is there
  std::vector<scene::WallSpec> walls = {
      block("rear plate", left, l.reservoir_from, l.bottom, 0, width, law),
      moving(block("piston", l.reservoir_from, l.reservoir_to, l.bottom, l.piston_top(from), width, law),
             double(k - from) * l.dosing * l.thickness, speed),
      block("transfer plate", l.reservoir_to, l.well_from, l.bottom, 0, width, law),
      moving(block("platform", l.well_from, l.well_to, l.bottom, l.platform_top(from), width, law),
             -double(k - from) * l.thickness, speed),
      block("lip", l.well_to, l.overflow_from, l.bottom, 0, width, law),
  };
  return walls;
}

}  // namespace spreadmap
