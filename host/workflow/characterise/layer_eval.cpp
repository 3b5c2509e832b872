#include "workflow/characterise/layer_eval.hpp"

#include <spreadmap/metric.hpp>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/units.hpp"
#include "engine/csv_input.hpp"
#include "engine/vtp_io.hpp"
#include "workflow/spreading/machine_layout.hpp"

namespace spreadmap {

LayerResult characterise_layer(PluginRegistry &registry, const LayerRequest &rq, const engine::ParticleSet &p) {
  const LoadedPlugin &plugin = registry.get("metrics", rq.plugin);
  PluginInstance inst(plugin, rq.params.dump(), "characterise");
  const auto *ops = inst.ops<sm_metrics_ops_v1>();

  sm_layer_input_v1 in{};
  in.n = p.size();
  in.x = p.x.data();
  in.y = p.y.data();
  in.z = p.z.data();
  in.r = p.radius.data();
  in.region[0] = rq.region.x0;
  in.region[1] = rq.region.x1;
  in.region[2] = rq.region.y0;
  in.region[3] = rq.region.y1;
  in.substrate_z = rq.substrate_z;
  in.periodic_y[0] = rq.periodic_y ? rq.periodic_y->first : 0.0;
  in.periodic_y[1] = rq.periodic_y ? rq.periodic_y->second : 0.0;
  in.speed = rq.speed;
  in.gap = rq.gap;
  in.substrate = p.fixed.empty() ? nullptr : p.fixed.data();  // fixed spheres: a rough substrate, ground

  sm_error err{};
  const char *text = ops->evaluate(inst.get(), &in, &err);
  if (!text) throw RunFailure("metrics/" + rq.plugin + ": " + std::string(err.text));
  const auto doc = nlohmann::json::parse(text);

  LayerResult out;
  out.metrics = doc.at("metrics");
  out.units = doc.at("units");
  for (const auto &w : doc.value("warnings", nlohmann::json::array())) out.warnings.push_back(w.get<std::string>());
  if (doc.contains("profiles")) out.profiles = doc["profiles"];
  if (ops->heightmap) {
    const double *h = ops->heightmap(inst.get(), &out.nx, &out.ny, &out.x0, &out.y0, &out.cell);
    if (h) out.height.assign(h, h + std::size_t(out.nx) * out.ny);
  }
  return out;
}

engine::ParticleSet read_particle_file(const std::filesystem::path &file) {
  if (!std::filesystem::exists(file))
    throw InputError(file.string() +
                     ": no such file (give a spreadmap .vtp state or a CSV with x, y, z, radius columns)");
  const std::string ext = file.extension().string();
  try {
    if (ext == ".vtp") return engine::read_vtp(file).particles;
    if (ext == ".csv" || ext == ".txt") return engine::read_particles_csv(file);
  } catch (const InputError &) {
    throw;
  } catch (const std::exception &e) {
    throw InputError(std::string(e.what()));
  }
  throw InputError(file.string() + ": unknown particle file type '" + ext +
                   "' (give a .vtp written by spreadmap or a .csv with x, y, z, radius columns in metres)");
}

static std::pair<double, double> parse_range(const std::string &text, const std::string &what) {
  const auto colon = text.find(':');
  if (colon == std::string::npos)
    throw InputError(what + ": '" + text + "' is not a range; write LO:HI, e.g. 14mm:24mm");
  try {
    const double lo = parse_in(text.substr(0, colon), "m"), hi = parse_in(text.substr(colon + 1), "m");
    if (!(hi > lo)) throw std::invalid_argument("the upper bound must be above the lower one");
    return {lo, hi};
  } catch (const std::invalid_argument &e) {
    throw InputError(what + ": '" + text + "': " + e.what());
  }
}

Region parse_region(const std::string &text, const std::string &what) {
  const auto comma = text.find(',');
  if (comma == std::string::npos)
    throw InputError(what + ": '" + text + "': write X0:X1,Y0:Y1, e.g. 14mm:24mm,0:2.5mm");
  const auto [x0, x1] = parse_range(text.substr(0, comma), what);
  const auto [y0, y1] = parse_range(text.substr(comma + 1), what);
  return {x0, x1, y0, y1};
}

// Default sampling region. Full-width scenes: the study's 50 mm x 50 mm square centred on the
// substrate. Periodic strips: the whole width over the middle 40 % of the spreader's travel, clear
// of the heap at the start and of the spreader's wake at the end. A machine: its build platform.
Region default_region(const Scene &scene, const sm_spreader_description_v2 &spreader) {
  const double length = scene.domain.length, width = scene.domain.width;
  if (scene.machine) {
    const MachineLayout l = machine_layout(scene);
    return {l.well_from, l.well_to, 0.0, width};
  }
  if (!scene.domain.periodic_y) {
    const double side = 0.05;
    return {length / 2 - side / 2, length / 2 + side / 2, width / 2 - side / 2, width / 2 + side / 2};
  }
  const double start = spreader.start, end = spreader.end;
  return {start + 0.3 * (end - start), start + 0.7 * (end - start), 0.0, width};
}

void take_spreader(LayerRequest &request, const sm_spreader_description_v2 &spreader) {
  request.speed = spreader.speed;
  request.gap = spreader.gap;
}

const std::vector<std::string> &standard_metric_order() {
  static const std::vector<std::string> order = {"vs",
                                                 "rq",
                                                 "mean_height",
                                                 "solid_thickness",
                                                 "packing_fraction",
                                                 "packing_fraction_gap",
                                                 "coverage",
                                                 "largest_bare_patch",
                                                 "particles_in_region",
                                                 "loose_spheres",
                                                 "cell",
                                                 "layer_d10",
                                                 "layer_d50",
                                                 "layer_d90",
                                                 "feed_d10",
                                                 "feed_d50",
                                                 "feed_d90",
                                                 "d10_ratio",
                                                 "d50_ratio",
                                                 "d90_ratio",
                                                 "layer_d50_number",
                                                 "feed_d50_number",
                                                 "d50_number_ratio",
                                                 "fines_diameter",
                                                 "layer_fines",
                                                 "feed_fines",
                                                 "layer_height",
                                                 "effective_thickness",
                                                 "deposited_thickness",
                                                 "layer_relative_density",
                                                 "packing_top",
                                                 "packing_bulk",
                                                 "top_thickness"};
  return order;
}

}  // namespace spreadmap
