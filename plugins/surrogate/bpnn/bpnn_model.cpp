// Back-propagation network: forward pass, loss with its analytic gradient, and the three trainers.
#include "bpnn_model.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "../common/lbfgs.hpp"
#include "spreadmap/random.hpp"

namespace sm = spreadmap;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace spreadmap::surrogate {

Activation activation_from_name(const std::string &n) {
  if (n == "sigmoid") return Activation::sigmoid;
  if (n == "tanh") return Activation::tanh;
  if (n == "atan") return Activation::atan;
  throw std::invalid_argument("activation '" + n + "' is not one of sigmoid|tanh|atan");
}
Optimiser optimiser_from_name(const std::string &n) {
  if (n == "gd") return Optimiser::gd;
  if (n == "adam") return Optimiser::adam;
  if (n == "lbfgs") return Optimiser::lbfgs;
  throw std::invalid_argument("optimiser '" + n + "' is not one of gd|adam|lbfgs");
}
Regularisation regularisation_from_name(const std::string &n) {
  if (n == "ratio") return Regularisation::ratio;
  if (n == "sum") return Regularisation::sum;
  throw std::invalid_argument("regularisation '" + n + "' is not one of ratio|sum");
}
const char *name_of(Activation a) {
  return a == Activation::sigmoid ? "sigmoid" : a == Activation::tanh ? "tanh" : "atan";
}
const char *name_of(Optimiser o) { return o == Optimiser::gd ? "gd" : o == Optimiser::adam ? "adam" : "lbfgs"; }
const char *name_of(Regularisation r) { return r == Regularisation::ratio ? "ratio" : "sum"; }

nlohmann::json BpnnFitInfo::to_json() const {
  nlohmann::json j = {{"loss", loss}, {"mse", mse}, {"epochs", epochs}, {"stopped_early", stopped_early}};
  if (validation_mse >= 0) j["validation_mse"] = validation_mse;
  if (!fold_epochs.empty()) j["fold_epochs"] = fold_epochs;
  return j;
}

namespace {

MatrixXd activate(Activation a, const MatrixXd &z) {
  switch (a) {
    case Activation::sigmoid:
      return (1.0 + (-z.array()).exp()).inverse().matrix();
    case Activation::tanh:
      return z.array().tanh().matrix();
    case Activation::atan:
      return z.unaryExpr([](double v) { return std::atan(v); });
  }
  return z;
}
// Derivative from the pre-activation z and the activation value f(z).
MatrixXd derivative(Activation a, const MatrixXd &z, const MatrixXd &f) {
  switch (a) {
    case Activation::sigmoid:
      return (f.array() * (1.0 - f.array())).matrix();
    case Activation::tanh:
      return (1.0 - f.array().square()).matrix();
    case Activation::atan:
      return (1.0 + z.array().square()).inverse().matrix();
  }
  return z;
}

void check_data(const MatrixXd &x, const MatrixXd &y) {
  if (x.rows() != y.rows()) throw std::invalid_argument("bpnn: inputs and outputs differ in row count");
  if (x.rows() < 2) throw std::invalid_argument("bpnn: at least 2 training rows are needed");
  if (x.cols() < 1 || y.cols() < 1) throw std::invalid_argument("bpnn: need at least one input and one output");
  if (!x.allFinite() || !y.allFinite()) throw std::invalid_argument("bpnn: training data contain NaN or infinity");
}

MatrixXd rows_of(const MatrixXd &m, const std::vector<Eigen::Index> &idx) {
  MatrixXd out(Eigen::Index(idx.size()), m.cols());
  for (std::size_t i = 0; i < idx.size(); ++i) out.row(Eigen::Index(i)) = m.row(idx[i]);
  return out;
}

}  // namespace

long BpnnModel::weight_count() const {
  long n = 0;
  for (const auto &w : weights_) n += long(w.size());
  return n;
}

void BpnnModel::initialise(int n_in, int n_out) {
  if (config_.hidden_layers < 1 || config_.units < 1)
    throw std::invalid_argument("bpnn: need at least one hidden unit");
  Random rng(config_.seed);
  weights_.clear(), biases_.clear();
  int in = n_in;
  for (int l = 0; l <= config_.hidden_layers; ++l) {
    const int out = l == config_.hidden_layers ? n_out : config_.units;
    const double limit = std::sqrt(6.0 / double(in + out));  // Glorot-uniform
    MatrixXd w(out, in);
    for (Eigen::Index k = 0; k < w.size(); ++k) w.data()[k] = rng.uniform(-limit, limit);
    weights_.push_back(w);
    biases_.push_back(VectorXd::Zero(out));
    in = out;
  }
  if (x_scale_.mean.size() != n_in) {  // untrained: identity scaling so predict() is usable
    x_scale_ = {Eigen::RowVectorXd::Zero(n_in), Eigen::RowVectorXd::Ones(n_in)};
    y_scale_ = {Eigen::RowVectorXd::Zero(n_out), Eigen::RowVectorXd::Ones(n_out)};
  }
}

VectorXd BpnnModel::parameters() const {
  long n = 0;
  for (std::size_t l = 0; l < weights_.size(); ++l) n += long(weights_[l].size() + biases_[l].size());
  VectorXd p(n);
  long at = 0;
  for (std::size_t l = 0; l < weights_.size(); ++l) {
    p.segment(at, weights_[l].size()) = Eigen::Map<const VectorXd>(weights_[l].data(), weights_[l].size());
    at += long(weights_[l].size());
    p.segment(at, biases_[l].size()) = biases_[l];
    at += long(biases_[l].size());
  }
  return p;
}

void BpnnModel::set_parameters(const VectorXd &p) {
  long at = 0;
  for (std::size_t l = 0; l < weights_.size(); ++l) {
    Eigen::Map<VectorXd>(weights_[l].data(), weights_[l].size()) = p.segment(at, weights_[l].size());
    at += long(weights_[l].size());
    biases_[l] = p.segment(at, biases_[l].size());
    at += long(biases_[l].size());
  }
  if (at != p.size()) throw std::invalid_argument("bpnn: parameter vector has the wrong length");
}

double BpnnModel::loss(const VectorXd &p, const MatrixXd &xs, const MatrixXd &ys, VectorXd *grad,
                       double *mse_out) const {
  const std::size_t n_layers = weights_.size();
  // Views of p shaped like the layers.
  std::vector<Eigen::Map<const MatrixXd>> w;
  std::vector<Eigen::Map<const VectorXd>> b;
  long at = 0;
  for (std::size_t l = 0; l < n_layers; ++l) {
    w.emplace_back(p.data() + at, weights_[l].rows(), weights_[l].cols());
    at += long(weights_[l].size());
    b.emplace_back(p.data() + at, biases_[l].size());
    at += long(biases_[l].size());
  }
  // Forward, samples as columns, keeping pre-activations z and activations a.
  std::vector<MatrixXd> z(n_layers), a(n_layers + 1);
  a[0] = xs.transpose();
  for (std::size_t l = 0; l < n_layers; ++l) {
    z[l] = (w[l] * a[l]).colwise() + VectorXd(b[l]);
    a[l + 1] = l + 1 == n_layers ? z[l] : activate(config_.activation, z[l]);
  }
  const MatrixXd e = a[n_layers] - ys.transpose();
  const double n = double(xs.rows()), n_out = double(ys.cols());
  const double lambda = config_.lambda, n_w = double(weight_count());
  double sq_w = 0;
  for (const auto &wl : w) sq_w += wl.squaredNorm();
  const double mse = e.squaredNorm() / (n * n_out);
  if (mse_out) *mse_out = mse;
  // data = c * sum(e^2); reg = r * sum(W^2)
  const bool ratio = config_.regularisation == Regularisation::ratio;
  const double c = ratio ? (1.0 - lambda) / (n * n_out) : 1.0 / n;
  const double r = ratio ? lambda / n_w : lambda;
  const double value = c * e.squaredNorm() + r * sq_w;
  if (!grad) return value;

  grad->resize(p.size());
  MatrixXd dz = 2.0 * c * e;  // dL/dz of the (linear) output layer
  std::vector<long> offset(n_layers);
  at = 0;
  for (std::size_t l = 0; l < n_layers; ++l) offset[l] = at, at += long(w[l].size() + b[l].size());
  for (std::size_t l = n_layers; l-- > 0;) {
    MatrixXd dw = dz * a[l].transpose() + 2.0 * r * MatrixXd(w[l]);
    grad->segment(offset[l], dw.size()) = Eigen::Map<const VectorXd>(dw.data(), dw.size());
    grad->segment(offset[l] + long(dw.size()), b[l].size()) = dz.rowwise().sum();
    if (l > 0) dz = ((w[l].transpose() * dz).array() * derivative(config_.activation, z[l - 1], a[l]).array()).matrix();
  }
  return value;
}

MatrixXd BpnnModel::forward(const MatrixXd &xs) const {
  MatrixXd a = xs.transpose();
  for (std::size_t l = 0; l < weights_.size(); ++l) {
    MatrixXd z = (weights_[l] * a).colwise() + biases_[l];
    a = l + 1 == weights_.size() ? z : activate(config_.activation, z);
  }
  return a.transpose();
}

BpnnModel::Run BpnnModel::train(const MatrixXd &xs, const MatrixXd &ys, const MatrixXd &xv, const MatrixXd &yv,
                                long max_epochs) {
  initialise(int(xs.cols()), int(ys.cols()));
  Run run;
  run.p = parameters();
  VectorXd best_p = run.p;
  const bool validate = xv.rows() > 0;
  long since_best = 0;
  // Returns false when early stopping says to stop.
  auto watch = [&](const VectorXd &q, long epoch) {
    if (!validate) return true;
    double v = 0;
    loss(q, xv, yv, nullptr, &v);
    if (v < run.validation_mse) run.validation_mse = v, best_p = q, run.best_epoch = epoch, since_best = 0;
    else if (++since_best >= config_.patience) return false;
    return true;
  };

  if (config_.optimiser == Optimiser::lbfgs) {
    LbfgsOptions o;
    o.max_iterations = max_epochs;
    o.relative_tolerance = config_.tolerance;
    o.gradient_tolerance = 1e-12;
    const auto objective = [&](const VectorXd &q, VectorXd &gq) { return loss(q, xs, ys, &gq); };
    const LbfgsResult r = lbfgs_minimise(objective, run.p, o, [&](long epoch, const VectorXd &q, double) {
      const bool go_on = watch(q, epoch);
      run.stopped_early = !go_on;
      return go_on;
    });
    run.epochs = r.iterations;
  } else {
    VectorXd g(run.p.size()), m = VectorXd::Zero(run.p.size()), v = VectorXd::Zero(run.p.size());
    const double b1 = 0.9, b2 = 0.999;
    double b1t = 1, b2t = 1;
    VectorXd &p = run.p;
    for (run.epochs = 0; run.epochs < max_epochs;) {
      loss(p, xs, ys, &g);
      if (config_.optimiser == Optimiser::gd) {
        p -= config_.learning_rate * g;
      } else {
        m = b1 * m + (1 - b1) * g;
        v = b2 * v + (1 - b2) * g.cwiseAbs2();
        b1t *= b1, b2t *= b2;
        p.array() -= config_.learning_rate * (m.array() / (1 - b1t)) / ((v.array() / (1 - b2t)).sqrt() + 1e-8);
      }
      ++run.epochs;
      if (!p.allFinite()) throw std::runtime_error("bpnn: training diverged (non-finite weights); lower learning_rate");
      if (!watch(p, run.epochs)) {
        run.stopped_early = true;
        break;
      }
    }
  }
  if (validate) run.p = best_p;
  return run;
}

BpnnFitInfo BpnnModel::fit(const MatrixXd &x, const MatrixXd &y) {
  check_data(x, y);
  x_scale_ = Standardiser::fit(x);
  y_scale_ = Standardiser::fit(y);
  const MatrixXd xs_all = x_scale_.forward(x), ys_all = y_scale_.forward(y);

  // A seeded order of the rows for the validation share or the stopping folds.
  std::vector<Eigen::Index> order(std::size_t(x.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index(0));
  if (config_.validation_share > 0 || config_.stopping_folds > 0) {
    Random shuffle(config_.seed ^ 0x9e3779b97f4a7c15ULL);
    for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[shuffle.below(i)]);
  }
  info_ = {};
  if (config_.stopping_folds >= 2) {
    // Early stopping by cross-validation: each fold trains on the others and keeps the epoch of its
    // lowest validation error; the network is then trained on every row for the mean of those epochs.
    const auto k = std::size_t(config_.stopping_folds);
    if (k > order.size() || order.size() - (order.size() + k - 1) / k < 2)
      throw std::invalid_argument("bpnn: stopping_folds = " + std::to_string(k) + " with " +
                                  std::to_string(order.size()) + " rows leaves a fold fewer than 2 training rows");
    double epochs_sum = 0, validation_sum = 0;
    for (std::size_t f = 0; f < k; ++f) {
      std::vector<Eigen::Index> val, tr;
      for (std::size_t i = 0; i < order.size(); ++i) (i % k == f ? val : tr).push_back(order[i]);
      const Run r =
          train(rows_of(xs_all, tr), rows_of(ys_all, tr), rows_of(xs_all, val), rows_of(ys_all, val), config_.epochs);
      info_.fold_epochs.push_back(r.best_epoch);
      epochs_sum += double(r.best_epoch), validation_sum += r.validation_mse;
    }
    const Run all = train(xs_all, ys_all, MatrixXd(), MatrixXd(), std::max(1L, std::lround(epochs_sum / double(k))));
    set_parameters(all.p);
    info_.epochs = all.epochs, info_.stopped_early = true, info_.validation_mse = validation_sum / double(k);
    info_.loss = loss(all.p, xs_all, ys_all, nullptr, &info_.mse);
    return info_;
  }

  // Hold out a seeded validation share for early stopping.
  long n_val = 0;
  if (config_.validation_share > 0) {
    n_val = std::max(1L, std::lround(config_.validation_share * double(x.rows())));
    if (x.rows() - n_val < 2) throw std::invalid_argument("bpnn: validation_share leaves fewer than 2 training rows");
  }
  const std::vector<Eigen::Index> val(order.begin(), order.begin() + n_val), tr(order.begin() + n_val, order.end());
  const MatrixXd xs = rows_of(xs_all, tr), ys = rows_of(ys_all, tr);
  const Run r = train(xs, ys, rows_of(xs_all, val), rows_of(ys_all, val), config_.epochs);
  set_parameters(r.p);
  info_.epochs = r.epochs, info_.stopped_early = r.stopped_early;
  if (n_val > 0) info_.validation_mse = r.validation_mse;
  info_.loss = loss(r.p, xs, ys, nullptr, &info_.mse);
  return info_;
}

MatrixXd BpnnModel::predict(const MatrixXd &x) const {
  if (!fitted()) throw std::logic_error("bpnn: predict() before fit() or load()");
  if (x.cols() != weights_.front().cols())
    throw std::invalid_argument("bpnn: expected " + std::to_string(weights_.front().cols()) + " inputs, got " +
                                std::to_string(x.cols()));
  return y_scale_.inverse(forward(x_scale_.forward(x)));
}

nlohmann::json BpnnModel::to_json() const {
  nlohmann::json layers = nlohmann::json::array();
  for (std::size_t l = 0; l < weights_.size(); ++l) {
    const auto &w = weights_[l];
    layers.push_back({{"rows", w.rows()},
                      {"cols", w.cols()},
                      {"weights", std::vector<double>(w.data(), w.data() + w.size())},
                      {"biases", std::vector<double>(biases_[l].data(), biases_[l].data() + biases_[l].size())}});
  }
  return {{"activation", name_of(config_.activation)},
          {"layers", layers},
          {"x_scale", x_scale_.to_json()},
          {"y_scale", y_scale_.to_json()},
          {"fit", info_.to_json()}};
}

BpnnModel BpnnModel::from_json(const nlohmann::json &j, BpnnConfig config) {
  config.activation = activation_from_name(j.at("activation").get<std::string>());
  BpnnModel m(config);
  for (const auto &layer : j.at("layers")) {
    const auto rows = layer.at("rows").get<Eigen::Index>(), cols = layer.at("cols").get<Eigen::Index>();
    const auto w = layer.at("weights").get<std::vector<double>>(), b = layer.at("biases").get<std::vector<double>>();
    if (Eigen::Index(w.size()) != rows * cols || Eigen::Index(b.size()) != rows)
      throw std::invalid_argument("bpnn state: a layer's weights or biases have the wrong length");
    m.weights_.push_back(Eigen::Map<const MatrixXd>(w.data(), rows, cols));
    m.biases_.push_back(Eigen::Map<const VectorXd>(b.data(), rows));
  }
  if (m.weights_.empty()) throw std::invalid_argument("bpnn state: no layers");
  for (std::size_t l = 1; l < m.weights_.size(); ++l)
    if (m.weights_[l].cols() != m.weights_[l - 1].rows())
      throw std::invalid_argument("bpnn state: layer sizes do not chain");
  m.config_.hidden_layers = int(m.weights_.size()) - 1;
  m.config_.units = int(m.weights_.front().rows());
  m.x_scale_ = Standardiser::from_json(j.at("x_scale"));
  m.y_scale_ = Standardiser::from_json(j.at("y_scale"));
  if (m.x_scale_.mean.size() != m.weights_.front().cols() || m.y_scale_.mean.size() != m.weights_.back().rows())
    throw std::invalid_argument("bpnn state: scaling does not match the layer sizes");
  if (j.contains("fit")) {
    const auto &f = j.at("fit");
    m.info_.loss = f.value("loss", 0.0), m.info_.mse = f.value("mse", 0.0);
    m.info_.epochs = f.value("epochs", 0L), m.info_.stopped_early = f.value("stopped_early", false);
    m.info_.validation_mse = f.value("validation_mse", -1.0);
  }
  return m;
}

}  // namespace spreadmap::surrogate
