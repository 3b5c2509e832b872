// The surrogate plugins end to end, loaded from their .so files like the host does: the study's
// 45-point fit (35/10 split) and its Table-4 scores, model files that predict bit for bit again,
// and the adaptive designs (one fidelity, and cheap beside expensive) against the full-factorial map.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "host/analysis/adaptive.hpp"
#include "host/analysis/grid.hpp"
#include "host/analysis/model_file.hpp"
#include "host/analysis/multifidelity.hpp"
#include "host/analysis/plugin_model.hpp"
#include "host/analysis/report.hpp"
#include "host/analysis/scores.hpp"
#include "tests/unit/surrogate_study_function.hpp"

namespace sm = spreadmap;
namespace sa = spreadmap::analysis;

namespace {

const sm_plugin_v1 *plugin(const std::string &name) {
  const std::string path = std::string(SPREADMAP_BINARY_DIR) + "/lib/spreadmap/plugins/surrogate/" + name + ".so";
  void *lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept open until exit, like the registry
  if (!lib) throw std::runtime_error("cannot open " + path + ": " + dlerror());
  auto entry = reinterpret_cast<sm_plugin_entry_v1>(dlsym(lib, "spreadmap_plugin_v1"));
  if (!entry) throw std::runtime_error(path + " has no spreadmap_plugin_v1");
  return entry();
}

// The schema's defaults as the host would pass them (validated SI values).
std::string default_params(const sm_plugin_v1 *p, const nlohmann::json &overrides = nlohmann::json::object()) {
  nlohmann::json j = nlohmann::json::object();
  for (uint32_t i = 0; i < p->n_params; ++i) {
    const auto &s = p->params[i];
    if (s.type == SM_ENUM || s.type == SM_STRING) j[s.name] = s.def_text;
    else if (s.type == SM_INTEGER) j[s.name] = long(s.def);
    else if (s.type == SM_BOOLEAN) j[s.name] = s.def != 0;
    else j[s.name] = s.def;
  }
  j.update(overrides);
  return j.dump();
}

struct Study {
  Eigen::MatrixXd x = sm::test::study_grid(), y = sm::test::study_outputs(x);
  sa::Split split = sa::study_split(45, 1);
};

sa::Report fit_and_score(const std::string &name, const Study &s) {
  auto m = sa::PluginModel::create(plugin(name), default_params(plugin(name)));
  Eigen::MatrixXd xt(s.split.train.size(), 2), yt(s.split.train.size(), 2);
  for (std::size_t i = 0; i < s.split.train.size(); ++i)
    xt.row(Eigen::Index(i)) = s.x.row(Eigen::Index(s.split.train[i])),
    yt.row(Eigen::Index(i)) = s.y.row(Eigen::Index(s.split.train[i]));
  m->fit(xt, yt);
  return sa::make_report(*m, s.x, s.y, s.split, {"vs", "rq"});
}

}  // namespace

TEST(SurrogateStudy, BpnnWithDefaultsMeetsTheStudysAccuracy) {
  const Study s;
  ASSERT_EQ(s.split.train.size(), 35u);
  const sa::Report r = fit_and_score("bpnn", s);
  for (const auto &o : r.outputs) {
    std::printf("bpnn %s: nrmse train %.3f %% test %.3f %%, R train %.5f test %.5f\n", o.name.c_str(), o.nrmse_train,
                o.nrmse_test, o.r_train, o.r_test);
    EXPECT_LE(o.nrmse_test, 2.5) << o.name;  // the study: 2.21 % (V_s), 2.27 % (R_q)
    EXPECT_GE(o.r_test, 0.98) << o.name;
  }
}

TEST(SurrogateStudy, GpWithDefaultsIsWithinOnePercent) {
  const Study s;
  const sa::Report r = fit_and_score("gp", s);
  for (const auto &o : r.outputs) {
    std::printf("gp %s: nrmse train %.5f %% test %.5f %%, R test %.7f\n", o.name.c_str(), o.nrmse_train, o.nrmse_test,
                o.r_test);
    EXPECT_LE(o.nrmse_test, 1.0) << o.name;
  }
}

TEST(SurrogateStudy, SavedModelLoadedAgainPredictsBitwise) {
  const Study s;
  const auto path = (std::filesystem::temp_directory_path() / "surrogate_study_model.json").string();
  for (const std::string name : {"bpnn", "gp"}) {
    const sm_plugin_v1 *p = plugin(name);
    const nlohmann::json params = nlohmann::json::parse(default_params(p, {{"epochs", 300}, {"restarts", 2}}));
    nlohmann::json used = nlohmann::json::object();
    for (uint32_t i = 0; i < p->n_params; ++i) used[p->params[i].name] = params[p->params[i].name];
    auto m = sa::PluginModel::create(p, used.dump());
    m->fit(s.x, s.y);
    sa::ModelFile f;
    f.plugin = "surrogate/" + name, f.plugin_version = p->version, f.params = used, f.state = m->state();
    f.inputs = {{"U", "m/s", 0.04, 0.1}, {"omega", "rad/s", -20, 20}};
    f.outputs = {{"vs", "m^2/s", s.y.col(0).minCoeff(), s.y.col(0).maxCoeff()},
                 {"rq", "m", s.y.col(1).minCoeff(), s.y.col(1).maxCoeff()}};
    f.training = {{"rows", 45}};
    sa::save_model_json(path, f);

    const sa::ModelFile g = sa::load_model_json(path);
    EXPECT_EQ(g.plugin_name(), name);
    EXPECT_EQ(g.inputs[1].unit, "rad/s");
    auto again = sa::PluginModel::create(plugin(g.plugin_name()), g.params.dump());
    again->load(g.state, Eigen::Index(g.outputs.size()));
    const Eigen::MatrixXd q = sa::grid_points({{"U", 0.04, 0.1, 31}, {"omega", -20, 20, 29}});
    const sa::Prediction a = m->predict(q), b = again->predict(q);
    EXPECT_TRUE((a.mean.array() == b.mean.array()).all()) << name;
    EXPECT_TRUE((a.std.array() == b.std.array()).all()) << name;
  }
  std::filesystem::remove(path);
  EXPECT_THROW(sa::load_model_json(path), std::runtime_error);
}

namespace {
// A response that varies faster along U than the factorial's 5 levels resolve (a full period of
// V_s's ripple in 40 mm/s, of R_q's in 45 mm/s), smooth and nearly linear along omega: the case
// where a fixed 5 x 9 grid spends its cases on the wrong axis.
double ripple_vs(double u, double w) {
  return u * 260e-6 * (1 + 0.1 * std::sin(2 * M_PI * (u - 0.04) / 0.04)) * (1 + 0.05 * std::tanh((w + 2) / 15));
}
double ripple_rq(double u, double w) {
  return 100e-6 * (1 + 0.1 * std::cos(2 * M_PI * (u - 0.04) / 0.045) + 0.03 * (w + 3) / 20);
}
Eigen::MatrixXd ripple(const Eigen::MatrixXd &x) {
  Eigen::MatrixXd y(x.rows(), 2);
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    y(r, 0) = ripple_vs(x(r, 0), x(r, 1)), y(r, 1) = ripple_rq(x(r, 0), x(r, 1));
  return y;
}
}  // namespace

TEST(SurrogateStudy, AdaptiveDesignMatchesTheFullFactorialWithHalfTheCases) {
  const sm_plugin_v1 *gp = plugin("gp");
  const auto make = [&] { return std::unique_ptr<sa::Model>(sa::PluginModel::create(gp, default_params(gp))); };
  const Eigen::MatrixXd dense = sa::grid_points({{"U", 0.04, 0.1, 41}, {"omega", -20, 20, 41}}), truth = ripple(dense);
  const auto dense_error = [&](const sa::Model &m) {
    const Eigen::MatrixXd p = m.predict(dense).mean;
    return std::max(sa::nrmse_percent(truth.col(0), p.col(0)), sa::nrmse_percent(truth.col(1), p.col(1)));
  };
  const Eigen::MatrixXd xf = sm::test::study_grid();  // the study's 5 x 9 = 45 cases
  auto factorial = make();
  factorial->fit(xf, ripple(xf));
  const double e_full = dense_error(*factorial);

  std::size_t evaluations = 0;
  const auto evaluate = [&](const Eigen::VectorXd &v) {
    ++evaluations;
    return Eigen::Vector2d(ripple_vs(v[0], v[1]), ripple_rq(v[0], v[1])).eval();
  };
  sa::AdaptiveOptions o;
  o.budget = 22;                                                    // at most half of 45
  o.target_loo_nrmse = 1.0;                                         // [%], held for 3 consecutive fits (the default)
  const Eigen::MatrixXd candidates = sm::test::study_grid(13, 17);  // U step 5 mm/s, omega step 2.5 rad/s
  const sa::AdaptiveResult r = sa::adaptive_design(candidates, make, evaluate, o);
  auto adaptive = make();
  adaptive->fit(r.x, r.y);
  const double e_adaptive = dense_error(*adaptive);
  std::printf("full factorial (45 cases): dense NRMSE %.3f %%; adaptive (%zu cases, stop: %s): %.3f %%\n", e_full,
              evaluations, r.stop_reason.c_str(), e_adaptive);
  EXPECT_EQ(evaluations, r.chosen.size());
  EXPECT_LE(evaluations, 22u);
  EXPECT_LE(e_adaptive, e_full);
  EXPECT_EQ(r.history.back().cases, evaluations);
  if (r.reached_target) {
    for (double e : r.history.back().loo_nrmse) EXPECT_LE(e, o.target_loo_nrmse);
  }
}

TEST(SurrogateStudy, CornersAndCentreOfTheStudysGridStartTheExpensiveCases) {
  const Eigen::MatrixXd x = sm::test::study_grid();
  std::vector<Eigen::RowVector2d> got;
  for (auto i : sa::corners_and_centre(x, sa::space_filling_start(x))) got.push_back(x.row(Eigen::Index(i)));
  const std::vector<Eigen::RowVector2d> want = {{0.04, -20}, {0.1, -20}, {0.07, 0}, {0.04, 20}, {0.1, 20}};
  ASSERT_EQ(got.size(), want.size());
  for (const auto &w : want)
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](const auto &g) { return (g - w).norm() < 1e-12; })) << w;
}

// A cheap fidelity that is the expensive one with a bias smooth in both inputs (V_s 2-4 % high, rising
// with U; R_q 3 % low, tilted with omega), like a narrow strip against the full width: with at most 15
// expensive cases the model over both fidelities predicts the expensive surface as well as the GP
// fitted to the 45 expensive cases of the full factorial, and better than the same number of
// expensive cases chosen alone.
TEST(SurrogateStudy, MultiFidelityMatchesTheFullFactorialWithFifteenExpensiveCases) {
  const sm_plugin_v1 *gp = plugin("gp");
  const auto make = [&] { return std::unique_ptr<sa::Model>(sa::PluginModel::create(gp, default_params(gp))); };
  const Eigen::MatrixXd dense = sa::grid_points({{"U", 0.04, 0.1, 41}, {"omega", -20, 20, 41}}), truth = ripple(dense);
  Eigen::MatrixXd dense_expensive(dense.rows(), 3);
  dense_expensive << dense, Eigen::VectorXd::Ones(dense.rows());
  const auto dense_error = [&](const sa::Model &m, const Eigen::MatrixXd &at) {
    const Eigen::MatrixXd p = m.predict(at).mean;
    return std::max(sa::nrmse_percent(truth.col(0), p.col(0)), sa::nrmse_percent(truth.col(1), p.col(1)));
  };
  const Eigen::MatrixXd xf = sm::test::study_grid();
  auto factorial = make();
  factorial->fit(xf, ripple(xf));
  const double e_full = dense_error(*factorial, dense);

  std::size_t cheap = 0, expensive = 0;
  const auto evaluate = [&](const Eigen::VectorXd &v, bool exp) {
    const double u = v[0], w = v[1];
    ++(exp ? expensive : cheap);
    if (exp) return Eigen::Vector2d(ripple_vs(u, w), ripple_rq(u, w)).eval();
    return Eigen::Vector2d(ripple_vs(u, w) * (1.03 + 0.01 * (u - 0.07) / 0.03), ripple_rq(u, w) * 0.97 + 2e-6 * w / 20)
        .eval();
  };
  sa::MultiFidelityOptions o;
  o.budget_cheap = 45, o.budget_expensive = 15, o.target_loo_nrmse = 1.0;
  const sa::MultiFidelityResult r =
      sa::multi_fidelity_design(sm::test::study_grid(13, 17), make, evaluate, o);  // U step 5 mm/s, omega 2.5 rad/s
  auto both = make();
  both->fit(r.x, r.y);
  const double e_both = dense_error(*both, dense_expensive);
  EXPECT_EQ(cheap, r.cheap);
  EXPECT_EQ(expensive, r.expensive);
  EXPECT_LE(expensive, 15u);
  EXPECT_LE(cheap, 45u);
  // The same expensive budget alone, on the same candidates.
  sa::AdaptiveOptions alone;
  alone.budget = r.expensive, alone.target_loo_nrmse = o.target_loo_nrmse;
  const auto expensive_only = [&](const Eigen::VectorXd &v) { return evaluate(v, true); };
  const sa::AdaptiveResult a = sa::adaptive_design(sm::test::study_grid(13, 17), make, expensive_only, alone);
  auto single = make();
  single->fit(a.x, a.y);
  const double e_single = dense_error(*single, dense);
  std::printf(
      "full factorial (45 expensive): dense NRMSE %.3f %%; multi-fidelity (%zu cheap, %zu expensive, stop: %s): "
      "%.3f %%; the same %zu expensive alone (stop: %s): %.3f %%\n",
      e_full, r.cheap, r.expensive, r.stop_reason.c_str(), e_both, a.chosen.size(), a.stop_reason.c_str(), e_single);
  EXPECT_LE(e_both, e_full);
  EXPECT_LT(e_both, e_single);
  EXPECT_EQ(r.history.back().expensive, r.expensive);
  if (r.reached_target) {
    for (double e : r.history.back().loo_nrmse) EXPECT_LE(e, o.target_loo_nrmse);
  }
}
