// How a surrogate's accuracy is measured: which rows it is scored on that it was not fitted to.
//   holdout     the study's Table 4: 10 of 45 rows (the same share otherwise) held out for testing
//   kfold:K     K-fold cross-validation: every row is predicted once by a model fitted without it
//   loo         leave-one-out: K-fold with one row per fold
//   column:NAME a column of the table says `train` or `test` per row
//   auto        chosen by the number of usable rows (choose_validation); the default
#pragma once
#include <cstddef>
#include <string>

namespace spreadmap::analysis {

struct Validation {
  enum class Kind { automatic, holdout, kfold, loo, column };
  Kind kind = Kind::automatic;
  std::size_t folds = 5;  // kfold only
  std::string column;     // column only
  std::string reason;     // why this one: "as asked", or the size rule that chose it
  bool is_cross_validation() const { return kind == Kind::kfold || kind == Kind::loo; }
};

// Rows from which `auto` picks the study's holdout, and below which it picks leave-one-out.
inline constexpr std::size_t holdout_from_rows = 40, loo_below_rows = 12;

// Reads "auto", "holdout" (or "study"), "kfold", "kfold:K", "loo", "column" (the column `split`)
// or "column:NAME". Throws std::invalid_argument naming the allowed forms.
Validation parse_validation(const std::string &text, std::size_t default_folds = 5);
// `auto` made concrete for a table of `rows` usable rows: holdout from 40 rows, 5-fold from 12,
// leave-one-out below; other kinds are returned as they are.
Validation resolve_validation(Validation asked, std::size_t rows);
// "leave-one-out (9 folds)", "5-fold", "holdout (the study's 35/10 share)", "column 'split'".
std::string describe(const Validation &v);
// The spelling parse_validation reads back: "loo", "kfold:5", "holdout", "column:split".
std::string spelling(const Validation &v);

}  // namespace spreadmap::analysis
