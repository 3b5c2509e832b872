#include "workflow/spreading/powder_sizes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/suggest.hpp"
#include "powder/size_fit.hpp"

namespace spreadmap {
namespace {

using powder::FractionBasis;
using powder::SizeDistribution;

FractionBasis basis_of(const Powder &powder) {
  return powder.basis == "volume" || powder.basis == "mass" ? FractionBasis::volume : FractionBasis::number;
}

bool by_quantiles(const Powder &powder) { return powder.d10 > 0 || powder.d90 > 0; }

std::string um(double d) { return fmt::format("{:.4g}", d * 1e6); }

// The size keys each distribution takes; a key written for another distribution is refused.
const std::map<std::string, std::vector<std::string>> keys_of = {
    {"mono", {"diameter"}},
    {"lognormal", {"basis", "d10", "d50", "d90", "sigma", "d_min", "d_max"}},
    {"normal", {"basis", "d10", "d50", "d90", "standard_deviation", "d_min", "d_max"}},
    {"table", {"basis", "table"}},
};
const std::vector<std::string> size_keys = {"diameter",           "basis", "d10",   "d50",  "d90", "sigma",
                                            "standard_deviation", "d_min", "d_max", "table"};

}  // namespace

SizeDistribution size_distribution(const Powder &powder) {
  const FractionBasis basis = basis_of(powder);
  if (powder.distribution == "lognormal") {
    if (!by_quantiles(powder))
      return SizeDistribution::lognormal(powder.d50, powder.sigma, basis, powder.d_min, powder.d_max);
    const auto fit = powder::fit_lognormal(powder.d10, powder.d50, powder.d90);
    return SizeDistribution::lognormal(fit.d50, fit.spread, basis, powder.d_min, powder.d_max);
  }
  if (powder.distribution == "normal") {
    if (!by_quantiles(powder))
      return SizeDistribution::normal(powder.d50, powder.standard_deviation, basis, powder.d_min, powder.d_max);
    const auto fit = powder::fit_normal(powder.d10, powder.d50, powder.d90);
    return SizeDistribution::normal(fit.d50, fit.spread, basis, powder.d_min, powder.d_max);
  }
  if (powder.distribution == "table") {
    if (!powder.table.is_array() || powder.table.empty())
      throw InputError(
          "scene.powder.table: a table distribution needs table: [{diameter: 20 um, fraction: 0.3}, ...] or "
          "a CSV file");
    std::vector<double> from, to, fraction;
    for (const auto &row : powder.table) {
      const bool one = row.contains("diameter");
      from.push_back(row.at(one ? "diameter" : "from").get<double>());
      to.push_back(row.at(one ? "diameter" : "to").get<double>());
      fraction.push_back(row.at("fraction").get<double>());
    }
    return SizeDistribution::classes(from, to, fraction, basis);
  }
  return SizeDistribution::monodisperse(powder.diameter);
}

namespace {

// The size keys as the user wrote them in scene.powder: whether each is written, where, its key path.
struct WrittenSizes {
  const YAML::Node &user;
  const std::string &file;
  bool has_user = user && user.IsMap();

  bool written(const std::string &key) const { return has_user && user[key]; }
  Location at(const std::string &key) const { return Location::of(file, written(key) ? user[key] : user); }
  static std::string path(const std::string &key) { return "scene.powder." + key; }
};

// A size key written for another distribution than the powder's.
void report_foreign_size_keys(const Powder &powder, const WrittenSizes &w, Diagnostics &diag) {
  const std::string &kind = powder.distribution;
  const auto &mine = keys_of.at(kind);
  for (const auto &key : size_keys)
    if (w.written(key) && std::find(mine.begin(), mine.end(), key) == mine.end())
      diag.error(
          w.at(key), w.path(key), fmt::format("{} does not apply to distribution: {}", key, kind),
          fmt::format("distribution: {} takes {}{}", kind, join(mine),
                      kind == "mono" ? "; set distribution: lognormal, normal or table for a size distribution" : ""));
}

// A lognormal or normal distribution given by its quantiles: all three, in order, and no width beside them.
void check_size_quantiles(const Powder &powder, const WrittenSizes &w, Diagnostics &diag) {
  const std::string &kind = powder.distribution;
  const char *width = kind == "lognormal" ? "sigma" : "standard_deviation";
  for (const auto &[key, value] : {std::pair{"d10", powder.d10}, std::pair{"d90", powder.d90}})
    if (!(value > 0))
      diag.error(w.at(key), w.path(key), "missing: d10, d50 and d90 go together",
                 "give all three (the diameters below which 10, 50 and 90 % of the powder lie)");
  if (!w.written("d50"))
    diag.error(w.at("d50"), w.path("d50"), "missing: d10 and d90 need d50 too",
               "give all three (the diameters below which 10, 50 and 90 % of the powder lie)");
  if (w.written(width))
    diag.error(w.at(width), w.path(width), fmt::format("give {} or d10 and d90, not both", width),
               fmt::format("the three quantiles determine the {}'s width", kind));
  const std::string order_hint = fmt::format(
      "D10 < D50 < D90: the diameters below which 10, 50 and 90 % of the powder (by {}) lie; check the order "
      "and the units",
      powder.basis);
  const bool d50_given = w.written("d50");  // else d50 is the default 250 um: the error above says so
  if (d50_given && powder.d10 > 0 && !(powder.d10 < powder.d50))
    diag.error(w.at("d10"), w.path("d10"),
               fmt::format("D10 = {} um is not below D50 = {} um", um(powder.d10), um(powder.d50)), order_hint);
  if (d50_given && powder.d90 > 0 && !(powder.d50 < powder.d90))
    diag.error(w.at("d90"), w.path("d90"),
               fmt::format("D90 = {} um is not above D50 = {} um", um(powder.d90), um(powder.d50)), order_hint);
}

// A lognormal or normal distribution: its quantiles or its width, and a truncation that is not empty.
void check_size_spread(const Powder &powder, const WrittenSizes &w, Diagnostics &diag) {
  if (by_quantiles(powder)) {
    check_size_quantiles(powder, w, diag);
  } else if (powder.distribution == "normal" && !(powder.standard_deviation > 0)) {
    diag.error(w.at("standard_deviation"), w.path("standard_deviation"), "a normal distribution needs a width",
               "give standard_deviation (with d50, the mean), or d10, d50 and d90");
  }
  if (powder.d_min > 0 && powder.d_max > 0 && !(powder.d_min < powder.d_max))
    diag.error(w.at("d_min"), w.path("d_min"),
               fmt::format("the truncation [d_min, d_max] = [{}, {}] um is empty", um(powder.d_min), um(powder.d_max)),
               "d_min is the smallest diameter kept, d_max the largest");
}

// What the heap will sample, against the quantiles asked: a warning when they are off by more than
// the tolerance, saying whether the family or the truncation is to blame.
std::vector<std::string> quantile_misfit_warning(const Powder &powder, const SizeDistribution &sizes,
                                                 const std::string &file) {
  const std::string &kind = powder.distribution;
  const FractionBasis basis = basis_of(powder);
  const double given[3] = {powder.d10, powder.d50, powder.d90};
  double sampled[3], worst = 0;
  for (int i = 0; i < 3; ++i) {
    sampled[i] = sizes.quantile(0.1 + 0.4 * i, basis);
    worst = std::max(worst, std::abs(sampled[i] / given[i] - 1));
  }
  if (worst <= powder::quantile_misfit_tolerance) return {};
  const auto fit = kind == "lognormal" ? powder::fit_lognormal(given[0], given[1], given[2])
                                       : powder::fit_normal(given[0], given[1], given[2]);
  const std::string asked =
      fmt::format("D10/D50/D90 = {}/{}/{} um by {}", um(given[0]), um(given[1]), um(given[2]), powder.basis);
  const std::string gets =
      fmt::format("{}/{}/{} um, up to {:.1f} % off (tolerance {:g} %)", um(sampled[0]), um(sampled[1]), um(sampled[2]),
                  100 * worst, 100 * powder::quantile_misfit_tolerance);
  const std::string family =
      kind == "lognormal"
          ? fmt::format("a lognormal (least squares in ln d: median {} um, sigma {:.3g})", um(fit.d50), fit.spread)
          : fmt::format("a normal (least squares: mean {} um, standard deviation {} um)", um(fit.d50), um(fit.spread));
  if (fit.misfit > powder::quantile_misfit_tolerance)
    return {
        fmt::format("{}: scene.powder: {} are not those of {}, which gives {}; check the values, or give the "
                    "measured sizes as distribution: table",
                    file, asked, family, gets)};
  return {
      fmt::format("{}: scene.powder: the truncation to [{}, {}] um moves {} to {}; widen d_min/d_max, or "
                  "leave them 0 for the default",
                  file, um(sizes.lower()), um(sizes.upper()), asked, gets)};
}

}  // namespace

std::vector<std::string> check_powder_sizes(const Powder &powder, const YAML::Node &user, const std::string &file,
                                            Diagnostics &diag) {
  const WrittenSizes w{user, file};
  const std::size_t errors_before = diag.errors().size();
  const std::string &kind = powder.distribution;
  const auto &mine = keys_of.at(kind);
  report_foreign_size_keys(powder, w, diag);
  if (kind == "lognormal" || kind == "normal") check_size_spread(powder, w, diag);
  if (kind == "table" && !w.written("table"))
    diag.error(w.at("table"), w.path("table"), "distribution: table needs the table",
               "give table: [{diameter: 20 um, fraction: 0.3}, ...], rows {from, to, fraction}, or a CSV file");
  if (diag.errors().size() != errors_before || (kind == "table" && !powder.table.is_array())) return {};

  SizeDistribution sizes;
  try {
    sizes = size_distribution(powder);
    sizes.validate();
  } catch (const std::exception &e) {
    diag.error(w.at("distribution"), "scene.powder", e.what(),
               fmt::format("distribution: {} takes {}", kind, join(mine)));
    return {};
  }
  if (!by_quantiles(powder)) return {};
  return quantile_misfit_warning(powder, sizes, file);
}

}  // namespace spreadmap
