#include "optimum.hpp"

#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <stdexcept>
#include <nlohmann/json.hpp>

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
void check_columns(const GridMap &g, std::size_t vs, std::size_t rq) {
  const auto n = std::size_t(g.prediction.mean.cols());
  if (vs >= n || rq >= n) throw std::invalid_argument("optimum: output column out of range");
}
}  // namespace

double normal_quantile(double p) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("normal_quantile: p must lie in (0, 1)");
  if (p == 0.5) return 0.0;
  return -std::sqrt(2.0) * boost::math::erfc_inv(2 * p);
}

Optimum find_optimum(const GridMap &g, std::size_t vs, std::size_t rq, double rq_max, const OptimumRule &rule) {
  check_columns(g, vs, rq);
  if (!(rule.confidence >= 0.5 && rule.confidence < 1))
    throw std::invalid_argument("optimum: the confidence must lie in [0.5, 1)");
  const auto &m = g.prediction.mean;
  const bool model_std = g.prediction.std.size() > 0;
  const bool has_std = model_std || rule.fallback_rq_std >= 0;
  const double z = normal_quantile(rule.confidence);
  if (z > 0 && !has_std)
    throw std::invalid_argument("optimum: a confidence above 0.5 needs the predictive spread of R_q");
  const auto spread = [&](Eigen::Index r) {
    return model_std ? g.prediction.std(r, Eigen::Index(rq)) : rule.fallback_rq_std;
  };
  Optimum o;
  o.rq_max = rq_max;
  o.confidence = rule.confidence;
  double best = -HUGE_VAL;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    // z = 0 compares the mean alone, exactly as the mean rule always did
    const double upper = z == 0 ? m(r, Eigen::Index(rq)) : m(r, Eigen::Index(rq)) + z * spread(r);
    if (!(upper <= rq_max)) continue;
    if (m(r, Eigen::Index(vs)) > best) best = m(r, Eigen::Index(vs)), o.row = std::size_t(r), o.found = true;
  }
  if (!o.found) return o;
  const auto r = Eigen::Index(o.row);
  o.x = g.x.row(r).transpose();
  o.vs = m(r, Eigen::Index(vs)), o.rq = m(r, Eigen::Index(rq));
  if (has_std) {
    o.rq_std = spread(r);
    o.std_source = model_std ? "model" : rule.std_source;
    o.probability =
        o.rq_std > 0 ? 0.5 * std::erfc(-(rq_max - o.rq) / (o.rq_std * std::sqrt(2.0))) : (o.rq <= rq_max ? 1.0 : 0.0);
  }
  return o;
}

std::vector<Optimum> find_optima(const GridMap &g, std::size_t vs, std::size_t rq, const std::vector<double> &targets,
                                 const OptimumRule &rule) {
  std::vector<Optimum> out;
  for (double t : targets) out.push_back(find_optimum(g, vs, rq, t, rule));
  return out;
}

nlohmann::json Optimum::to_json(const std::vector<std::string> &names) const {
  nlohmann::json j = {{"rq_max", rq_max}, {"confidence", confidence}, {"found", found}};
  if (!found) return j;
  nlohmann::json in = nlohmann::json::object();
  for (Eigen::Index k = 0; k < x.size(); ++k)
    in[k < Eigen::Index(names.size()) ? names[std::size_t(k)] : "x" + std::to_string(k)] = x[k];
  j["inputs"] = in, j["vs"] = vs, j["rq"] = rq, j["grid_row"] = row;
  if (rq_std >= 0) j["rq_std"] = rq_std, j["probability"] = probability, j["rq_std_source"] = std_source;
  return j;
}

Table frontier(const GridMap &g, std::size_t vs, std::size_t rq, std::vector<double> levels, std::size_t n_levels) {
  check_columns(g, vs, rq);
  const auto &m = g.prediction.mean;
  const Eigen::VectorXd rqs = m.col(Eigen::Index(rq)), vss = m.col(Eigen::Index(vs));
  if (levels.empty()) {
    if (n_levels < 2) throw std::invalid_argument("frontier: need at least 2 levels");
    const double lo = rqs.minCoeff(), hi = rqs.maxCoeff();
    for (std::size_t i = 0; i < n_levels; ++i) levels.push_back(lo + (hi - lo) * double(i) / double(n_levels - 1));
  }
  std::sort(levels.begin(), levels.end());
  // Visit points by ascending R_q, carrying the best V_s so far: each level costs O(1) amortised.
  std::vector<Eigen::Index> order(std::size_t(m.rows()));
  for (Eigen::Index r = 0; r < m.rows(); ++r) order[std::size_t(r)] = r;
  std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) { return rqs[a] < rqs[b]; });
  std::vector<std::string> cols = {"rq_level", "vs_max"};
  cols.insert(cols.end(), g.inputs.begin(), g.inputs.end());
  cols.push_back("rq");
  Table t(cols, "frontier");
  std::size_t next = 0;
  Eigen::Index best = -1;
  for (double level : levels) {
    while (next < order.size() && rqs[order[next]] <= level) {
      if (best < 0 || vss[order[next]] > vss[best]) best = order[next];
      ++next;
    }
    if (best < 0) continue;  // no grid point is this smooth
    std::vector<double> row = {level, vss[best]};
    for (Eigen::Index k = 0; k < g.x.cols(); ++k) row.push_back(g.x(best, k));
    row.push_back(rqs[best]);
    t.add_row(row);
  }
  return t;
}

}  // namespace spreadmap::analysis
