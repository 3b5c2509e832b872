// spreadmap calibrate FILE.yaml [--out DIR] [--at name=value,...]: identify contact parameters from
// measured bulk angles (calibration.hpp), or with --at only simulate the tests at given values.
#include <fmt/format.h>

#include <sstream>

#include "core/error.hpp"
#include "core/suggest.hpp"
#include "workflow/calibrate/calibration.hpp"
#include "workflow/stage/command_line.hpp"
#include "workflow/stage/commands.hpp"

namespace spreadmap {
namespace {

// "friction=0.45,rolling_friction=0.12" -> one value per parameter of the file, in its order.
std::vector<double> parse_at(const std::string &text, const calibrate::CalibrationFile &c) {
  std::vector<double> values(c.parameters.size(), std::nan(""));
  std::vector<std::string> names;
  for (const auto &p : c.parameters) names.push_back(p.name);
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto eq = item.find('=');
    const std::string name = item.substr(0, eq);
    const auto it = std::find(names.begin(), names.end(), name);
    if (eq == std::string::npos || it == names.end())
      throw InputError(fmt::format("--at: '{}' is not NAME=VALUE for a parameter of {} ({}); write e.g. --at {}=0.5",
                                   item, c.file.string(), join(names), names.front()));
    try {
      values[std::size_t(it - names.begin())] = std::stod(item.substr(eq + 1));
    } catch (const std::exception &) {
      throw InputError(fmt::format("--at: '{}' has no number after '='", item));
    }
  }
  for (std::size_t k = 0; k < values.size(); ++k)
    if (std::isnan(values[k]))
      throw InputError(fmt::format("--at: no value for {}; give every parameter: {}", names[k], join(names)));
  return values;
}

}  // namespace

int cmd_calibrate(int argc, char **argv) {
  namespace po = boost::program_options;
  po::options_description d("calibrate options");
  std::string file, out, at;
  cli::Common common;
  d.add_options()("file", po::value(&file)->required(), "calibration file (docs/calibration.md)")(
      "out", po::value(&out), "output folder (default runs/<name>)")(
      "at", po::value(&at), "only simulate the tests at NAME=VALUE,... (every parameter of the file)");
  common.add(d);
  po::positional_options_description p;
  p.add("file", 1);
  po::variables_map vm;
  if (!cli::parse(argc, argv, d, p, vm, "calibrate FILE.yaml [--out DIR] [--at NAME=VALUE,...]")) return 0;
  common.apply();
  auto &registry = PluginRegistry::global();
  const auto c = calibrate::read_calibration_file(file, registry);
  const std::filesystem::path dir = out.empty() ? std::filesystem::path("runs") / c.name : std::filesystem::path(out);
  if (!at.empty()) calibrate::run_at(c, parse_at(at, c), dir, registry);
  else calibrate::run_calibration(c, dir, registry);
  return 0;
}

}  // namespace spreadmap
