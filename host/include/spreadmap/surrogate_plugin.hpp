// A surrogate plugin's C++ side: SurrogateGlue builds the sm_surrogate_ops_v1 table from the plugin's
// class, so each plugin writes only its model; SPREADMAP_SURROGATE_PLUGIN ends its file. The class provides:
//   void fit(const Eigen::MatrixXd &x, const Eigen::MatrixXd &y);
//     or, to take the dataset's known noise: fit(x, y, noise_var) (noise_var empty when none is given)
//   Eigen::MatrixXd predict(const Eigen::MatrixXd &x, Eigen::MatrixXd *std) const;  // std may be null
//   nlohmann::json state() const;  void load(const nlohmann::json &);  nlohmann::json info() const;
//   int n_inputs() const;  static constexpr int has_std;
//   std::string saved_text, info_text;   // the buffers save() and fit_info() hand out
// Exceptions never cross the C boundary: they become sm_error text. The returned strings live in
// the instance until the next save()/fit_info() call on it (not thread-safe per instance).
#pragma once
#include <spreadmap/plugin.hpp>
#include <spreadmap/surrogate.hpp>

#include <Eigen/Dense>
#include <exception>
#include <nlohmann/json.hpp>
#include <string>

namespace spreadmap {
namespace detail {
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

}  // namespace detail

template <class Self> struct SurrogateGlue {
  using RowMajor = detail::RowMajor;
  static int fail(sm_error *err, const std::exception &e) {
    detail::set_error(err, e.what());
    return 1;
  }
  static int fit(void *self, const sm_dataset_v1 *d, sm_error *err) {
    try {
      if (!d || !d->x || !d->y) throw std::invalid_argument("fit: no data");
      const Eigen::MatrixXd x = Eigen::Map<const RowMajor>(d->x, d->rows, d->n_in);
      const Eigen::MatrixXd y = Eigen::Map<const RowMajor>(d->y, d->rows, d->n_out);
      Self &model = *static_cast<Self *>(self);
      if constexpr (takes_noise_var) {
        Eigen::MatrixXd noise;
        if (d->noise_var) noise = Eigen::Map<const RowMajor>(d->noise_var, d->rows, d->n_out);
        model.fit(x, y, noise);
      } else {
        model.fit(x, y);
      }
      return 0;
    } catch (const std::exception &e) {
      return fail(err, e);
    }
  }
  static int predict(const void *self, uint32_t rows, const double *x, double *mean, double *std, sm_error *err) {
    try {
      const Self &m = *static_cast<const Self *>(self);
      const Eigen::MatrixXd xm = Eigen::Map<const RowMajor>(x, rows, m.n_inputs());
      Eigen::MatrixXd s;
      const Eigen::MatrixXd mu = m.predict(xm, std ? &s : nullptr);
      Eigen::Map<RowMajor>(mean, rows, mu.cols()) = mu;
      if (std) Eigen::Map<RowMajor>(std, rows, mu.cols()) = s;
      return 0;
    } catch (const std::exception &e) {
      return fail(err, e);
    }
  }
  static const char *save(void *self) {
    auto *s = static_cast<Self *>(self);
    try {
      s->saved_text = s->state().dump();
    } catch (const std::exception &e) {
      s->saved_text.clear();  // documented: empty text = nothing to save (not fitted)
    }
    return s->saved_text.c_str();
  }
  static int load(void *self, const char *state_json, sm_error *err) {
    try {
      static_cast<Self *>(self)->load(nlohmann::json::parse(state_json));
      return 0;
    } catch (const std::exception &e) {
      return fail(err, e);
    }
  }
  static const char *fit_info(void *self) {
    auto *s = static_cast<Self *>(self);
    s->info_text = s->info().dump();
    return s->info_text.c_str();
  }
  static constexpr int takes_noise_var = requires(Self & m, const Eigen::MatrixXd &a) { m.fit(a, a, a); }
  ? 1 : 0;
  static constexpr sm_surrogate_ops_v1 table{Self::has_std, &fit, &predict, &save, &load, &fit_info, takes_noise_var};
};

}  // namespace spreadmap

// The last line of a surrogate plugin: SPREADMAP_SURROGATE_PLUGIN(Class, "name", "1.0.0", "summary").
#define SPREADMAP_SURROGATE_PLUGIN(CLASS, NAME, VERSION, SUMMARY) \
  SPREADMAP_PLUGIN("surrogate", CLASS, NAME, VERSION, SUMMARY, &::spreadmap::SurrogateGlue<CLASS>::table)
