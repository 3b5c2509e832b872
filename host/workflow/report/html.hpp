// The few pieces of HTML the run report is made of: escaped text, images inlined as data URIs (the
// page fetches nothing), and tables built row by row.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace spreadmap::html {

std::string escape(const std::string &text);  // & < > " '
std::string base64(const std::string &bytes);
// <img src="data:image/png;base64,..." alt="..." class="..."/> of a PNG file; "" when it is missing.
std::string inline_png(const std::filesystem::path &png, const std::string &alt, const std::string &css_class = "");

// A table: cells are HTML (escape text yourself), the header row is text.
class HtmlTable {
 public:
  explicit HtmlTable(std::vector<std::string> header, std::string css_class = "");
  void add(std::vector<std::string> cells);
  bool empty() const { return rows_.empty(); }
  std::string str() const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
  std::string class_;
};

}  // namespace spreadmap::html
