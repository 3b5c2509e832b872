#include "plugin_model.hpp"

#include <cstring>
#include <string>

#include "core/plugin_abi.hpp"
#include <stdexcept>
#include <nlohmann/json.hpp>

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

const sm_surrogate_ops_v1 *surrogate_ops(const sm_plugin_v1 *p) {
  if (!p) throw std::invalid_argument("no surrogate plugin given");
  if (const std::string refusal = abi_refusal(p->abi); !refusal.empty())
    throw std::runtime_error(std::string("surrogate/") + p->name + " " + refusal);
  if (std::strcmp(p->kind, "surrogate") != 0)
    throw std::invalid_argument(std::string(p->kind) + "/" + p->name + " is not a surrogate plugin");
  if (!p->ops) throw std::runtime_error(std::string("surrogate/") + p->name + " has no ops table");
  return static_cast<const sm_surrogate_ops_v1 *>(p->ops);
}
}  // namespace

PluginModel::PluginModel(const sm_plugin_v1 *plugin, void *instance)
    : plugin_(plugin), ops_(surrogate_ops(plugin)), instance_(instance) {
  if (!instance) throw std::invalid_argument(label() + ": no instance given");
}

std::unique_ptr<PluginModel> PluginModel::create(const sm_plugin_v1 *plugin, const std::string &params_json) {
  surrogate_ops(plugin);
  sm_error err{};
  void *instance = plugin->create(params_json.c_str(), &err);
  if (!instance) throw std::runtime_error(std::string("surrogate/") + plugin->name + ": " + err.text);
  auto m = std::make_unique<PluginModel>(plugin, instance);
  m->owned_ = true;
  return m;
}

PluginModel::~PluginModel() {
  if (owned_) plugin_->destroy(instance_);
}

std::string PluginModel::label() const { return std::string("surrogate/") + plugin_->name; }

void PluginModel::fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y) { fit_with_noise(x, y, {}); }

void PluginModel::fit_with_noise(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise_var) {
  const RowMajor xr = x, yr = y, vr = noise_var;
  if (x.rows() != y.rows()) throw std::invalid_argument(label() + ": inputs and outputs differ in row count");
  if (noise_var.size() && (noise_var.rows() != y.rows() || noise_var.cols() != y.cols()))
    throw std::invalid_argument(label() + ": the noise variances are not one per output value");
  const sm_dataset_v1 d{uint32_t(x.rows()), uint32_t(x.cols()), uint32_t(y.cols()),
                        xr.data(),          yr.data(),          noise_var.size() ? vr.data() : nullptr};
  sm_error err{};
  if (ops_->fit(instance_, &d, &err) != 0) throw std::runtime_error(label() + ": fit failed: " + err.text);
  n_out_ = y.cols();
}

Prediction PluginModel::predict(const Eigen::MatrixXd &x) const {
  if (n_out_ == 0) throw std::logic_error(label() + ": predict() before fit() or load()");
  const RowMajor xr = x;
  RowMajor mean(x.rows(), n_out_), sd;
  if (has_std()) sd.resize(x.rows(), n_out_);
  sm_error err{};
  if (ops_->predict(instance_, uint32_t(x.rows()), xr.data(), mean.data(), has_std() ? sd.data() : nullptr, &err) != 0)
    throw std::runtime_error(label() + ": predict failed: " + err.text);
  return {mean, sd};
}

nlohmann::json PluginModel::state() const {
  const char *text = ops_->save(instance_);
  if (!text || !*text) throw std::runtime_error(label() + ": nothing to save (the model is not fitted)");
  return nlohmann::json::parse(text);
}

void PluginModel::load(const nlohmann::json &state) {
  if (!state.contains("y_scale") || !state["y_scale"].contains("mean"))
    throw std::runtime_error(label() + ": the saved state does not say its output count; use load(state, n_outputs)");
  load(state, Eigen::Index(state["y_scale"]["mean"].size()));
}

void PluginModel::load(const nlohmann::json &state, Eigen::Index n_outputs) {
  sm_error err{};
  if (ops_->load(instance_, state.dump().c_str(), &err) != 0)
    throw std::runtime_error(label() + ": cannot load the saved state: " + err.text);
  n_out_ = n_outputs;
}

nlohmann::json PluginModel::fit_info() const {
  const char *text = ops_->fit_info(instance_);
  return text && *text ? nlohmann::json::parse(text) : nlohmann::json::object();
}

}  // namespace spreadmap::analysis
