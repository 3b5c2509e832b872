// A CSV table with a header row: cells kept as text, read as numbers on demand. Column names match
// case-insensitively (`Vs` finds `vs`). Errors name the file, line and column (1-based).
#pragma once
#include <Eigen/Dense>

#include <cstddef>
#include <string>
#include <vector>

namespace spreadmap::analysis {

class Table {
 public:
  Table() = default;
  explicit Table(std::vector<std::string> columns, std::string source = "table");

  static Table read_csv(const std::string &path);
  static Table parse_csv(const std::string &text, const std::string &source);
  void write_csv(const std::string &path) const;  // atomic
  std::string to_csv() const;

  std::size_t rows() const { return cells_.size(); }
  std::size_t cols() const { return columns_.size(); }
  const std::vector<std::string> &columns() const { return columns_; }
  const std::string &source() const { return source_; }

  // Index of a column, case-insensitive; throws naming the file and the columns there are.
  std::size_t column(const std::string &name) const;
  bool has_column(const std::string &name) const;
  const std::string &text(std::size_t row, std::size_t col) const { return cells_.at(row).at(col); }
  // The row's line in the file it was read from (1-based); 0 for a row built in memory.
  std::size_t line(std::size_t row) const { return row < lines_.size() ? lines_[row] : 0; }
  double number(std::size_t row, std::size_t col) const;  // throws with file:line:column
  std::vector<double> numbers(const std::string &column) const;
  std::vector<std::string> texts(const std::string &column) const;
  // The named columns as a matrix (rows x names), optionally only the given rows.
  Eigen::MatrixXd matrix(const std::vector<std::string> &names) const;
  Eigen::MatrixXd matrix(const std::vector<std::string> &names, const std::vector<std::size_t> &rows) const;

  void add_row(std::vector<std::string> cells);
  void add_row(const std::vector<double> &values);
  // Appends a column (must have rows() entries, or the table must be empty of rows and columns).
  void add_column(const std::string &name, const std::vector<double> &values);
  void add_column(const std::string &name, const std::vector<std::string> &values);

  // Shortest text that reads back as the same double ("nan", "inf", "-inf" for the others).
  static std::string format(double v);

 private:
  std::vector<std::string> columns_;
  std::vector<std::vector<std::string>> cells_;
  std::vector<std::size_t> lines_;  // source line of each row (1-based), 0 for rows built in memory
  std::string source_ = "table";
};

}  // namespace spreadmap::analysis
