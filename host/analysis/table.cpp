// CSV reading and writing with positions kept for error messages.
#include "table.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/csv_line.hpp"
#include "core/files.hpp"
#include "read_file.hpp"

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}
std::string trim(const std::string &s) {
  const auto b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}
std::string quoted(const std::string &s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

Table::Table(std::vector<std::string> columns, std::string source)
    : columns_(std::move(columns)), source_(std::move(source)) {}

Table Table::read_csv(const std::string &path) { return parse_csv(read_file(path), path); }

Table Table::parse_csv(const std::string &text, const std::string &source) {
  Table t({}, source);
  std::size_t line_no = 0, pos = 0;
  bool header = true;
  while (pos <= text.size()) {
    const std::size_t nl = std::min(text.find('\n', pos), text.size());
    std::string line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty()) {
      if (nl >= text.size()) break;
      continue;
    }
    const std::string where = source + ":" + std::to_string(line_no);
    auto fields = core::split_csv_line(line, where);
    if (header) {
      for (const auto &f : fields) {
        if (f.text.empty())
          throw std::runtime_error(where + ":" + std::to_string(f.column) + ": empty column name in the header");
        if (t.has_column(f.text))
          throw std::runtime_error(where + ":" + std::to_string(f.column) + ": column '" + f.text +
                                   "' appears twice (names match case-insensitively)");
        t.columns_.push_back(f.text);
      }
      header = false;
    } else {
      if (fields.size() != t.columns_.size())
        throw std::runtime_error(where + ": " + std::to_string(fields.size()) + " fields, the header has " +
                                 std::to_string(t.columns_.size()));
      std::vector<std::string> row;
      for (auto &f : fields) row.push_back(std::move(f.text));
      t.cells_.push_back(std::move(row));
      t.lines_.push_back(line_no);
    }
    if (nl >= text.size()) break;
  }
  if (header) throw std::runtime_error(source + ": no header row (the file is empty)");
  return t;
}

std::string Table::to_csv() const {
  std::string s;
  for (std::size_t c = 0; c < columns_.size(); ++c) s += (c ? "," : "") + quoted(columns_[c]);
  s += '\n';
  for (const auto &row : cells_) {
    for (std::size_t c = 0; c < row.size(); ++c) s += (c ? "," : "") + quoted(row[c]);
    s += '\n';
  }
  return s;
}

void Table::write_csv(const std::string &path) const { write_atomic(path, to_csv()); }

bool Table::has_column(const std::string &name) const {
  const std::string n = lower(name);
  return std::any_of(columns_.begin(), columns_.end(), [&](const std::string &c) { return lower(c) == n; });
}

std::size_t Table::column(const std::string &name) const {
  const std::string n = lower(name);
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (lower(columns_[c]) == n) return c;
  std::string have;
  for (const auto &c : columns_) have += (have.empty() ? "" : ", ") + c;
  throw std::runtime_error(source_ + ": no column '" + name + "'; the columns are: " + have);
}

double Table::number(std::size_t row, std::size_t col) const {
  const std::string &s = cells_.at(row).at(col);
  double v = 0;
  const std::string l = lower(s);
  if (l == "nan") return std::nan("");
  if (l == "inf" || l == "+inf") return HUGE_VAL;
  if (l == "-inf") return -HUGE_VAL;
  const char *b = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0), *e = s.data() + s.size();
  const auto r = std::from_chars(b, e, v);
  if (s.empty() || r.ec != std::errc() || r.ptr != e) {
    const std::string line =
        row < lines_.size() && lines_[row] ? std::to_string(lines_[row]) : "row " + std::to_string(row + 1);
    throw std::runtime_error(source_ + ":" + line + ": column " + std::to_string(col + 1) + " ('" + columns_[col] +
                             "'): '" + s + "' is not a number");
  }
  return v;
}

std::vector<double> Table::numbers(const std::string &name) const {
  const std::size_t c = column(name);
  std::vector<double> v(rows());
  for (std::size_t r = 0; r < rows(); ++r) v[r] = number(r, c);
  return v;
}

std::vector<std::string> Table::texts(const std::string &name) const {
  const std::size_t c = column(name);
  std::vector<std::string> v(rows());
  for (std::size_t r = 0; r < rows(); ++r) v[r] = cells_[r][c];
  return v;
}

Eigen::MatrixXd Table::matrix(const std::vector<std::string> &names) const {
  std::vector<std::size_t> all(rows());
  for (std::size_t r = 0; r < rows(); ++r) all[r] = r;
  return matrix(names, all);
}

Eigen::MatrixXd Table::matrix(const std::vector<std::string> &names, const std::vector<std::size_t> &rows) const {
  Eigen::MatrixXd m(Eigen::Index(rows.size()), Eigen::Index(names.size()));
  for (std::size_t j = 0; j < names.size(); ++j) {
    const std::size_t c = column(names[j]);
    for (std::size_t i = 0; i < rows.size(); ++i) m(Eigen::Index(i), Eigen::Index(j)) = number(rows[i], c);
  }
  return m;
}

void Table::add_row(std::vector<std::string> cells) {
  if (cells.size() != columns_.size())
    throw std::invalid_argument(source_ + ": a row of " + std::to_string(cells.size()) + " cells for " +
                                std::to_string(columns_.size()) + " columns");
  cells_.push_back(std::move(cells));
  lines_.push_back(0);
}

void Table::add_row(const std::vector<double> &values) {
  std::vector<std::string> cells;
  for (double v : values) cells.push_back(format(v));
  add_row(std::move(cells));
}

void Table::add_column(const std::string &name, const std::vector<std::string> &values) {
  if (has_column(name)) throw std::invalid_argument(source_ + ": column '" + name + "' exists already");
  if (columns_.empty() && cells_.empty()) cells_.resize(values.size()), lines_.resize(values.size(), 0);
  if (values.size() != cells_.size())
    throw std::invalid_argument(source_ + ": column '" + name + "' has " + std::to_string(values.size()) +
                                " values for " + std::to_string(cells_.size()) + " rows");
  columns_.push_back(name);
  for (std::size_t r = 0; r < values.size(); ++r) cells_[r].push_back(values[r]);
}

void Table::add_column(const std::string &name, const std::vector<double> &values) {
  std::vector<std::string> cells;
  for (double v : values) cells.push_back(format(v));
  add_column(name, cells);
}

std::string Table::format(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace spreadmap::analysis
