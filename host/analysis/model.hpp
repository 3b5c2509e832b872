// The surrogate as the analysis sees it: fit, predict (mean and optional std), state and facts.
// PluginModel adapts a loaded surrogate plugin (sm_plugin_v1 + instance); tests may wrap anything.
#pragma once
#include <Eigen/Dense>
#include <nlohmann/json_fwd.hpp>

namespace spreadmap::analysis {

struct Prediction {
  Eigen::MatrixXd mean;  // rows x outputs
  Eigen::MatrixXd std;   // rows x outputs, or empty when the model gives none
};

// Not thread-safe: one caller at a time per instance.
struct Model {
  virtual ~Model() = default;
  virtual void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y) = 0;  // rows = samples
  // The same with the variance of each y known beforehand (rows x outputs, 0 where unknown; e.g. the
  // scatter of replicated runs over their count). A model that cannot use it fits without it.
  virtual void fit_with_noise(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise_var) {
    (void)noise_var;
    fit(x, y);
  }
  virtual bool takes_noise() const { return false; }  // whether fit_with_noise uses noise_var
  virtual Prediction predict(const Eigen::MatrixXd &x) const = 0;
  virtual bool has_std() const = 0;
  virtual nlohmann::json state() const = 0;  // what save() writes: enough to predict again
  virtual void load(const nlohmann::json &state) = 0;
  virtual nlohmann::json fit_info() const = 0;  // facts of the last fit
};

}  // namespace spreadmap::analysis
