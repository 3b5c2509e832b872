#include "validation.hpp"

#include <stdexcept>

namespace spreadmap::analysis {

namespace {
const char *allowed = "auto, holdout (the study's 35/10), kfold:K, loo or column:NAME";

std::size_t folds_of(const std::string &text, const std::string &digits) {
  std::size_t used = 0;
  unsigned long k = 0;
  try {
    k = std::stoul(digits, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  if (digits.empty() || used != digits.size() || k < 2)
    throw std::invalid_argument("'" + text + "': K of kfold:K must be a whole number of at least 2, e.g. kfold:5");
  return std::size_t(k);
}
}  // namespace

Validation parse_validation(const std::string &text, std::size_t default_folds) {
  Validation v;
  v.reason = "as asked";
  const auto colon = text.find(':');
  const std::string head = text.substr(0, colon), tail = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (colon != std::string::npos && head != "kfold" && head != "column")
    throw std::invalid_argument("'" + text + "' is not a split; use " + allowed);
  if (head == "auto") v.kind = Validation::Kind::automatic, v.reason.clear();
  else if (head == "holdout" || head == "study") v.kind = Validation::Kind::holdout;
  else if (head == "loo") v.kind = Validation::Kind::loo;
  else if (head == "kfold")
    v.kind = Validation::Kind::kfold, v.folds = colon == std::string::npos ? default_folds : folds_of(text, tail);
  else if (head == "column") {
    v.kind = Validation::Kind::column, v.column = colon == std::string::npos ? "split" : tail;
    if (v.column.empty()) throw std::invalid_argument("'" + text + "': name the column, e.g. column:split");
  } else throw std::invalid_argument("'" + text + "' is not a split; use " + allowed);
  return v;
}

Validation resolve_validation(Validation v, std::size_t rows) {
  if (v.kind != Validation::Kind::automatic) return v;
  const std::string n = std::to_string(rows) + " usable rows";
  if (rows >= holdout_from_rows) {
    v.kind = Validation::Kind::holdout;
    v.reason = n + ", at least " + std::to_string(holdout_from_rows) + ": the study's holdout leaves enough to test";
  } else if (rows >= loo_below_rows) {
    v.kind = Validation::Kind::kfold, v.folds = 5;
    v.reason = n + ", " + std::to_string(loo_below_rows) + " to " + std::to_string(holdout_from_rows - 1) +
               ": too few for a held-out test set, enough for 5 folds";
  } else {
    v.kind = Validation::Kind::loo;
    v.reason = n + ", fewer than " + std::to_string(loo_below_rows) + ": every row is needed to fit";
  }
  return v;
}

std::string describe(const Validation &v) {
  switch (v.kind) {
    case Validation::Kind::automatic:
      return "chosen by size";
    case Validation::Kind::holdout:
      return "holdout (the study's 35/10 share)";
    case Validation::Kind::kfold:
      return std::to_string(v.folds) + "-fold cross-validation";
    case Validation::Kind::loo:
      return "leave-one-out cross-validation";
    case Validation::Kind::column:
      return "column '" + v.column + "'";
  }
  return "";
}

std::string spelling(const Validation &v) {
  switch (v.kind) {
    case Validation::Kind::automatic:
      return "auto";
    case Validation::Kind::holdout:
      return "holdout";
    case Validation::Kind::kfold:
      return "kfold:" + std::to_string(v.folds);
    case Validation::Kind::loo:
      return "loo";
    case Validation::Kind::column:
      return "column:" + v.column;
  }
  return "";
}

}  // namespace spreadmap::analysis
