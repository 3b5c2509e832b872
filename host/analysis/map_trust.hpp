// Whether the map of one output can be trusted, by a stated rule on the cross-validated error the
// train stage recorded in model.json: the out-of-fold predictions must explain at least half the
// variance of the cases they were not fitted to (Q^2 = 1 - SSE_cv / SS_about_mean >= 0.5). Below
// that the contours show the surrogate's guesses more than the process: a map that looks confident
// but predicts unseen cases no better than (or little better than) their mean.
#pragma once
#include <limits>
#include <string>
#include <vector>

#include "model_file.hpp"

namespace spreadmap::analysis {

constexpr double min_trusted_q2_cv = 0.5;

struct MapTrust {
  enum class Verdict { trusted, untrusted, unknown };
  std::string output;
  Verdict verdict = Verdict::unknown;
  double q2_cv = std::numeric_limits<double>::quiet_NaN();
  double r_cv = std::numeric_limits<double>::quiet_NaN();
  double nrmse_cv = std::numeric_limits<double>::quiet_NaN();  // [%]
  double rmse_cv = std::numeric_limits<double>::quiet_NaN();   // [output unit]
  std::string reason;  // one sentence: why, with the numbers
  bool untrusted() const { return verdict == Verdict::untrusted; }
  nlohmann::json to_json() const;
};

// One verdict per output of the model, in its order. A model trained without cross-validation (or
// written before q2_cv was recorded) gets `unknown`, with the reason.
std::vector<MapTrust> judge_map_trust(const ModelFile &model);
// One line for each map (V_s, R_q) that cannot be trusted, for the figure and the log.
std::vector<std::string> trust_notes(const std::vector<MapTrust> &trust);

}  // namespace spreadmap::analysis
