// One network per output, or one for all: fitting, prediction and state of the set.
#include "bpnn_networks.hpp"

#include <stdexcept>

using Eigen::MatrixXd;

namespace spreadmap::surrogate {

void BpnnNetworks::fit(const MatrixXd &x, const MatrixXd &y) {
  std::vector<BpnnModel> nets;
  if (!per_output_) {
    nets.emplace_back(config_).fit(x, y);
  } else {
    for (Eigen::Index j = 0; j < y.cols(); ++j) nets.emplace_back(config_).fit(x, y.col(j));
  }
  nets_ = std::move(nets);
}

MatrixXd BpnnNetworks::predict(const MatrixXd &x) const {
  if (!fitted()) throw std::logic_error("bpnn: predict() before fit() or load()");
  if (nets_.size() == 1) return nets_.front().predict(x);
  MatrixXd out(x.rows(), Eigen::Index(nets_.size()));
  for (std::size_t j = 0; j < nets_.size(); ++j) out.col(Eigen::Index(j)) = nets_[j].predict(x);
  return out;
}

nlohmann::json BpnnNetworks::to_json() const {
  if (!fitted()) throw std::logic_error("bpnn: not fitted");
  if (!per_output_) return nets_.front().to_json();
  nlohmann::json all = nlohmann::json::array();
  for (const auto &n : nets_) all.push_back(n.to_json());
  return {{"networks", all}};
}

BpnnNetworks BpnnNetworks::from_json(const nlohmann::json &j, BpnnConfig config) {
  const bool per_output = j.contains("networks");
  BpnnNetworks set(config, per_output);
  if (!per_output) {
    set.nets_.push_back(BpnnModel::from_json(j, config));
    return set;
  }
  for (const auto &n : j.at("networks")) {
    set.nets_.push_back(BpnnModel::from_json(n, config));
    if (set.nets_.back().predict(MatrixXd::Zero(1, set.n_inputs())).cols() != 1)
      throw std::invalid_argument("bpnn state: a per-output network has more than one output");
    if (set.nets_.back().n_inputs() != set.n_inputs())
      throw std::invalid_argument("bpnn state: the per-output networks differ in their inputs");
  }
  if (set.nets_.empty()) throw std::invalid_argument("bpnn state: 'networks' is empty");
  set.config_ = set.nets_.front().config();
  return set;
}

nlohmann::json BpnnNetworks::fit_info() const {
  if (!per_output_ || nets_.size() <= 1)
    return nets_.empty() ? nlohmann::json::object() : nets_.front().fit_info().to_json();
  nlohmann::json all = nlohmann::json::array();
  for (const auto &n : nets_) all.push_back(n.fit_info().to_json());
  return {{"per_output", all}};
}

}  // namespace spreadmap::surrogate
