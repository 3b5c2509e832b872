#include "optimum.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
void check_columns(const GridMap &g, std::size_t vs, std::size_t rq) {
  const auto n = std::size_t(g.prediction.mean.cols());
  if (vs >= n || rq >= n) throw std::invalid_argument("optimum: output column out of range");
}
}  // namespace

Optimum find_optimum(const GridMap &g, std::size_t vs, std::size_t rq, double rq_max) {
  check_columns(g, vs, rq);
  const auto &m = g.prediction.mean;
  Optimum o;
  o.rq_max = rq_max;
  double best = -HUGE_VAL;
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    if (!(m(r, Eigen::Index(rq)) <= rq_max)) continue;
    if (m(r, Eigen::Index(vs)) > best) best = m(r, Eigen::Index(vs)), o.row = std::size_t(r), o.found = true;
  }
  if (!o.found) return o;
  const auto r = Eigen::Index(o.row);
  o.x = g.x.row(r).transpose();
  o.vs = m(r, Eigen::Index(vs)), o.rq = m(r, Eigen::Index(rq));
  if (g.prediction.std.size()) {
    o.rq_std = g.prediction.std(r, Eigen::Index(rq));
    o.probability =
        o.rq_std > 0 ? 0.5 * std::erfc(-(rq_max - o.rq) / (o.rq_std * std::sqrt(2.0))) : (o.rq <= rq_max ? 1.0 : 0.0);
  }
  return o;
}

std::vector<Optimum> find_optima(const GridMap &g, std::size_t vs, std::size_t rq, const std::vector<double> &targets) {
  std::vector<Optimum> out;
  for (double t : targets) out.push_back(find_optimum(g, vs, rq, t));
  return out;
}

nlohmann::json Optimum::to_json(const std::vector<std::string> &names) const {
  nlohmann::json j = {{"rq_max", rq_max}, {"found", found}};
  if (!found) return j;
  nlohmann::json in = nlohmann::json::object();
  for (Eigen::Index k = 0; k < x.size(); ++k)
    in[k < Eigen::Index(names.size()) ? names[std::size_t(k)] : "x" + std::to_string(k)] = x[k];
  j["inputs"] = in, j["vs"] = vs, j["rq"] = rq, j["grid_row"] = row;
  if (rq_std >= 0) j["rq_std"] = rq_std, j["probability"] = probability;
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
