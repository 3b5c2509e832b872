#include "core/units.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <map>
#include <stdexcept>

#include "core/suggest.hpp"

namespace spreadmap {
namespace {

constexpr double pi = 3.14159265358979323846;

// {factor, pow10, dimension}: decimal scales go to pow10 (see Unit).
const std::map<std::string, Unit> &base_units() {
  static const std::map<std::string, Unit> units = {
      {"m", {1, 0, {{1, 0, 0}}}},
      {"g", {1, -3, {{0, 1, 0}}}},
      {"s", {1, 0, {{0, 0, 1}}}},
      {"min", {60, 0, {{0, 0, 1}}}},
      {"h", {3600, 0, {{0, 0, 1}}}},
      {"rad", {1, 0, {}}},
      {"deg", {pi / 180, 0, {}}},
      {"rpm", {2 * pi / 60, 0, {{0, 0, -1}}}},
      {"N", {1, 0, {{1, 1, -2}}}},
      {"Pa", {1, 0, {{-1, 1, -2}}}},
      {"J", {1, 0, {{2, 1, -2}}}},
      {"Hz", {1, 0, {{0, 0, -1}}}},
      {"%", {1, -2, {}}},
      {"-", {1, 0, {}}},
      {"1", {1, 0, {}}},
      {"t", {1, 3, {{0, 1, 0}}}},
  };
  return units;
}

const std::map<std::string, int> &prefixes() {
  static const std::map<std::string, int> p = {{"n", -9}, {"u", -6}, {"\xC2\xB5", -6}, {"\xCE\xBC", -6}, {"m", -3},
                                               {"c", -2}, {"k", 3},  {"M", 6},         {"G", 9}};
  return p;
}

// One symbol with an optional prefix: "mm", "kg", "GPa", "um".
std::optional<Unit> parse_symbol(const std::string &sym) {
  const auto &base = base_units();
  if (auto it = base.find(sym); it != base.end()) return it->second;
  for (const auto &[prefix, pow10] : prefixes()) {
    if (sym.size() > prefix.size() && sym.compare(0, prefix.size(), prefix) == 0) {
      auto it = base.find(sym.substr(prefix.size()));
      if (it != base.end() && it->first != "%" && it->first != "-" && it->first != "1")
        return Unit{it->second.factor, pow10 + it->second.pow10, it->second.dim};
    }
  }
  return std::nullopt;
}

}  // namespace

std::string Dimension::str() const {
  static const char *names[3] = {"m", "kg", "s"};
  std::string num, den;
  for (int i : {1, 0, 2}) {
    const int p = e[i];
    if (p == 0) continue;
    std::string part = std::string(names[i]) + (std::abs(p) > 1 ? "^" + std::to_string(std::abs(p)) : "");
    std::string &side = p > 0 ? num : den;
    side += (side.empty() ? "" : "*") + part;
  }
  if (num.empty() && den.empty()) return "1";
  return (num.empty() ? "1" : num) + (den.empty() ? "" : "/" + den);
}

// 10^k by repeated multiplication: exact up to k = 22, so the decimal step of to_si() is a single
// correctly rounded multiplication or division.
static double power_of_ten(int k) {
  double p = 1;
  for (int i = 0; i < k; ++i) p *= 10;
  return p;
}

double Unit::to_si(double value) const {
  double scaled = value;
  if (pow10 > 0) scaled = value * power_of_ten(pow10);
  else if (pow10 < 0) scaled = value / power_of_ten(-pow10);
  return factor == 1.0 ? scaled : scaled * factor;
}

std::optional<Unit> parse_unit(const std::string &text, std::string *why) {
  Unit result;
  std::size_t i = 0;
  int sign = +1;  // +1 numerator, -1 after '/'
  bool any = false;
  auto fail = [&](const std::string &msg) -> std::optional<Unit> {
    if (why) *why = msg;
    return std::nullopt;
  };
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '*' || c == '.') {
      ++i;
      continue;
    }
    if (c == '/') {
      if (sign < 0) return fail("only one '/' is allowed in a unit");
      sign = -1;
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < text.size() && text[j] != ' ' && text[j] != '*' && text[j] != '/' && text[j] != '^' &&
           !(text[j] == '.' && j > i))
      ++j;
    const std::string sym = text.substr(i, j - i);
    int power = 1;
    if (j < text.size() && text[j] == '^') {
      std::size_t k = j + 1;
      if (k < text.size() && (text[k] == '-' || text[k] == '+')) ++k;
      while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) ++k;
      try {
        power = std::stoi(text.substr(j + 1, k - j - 1));
      } catch (...) {
        return fail("'^' must be followed by a whole number");
      }
      j = k;
    } else if (!sym.empty() && std::isdigit(static_cast<unsigned char>(sym.back())) && sym != "1") {
      // "m3" means m^3
      std::size_t k = sym.size();
      while (k > 0 && std::isdigit(static_cast<unsigned char>(sym[k - 1]))) --k;
      auto u = parse_symbol(sym.substr(0, k));
      if (!u) return fail("unknown unit '" + sym + "'");
      power = std::stoi(sym.substr(k));
      result.factor *= std::pow(u->factor, sign * power);
      result.pow10 += sign * power * u->pow10;
      for (int d = 0; d < 3; ++d) result.dim.e[d] += sign * power * u->dim.e[d];
      any = true;
      i = j;
      continue;
    }
    auto u = parse_symbol(sym);
    if (!u) return fail("unknown unit '" + sym + "'");
    result.factor *= std::pow(u->factor, sign * power);
    result.pow10 += sign * power * u->pow10;
    for (int d = 0; d < 3; ++d) result.dim.e[d] += sign * power * u->dim.e[d];
    any = true;
    i = j;
  }
  if (!any) return fail("empty unit");
  return result;
}

Quantity parse_quantity(const std::string &text) {
  std::size_t b = text.find_first_not_of(" \t"), e = text.find_last_not_of(" \t");
  if (b == std::string::npos) throw std::invalid_argument("expected a number, got nothing");
  const std::string s = text.substr(b, e - b + 1);
  const std::string low = lower(s);
  if (low.find("nan") != std::string::npos || low.find("inf") != std::string::npos)
    throw std::invalid_argument("'" + s + "' is not a finite number");
  std::size_t used = 0;
  double v;
  try {
    v = std::stod(s, &used);
  } catch (const std::out_of_range &) {
    throw std::invalid_argument("'" + s + "' is outside the range of a double");
  } catch (...) {
    throw std::invalid_argument("'" + s + "' is not a number (write e.g. 250 um, 0.1 m/s or 4430)");
  }
  if (!std::isfinite(v)) throw std::invalid_argument("'" + s + "' is not a finite number");
  Quantity q;
  std::string rest = s.substr(used);
  if (rest.find_first_not_of(" \t") == std::string::npos) {
    q.value = v;
    return q;
  }
  rest = rest.substr(rest.find_first_not_of(" \t"));
  std::string why;
  auto u = parse_unit(rest, &why);
  if (!u)
    throw std::invalid_argument(
        "'" + s + "': " + why +
        " (known: m, g, s, min, h, rad, deg, rpm, N, Pa, J, Hz, % with prefixes n u m c k M G)");
  q.has_unit = true;
  q.unit = *u;
  q.value = u->to_si(v);
  if (!std::isfinite(q.value)) throw std::invalid_argument("'" + s + "' is not a finite number in SI");
  return q;
}

double parse_in(const std::string &text, const std::string &si_unit) {
  const Quantity q = parse_quantity(text);
  if (!q.has_unit) return q.value;
  const auto target = parse_unit(si_unit);
  if (!target) throw std::invalid_argument("internal: unknown schema unit '" + si_unit + "'");
  if (!(q.unit.dim == target->dim))
    throw std::invalid_argument("'" + text + "' has the dimension of " + q.unit.dim.str() + ", expected " +
                                target->dim.str() + " (a value in " + si_unit + ")");
  return q.value / target->to_si(1.0);
}

std::string display(double v, const std::string &unit) {
  if (unit == "m^2/s") return fmt::format("{:.4g} mm^2/s", v * 1e6);
  if (unit == "m/s") return fmt::format("{:.4g} mm/s", v * 1e3);
  if (unit == "m") return fmt::format("{:.4g} um", v * 1e6);
  if (unit == "rad/s") return fmt::format("{:.4g} rad/s", v);
  if (unit.empty() || unit == "-" || unit == "1") return fmt::format("{:.4g}", v);
  return fmt::format("{:.4g} {}", v, unit);
}

}  // namespace spreadmap
