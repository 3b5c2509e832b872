#include "model_file.hpp"

#include <stdexcept>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "read_file.hpp"

namespace sm = spreadmap;

namespace spreadmap::analysis {

namespace {
nlohmann::json to_json(const std::vector<Variable> &vars) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto &v : vars) a.push_back({{"name", v.name}, {"unit", v.unit}, {"min", v.min}, {"max", v.max}});
  return a;
}
std::vector<Variable> variables(const nlohmann::json &a) {
  std::vector<Variable> out;
  for (const auto &v : a)
    out.push_back({v.at("name").get<std::string>(), v.value("unit", "-"), v.value("min", 0.0), v.value("max", 0.0)});
  return out;
}
}  // namespace

std::string ModelFile::plugin_name() const {
  const auto slash = plugin.find('/');
  return slash == std::string::npos ? plugin : plugin.substr(slash + 1);
}

void save_model_json(const std::string &path, const ModelFile &m) {
  const nlohmann::json j = {{"format", "spreadmap-model"},        {"version", 1},       {"plugin", m.plugin},
                            {"plugin_version", m.plugin_version}, {"params", m.params}, {"inputs", to_json(m.inputs)},
                            {"outputs", to_json(m.outputs)},      {"state", m.state},   {"training", m.training}};
  write_atomic(path, j.dump(1) + "\n");
}

ModelFile load_model_json(const std::string &path) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read_file(path));
  } catch (const nlohmann::json::exception &e) {
    throw std::runtime_error(path + ": not valid JSON: " + e.what());
  }
  try {
    if (j.value("format", "") != "spreadmap-model")
      throw std::runtime_error("not a spreadmap model file (\"format\" is not \"spreadmap-model\")");
    if (j.value("version", 0) != 1)
      throw std::runtime_error("model file version " + j.value("version", nlohmann::json(nullptr)).dump() +
                               " is not supported (this build reads version 1)");
    ModelFile m;
    m.plugin = j.at("plugin").get<std::string>();
    m.plugin_version = j.value("plugin_version", "");
    m.params = j.value("params", nlohmann::json::object());
    m.inputs = variables(j.at("inputs"));
    m.outputs = variables(j.at("outputs"));
    m.state = j.at("state");
    m.training = j.value("training", nlohmann::json::object());
    m.path = path;
    return m;
  } catch (const nlohmann::json::exception &e) {
    throw std::runtime_error(path + ": " + e.what());
  } catch (const std::runtime_error &e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace spreadmap::analysis
