#include "workflow/report/html.hpp"

#include <fstream>
#include <sstream>

namespace spreadmap::html {

std::string escape(const std::string &text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  return out;
}

std::string base64(const std::string &bytes) {
  static const char table[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (unsigned(static_cast<unsigned char>(bytes[i])) << 16) |
                       (unsigned(static_cast<unsigned char>(bytes[i + 1])) << 8) |
                       unsigned(static_cast<unsigned char>(bytes[i + 2]));
    out += table[(v >> 18) & 63], out += table[(v >> 12) & 63], out += table[(v >> 6) & 63], out += table[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = unsigned(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= unsigned(static_cast<unsigned char>(bytes[i + 1])) << 8;
    out += table[(v >> 18) & 63], out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string inline_png(const std::filesystem::path &png, const std::string &alt, const std::string &css_class) {
  std::ifstream in(png, std::ios::binary);
  if (!in) return "";
  std::ostringstream bytes;
  bytes << in.rdbuf();
  const std::string data = bytes.str();
  // a PNG starts with its 8-byte signature: anything else (a torn or foreign file) is left out
  if (data.size() < 8 || data.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return "";
  return "<img src=\"data:image/png;base64," + base64(data) + "\" alt=\"" + escape(alt) + "\"" +
         (css_class.empty() ? "" : " class=\"" + css_class + "\"") + "/>";
}

HtmlTable::HtmlTable(std::vector<std::string> header, std::string css_class)
    : header_(std::move(header)), class_(std::move(css_class)) {}

void HtmlTable::add(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }

std::string HtmlTable::str() const {
  std::string out = class_.empty() ? "<table>\n<thead><tr>" : "<table class=\"" + class_ + "\">\n<thead><tr>";
  for (const auto &h : header_) out += "<th>" + escape(h) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto &row : rows_) {
    out += "<tr>";
    for (const auto &cell : row) out += "<td>" + cell + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

}  // namespace spreadmap::html
