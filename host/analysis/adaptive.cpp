#include "adaptive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <nlohmann/json.hpp>

#include "scores.hpp"

namespace sm = spreadmap;

namespace spreadmap::analysis {

std::vector<std::size_t> space_filling_start(const Eigen::MatrixXd &c) {
  if (c.rows() == 0) throw std::invalid_argument("adaptive design: no candidates");
  const Eigen::RowVectorXd lo = c.colwise().minCoeff(), hi = c.colwise().maxCoeff();
  const Eigen::RowVectorXd span = (hi - lo).unaryExpr([](double s) { return s > 0 ? s : 1.0; });
  const Eigen::MatrixXd z = (c.rowwise() - lo).array().rowwise() / span.array();
  const auto d = c.cols();
  std::size_t lattice = 1;
  for (Eigen::Index k = 0; k < d; ++k) lattice *= 3;
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < lattice; ++p) {
    Eigen::RowVectorXd target(d);
    std::size_t rest = p;
    for (Eigen::Index k = 0; k < d; ++k) target[k] = 0.5 * double(rest % 3), rest /= 3;
    Eigen::Index best = 0;
    (z.rowwise() - target).rowwise().squaredNorm().minCoeff(&best);
    if (std::find(out.begin(), out.end(), std::size_t(best)) == out.end()) out.push_back(std::size_t(best));
  }
  return out;
}

std::vector<double> loo_nrmse_percent(const Model &fitted, const Eigen::MatrixXd &y,
                                      const std::vector<Eigen::Index> &rows) {
  const nlohmann::json info = fitted.fit_info();
  if (!info.contains("loo_mean"))
    throw std::invalid_argument("the model reports no leave-one-out predictions (loo_mean): use a surrogate that does");
  std::vector<Eigen::Index> picked = rows;
  if (picked.empty())
    for (Eigen::Index k = 0; k < y.rows(); ++k) picked.push_back(k);
  std::vector<double> out;
  for (Eigen::Index c = 0; c < y.cols(); ++c) {
    Eigen::VectorXd truth(Eigen::Index(picked.size())), loo(truth.size());
    for (std::size_t k = 0; k < picked.size(); ++k)
      truth[Eigen::Index(k)] = y(picked[k], c),
      loo[Eigen::Index(k)] = info["loo_mean"].at(std::size_t(picked[k])).at(std::size_t(c)).get<double>();
    out.push_back(nrmse_percent(truth, loo));
  }
  return out;
}

bool target_held(std::size_t &in_a_row, const std::vector<double> &loo_nrmse, double target, std::size_t fits,
                 std::size_t confirm) {
  const bool good =
      std::all_of(loo_nrmse.begin(), loo_nrmse.end(), [&](double e) { return std::isfinite(e) && e <= target; });
  in_a_row = good && fits > 1 ? in_a_row + 1 : 0;
  return in_a_row >= std::max<std::size_t>(1, confirm);
}

AdaptiveResult adaptive_design(const Eigen::MatrixXd &cand, const std::function<std::unique_ptr<Model>()> &make_model,
                               const std::function<Eigen::VectorXd(const Eigen::VectorXd &)> &evaluate,
                               const AdaptiveOptions &opt) {
  AdaptiveResult r;
  std::vector<std::size_t> start = opt.initial.empty() ? space_filling_start(cand) : opt.initial;
  if (start.size() < 3) throw std::invalid_argument("adaptive design: start with at least 3 cases");
  for (auto i : start)
    if (i >= std::size_t(cand.rows()))
      throw std::invalid_argument("adaptive design: an initial row is not a candidate");
  if (opt.budget < start.size())
    throw std::invalid_argument("adaptive design: budget " + std::to_string(opt.budget) + " is below the " +
                                std::to_string(start.size()) + " initial cases");
  std::vector<bool> used(std::size_t(cand.rows()), false);
  std::vector<Eigen::VectorXd> ys;
  auto run = [&](std::size_t i) {
    const Eigen::VectorXd y = evaluate(cand.row(Eigen::Index(i)).transpose());
    if (!ys.empty() && y.size() != ys.front().size())
      throw std::runtime_error("adaptive design: evaluate() changed its output count");
    ys.push_back(y), r.chosen.push_back(i), used[i] = true;
  };
  for (auto i : start) run(i);
  std::size_t good_in_a_row = 0;

  while (true) {
    const auto n = Eigen::Index(r.chosen.size());
    r.x.resize(n, cand.cols()), r.y.resize(n, ys.front().size());
    for (Eigen::Index k = 0; k < n; ++k)
      r.x.row(k) = cand.row(Eigen::Index(r.chosen[std::size_t(k)])), r.y.row(k) = ys[std::size_t(k)];
    auto model = make_model();
    if (!model->has_std())
      throw std::invalid_argument("adaptive design: the model gives no standard deviation (use a surrogate that does)");
    model->fit(r.x, r.y);
    AdaptiveStep step{std::size_t(n), loo_nrmse_percent(*model, r.y)};
    r.history.push_back(step);
    if (target_held(good_in_a_row, step.loo_nrmse, opt.target_loo_nrmse, r.history.size(), opt.confirm))
      return r.reached_target = true, r.stop_reason = "target", r;
    if (r.chosen.size() >= opt.budget) return r.stop_reason = "budget", r;
    if (r.chosen.size() >= std::size_t(cand.rows())) return r.stop_reason = "candidates exhausted", r;

    // Next: the unused candidate of largest normalised predictive std.
    const Prediction p = model->predict(cand);
    Eigen::RowVectorXd range = r.y.colwise().maxCoeff() - r.y.colwise().minCoeff();
    range = range.unaryExpr([](double v) { return v > 0 ? v : 1.0; });
    double best = -1;
    std::size_t pick = 0;
    for (Eigen::Index i = 0; i < cand.rows(); ++i) {
      if (used[std::size_t(i)]) continue;
      const double score = (p.std.row(i).array() / range.array()).maxCoeff();
      if (score > best) best = score, pick = std::size_t(i);
    }
    run(pick);
  }
}

}  // namespace spreadmap::analysis
