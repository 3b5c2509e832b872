// Gaussian-process regression: kernels, marginal likelihood with its gradient, fit and prediction.
#include <algorithm>
#include "gp_model.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "../common/lbfgs.hpp"
#include "spreadmap/random.hpp"

namespace sm = spreadmap;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace spreadmap::surrogate {

Kernel kernel_from_name(const std::string &n) {
  if (n == "squared_exponential") return Kernel::squared_exponential;
  if (n == "matern52") return Kernel::matern52;
  throw std::invalid_argument("kernel '" + n + "' is not one of squared_exponential|matern52");
}
const char *name_of(Kernel k) { return k == Kernel::squared_exponential ? "squared_exponential" : "matern52"; }

namespace {
constexpr double sqrt5 = 2.23606797749979;
constexpr double log_2pi = 1.8378770664093453;

// Bounds of theta = log(s^2, l_1..d, n_1^2..n_G^2) on standardised data.
void bounds(const GpConfig &c, int d, int noises, VectorXd &lo, VectorXd &hi) {
  lo.resize(d + 1 + noises), hi.resize(d + 1 + noises);
  lo[0] = std::log(1e-4), hi[0] = std::log(1e4);
  lo.segment(1, d).setConstant(std::log(1e-2)), hi.segment(1, d).setConstant(std::log(1e3));
  lo.tail(noises).setConstant(std::log(c.noise_min)), hi.tail(noises).setConstant(std::log(c.noise_max));
}

// The nugget of each row: theta[d + 1 + its group], or theta[d + 1] for all when there are no groups.
VectorXd row_noise(const VectorXd &theta, int d, Eigen::Index n, const std::vector<int> *group) {
  if (!group) return VectorXd::Constant(n, std::exp(theta[d + 1]));
  VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = std::exp(theta[d + 1 + (*group)[std::size_t(i)]]);
  return v;
}

// k as a function of the ARD-scaled squared distance r2, and dk/d(r_d^2 term) factor q such that
// dk/dlog(l_d) = q * r_d^2 (r_d^2 = scaled squared distance along d).
struct KernelValue {
  double k, q;
};
KernelValue kernel_value(Kernel kind, double s2, double r2) {
  if (kind == Kernel::squared_exponential) {
    const double k = s2 * std::exp(-0.5 * r2);
    return {k, k};
  }
  const double r = std::sqrt(r2), e = std::exp(-sqrt5 * r);
  return {s2 * (1 + sqrt5 * r + 5.0 / 3.0 * r2) * e, s2 * 5.0 / 3.0 * (1 + sqrt5 * r) * e};
}
}  // namespace

MatrixXd GpModel::kernel(const VectorXd &theta, const MatrixXd &a, const MatrixXd &b) const {
  const int d = int(a.cols());
  const double s2 = std::exp(theta[0]);
  const Eigen::RowVectorXd inv_l = (-theta.segment(1, d).array()).exp().matrix().transpose();
  const MatrixXd as = a.array().rowwise() * inv_l.array(), bs = b.array().rowwise() * inv_l.array();
  MatrixXd k(a.rows(), b.rows());
  for (Eigen::Index j = 0; j < b.rows(); ++j)
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      k(i, j) = kernel_value(config_.kernel, s2, (as.row(i) - bs.row(j)).squaredNorm()).k;
  return k;
}

double GpModel::negative_log_likelihood(const VectorXd &theta, const MatrixXd &xs, const VectorXd &ys, VectorXd *grad,
                                        const VectorXd *known, const std::vector<int> *group) const {
  const Eigen::Index n = xs.rows();
  const int d = int(xs.cols());
  if (group && Eigen::Index(group->size()) != n) throw std::invalid_argument("gp: one noise group per row expected");
  const VectorXd noise = row_noise(theta, d, n, group);
  MatrixXd k = kernel(theta, xs, xs);
  k.diagonal() += noise;
  if (known) k.diagonal() += *known;
  const Eigen::LLT<MatrixXd> llt(k);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const VectorXd alpha = llt.solve(ys);
  const MatrixXd l = llt.matrixL();
  const double value = 0.5 * ys.dot(alpha) + l.diagonal().array().log().sum() + 0.5 * double(n) * log_2pi;
  if (!grad) return value;

  // d(-lml)/dtheta_j = 0.5 sum_ab W_ab dK_ab/dtheta_j, W = K^-1 - alpha alpha^T.
  const MatrixXd w = llt.solve(MatrixXd::Identity(n, n)) - alpha * alpha.transpose();
  grad->setZero(theta.size());
  const double s2 = std::exp(theta[0]);
  const Eigen::RowVectorXd inv_l = (-theta.segment(1, d).array()).exp().matrix().transpose();
  const MatrixXd xl = xs.array().rowwise() * inv_l.array();
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::RowVectorXd diff2 = (xl.row(i) - xl.row(j)).array().square().matrix();
      const KernelValue kv = kernel_value(config_.kernel, s2, diff2.sum());
      const double half_w = 0.5 * w(i, j);
      (*grad)[0] += half_w * kv.k;                               // dk/dlog s^2 = k
      grad->segment(1, d) += half_w * kv.q * diff2.transpose();  // dk/dlog l_d = q r_d^2
    }
  // dK/dlog n_g^2 = n_g^2 on the diagonal of group g's rows
  for (Eigen::Index i = 0; i < n; ++i)
    (*grad)[d + 1 + (group ? (*group)[std::size_t(i)] : 0)] += 0.5 * noise[i] * w(i, i);
  return value;
}

double GpModel::negative_log_posterior(const VectorXd &theta, const MatrixXd &xs, const VectorXd &ys, VectorXd *grad,
                                       const VectorXd *known, const std::vector<int> *group) const {
  double value = negative_log_likelihood(theta, xs, ys, grad, known, group);
  if (config_.noise_prior_width <= 0 || !std::isfinite(value)) return value;
  // log-normal prior on each noise share n_g^2: log n_g^2 ~ N(log median, width^2)
  for (Eigen::Index j = xs.cols() + 1; j < theta.size(); ++j) {
    const double z = (theta[j] - std::log(config_.noise_prior_median)) / config_.noise_prior_width;
    value += 0.5 * z * z;
    if (grad) (*grad)[j] += z / config_.noise_prior_width;
  }
  return value;
}

const VectorXd *GpModel::known_noise(std::size_t c) const { return c < known_.size() ? &known_[c] : nullptr; }

void GpModel::prepare(Output &out, const VectorXd &ys, const VectorXd *known) const {
  const int d = int(xs_.cols());
  MatrixXd k = kernel(out.theta, xs_, xs_);
  k.diagonal() += row_noise(out.theta, d, xs_.rows(), groups());
  if (known) k.diagonal() += *known;
  const Eigen::LLT<MatrixXd> llt(k);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("gp: the covariance matrix is not positive definite; raise noise_min");
  out.chol = llt.matrixL();
  out.alpha = llt.solve(ys);
  const MatrixXd k_inv = llt.solve(MatrixXd::Identity(k.rows(), k.cols()));
  out.loo = ys - (out.alpha.array() / k_inv.diagonal().array()).matrix();
  out.lml = -(0.5 * ys.dot(out.alpha) + out.chol.diagonal().array().log().sum() + 0.5 * double(ys.size()) * log_2pi);
}

void GpModel::fit(const MatrixXd &x, const MatrixXd &y, const MatrixXd &noise_var) {
  if (x.rows() != y.rows()) throw std::invalid_argument("gp: inputs and outputs differ in row count");
  if (noise_var.size() && (noise_var.rows() != y.rows() || noise_var.cols() != y.cols()))
    throw std::invalid_argument("gp: the known noise variances are not one per output value");
  if (noise_var.size() && (!noise_var.allFinite() || noise_var.minCoeff() < 0))
    throw std::invalid_argument("gp: a known noise variance is negative, NaN or infinite");
  if (x.rows() < 2 || x.cols() < 1 || y.cols() < 1)
    throw std::invalid_argument("gp: need >= 2 rows, >= 1 input and output");
  if (!x.allFinite() || !y.allFinite()) throw std::invalid_argument("gp: training data contain NaN or infinity");
  if (config_.restarts < 1) throw std::invalid_argument("gp: restarts must be >= 1");
  x_train_ = x, y_train_ = y;
  x_scale_ = Standardiser::fit(x), y_scale_ = Standardiser::fit(y);
  xs_ = x_scale_.forward(x);
  set_known_noise(noise_var);
  set_noise_groups({});
  const MatrixXd ys_all = y_scale_.forward(y);
  const int d = int(x.cols()), noises = noise_count();
  VectorXd lo, hi;
  bounds(config_, d, noises, lo, hi);
  // No length scale below half the spacing of the design along that input: features finer than the
  // sampling cannot be resolved, and on a small lattice of noisy DEM results the likelihood
  // otherwise prefers a near-zero length with near-zero noise (spikes at every training point).
  for (int k = 0; k < d; ++k) {
    std::vector<double> v(xs_.col(k).data(), xs_.col(k).data() + xs_.rows());
    std::sort(v.begin(), v.end());
    double spacing = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < v.size(); ++i)
      if (v[i] - v[i - 1] > 1e-9) spacing = std::min(spacing, v[i] - v[i - 1]);
    if (std::isfinite(spacing)) lo[1 + k] = std::min(hi[1 + k], std::max(lo[1 + k], std::log(0.5 * spacing)));
  }
  LbfgsOptions o;
  o.max_iterations = config_.max_iterations;
  o.gradient_tolerance = 1e-7;
  o.relative_tolerance = 1e-12;
  o.lower = lo, o.upper = hi;

  outputs_.assign(std::size_t(y.cols()), {});
  for (Eigen::Index c = 0; c < y.cols(); ++c) {
    const VectorXd ys = ys_all.col(c);
    Random rng(config_.seed + std::uint64_t(c) * 0x9e3779b97f4a7c15ULL);
    const VectorXd *known = known_noise(std::size_t(c));
    const auto objective = [&](const VectorXd &t, VectorXd &g) {
      return negative_log_posterior(t, xs_, ys, &g, known, groups());
    };
    double best = std::numeric_limits<double>::infinity();
    Output &out = outputs_[std::size_t(c)];
    for (int start = 0; start < config_.restarts; ++start) {
      VectorXd t(d + 1 + noises);
      if (start == 0) {
        t.setZero();
        t.tail(noises).setConstant(std::log(std::max(config_.noise_min, std::min(config_.noise_max, 1e-4))));
      } else {
        t[0] = rng.uniform(std::log(0.1), std::log(10.0));
        for (int k = 0; k < d; ++k) t[1 + k] = rng.uniform(std::log(0.1), std::log(10.0));
        for (int g = 0; g < noises; ++g)
          t[d + 1 + g] = rng.uniform(lo[d + 1], std::max(lo[d + 1], std::min(hi[d + 1], std::log(0.1))));
      }
      t = t.cwiseMax(lo).cwiseMin(hi);
      const LbfgsResult r = lbfgs_minimise(objective, t, o);
      if (std::isfinite(r.value) && r.value < best) best = r.value, out.theta = t, out.iterations = r.iterations;
    }
    if (!std::isfinite(best)) throw std::runtime_error("gp: no start gave a finite likelihood; raise noise_min");
    prepare(out, ys, known);
  }
}

// values empty: found from the training inputs (fit); given: a saved state's (from_json).
void GpModel::set_noise_groups(std::vector<double> values) {
  group_values_.clear(), group_.clear();
  const int c = config_.noise_group_input;
  if (c < 0) return;
  if (c >= x_train_.cols())
    throw std::invalid_argument("gp: noise_by_input = " + std::to_string(c + 1) + " is past the " +
                                std::to_string(x_train_.cols()) +
                                " inputs; set it to 0 (one noise) or an input's number");
  if (values.empty()) {
    values.assign(x_train_.col(c).data(), x_train_.col(c).data() + x_train_.rows());
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
  }
  if (values.size() > std::size_t(max_noise_groups))
    throw std::invalid_argument("gp: input " + std::to_string(c + 1) + " takes " + std::to_string(values.size()) +
                                " values; a noise per value allows at most " + std::to_string(max_noise_groups) +
                                " (group by a fidelity or a batch, not a setting)");
  for (Eigen::Index i = 0; i < x_train_.rows(); ++i) {
    const auto at = std::find(values.begin(), values.end(), x_train_(i, c));
    if (at == values.end()) throw std::invalid_argument("gp state: a row's noise group is not among noise_groups");
    group_.push_back(int(at - values.begin()));
  }
  group_values_ = std::move(values);
}

void GpModel::set_known_noise(const MatrixXd &noise_var) {
  noise_var_ = noise_var;
  known_.clear();
  if (noise_var.size() == 0) return;
  for (Eigen::Index c = 0; c < noise_var.cols(); ++c) {
    const double scale = y_scale_.scale[c];
    known_.push_back(noise_var.col(c) / (scale * scale));
  }
}

MatrixXd GpModel::predict(const MatrixXd &x, MatrixXd *std) const {
  if (!fitted()) throw std::logic_error("gp: predict() before fit() or load()");
  if (x.cols() != xs_.cols())
    throw std::invalid_argument("gp: expected " + std::to_string(xs_.cols()) + " inputs, got " +
                                std::to_string(x.cols()));
  const MatrixXd xq = x_scale_.forward(x);
  MatrixXd mean(x.rows(), Eigen::Index(outputs_.size()));
  if (std) std->resize(x.rows(), Eigen::Index(outputs_.size()));
  for (std::size_t c = 0; c < outputs_.size(); ++c) {
    const Output &out = outputs_[c];
    const MatrixXd ks = kernel(out.theta, xq, xs_);  // query x train
    mean.col(Eigen::Index(c)) = ks * out.alpha;
    if (std) {
      const MatrixXd v = out.chol.triangularView<Eigen::Lower>().solve(ks.transpose());
      const VectorXd var = (std::exp(out.theta[0]) - v.colwise().squaredNorm().array()).max(0.0).matrix();
      std->col(Eigen::Index(c)) = var.array().sqrt().matrix() * y_scale_.scale[Eigen::Index(c)];
    }
  }
  return y_scale_.inverse(mean);
}

MatrixXd GpModel::loo_mean() const {
  MatrixXd z(xs_.rows(), Eigen::Index(outputs_.size()));
  for (std::size_t c = 0; c < outputs_.size(); ++c) z.col(Eigen::Index(c)) = outputs_[c].loo;
  return y_scale_.inverse(z);
}

namespace {
nlohmann::json matrix_json(const MatrixXd &m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    std::vector<double> row(std::size_t(m.cols()));
    for (Eigen::Index c = 0; c < m.cols(); ++c) row[std::size_t(c)] = m(r, c);
    rows.push_back(row);
  }
  return rows;
}
MatrixXd matrix_from_json(const nlohmann::json &j, Eigen::Index cols, const char *what) {
  MatrixXd m(Eigen::Index(j.size()), cols);
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    const auto row = j.at(std::size_t(r)).get<std::vector<double>>();
    if (Eigen::Index(row.size()) != cols)
      throw std::invalid_argument(std::string("gp state: a row of ") + what + " has the wrong length");
    for (Eigen::Index c = 0; c < cols; ++c) m(r, c) = row[std::size_t(c)];
  }
  return m;
}
}  // namespace

nlohmann::json GpModel::to_json() const {
  nlohmann::json thetas = nlohmann::json::array();
  for (const auto &o : outputs_) thetas.push_back(std::vector<double>(o.theta.data(), o.theta.data() + o.theta.size()));
  nlohmann::json j = {{"kernel", name_of(config_.kernel)}, {"x_scale", x_scale_.to_json()},
                      {"y_scale", y_scale_.to_json()},     {"x", matrix_json(x_train_)},
                      {"y", matrix_json(y_train_)},        {"theta", thetas}};
  if (noise_var_.size()) j["noise_var"] = matrix_json(noise_var_);  // absent: none given
  if (!group_values_.empty())                                       // absent: one nugget
    j["noise_groups"] = {{"input", config_.noise_group_input}, {"values", group_values_}};
  return j;
}

GpModel GpModel::from_json(const nlohmann::json &j, GpConfig config) {
  config.kernel = kernel_from_name(j.at("kernel").get<std::string>());
  GpModel m(config);
  m.x_scale_ = Standardiser::from_json(j.at("x_scale"));
  m.y_scale_ = Standardiser::from_json(j.at("y_scale"));
  const Eigen::Index d = m.x_scale_.mean.size(), n_out = m.y_scale_.mean.size();
  m.x_train_ = matrix_from_json(j.at("x"), d, "x");
  m.y_train_ = matrix_from_json(j.at("y"), n_out, "y");
  if (m.x_train_.rows() != m.y_train_.rows() || m.x_train_.rows() < 1)
    throw std::invalid_argument("gp state: x and y differ in rows");
  m.xs_ = m.x_scale_.forward(m.x_train_);
  m.config_.noise_group_input = j.contains("noise_groups") ? j["noise_groups"].at("input").get<int>() : -1;
  m.set_noise_groups(j.contains("noise_groups") ? j["noise_groups"].at("values").get<std::vector<double>>()
                                                : std::vector<double>{});
  m.set_known_noise(j.contains("noise_var") ? matrix_from_json(j.at("noise_var"), n_out, "noise_var") : MatrixXd());
  if (m.noise_var_.size() && m.noise_var_.rows() != m.y_train_.rows())
    throw std::invalid_argument("gp state: noise_var and y differ in rows");
  const MatrixXd ys = m.y_scale_.forward(m.y_train_);
  const auto &thetas = j.at("theta");
  if (Eigen::Index(thetas.size()) != n_out) throw std::invalid_argument("gp state: one theta per output expected");
  m.outputs_.assign(std::size_t(n_out), {});
  for (Eigen::Index c = 0; c < n_out; ++c) {
    const auto t = thetas.at(std::size_t(c)).get<std::vector<double>>();
    if (Eigen::Index(t.size()) != d + 1 + m.noise_count())
      throw std::invalid_argument("gp state: theta has the wrong length");
    m.outputs_[std::size_t(c)].theta = Eigen::Map<const VectorXd>(t.data(), Eigen::Index(t.size()));
    m.prepare(m.outputs_[std::size_t(c)], ys.col(c), m.known_noise(std::size_t(c)));
  }
  return m;
}

nlohmann::json GpModel::info() const {
  nlohmann::json outs = nlohmann::json::array();
  const int d = int(xs_.cols());
  for (std::size_t c = 0; c < outputs_.size(); ++c) {
    const Output &o = outputs_[c];
    const double ys = y_scale_.scale[Eigen::Index(c)];
    std::vector<double> length(static_cast<std::size_t>(d));
    for (int k = 0; k < d; ++k) length[std::size_t(k)] = std::exp(o.theta[1 + k]) * x_scale_.scale[k];
    // With noise groups, noise_std is the last group's (the grouping input's largest value: the
    // expensive fidelity, which a map predicts); each group's is under noise_std_by_group.
    const int last = d + noise_count();
    nlohmann::json out = {
        {"signal_std", std::sqrt(std::exp(o.theta[0])) * ys},
        {"length_scales", length},
        {"noise_std", std::sqrt(std::exp(o.theta[last])) * ys},
        {"noise_at_lower_bound", o.theta.tail(noise_count()).minCoeff() <= std::log(config_.noise_min) + 1e-9},
        {"log_marginal_likelihood", o.lml},
        {"iterations", o.iterations}};
    for (std::size_t g = 0; g < group_values_.size(); ++g)
      out["noise_std_by_group"].push_back(
          {{"value", group_values_[g]}, {"noise_std", std::sqrt(std::exp(o.theta[d + 1 + Eigen::Index(g)])) * ys}});
    outs.push_back(out);
  }
  return {{"kernel", name_of(config_.kernel)},
          {"restarts", config_.restarts},
          {"noise_prior", {{"median_share", config_.noise_prior_median}, {"log_width", config_.noise_prior_width}}},
          {"noise_group_input",
           config_.noise_group_input < 0 ? nlohmann::json() : nlohmann::json(config_.noise_group_input + 1)},
          {"outputs", outs},
          {"loo_mean", fitted() ? matrix_json(loo_mean()) : nlohmann::json::array()}};
}

}  // namespace spreadmap::surrogate
