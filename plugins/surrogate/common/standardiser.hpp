// Column-wise standardisation z = (v - mean) / scale, kept in a model's state so that predictions
// are made in the units the model was fitted in. A constant column gets scale 1 (no division by 0).
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace spreadmap::surrogate {

struct Standardiser {
  Eigen::RowVectorXd mean, scale;

  static Standardiser fit(const Eigen::MatrixXd &v) {
    Standardiser s;
    s.mean = v.colwise().mean();
    s.scale.resize(v.cols());
    for (Eigen::Index j = 0; j < v.cols(); ++j) {
      const double var = (v.col(j).array() - s.mean[j]).square().sum() / std::max<double>(1.0, double(v.rows()));
      s.scale[j] = var > 0 ? std::sqrt(var) : 1.0;
    }
    return s;
  }
  Eigen::MatrixXd forward(const Eigen::MatrixXd &v) const {
    return (v.rowwise() - mean).array().rowwise() / scale.array();
  }
  Eigen::MatrixXd inverse(const Eigen::MatrixXd &z) const {
    return (z.array().rowwise() * scale.array()).rowwise() + mean.array();
  }
  nlohmann::json to_json() const {
    return {{"mean", std::vector<double>(mean.data(), mean.data() + mean.size())},
            {"scale", std::vector<double>(scale.data(), scale.data() + scale.size())}};
  }
  static Standardiser from_json(const nlohmann::json &j) {
    Standardiser s;
    const auto m = j.at("mean").get<std::vector<double>>(), c = j.at("scale").get<std::vector<double>>();
    if (m.size() != c.size()) throw std::runtime_error("standardiser: mean and scale differ in length");
    s.mean = Eigen::Map<const Eigen::RowVectorXd>(m.data(), Eigen::Index(m.size()));
    s.scale = Eigen::Map<const Eigen::RowVectorXd>(c.data(), Eigen::Index(c.size()));
    return s;
  }
};

}  // namespace spreadmap::surrogate
