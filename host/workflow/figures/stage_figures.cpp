#include "workflow/figures/stage_figures.hpp"

#include "core/units.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <mutex>

#include "analysis/table.hpp"

#ifdef SPREADMAP_WITH_RENDER
#include <spreadmap/render/figures.hpp>
#endif

#include <fstream>
#include <nlohmann/json.hpp>

#include "workflow/figures/figure_style.hpp"
#include "analysis/known_columns.hpp"

namespace spreadmap::figures {

std::string case_title(const std::string &id, const nlohmann::json &inputs) {
  std::string t = id;
  const char *sep = ": ";
  for (auto &[k, v] : inputs.items()) {
    if (!v.is_number()) continue;
    const std::string unit = k == "U" ? "m/s" : k == "omega" ? "rad/s" : k == "gap" ? "m" : "";
    t += sep + k + " = " + display(v.get<double>(), unit);
    sep = ", ";
  }
  return t;
}

bool whole_png(const fs::path &png) {
  // the 8-byte signature first, the IEND chunk (its type and fixed CRC) last: a torn write lacks it
  static const std::string signature = "\x89PNG\r\n\x1a\n", end = std::string("IEND\xae\x42\x60\x82", 8);
  std::ifstream in(png, std::ios::binary | std::ios::ate);
  if (!in || in.tellg() < std::streamoff(signature.size() + end.size())) return false;
  std::string head(signature.size(), '\0'), tail(end.size(), '\0');
  in.seekg(std::streamoff(-end.size()), std::ios::end);
  in.read(tail.data(), std::streamsize(tail.size()));
  in.seekg(0);
  in.read(head.data(), std::streamsize(head.size()));
  return in && head == signature && tail == end;
}

#ifndef SPREADMAP_WITH_RENDER

bool available() { return false; }
static void unavailable() {
  static std::once_flag once;
  std::call_once(once,
                 [] { spdlog::warn("figures: this build has no VTK (SPREADMAP_ENABLE_VTK=OFF); no PNG is written"); });
}
void snapshot(const engine::ParticleSet &, const Scene &, const nlohmann::json &, const fs::path &, const std::string &,
              const nlohmann::json &) {
  unavailable();
}
std::size_t frames(const std::vector<engine::ParticleSet> &, const std::vector<nlohmann::json> &, const Scene &,
                   const nlohmann::json &, const fs::path &, const std::string &) {
  unavailable();
  return 0;
}
void heightmap(const HeightGrid &, const fs::path &, const std::string &) { unavailable(); }
void parity(const analysis::Report &, const analysis::Table &, const std::vector<std::string> &, const fs::path &) {
  unavailable();
}
void surfaces(const analysis::GridMap &, const std::vector<std::string> &, const analysis::Table &, const fs::path &) {
  unavailable();
}
void process_map(const analysis::GridMap &, std::size_t, std::size_t, const analysis::Table &,
                 const std::vector<analysis::Optimum> &, const fs::path &, const analysis::Table &, int,
                 const std::vector<analysis::MapTrust> &) {
  unavailable();
}
void tradeoff(const std::vector<TradeoffRow> &, double, double, const fs::path &) { unavailable(); }

#else

bool available() { return true; }

namespace {

// A figure that fails is reported and skipped: the numbers it would show are already on disk.
template <class F> void guarded(const fs::path &png, F &&draw) {
  try {
    draw();
  } catch (const std::exception &e) {
    spdlog::warn("figure {} not written: {}", png.string(), e.what());
  }
}

// A figure's options: its default size, scaled to the stage's width when `render: {width: W}` sets
// one (the aspect stays), and the stage's vector copy.
render::Options sized(int width, int height, const std::string &title = "") {
  const Style &style = current_style();
  render::Options o;
  o.width = width;
  o.height = height;
  if (style.width > 0) {
    o.height = std::max(100, int(std::lround(double(height) * style.width / width)));
    o.width = style.width;
  }
  o.title = title;
  o.vector_format = style.vector;
  return o;
}

// Grid rows run with the first input slowest; the renderer wants omega slowest (f[iw * nu + iu]).
struct PlaneGrid {
  std::vector<double> u, omega;
  bool ok = false;
  std::vector<double> field(const Eigen::MatrixXd &m, Eigen::Index col) const {
    std::vector<double> f(u.size() * omega.size());
    for (std::size_t iu = 0; iu < u.size(); ++iu)
      for (std::size_t iw = 0; iw < omega.size(); ++iw)
        f[iw * u.size() + iu] = m(Eigen::Index(iu * omega.size() + iw), col);
    return f;
  }
};

PlaneGrid plane(const analysis::GridMap &g) {
  PlaneGrid p;
  // two inputs, or more whose others are held at one value (a two-fidelity model at fidelity 1)
  if (g.x.cols() < 2 || g.x.rows() < 4) return p;
  for (Eigen::Index c = 2; c < g.x.cols(); ++c)
    if ((g.x.col(c).array() != g.x(0, c)).any()) return p;
  for (Eigen::Index r = 0; r < g.x.rows() && (r == 0 || g.x(r, 0) == g.x(0, 0)); ++r) p.omega.push_back(g.x(r, 1));
  const std::size_t nw = p.omega.size();
  if (nw < 2 || g.x.rows() % Eigen::Index(nw) != 0) return p;
  for (Eigen::Index r = 0; r < g.x.rows(); r += Eigen::Index(nw)) p.u.push_back(g.x(r, 0));
  p.ok = p.u.size() >= 2;
  return p;
}

// A column's symbol and unit as a figure prints them: the file's unit, else spreadmap's own.
render::PlottedQuantity quantity(const std::string &name, const std::string &unit) {
  if (!is_contract_metric(name)) return {name, unit};
  return {known_symbol(name), unit.empty() ? known_unit(name) : unit};
}

}  // namespace

namespace {

// The particles with the spreader as `record` (case.json) describes it, at `pose` (null: where it
// stopped).
render::SnapshotInput snapshot_input(const engine::ParticleSet &p, const Scene &scene, const nlohmann::json &record,
                                     const nlohmann::json &pose) {
  render::SnapshotInput in;
  in.x = p.x;
  in.y = p.y;
  in.z = p.z;
  in.r = p.radius;
  in.speed.resize(p.size(), 0.0);
  if (p.vx.size() == p.size())
    for (std::size_t i = 0; i < p.size(); ++i)
      in.speed[i] = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  in.domain.hi = {scene.domain.length, scene.domain.width, scene.domain.height};
  const auto &body = record.is_object() ? record.value("spreader", nlohmann::json()) : nlohmann::json();
  const auto &at = pose.is_object()
                       ? pose
                       : (record.is_object() ? record.value("spreader_end", nlohmann::json()) : nlohmann::json());
  if (!body.is_object() || !at.is_object() || !at.contains("reference")) return in;  // an older record: none drawn
  in.spreader.outline_x = body.at("outline_x").get<std::vector<double> >();
  in.spreader.outline_z = body.at("outline_z").get<std::vector<double> >();
  in.spreader.y_centre = body.at("y_centre");
  in.spreader.length = body.at("length");
  in.spreader.turns = body.at("turns");
  in.spreader.reference = at.at("reference").get<std::array<double, 3> >();
  in.spreader.angle = at.at("angle");
  return in;
}

}  // namespace

void snapshot(const engine::ParticleSet &p, const Scene &scene, const nlohmann::json &record, const fs::path &png,
              const std::string &title, const nlohmann::json &pose) {
  guarded(png, [&] { render::snapshot(snapshot_input(p, scene, record, pose), png, sized(1600, 900, title)); });
}

std::size_t frames(const std::vector<engine::ParticleSet> &states, const std::vector<nlohmann::json> &poses,
                   const Scene &scene, const nlohmann::json &record, const fs::path &dir, const std::string &title) {
  std::size_t written = 0;
  guarded(dir / "frame_0000.png", [&] {
    std::vector<render::SnapshotInput> in;
    for (std::size_t k = 0; k < states.size(); ++k)
      in.push_back(snapshot_input(states[k], scene, record, k < poses.size() ? poses[k] : nlohmann::json()));
    written = render::animation_frames(in, dir, "frame", sized(1600, 900, title)).size();
  });
  return written;
}

void heightmap(const HeightGrid &layer, const fs::path &png, const std::string &title) {
  if (layer.height.empty()) return;
  guarded(png, [&] {
    render::HeightmapInput in;
    in.nx = int(layer.nx);
    in.ny = int(layer.ny);
    in.height = layer.height;
    in.origin = {layer.x0, layer.y0};
    in.cell = {layer.cell, layer.cell};
    render::heightmap(
        in, png,
        sized(1400, std::max(500, std::min(1400, int(1400.0 * layer.ny / std::max<std::uint32_t>(1, layer.nx)) + 300)),
              title));
  });
}

void parity(const analysis::Report &report, const analysis::Table &cv, const std::vector<std::string> &outputs,
            const fs::path &png) {
  guarded(png, [&] {
    const auto &t = report.parity;
    const auto split = t.texts("split");
    render::ParityInput in;
    for (const auto &name : outputs) {
      render::ParityPanel panel;
      panel.quantity = quantity(name, "");
      const auto truth = t.numbers(name + "_true"), pred = t.numbers(name + "_predicted");
      for (std::size_t i = 0; i < truth.size(); ++i) {
        auto &sim = split[i] == "test" ? panel.test_simulated : panel.train_simulated;
        auto &fit = split[i] == "test" ? panel.test_predicted : panel.train_predicted;
        sim.push_back(truth[i]);
        fit.push_back(pred[i]);
      }
      if (cv.has_column(name + "_true") && cv.has_column(name + "_cv"))
        panel.cv_simulated = cv.numbers(name + "_true"), panel.cv_predicted = cv.numbers(name + "_cv");
      in.panels.push_back(std::move(panel));
    }
    render::parity(in, png, sized(700 * int(std::max<std::size_t>(1, outputs.size())), 700));
  });
}

void surfaces(const analysis::GridMap &grid, const std::vector<std::string> &units, const analysis::Table &data,
              const fs::path &dir) {
  const PlaneGrid p = plane(grid);
  if (!p.ok) return;
  for (std::size_t o = 0; o < grid.outputs.size(); ++o) {
    const fs::path png = dir / ("surface_" + grid.outputs[o] + ".png");
    guarded(png, [&] {
      render::SurfaceInput in;
      in.quantity = quantity(grid.outputs[o], o < units.size() ? units[o] : "");
      in.u = p.u;
      in.omega = p.omega;
      in.values = p.field(grid.prediction.mean, Eigen::Index(o));
      if (data.has_column(grid.inputs[0]) && data.has_column(grid.inputs[1]) && data.has_column(grid.outputs[o])) {
        const auto u = data.numbers(grid.inputs[0]), w = data.numbers(grid.inputs[1]),
                   v = data.numbers(grid.outputs[o]);
        const auto split = data.has_column("split") ? data.texts("split") : std::vector<std::string>(u.size());
        for (std::size_t i = 0; i < u.size(); ++i) in.points.push_back({u[i], w[i], v[i], split[i] == "test"});
      }
      render::surface(in, png, sized(1400, 1000));
    });
  }
}

void process_map(const analysis::GridMap &grid, std::size_t vs, std::size_t rq, const analysis::Table &frontier,
                 const std::vector<analysis::Optimum> &optima, const fs::path &png, const analysis::Table &cases,
                 int verified, const std::vector<analysis::MapTrust> &trust) {
  const PlaneGrid p = plane(grid);
  if (!p.ok) return;
  guarded(png, [&] {
    render::MapInput in;
    in.u = p.u;
    in.omega = p.omega;
    in.vs = p.field(grid.prediction.mean, Eigen::Index(vs));
    in.rq = p.field(grid.prediction.mean, Eigen::Index(rq));
    if (grid.prediction.std.size() > 0) {
      in.vs_std = p.field(grid.prediction.std, Eigen::Index(vs));
      in.rq_std = p.field(grid.prediction.std, Eigen::Index(rq));
    }
    if (frontier.rows() > 0 && frontier.has_column(grid.inputs[0]) && frontier.has_column(grid.inputs[1])) {
      const auto u = frontier.numbers(grid.inputs[0]), w = frontier.numbers(grid.inputs[1]);
      for (std::size_t i = 0; i < u.size(); ++i)
        if (std::isfinite(u[i]) && std::isfinite(w[i])) in.frontier.push_back({u[i], w[i]});
    }
    if (!optima.empty() && optima.front().found) {
      const auto &o = optima.front();
      in.optimum = {true, o.x(0), o.x(1), o.vs, o.rq, verified, o.probability, o.confidence};
      in.rq_target = o.rq_max;
    }
    if (cases.has_column(grid.inputs[0]) && cases.has_column(grid.inputs[1])) {
      const auto u = cases.numbers(grid.inputs[0]), w = cases.numbers(grid.inputs[1]);
      for (std::size_t i = 0; i < u.size(); ++i) in.cases.push_back({u[i], w[i]});
    }
    in.notes = analysis::trust_notes(trust);
    for (const auto &t : trust) {
      in.rq_greyed |= t.untrusted() && t.output == roughness_column;
      in.vs_greyed |= t.untrusted() && t.output == spread_rate_column;
    }
    render::process_map(in, png, sized(1600, 1100, "Process map: R_q (filled) and V_s (lines)"));
  });
}

void tradeoff(const std::vector<TradeoffRow> &rows, double vs_scatter_percent, double rq_scatter_percent,
              const fs::path &png) {
  guarded(png, [&] {
    render::TradeoffInput in;
    for (const auto &r : rows)
      in.points.push_back({r.name, r.wall_seconds, r.vs_error_percent, r.rq_error_percent, r.reference});
    in.vs_scatter = vs_scatter_percent;
    in.rq_scatter = rq_scatter_percent;
    render::tradeoff(in, png, sized(1400, 1000, "Speed-accuracy trade: error against the reference over cost"));
  });
}

#endif

}  // namespace spreadmap::figures
