// Model over a surrogate plugin's C table. The plugin must be of kind "surrogate" and of this SDK's
// ABI. Errors from the plugin become std::runtime_error prefixed with "surrogate/<name>".
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/surrogate.hpp>

#include <memory>
#include <string>

#include "model.hpp"

namespace spreadmap::analysis {

class PluginModel : public Model {
 public:
  // Borrows an instance made by plugin->create(); the caller keeps ownership.
  PluginModel(const sm_plugin_v1 *plugin, void *instance);
  // Makes and owns an instance from validated SI parameters (a JSON object text).
  static std::unique_ptr<PluginModel> create(const sm_plugin_v1 *plugin, const std::string &params_json);
  ~PluginModel() override;
  PluginModel(const PluginModel &) = delete;
  PluginModel &operator=(const PluginModel &) = delete;

  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y) override;
  // noise_var reaches the plugin as sm_dataset_v1::noise_var (NULL when empty).
  void fit_with_noise(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise_var) override;
  Prediction predict(const Eigen::MatrixXd &x) const override;
  bool has_std() const override { return ops_->has_std != 0; }
  bool takes_noise() const override { return ops_->takes_noise_var != 0; }
  nlohmann::json state() const override;
  // The C table does not say how many outputs a model has: load() reads it from the state's
  // "y_scale" (both shipped plugins keep one); other plugins need the count given.
  void load(const nlohmann::json &state) override;
  void load(const nlohmann::json &state, Eigen::Index n_outputs);
  nlohmann::json fit_info() const override;

  std::string label() const;  // "surrogate/<name>"
  const sm_plugin_v1 *plugin() const { return plugin_; }

 private:
  const sm_plugin_v1 *plugin_;
  const sm_surrogate_ops_v1 *ops_;
  void *instance_;
  bool owned_ = false;
  Eigen::Index n_out_ = 0;  // outputs of the last fit or load
};

}  // namespace spreadmap::analysis
