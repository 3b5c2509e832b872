#include "workflow/calibrate/calibration.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "analysis/plugin_model.hpp"
#include "core/error.hpp"
#include "core/files.hpp"
#include "workflow/calibrate/bulk_test.hpp"
#include "workflow/calibrate/identify.hpp"

namespace spreadmap::calibrate {
namespace fs = std::filesystem;
namespace {

// Full factorial: levels^np rows, the first parameter varying slowest.
Eigen::MatrixXd design(const std::vector<ParameterRange> &box, int levels) {
  const auto np = static_cast<Eigen::Index>(box.size());
  Eigen::Index rows = 1;
  for (Eigen::Index k = 0; k < np; ++k) rows *= levels;
  Eigen::MatrixXd x(rows, np);
  for (Eigen::Index i = 0; i < rows; ++i) {
    Eigen::Index rest = i;
    for (Eigen::Index k = np - 1; k >= 0; --k) {
      const double f = double(rest % levels) / double(levels - 1);
      x(i, k) = box[std::size_t(k)].lo + f * (box[std::size_t(k)].hi - box[std::size_t(k)].lo);
      rest /= levels;
    }
  }
  return x;
}

std::vector<double> row(const Eigen::MatrixXd &x, Eigen::Index i) {
  std::vector<double> v(static_cast<std::size_t>(x.cols()));
  for (Eigen::Index k = 0; k < x.cols(); ++k) v[std::size_t(k)] = x(i, k);
  return v;
}

std::string values_text(const std::vector<ParameterRange> &box, const std::vector<double> &v) {
  std::string s;
  for (std::size_t k = 0; k < box.size(); ++k) s += fmt::format("{}{} = {:.4g}", k ? ", " : "", box[k].name, v[k]);
  return s;
}

std::unique_ptr<analysis::PluginModel> make_model(const CalibrationFile &c, PluginRegistry &registry) {
  return analysis::PluginModel::create(registry.get("surrogate", c.model).descriptor, c.model_params.dump());
}

// Leave-one-out root-mean-square error of the surrogate on one test's angles [deg].
double loo_rmse(const CalibrationFile &c, PluginRegistry &registry, const Eigen::MatrixXd &x,
                const Eigen::VectorXd &y) {
  double ss = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    Eigen::MatrixXd xi(x.rows() - 1, x.cols());
    Eigen::VectorXd yi(x.rows() - 1);
    for (Eigen::Index r = 0, k = 0; r < x.rows(); ++r)
      if (r != i) xi.row(k) = x.row(r), yi(k++) = y(r);
    auto m = make_model(c, registry);
    m->fit(xi, yi);
    const double e = m->predict(x.row(i)).mean(0, 0) - y(i);
    ss += e * e;
  }
  return std::sqrt(ss / double(x.rows()));
}

// The angle of every test at every row of the design [deg] (a row's tests kept from before are read
// back); adds the simulations' wall time to `seconds`.
Eigen::MatrixXd simulate_design(const CalibrationFile &c, const Eigen::MatrixXd &x, const fs::path &out,
                                PluginRegistry &registry, double &seconds) {
  const auto nt = static_cast<Eigen::Index>(c.tests.size());
  Eigen::MatrixXd y(x.rows(), nt);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index t = 0; t < nt; ++t) {
      const auto &test = c.tests[std::size_t(t)];
      const fs::path record = out / "cases" / fmt::format("c{:03d}", i) / (test.name + ".json");
      const auto r = run_bulk_test(test, c.parameters, row(x, i), record, registry);
      y(i, t) = r.angle.angle_deg;
      seconds += r.wall_seconds;
      spdlog::info("calibrate: run {}/{} {} at {}: {:.2f} deg{}", i + 1, x.rows(), test.name,
                   values_text(c.parameters, row(x, i)), r.angle.angle_deg, r.reused ? " (kept from before)" : "");
    }
  return y;
}

// Each parameter's best value and 68 % set, as calibration.json records them (and said in the log).
nlohmann::json identified_parameters(const CalibrationFile &c, const Identified &id) {
  nlohmann::json params = nlohmann::json::object();
  for (std::size_t k = 0; k < c.parameters.size(); ++k) {
    const auto &b = c.parameters[k];
    params[b.name] = {{"best", id.best[k]},
                      {"lower", id.lower[k]},
                      {"upper", id.upper[k]},
                      {"range", {b.lo, b.hi}},
                      {"bounded", !id.open_at_lo[k] && !id.open_at_hi[k]}};
    spdlog::info("calibrate: {} = {:.3g} (68 % set {:.3g} to {:.3g}){}", b.name, id.best[k], id.lower[k], id.upper[k],
                 id.open_at_lo[k] || id.open_at_hi[k]
                     ? fmt::format(" - reaches the range's {} side: not identified there by these tests",
                                   id.open_at_lo[k] ? "lower" : "upper")
                     : "");
  }
  return params;
}

}  // namespace

nlohmann::json run_at(const CalibrationFile &c, const std::vector<double> &values, const fs::path &out,
                      PluginRegistry &registry) {
  nlohmann::json tests = nlohmann::json::array();
  for (std::size_t t = 0; t < c.tests.size(); ++t) {
    const auto &test = c.tests[t];
    const auto r = run_bulk_test(test, c.parameters, values, out / "at" / (test.name + ".json"), registry);
    spdlog::info("{}: {:.2f} +- {:.2f} deg (spread over parts {:.2f} deg; {} particles, {:.1f} s)", test.name,
                 r.angle.angle_deg, r.angle.uncertainty_deg, r.angle.spread_deg, r.particles, r.wall_seconds);
    tests.push_back({{"test", test.name},
                     {"angle_deg", r.angle.angle_deg},
                     {"uncertainty_deg", r.angle.uncertainty_deg},
                     {"spread_deg", r.angle.spread_deg}});
  }
  nlohmann::json params = nlohmann::json::object();
  for (std::size_t k = 0; k < c.parameters.size(); ++k) params[c.parameters[k].name] = values[k];
  const nlohmann::json j = {{"parameters", params}, {"tests", tests}};
  write_atomic(out / "at.json", j.dump(2) + "\n");
  return j;
}

nlohmann::json run_calibration(const CalibrationFile &c, const fs::path &out, PluginRegistry &registry) {
  for (std::size_t t = 0; t < c.tests.size(); ++t)
    if (!c.tests[t].measured)
      throw InputError(
          fmt::format("{}: tests[{}] ({}) has no measured angle; give `angle:` and `uncertainty:`, or "
                      "run `spreadmap calibrate {} --at ...` to only simulate",
                      c.file.string(), t, c.tests[t].name, c.file.string()));
  const Eigen::MatrixXd x = design(c.parameters, c.levels);
  const auto nt = static_cast<Eigen::Index>(c.tests.size());
  double seconds = 0;
  const Eigen::MatrixXd y = simulate_design(c, x, out, registry, seconds);

  std::vector<MeasuredAngle> measured;
  std::vector<std::unique_ptr<analysis::PluginModel>> models;
  nlohmann::json tests = nlohmann::json::array();
  for (Eigen::Index t = 0; t < nt; ++t) {
    const auto &test = c.tests[std::size_t(t)];
    const double lo = y.col(t).minCoeff(), hi = y.col(t).maxCoeff();
    if (test.angle_deg < lo - 2 * test.sigma_deg || test.angle_deg > hi + 2 * test.sigma_deg)
      throw InputError(fmt::format(
          "{}: {} measured {:.2f} deg, but the test gives {:.2f} to {:.2f} deg over the parameter box; no parameters "
          "in it reproduce the measurement: widen the ranges under `parameters:` (or check the scene and the "
          "measurement)",
          test.where.str(), test.name, test.angle_deg, lo, hi));
    measured.push_back({test.name, test.angle_deg, test.sigma_deg});
    models.push_back(make_model(c, registry));
    models.back()->fit(x, y.col(t));
    const double loo = loo_rmse(c, registry, x, y.col(t));
    tests.push_back({{"test", test.name},
                     {"measured_deg", test.angle_deg},
                     {"uncertainty_deg", test.sigma_deg},
                     {"simulated_range_deg", {lo, hi}},
                     {"surrogate_loo_rmse_deg", loo}});
  }
  const auto id = identify(c.parameters, measured, [&](const Eigen::MatrixXd &q) {
    analysis::Prediction p{Eigen::MatrixXd(q.rows(), nt), Eigen::MatrixXd::Zero(q.rows(), nt)};
    for (Eigen::Index t = 0; t < nt; ++t) {
      const auto one = models[std::size_t(t)]->predict(q);
      p.mean.col(t) = one.mean.col(0);
      if (one.std.size()) p.std.col(t) = one.std.col(0);
    }
    return p;
  });
  const nlohmann::json params = identified_parameters(c, id);
  for (Eigen::Index t = 0; t < nt; ++t) {
    auto &j = tests[std::size_t(t)];
    j["predicted_deg"] = id.predicted_deg[std::size_t(t)];
    j["predicted_std_deg"] = id.predicted_std_deg[std::size_t(t)];
    spdlog::info(
        "calibrate: {}: measured {:.2f} +- {:.2f} deg, predicted at the best {:.2f} +- {:.2f} deg "
        "(surrogate leave-one-out error {:.2f} deg)",
        c.tests[std::size_t(t)].name, c.tests[std::size_t(t)].angle_deg, c.tests[std::size_t(t)].sigma_deg,
        id.predicted_deg[std::size_t(t)], id.predicted_std_deg[std::size_t(t)],
        j["surrogate_loo_rmse_deg"].get<double>());
  }
  const nlohmann::json result = {{"name", c.name},          {"parameters", params},         {"tests", tests},
                                 {"runs", x.rows() * nt},   {"simulated_seconds", seconds}, {"model", c.model},
                                 {"chi2_min", id.chi2_min}, {"chi2_delta", id.delta}};
  write_atomic(out / "calibration.json", result.dump(2) + "\n");
  return result;
}

}  // namespace spreadmap::calibrate
