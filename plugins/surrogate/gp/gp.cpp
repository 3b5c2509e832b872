// surrogate/gp: Gaussian-process regression as a plugin (mean and standard deviation per output).
// The math lives in gp_model.{hpp,cpp}; this file declares the parameter schema and the class the SDK wraps.
// fit_info() reports per output the fitted length scales (input units), signal and noise standard
// deviations (output units: the host's train report shows them), the log marginal likelihood, and
// `loo_mean`: closed-form leave-one-out predictions at the training rows (rows x outputs, output
// units) for cross-validated errors. The noise is learnt, with a weak log-normal prior (gp_model.hpp),
// one level for all rows or one per value of an input (noise_by_input).
#include <spreadmap/surrogate_plugin.hpp>

#include "gp_model.hpp"

namespace sm = spreadmap;
namespace ss = spreadmap::surrogate;

namespace {

struct Gp {
  static constexpr sm_param_v1 params[] = {
      sm::enumeration("kernel", "squared_exponential|matern52", "squared_exponential",
                      "covariance k: squared exponential or Matern 5/2, one length scale per input (ARD)"),
      sm::integer("restarts", 1, 100, 5, "starts of the likelihood maximisation (the best wins)"),
      sm::integer("seed", 0, 4294967295.0, 1, "seed of the random starts"),
      sm::number("noise_min", "-", 1e-14, 1, 1e-12,
                 "lower bound of the noise variance n^2 as a share of each output's variance"),
      sm::number("noise_max", "-", 1e-14, 10, 1, "upper bound of the noise variance, same scale"),
      sm::integer("max_iterations", 1, 100000, 300, "L-BFGS iterations per start"),
      sm::number("noise_prior_median", "-", 1e-12, 1, 1e-2,
                 "median of the log-normal prior on the noise variance n^2, as a share of each output's variance"),
      sm::number("noise_prior_width", "-", 0, 20, 3,
                 "standard deviation of log n^2 under that prior (0 = no prior: the plain marginal likelihood)"),
      sm::integer("noise_by_input", 0, 64, 0,
                  "0: one noise level for all rows; k: one per value of input k (1-based, at most 8 values), "
                  "e.g. a multi-fidelity design's fidelity, whose cheap runs scatter more"),
  };
  static constexpr int has_std = 1;

  ss::GpModel model;
  std::string saved_text, info_text;

  static Gp bind(const sm::Values &v) {
    ss::GpConfig c;
    c.kernel = ss::kernel_from_name(v.str("kernel"));
    c.restarts = int(v.integer("restarts"));
    c.seed = std::uint64_t(v.integer("seed"));
    c.noise_min = v["noise_min"];
    c.noise_max = v["noise_max"];
    c.max_iterations = v.integer("max_iterations");
    c.noise_prior_median = v["noise_prior_median"];
    c.noise_prior_width = v["noise_prior_width"];
    c.noise_group_input = int(v.integer("noise_by_input")) - 1;
    if (c.noise_min > c.noise_max)
      throw sm::ParamError("noise_min = " + std::to_string(c.noise_min) + " is above noise_max = " +
                           std::to_string(c.noise_max) + "; lower noise_min or raise noise_max");
    return Gp{ss::GpModel(c), {}, {}};
  }

  // noise_var: the dataset's known variances (the replicate scatter of each mean), added to the nugget
  void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y, const Eigen::MatrixXd &noise_var) {
    model.fit(x, y, noise_var);
  }
  int n_inputs() const {
    if (!model.fitted()) throw std::logic_error("surrogate/gp: predict() before fit() or load()");
    return model.n_inputs();
  }
  Eigen::MatrixXd predict(const Eigen::MatrixXd &x, Eigen::MatrixXd *std) const { return model.predict(x, std); }
  nlohmann::json state() const {
    if (!model.fitted()) throw std::logic_error("not fitted");
    return model.to_json();
  }
  void load(const nlohmann::json &j) { model = ss::GpModel::from_json(j, model.config()); }
  nlohmann::json info() const { return model.info(); }
};

}  // namespace

SPREADMAP_SURROGATE_PLUGIN(Gp, "gp", "1.0.0",
                           "Gaussian-process regression (ARD squared-exponential or Matern 5/2), mean and std")
