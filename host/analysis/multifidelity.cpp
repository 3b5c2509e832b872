#include "multifidelity.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "adaptive.hpp"

namespace spreadmap::analysis {
namespace {

// The candidates with a fidelity column appended.
Eigen::MatrixXd at_fidelity(const Eigen::MatrixXd &cand, double fidelity) {
  Eigen::MatrixXd x(cand.rows(), cand.cols() + 1);
  x << cand, Eigen::VectorXd::Constant(cand.rows(), fidelity);
  return x;
}

void check_rows(const std::vector<std::size_t> &rows, const Eigen::MatrixXd &cand, const char *what) {
  for (auto i : rows)
    if (i >= std::size_t(cand.rows()))
      throw std::invalid_argument(std::string("multi-fidelity design: an initial ") + what + " row is not a candidate");
}

}  // namespace

std::vector<std::size_t> corners_and_centre(const Eigen::MatrixXd &c, const std::vector<std::size_t> &start) {
  const Eigen::RowVectorXd lo = c.colwise().minCoeff(), hi = c.colwise().maxCoeff();
  std::vector<std::size_t> out;
  for (auto i : start) {
    const Eigen::RowVectorXd z = (c.row(Eigen::Index(i)) - lo).array() / (hi - lo).array().max(1e-300);
    const bool corner = ((z.array() < 0.25) || (z.array() > 0.75)).all();
    const bool centre = ((z.array() - 0.5).abs() < 0.25).all();
    if (corner || centre) out.push_back(i);
  }
  return out;
}

MultiFidelityResult multi_fidelity_design(
    const Eigen::MatrixXd &cand, const std::function<std::unique_ptr<Model>()> &make_model,
    const std::function<Eigen::VectorXd(const Eigen::VectorXd &, bool expensive)> &evaluate,
    const MultiFidelityOptions &opt) {
  const std::vector<std::size_t> lattice = space_filling_start(cand);
  const std::vector<std::size_t> start_cheap = opt.initial_cheap.empty() ? lattice : opt.initial_cheap;
  const std::vector<std::size_t> start_expensive =
      opt.initial_expensive.empty() ? corners_and_centre(cand, lattice) : opt.initial_expensive;
  check_rows(start_cheap, cand, "cheap");
  check_rows(start_expensive, cand, "expensive");
  if (start_expensive.size() < 3)
    throw std::invalid_argument("multi-fidelity design: start with at least 3 expensive cases");
  if (opt.budget_cheap < start_cheap.size() || opt.budget_expensive < start_expensive.size())
    throw std::invalid_argument("multi-fidelity design: a budget (cheap " + std::to_string(opt.budget_cheap) +
                                ", expensive " + std::to_string(opt.budget_expensive) + ") is below its " +
                                std::to_string(start_cheap.size()) + " and " + std::to_string(start_expensive.size()) +
                                " initial cases");

  MultiFidelityResult r;
  std::vector<bool> used_cheap(std::size_t(cand.rows()), false), used_expensive(used_cheap);
  std::vector<Eigen::VectorXd> xs, ys;
  auto run = [&](std::size_t i, bool expensive) {
    const Eigen::VectorXd x = cand.row(Eigen::Index(i)).transpose();
    const Eigen::VectorXd y = evaluate(x, expensive);
    if (!ys.empty() && y.size() != ys.front().size())
      throw std::runtime_error("multi-fidelity design: evaluate() changed its output count");
    Eigen::VectorXd xf(x.size() + 1);
    xf << x, expensive ? 1.0 : 0.0;
    xs.push_back(xf), ys.push_back(y), r.chosen.push_back(i);
    (expensive ? used_expensive : used_cheap)[i] = true;
    ++(expensive ? r.expensive : r.cheap);
  };
  for (auto i : start_cheap) run(i, false);
  for (auto i : start_expensive) run(i, true);
  const Eigen::MatrixXd cheap_x = at_fidelity(cand, 0.0), expensive_x = at_fidelity(cand, 1.0);
  std::size_t good_in_a_row = 0;

  while (true) {
    const auto n = Eigen::Index(xs.size());
    r.x.resize(n, cand.cols() + 1), r.y.resize(n, ys.front().size());
    std::vector<Eigen::Index> expensive_rows;
    for (Eigen::Index k = 0; k < n; ++k) {
      r.x.row(k) = xs[std::size_t(k)].transpose(), r.y.row(k) = ys[std::size_t(k)].transpose();
      if (r.x(k, cand.cols()) == 1.0) expensive_rows.push_back(k);
    }
    auto model = make_model();
    if (!model->has_std())
      throw std::invalid_argument("multi-fidelity design: the model gives no standard deviation (use a surrogate that does)");
    model->fit(r.x, r.y);
    MultiFidelityStep step{r.cheap, r.expensive, loo_nrmse_percent(*model, r.y, expensive_rows)};
    r.history.push_back(step);
    if (target_held(good_in_a_row, step.loo_nrmse, opt.target_loo_nrmse, r.history.size(), opt.confirm))
      return r.reached_target = true, r.stop_reason = "target", r;
    const bool cheap_left = r.cheap < opt.budget_cheap, expensive_left = r.expensive < opt.budget_expensive;
    if (!cheap_left && !expensive_left) return r.stop_reason = "budget", r;

    // Candidates by how unsure the expensive prediction is, most unsure first.
    const Prediction pe = model->predict(expensive_x), pc = model->predict(cheap_x);
    Eigen::RowVectorXd range(r.y.cols());
    for (Eigen::Index c = 0; c < r.y.cols(); ++c) {
      double lo = INFINITY, hi = -INFINITY;
      for (auto k : expensive_rows) lo = std::min(lo, r.y(k, c)), hi = std::max(hi, r.y(k, c));
      range[c] = hi > lo ? hi - lo : 1.0;
    }
    std::vector<double> se(std::size_t(cand.rows())), sc(se.size());
    for (Eigen::Index i = 0; i < cand.rows(); ++i)
      se[std::size_t(i)] = (pe.std.row(i).array() / range.array()).maxCoeff(),
      sc[std::size_t(i)] = (pc.std.row(i).array() / range.array()).maxCoeff();
    std::vector<std::size_t> order(se.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return se[a] > se[b]; });
    bool ran = false;
    for (auto i : order) {
      const bool cheap_here = cheap_left && !used_cheap[i], expensive_here = expensive_left && !used_expensive[i];
      if (cheap_here && (sc[i] >= opt.cheap_share * se[i] || !expensive_here)) {
        run(i, false), ran = true;
        break;
      }
      if (expensive_here) {
        run(i, true), ran = true;
        break;
      }
    }
    if (!ran) return r.stop_reason = "candidates exhausted", r;
  }
}

}  // namespace spreadmap::analysis
